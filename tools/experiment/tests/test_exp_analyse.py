"""ff-analyse on synthetic participants: planted effects found, null ones not,
readable errors on bad folders."""
import json
import warnings

import numpy as np
import pytest
from scipy import stats as sps

from ffexp import analysis, analyse_cli, design, logs, metrics, stats
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
    for bad in (0, -1, "3", 2.0):  # a seed from a typo would still give a plan: refused instead
        with pytest.raises(ValueError, match="positive integer"):
            design.plan(bad)


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
    assert text.endswith(", [participant_1.png](participant_1.png), [participant_2.png](participant_2.png)\n")


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


def with_line(path, number, text):
    """Replaces line `number` (1 = the header) of a file by the bytes `text`."""
    lines = path.read_bytes().split(b"\n")
    lines[number - 1] = text
    path.write_bytes(b"\n".join(lines))


@pytest.mark.parametrize("damage, expect", [
    (lambda f: (f / "exclusions.csv").write_bytes(b"trial,reason\n3,\xe9ternu\xe9\n"),  # saved as Latin-1
     "exclusions.csv:2: not UTF-8 text (byte 0xe9; save it as UTF-8)"),
    (lambda f: (f / "exclusions.csv").write_bytes("trial,reason\n4,x\n²,sneezed\n".encode()),
     "exclusions.csv:3: '²' is not a trial number 1..180"),
    (lambda f: with_line(f / "trials.csv", 3, (f / "trials.csv").read_bytes().split(b"\n")[2] + b"\xff"),
     "trials.csv:3: not UTF-8 text (byte 0xff; save it as UTF-8)"),
    (lambda f: with_line(f / "frames.csv", 7, b"1,0.3,\x80,240,1,0.3,0"),
     "frames.csv:7: not UTF-8 text (byte 0x80; save it as UTF-8)"),
    (lambda f: with_line(f / "frames.csv", 5, b'1,"' + b"9" * 200000 + b'",240,1,0.3,0'),
     "frames.csv:5: not a CSV row (field larger than field limit (131072))"),
    (lambda f: (f / "session.json").write_text(json.dumps(dict(json.loads((f / "session.json").read_text()),
                                                                participant=[1]))),
     "session.json:1: header's 'participant' is [1], not a positive whole number"),
    (lambda f: (f / "session.json").write_text(json.dumps(dict(json.loads((f / "session.json").read_text()),
                                                                order=3))),
     "session.json:1: header's 'order' is 3, not a text"),
    (lambda f: (f / "session.json").write_bytes((f / "session.json").read_bytes().replace(b'"x"', b'"\xe9"')),
     "session.json:5: not UTF-8 text (byte 0xe9; save it as UTF-8)"),  # {, age, format, format_version, gender
], ids=["latin-1-exclusions", "superscript-trial", "bad-byte-trials", "bad-byte-frames", "huge-field",
        "participant-list", "order-number", "bad-byte-session"])
def test_malformed_files_are_one_line_and_exit_2(planted_folders, tmp_path, capsys, damage, expect):
    f = copy_folder(planted_folders[0], tmp_path / "P01")
    damage(f)
    assert run_bad(f, tmp_path) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"ff-analyse: {f / expect}") and err.count("\n") == 1, err[:300]
    assert "Traceback" not in err


def test_a_torn_last_trial_is_left_out_and_said(planted_folders, tmp_path, capsys):
    f = copy_folder(planted_folders[0], tmp_path / "P01")
    trials = f / "trials.csv"
    text = trials.read_text()
    trials.write_text(text[:-1])  # a power cut before the last row's newline
    assert analyse_cli.main([str(f), planted_folders[1], "-o", str(tmp_path / "r"), "--no-participant-pages"]) == 0
    err = capsys.readouterr().err
    lines = text.count("\n")
    assert err == f"ff-analyse: {trials}:{lines}: the last line has no end (a write cut short): " \
                  "left out as an unfinished trial\n"
    assert len(analysis.Participant(str(f)).trials) == len(logs.read_trials(planted_folders[0])) - 1


