"""ff-analyse on synthetic participants: planted effects found, null ones not,
readable errors on bad folders."""
import json

import pytest

from ffexp import analysis, analyse_cli, design
from exp_synthetic import write_participant



def planted(r, s):
    return (0.85 if r == "frictionmap" else 0.45) * (0.7 + 0.3 * s)


@pytest.fixture(scope="module")
def planted_folders(tmp_path_factory):
    root = tmp_path_factory.mktemp("planted")
    return [write_participant(str(root), n, planted, lambda r, i: 2.0 + (1.0 if r == "heightmap" else 0.0) + 4.0 / i)
            for n in range(1, 7)]


@pytest.fixture(scope="module")
def null_folders(tmp_path_factory):
    root = tmp_path_factory.mktemp("null")
    return [write_participant(str(root), n, lambda r, s: 0.6, rng_seed=100) for n in range(1, 7)]


def test_design_is_balanced_seeded_and_ordered():
    p3, p4 = design.plan(3), design.plan(4)
    assert len(p3) == 180 and p3 == design.plan(3) and p3 != design.plan(5)
    assert {t["rendering"] for t in p3[:90]} == {"frictionmap"}
    assert {t["rendering"] for t in p4[:90]} == {"heightmap"}
    from collections import Counter
    c = Counter((t["strength"], t["target"]) for t in p3[90:])
    assert set(c.values()) == {10} and len(c) == 9


def test_planted_rendering_effect_found(planted_folders):
    ps = [analysis.Participant(f) for f in planted_folders]
    g = analysis.group_statistics(ps)
    assert g["anova"]["hit_rate"]["rendering"]["p"] < 0.001
    assert g["anova"]["movement_time"]["rendering"]["p"] < 0.001
    assert g["anova"]["hit_rate"]["group"]["p"] > 0.01  # order has no planted effect
    # straight strokes: no direction changes at all
    assert all(t["direction_changes"] == 0 for p in ps for t in p.trials)


def test_null_effect_not_found(null_folders):
    ps = [analysis.Participant(f) for f in null_folders]
    g = analysis.group_statistics(ps)
    assert g["anova"]["hit_rate"]["rendering"]["p"] > 0.05
    assert g["anova"]["hit_rate"]["strength"]["p_gg"] > 0.05


def test_cli_writes_figures_and_summary(planted_folders, tmp_path):
    with pytest.raises(SystemExit) as e:
        analyse_cli.main(["--help"])
    assert e.value.code == 0
    out = tmp_path / "report"
    assert analyse_cli.main([*planted_folders[:2], "-o", str(out)]) == 0
    for name in ("summary.md", "fig11_hit_rates.png", "fig12_movement_times.png", "fig13_direction_changes.png",
                 "fig14_movement_angles.png", "fig15_learning.png", "participant_1.png"):
        assert (out / name).stat().st_size > 1000 or name == "summary.md"
    text = (out / "summary.md").read_text()
    assert "RM-ANOVA" in text and "Bonferroni" in text and "Wilcoxon" in text


def copy_folder(src, dst):
    import shutil
    shutil.copytree(src, dst)
    return dst


def run_bad(folder, tmp_path):
    code = analyse_cli.main([str(folder), "-o", str(tmp_path / "r")])
    return code


@pytest.mark.parametrize("damage, expect", [
    ("truncate", "trials.csv:4: truncated row"),
    ("column", "trials.csv:1: missing column(s): crossing_y"),
    ("version", "session.json:1: log format version 0"),
    ("number", "trials.csv:3: column 'movement_time': 'abc' is not a number"),
])
def test_bad_input_names_file_and_line(planted_folders, tmp_path, capsys, damage, expect):
    f = copy_folder(planted_folders[0], tmp_path / "P01")
    trials = f / "trials.csv"
    lines = trials.read_text().splitlines()
    if damage == "truncate":
        lines = lines[:3] + [lines[3][:20]]
    elif damage == "column":
        lines = [l.rsplit(",", 3)[0] + "," + l.rsplit(",", 2)[1] + "," + l.rsplit(",", 1)[1] for l in lines]
        lines = [",".join(c for i, c in enumerate(l.split(",")) if i != 10) for l in lines]
    elif damage == "version":
        s = json.loads((f / "session.json").read_text()); s["format_version"] = 0
        (f / "session.json").write_text(json.dumps(s))
    elif damage == "number":
        cells = lines[2].split(","); cells[9] = "abc"; lines[2] = ",".join(cells)
    trials.write_text("\n".join(lines) + "\n")
    assert run_bad(f, tmp_path) == 2
    err = capsys.readouterr().err
    assert expect in err and "Traceback" not in err and err.count("\n") == 1


def test_not_a_participant_folder(tmp_path, capsys):
    assert analyse_cli.main([str(tmp_path), "-o", str(tmp_path / "r")]) == 2
    assert "session.json: missing" in capsys.readouterr().err