def test_not_a_participant_folder(tmp_path, capsys):
    assert analyse_cli.main([str(tmp_path), "-o", str(tmp_path / "r")]) == 2
    assert "session.json: missing" in capsys.readouterr().err


def in_order(folder, rendering, key):
    """One rendering's trials as read back from trials.csv, in trial order."""
    return [t[key] for t in sorted(logs.read_trials(folder), key=lambda t: t["trial"]) if t["rendering"] == rendering]


def block_rates(folders, rendering):
    """participants x 2: the hit rate of the first and the last 45 trials."""
    hits = np.array([in_order(f, rendering, "hit") for f in folders], float)
    return np.stack([hits[:, :45].mean(axis=1), hits[:, 45:].mean(axis=1)], axis=1)


def running_movement_times(folders, rendering):
    """participants x 81: movement time in trial order, its running mean over 10 trials."""
    return np.array([np.convolve(in_order(f, rendering, "movement_time"), np.ones(10) / 10, "valid")
                     for f in folders])


def test_block_hit_rates_and_learning_curves(planted_folders):
    g = analysis.group_statistics([analysis.Participant(f) for f in planted_folders])
    for r in logs.RENDERINGS:
        rates = block_rates(planted_folders, r)
        assert np.array_equal(g["blocks"][r]["rates"], rates)
        assert g["blocks"][r]["test"]["p"] == pytest.approx(sps.wilcoxon(rates[:, 0], rates[:, 1]).pvalue, rel=1e-12)
        runs = running_movement_times(planted_folders, r)
        curve = g["learning"][r]
        assert list(curve["x"]) == list(range(1, 82))
        assert curve["mean"] == pytest.approx(runs.mean(axis=0), abs=1e-12)
        assert curve["sd"] == pytest.approx(runs.std(axis=0, ddof=1), abs=1e-12)  # the sample SD
        assert curve["fit"] == pytest.approx(metrics.fit_power_law(np.arange(1.0, 82.0), runs.mean(axis=0)))
        a, b, c = curve["fit"]
        assert a > 0 and b > 0  # the planted 4 s / trial index: faster with practice


def test_excluded_trials_are_left_out(planted_folders, tmp_path):
    f = copy_folder(planted_folders[0], tmp_path / "P01")
    (f / "exclusions.csv").write_text("trial,reason\n1,jump\n95,device\n")
    p = analysis.Participant(str(f))
    assert p.excluded == {1: "jump", 95: "device"}
    assert [t["trial"] for t in p.trials] == [n for n in range(1, 181) if n not in (1, 95)]


def test_notes_say_what_the_anova_left_out(tmp_path):
    def never_a_heightmap_hit_at_033(number):
        return lambda r, s: 0.0 if (number == 1 and r == "heightmap" and s == 0.33) else 0.7
    folders = [write_participant(str(tmp_path), n, never_a_heightmap_hit_at_033(n)) for n in (1, 2, 3)]
    ps = [analysis.Participant(f) for f in folders]
    g = analysis.group_statistics(ps)
    # participant 1 has no correct trial in one cell: no movement time or direction changes there
    assert g["notes"] == ["movement_time: 1 participant(s) with an empty cell left out of the ANOVA",
                          "direction_changes: 1 participant(s) with an empty cell left out of the ANOVA"]
    assert "group" in g["anova"]["hit_rate"]  # three participants, both orders
    assert "group" not in g["anova"]["movement_time"]  # two left: no room for the order
    one = analysis.group_statistics(ps[1:2])
    assert one["anova"] == {} and one["notes"] == ["one participant: no group statistics"]


def test_a_participant_without_finished_trials(tmp_path):
    folder = str(tmp_path / "P01")
    logs.ParticipantLog(folder).close()
    logs.write_session(folder, dict(participant=1, seed=1, order="fm-hm"))
    with pytest.raises(logs.LogError, match="trials.csv: no finished trials"):
        analysis.Participant(folder)


def cell_lines(folders):
    """The summary's table, worked out from trials.csv alone."""
    lines = []
    trials = [logs.read_trials(f) for f in folders]
    for measure in ("hit_rate", "movement_time", "direction_changes"):
        for r in logs.RENDERINGS:
            cells = []
            for s in logs.STRENGTHS:
                per = []
                for tr in trials:
                    cell = [t for t in tr if t["rendering"] == r and t["strength"] == s]
                    if measure == "hit_rate":
                        per.append(np.mean([t["hit"] for t in cell]))
                    elif any(t["hit"] for t in cell):  # the others: over correct trials
                        per.append(np.mean([t["movement_time"] for t in cell if t["hit"]])
                                   if measure == "movement_time" else 0.0)  # straight strokes: no changes
                # the sample SD over participants; one participant's value alone
                cells.append(f"{np.mean(per):.2f} ± {np.std(per, ddof=1):.2f}" if len(per) > 1 else
                             f"{per[0]:.2f}" if per else "–")
            lines.append(f"| {measure.replace('_', ' ')} | {r} | " + " | ".join(cells) + " |")
    return lines


def test_the_summary_page(planted_folders, tmp_path):
    folders = planted_folders[:3]
    assert analyse_cli.main([*folders, "-o", str(tmp_path), "--no-participant-pages"]) == 0
    text = (tmp_path / "summary.md").read_text().splitlines()
    assert text[0] == "# frictionfield study: summary"
    assert text[2].endswith("3 participant(s): 1 (fm-hm, 180 trials, 0 excluded), 2 (hm-fm, 180 trials, 0 excluded), "
                            "3 (fm-hm, 180 trials, 0 excluded)")
    assert text[4:6] == ["| measure | rendering | s=1.00 | s=0.66 | s=0.33 |", "|---|---|---|---|---|"]
    assert text[6:12] == cell_lines(folders)
    assert text[12:14] == ["", "Hit rate over all trials of a cell (30 per participant, chance 1/3); movement time "
                               "and direction changes over correct trials. Mean ± SD over participants (sample SD, "
                               "n − 1; a cell with one participant's value shows it alone)."]
    for m in ("hit rate", "movement time", "direction changes"):
        head = text.index(f"**{m}**, RM-ANOVA rendering × strength with order between:")
        assert text[head - 1] == ""  # markdown: a paragraph of its own
        effects = [line.split(":")[0] for line in text[head + 1:head + 8]]
        assert effects == ["- rendering", "- rendering x group", "- strength", "- strength x group",
                           "- rendering x strength", "- rendering x strength x group", "- group"]
        assert text[head + 8].startswith("- strength, Bonferroni paired t: 1.0 vs 0.66: p")
        assert text[head + 8].count(" vs ") == 3
        assert text[head + 9].startswith("- heightmap vs frictionmap, Wilcoxon per strength: s=1.0: p")
    assert text[text.index("**direction changes**, RM-ANOVA rendering × strength with order between:") + 10] == ""
    assert text[-2] == ""
    for r in logs.RENDERINGS:
        rates = block_rates(folders, r)
        p = sps.wilcoxon(rates[:, 0], rates[:, 1]).pvalue
        assert f"- {r}: hit rate block 1 vs 2 (45 trials each), Wilcoxon {stats.format_p(p)}" in text
        a, b, c = metrics.fit_power_law(np.arange(1.0, 82.0), running_movement_times(folders, r).mean(axis=0))
        assert (f"- {r}: movement time learning curve y = a·x^-b + c: a = {a:.2f}, b = {b:.3f}, c = {c:.2f} "
                f"(start a+c = {a + c:.2f} s)") in text
    assert text[-1] == ("Figures: [fig11_hit_rates.png](fig11_hit_rates.png), [fig12_movement_times.png]"
                        "(fig12_movement_times.png), [fig13_direction_changes.png](fig13_direction_changes.png), "
                        "[fig14_movement_angles.png](fig14_movement_angles.png), [fig15_learning.png](fig15_learning.png)")
    assert not (tmp_path / "participant_1.png").exists()


def test_the_summary_of_empty_cells_and_no_learning(tmp_path, capsys):
    # nobody ever hits a heightmap target at s = 0.33; every movement takes 2 s
    folders = [write_participant(str(tmp_path), n, lambda r, s: 0.0 if (r, s) == ("heightmap", 0.33) else 0.7)
               for n in (1, 2)]
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        assert analyse_cli.main([*folders, "-o", str(tmp_path / "r"), "--no-participant-pages"]) == 0
    assert [w for w in caught if issubclass(w.category, RuntimeWarning)] == []  # the notes say it instead
    assert capsys.readouterr().out == f"ff-analyse: 2 participant(s) -> {tmp_path / 'r' / 'summary.md'}\n"
    text = (tmp_path / "r" / "summary.md").read_text().splitlines()
    assert text[6:12] == cell_lines(folders)
    assert text[8].endswith("| – |") and text[10].endswith("| – |")
    assert "**hit rate**, RM-ANOVA rendering × strength:" in text  # two participants: no room for the order
    assert not any(line.startswith("**movement time**") for line in text)
    assert "- note: movement_time: 2 participant(s) with an empty cell left out of the ANOVA" in text
    for r in logs.RENDERINGS:
        assert sum(line.startswith(f"- {r}: movement time") for line in text) == 1
        assert any(line.startswith(f"- {r}: movement time shows no power-law learning trend") for line in text)


def test_the_learning_curves_sd_is_the_sample_sd(tmp_path):
    # every movement of participant 1 takes 2 s, of participant 2 3 s: moving averages 2 and 3,
    # whose sample SD is |3 - 2| / sqrt(2) = 0.7071 (the population SD would be 0.5)
    folders = [write_participant(str(tmp_path), n, lambda r, s: 1.0, lambda r, i, n=n: float(n + 1)) for n in (1, 2)]
    g = analysis.group_statistics([analysis.Participant(f) for f in folders])
    for r in logs.RENDERINGS:
        assert g["learning"][r]["mean"] == pytest.approx(np.full(81, 2.5), abs=1e-5)
        assert g["learning"][r]["sd"] == pytest.approx(np.full(81, 1 / np.sqrt(2)), abs=1e-5)


def test_one_participant_shows_means_without_an_sd_and_without_warnings(planted_folders, tmp_path, capsys):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        assert analyse_cli.main([planted_folders[0], "-o", str(tmp_path / "r")]) == 0
        g = analysis.group_statistics([analysis.Participant(planted_folders[0])])
    assert [str(w.message) for w in caught if issubclass(w.category, RuntimeWarning)] == []
    text = (tmp_path / "r" / "summary.md").read_text().splitlines()
    assert text[6:12] == cell_lines(planted_folders[:1]) and "±" not in "".join(text[6:12])
    for r in logs.RENDERINGS:
        assert np.all(np.isnan(g["learning"][r]["sd"]))  # no spread to show


def test_the_same_participant_twice_is_refused(planted_folders, tmp_path, capsys):
    f = copy_folder(planted_folders[0], tmp_path / "again")
    assert analyse_cli.main([planted_folders[0], str(f), "-o", str(tmp_path / "r")]) == 2
    assert f"participant 1 is also {planted_folders[0]}" in capsys.readouterr().err
    assert analyse_cli.main([str(tmp_path / "nowhere"), "-o", str(tmp_path / "r")]) == 2
    assert "nowhere: not a folder" in capsys.readouterr().err


def test_a_report_folder_that_cannot_be_made(planted_folders, tmp_path, capsys):
    (tmp_path / "report").write_text("a file, not a folder")
    assert analyse_cli.main([planted_folders[0], "-o", str(tmp_path / "report" / "deeper")]) == 2
    err = capsys.readouterr().err
    assert err.startswith("ff-analyse: ") and "Not a directory" in err and err.count("\n") == 1
