"""make_report.py's report on a small benchmark run written by hand: every
figure below is worked out from the inputs in this file, not read from the
tool's output."""
import argparse
import os
import re
import subprocess
import sys

import pytest

import make_report

HOST_HEADER = ("id,scene,strategy,builtin,default,rendering,status,table_bytes,plan_bytes,fits_teensy,"
               "gradient_evaluations,max_g_core,max_g_ref,max_lsb,rms_lsb,p99_lsb,max_interior_lsb,worst_x,worst_y,"
               "worst_direction_deg,error_samples,eval_checksum,host_eval_ns,host_prepare_us,host_tick_ns")
# id: (default, table bytes, plan bytes, fits, gradient evaluations, max|G| core, ref, max, rms, p99, interior max,
#      worst x, worst y, checksum, host ns / eval, host us / prepare, host ns / tick)
HOST = {
    "neutral/closed-form": (1, 0, 1944, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 524288, 3.0, 0.06, 13.0),
    "heightmap-top/closed-form": (1, 0, 2000, 1, 5000, 0.9996, 1.0, 0.5, 0.1, 0.005, 0.4, 300, 200, 1000, 17,
                                  90, 80),
    # worst sample 2.2 px from the cone's apex (700, 40): within 3 spacings + 1
    "heightmap-top/table-4px-int16-gradient": (0, 48000, 2000, 1, 0, 0, 0, 2.0, 0.2, 0.3, 2.0, 702, 41, 999, 10,
                                               500, 70),
    # too big for a slot, and under 1 LSB: no place named
    "heightmap-top/table-1px-float-gradient": (0, 3072000, 2000, 0, 0, 0, 0, 0.8, 0.1, 0.2, 0.8, 400, 300, 1000, 9,
                                               9000, ""),
    # half a px from the left edge
    "heightmap-top/table-4px-float-height-cd": (0, 96000, 2000, 1, 0, 0, 0, 3.0, 0.3, 0.4, 0.7, 0.5, 200, 1000, 12,
                                                600, 75),
    "tunnel-pilot-a/closed-form": (1, 0, 2000, 1, 0, 0, 0, 0.2, 0.05, 0.1, 0.2, 300, 300, 7, 20, 100, 85),
    # 4 px from the tunnel's end at x = 100: within a spacing + 1
    "tunnel-pilot-a/table-8px-int16-gradient": (0, 12000, 2000, 1, 0, 0, 0, 1.2, 0.2, 0.3, 1.2, 104, 250, 7, 10,
                                                50, 84),
    "frictionmap-top/closed-form": (1, 0, 1944, 1, 0, 0, 0, 0.01, 0.001, 0.01, 0.01, 560.5, 86.5, 92348, 9.5,
                                    0.07, 78),
    # 2.5 px from the top edge, a 2 px table: within a spacing + 1
    "frictionmap-top/table-2px-float-profile": (0, 384000, 1944, 0, 0, 0, 0, 5.0, 1.0, 4.0, 5.0, 420.5, 2.5, 92348,
                                                30, 4000, ""),
    "bump-map/closed-form": (1, 0, 2100, 1, 0, 0, 0, 0.3, 0.05, 0.2, 0.3, 100, 100, 55, 29, 0.2, 98),
    "bump-map/table-4px-float-gradient": (0, 96000, 2100, 1, 0, 0, 0, 0.9, 0.1, 0.5, 0.9, 200, 200, 55, 10, 700,
                                          70),
}

# id: (prepare, gradient evaluations, eval instructions per call, tick instructions per tick (None: not measured),
#      worst tick)
M4 = {
    "neutral/closed-form": (2200, 0, 34, 150, 480),
    "heightmap-top/closed-form": (180000, 5000, 200, 850, 4440),
    "heightmap-top/table-4px-int16-gradient": (900000, 0, 100, 750, 4300),
    "heightmap-top/table-1px-float-gradient": (30000000, 0, 90, None, 0),
    "heightmap-top/table-4px-float-height-cd": (1000000, 0, 150, 800, 4400),
    "tunnel-pilot-a/closed-form": (400000, 0, 120, 900, 4500),
    "tunnel-pilot-a/table-8px-int16-gradient": (50000, 0, 100, 902, 4510),
    "frictionmap-top/closed-form": (2480, 0, 130, 770, 4360),
    "frictionmap-top/table-2px-float-profile": (6000000, 0, 140, None, 0),
    "bump-map/closed-form": (3000, 0, 400, 1100, 4600),
    "bump-map/table-4px-float-gradient": (2000000, 0, 100, 800, 4480),
}

M4_TRAILER = """tracker,thesis(),600000,2000,400,480,160
tracker,recommended(),1040000,2000,4080,520,227920
stopwatch_overhead_milli,16015
component,Tracker::on_sample (recommended(); per report),600000,200
component,Tracker::on_tick need_filter=false (finger present),100000,2000
component,Tracker::on_tick need_filter=true (recommended()),400000,2000
component,Tracker::on_tick without a finger,11264,256
component,AmplitudeMap::scale (strength 1),10240,256
component,AmplitudeMap::dac_code (linear calibration),12800,256
component,SampleMailbox::take,5120,256
component,element_gradient point sink,11264,256
component,HapticPipeline::tick without a finger,212000,2000
"""

CYCLES_HEADER = ("scene,instructions_mean,instructions_p99.9,instructions_max,cycles_best_mean,cycles_worst_mean,"
                 "cycles_best_p99.9,cycles_worst_p99.9,cycles_best_max,cycles_worst_max,worst_tick_kind,"
                 "swap_instructions,swap_cycles_worst,prepare_instructions,prepare_ms_best,prepare_ms_worst,"
                 "isr_best,isr_worst")
CYCLES = [
    "neutral,126,249,522,193,243,373,448,724,891,stroke,300,500,2577,0.02,0.03,105,327",
    "heightmap-top,847,4414,4416,1377,1622,6957,8129,6960,8142,stroke,,,167908,1.58,1.92,105,327",
    # (1,473 + 327) / 90,000 is 2 % exactly: at the goal, not over it
    "bump-map,832,4382,4474,1334,1592,6896,8084,1200,1473,mailbox-full,,,3164,1.9,2.01,105,327",
]


def write_run(folder, m4_done=True, m4_errors=(), grid_step=1, m4_failures=0):
    host = folder / "host"
    host.mkdir()
    lines = ["# tool: ff-bench (a test)", f"# run: full, error grid every {grid_step:g} px, not timed, 2 threads",
             HOST_HEADER]
    for cid, v in HOST.items():
        scene, strategy = cid.split("/")
        (default, table, plan, fits, gevals, gcore, gref, mx, rms, p99, interior, wx, wy, checksum, h_eval, h_prep,
         h_tick) = v
        lines.append(",".join(str(x) for x in (
            cid, scene, strategy, 1, default, "directional", "ok", table, plan, fits, gevals, gcore, gref, mx, rms,
            p99, interior, wx, wy, 0, 382721, checksum, h_eval, h_prep, h_tick)))
    (host / "host_cases.csv").write_text("\n".join(lines) + "\n")
    (host / "host_trackers.csv").write_text("# tool: ff-bench\nconfig,host_update_ns\nthesis(),30.4\n"
                                            "recommended(),44.42\n")
    m4 = ["m4bench,full", "calibration,40"]
    for cid, (prepare, gevals, per_eval, per_tick, tick_max) in M4.items():
        ticks = 2000 if per_tick is not None else 0
        checksum = HOST[cid][13] if cid != "heightmap-top/table-4px-int16-gradient" else 1000  # host says 999
        m4.append(",".join(str(x) for x in (
            "case", cid, HOST[cid][0], prepare, gevals, HOST[cid][1], HOST[cid][2], per_eval * 2048, 2048, checksum,
            (per_tick or 0) * ticks, ticks, tick_max, 0, prepare + 500 if ticks else -1)))
    m4_text = "\n".join(m4) + "\n" + M4_TRAILER + "".join(f"error,{e}\n" for e in m4_errors)
    if m4_done:
        m4_text += "done,%d\n" % m4_failures
    (folder / "m4bench.txt").write_text(m4_text)
    (folder / "cycles.csv").write_text("# ff-cyclemodel (a test)\n" + CYCLES_HEADER + "\n" + "\n".join(CYCLES) + "\n")
    (folder / "m4accuracy.csv").write_text("# tool: ff-m4accuracy\nscene,points,raw_max_lsb,scaled_max_lsb,"
                                           "scaled_rms_lsb,code_max_lsb,codes_off\nneutral,256,0,0,0,0.333333,0\n")
    return folder


def args_for(folder, **overrides):
    args = dict(host=str(folder / "host"), m4=str(folder / "m4bench.txt"), md=str(folder / "out" / "benchmarks.md"),
                csv=str(folder / "out" / "benchmarks.csv"), png=str(folder / "out" / "img" / "benchmarks.png"),
                png_link=None, environment="core at test", cycles=str(folder / "cycles.csv"),
                m4_accuracy=str(folder / "m4accuracy.csv"))
    args.update(overrides)
    return argparse.Namespace(**args)


@pytest.fixture
def run(tmp_path):
    write_run(tmp_path)
    cases, trackers = make_report.read_host(str(tmp_path / "host"))
    m4 = make_report.read_m4(str(tmp_path / "m4bench.txt"))
    rows = make_report.merge(cases, m4)
    return {"rows": rows, "by_id": {r["id"]: r for r in rows}, "m4": m4, "trackers": trackers,
            "text": make_report.report(rows, m4, trackers, args_for(tmp_path)), "folder": tmp_path}


GOLDEN = os.path.join(os.path.dirname(os.path.abspath(__file__)), "testdata", "make_report_golden.md")
TOOL = os.path.join(os.path.dirname(os.path.abspath(__file__)), "make_report.py")


def golden_text(text):
    """The report with what changes run to run (the date, the machine) made fixed."""
    return re.sub(r"\(\d{4}-\d{2}-\d{2}\)", "(DATE)", text)


def section(text, title):
    """The lines of the markdown section `## title`, up to the next one."""
    lines = text.splitlines()
    start = lines.index("## " + title)
    end = next((i for i in range(start + 1, len(lines)) if lines[i].startswith("## ")), len(lines))
    return lines[start + 1:end]


# ------------------------------------------------------------------ the inputs


def test_the_harness_output_is_read_per_call_and_per_tick(run):
    m4 = run["m4"]
    assert m4["mode"] == "full" and m4["calibration"] == 40 and m4["done"] == 0 and m4["errors"] == []
    hm = m4["cases"]["heightmap-top/closed-form"]
    assert hm == {"prepare": 180000, "gradient_evaluations": 5000, "table_bytes": 0, "plan_bytes": 2000,
                  "eval": 200.0, "checksum": 1000, "tick": 850.0, "tick_max": 4440, "pipeline_prepare": 180500}
    unticked = m4["cases"]["heightmap-top/table-1px-float-gradient"]
    assert unticked["tick"] is None and unticked["tick_max"] is None and unticked["pipeline_prepare"] is None
    assert m4["trackers"]["recommended()"] == {"mean": 520.0, "max": 4080, "configure": 520, "fade_noise": 227920}
    assert m4["components"]["AmplitudeMap::scale (strength 1)"] == 40.0 and m4["stopwatch"] == 16.015
    assert run["trackers"] == {"thesis()": 30.4, "recommended()": 44.42}


def test_a_tracker_line_without_its_setup_costs_reads_as_unknown(tmp_path):
    (tmp_path / "m4.txt").write_text("tracker,old(),1000,10,200\ndone,0\n")
    assert make_report.read_m4(str(tmp_path / "m4.txt"))["trackers"]["old()"] == {
        "mean": 100.0, "max": 200, "configure": None, "fade_noise": None}
    assert make_report.read_m4(None) is None


def test_merge_sums_memory_names_the_worst_spot_and_compares_checksums(run):
    by_id = run["by_id"]
    assert by_id["heightmap-top/table-4px-int16-gradient"]["memory_bytes"] == 50000
    assert [by_id[i]["where"] for i in ("heightmap-top/table-4px-int16-gradient",
                                        "heightmap-top/table-4px-float-height-cd",
                                        "tunnel-pilot-a/table-8px-int16-gradient",
                                        "frictionmap-top/table-2px-float-profile",
                                        "heightmap-top/table-1px-float-gradient")] == [
        "cone apex", "screen edge", "tunnel end (x = 100)", "screen edge", ""]
    assert by_id["heightmap-top/closed-form"]["max_g_rel_error"] == pytest.approx(4e-4)
    assert by_id["neutral/closed-form"]["max_g_rel_error"] is None  # no field: no max|G|
    assert by_id["heightmap-top/table-4px-int16-gradient"]["checksum_match"] is False
    assert by_id["heightmap-top/closed-form"]["checksum_match"] is True
    assert by_id["heightmap-top/closed-form"]["fits_teensy"] == 1


def test_a_table_without_a_measured_tick_is_estimated_from_its_scenes_closed_form(run):
    # the closed form's tick (850) minus its evaluation (200) plus the table's (90)
    estimated = run["by_id"]["heightmap-top/table-1px-float-gradient"]
    assert estimated["m4_tick"] == 740 and estimated["m4_tick_estimated"]
    assert make_report.tick_text(estimated) == "≈740"
    assert not run["by_id"]["heightmap-top/closed-form"]["m4_tick_estimated"]


def test_merge_without_the_m4_harness_leaves_the_m4_figures_empty(run):
    cases, _ = make_report.read_host(str(run["folder"] / "host"))
    row = make_report.merge(cases, None)[1]
    assert (row["m4_eval"], row["m4_tick"], row["m4_prepare"], row["checksum_match"]) == (None, None, None, None)
    assert make_report.tick_text(row) == "–"


@pytest.mark.parametrize("x, y, max_lsb, strategy, scene, said", [
    # a 4 px table reaches 3 x 4 + 1 = 13 px around the apex (700, 40): 12 and 13 px are in, 14 out
    (700, 52, 2.0, "table-4px-int16-gradient", "heightmap-top", "cone apex"),
    (700, 53, 2.0, "table-4px-int16-gradient", "heightmap-top", "cone apex"),
    (700, 54, 2.0, "table-4px-int16-gradient", "heightmap-top", "valley floor or curvature (x 700, y 54)"),
    (700, 53, 2.0, "table-4px-int16-gradient", "heightmap-middle", "valley floor or curvature (x 700, y 53)"),
    # a tunnel end: one spacing + 1 = 5 px
    (505, 300, 2.0, "table-4px-int16-gradient", "tunnel-pilot-b", "tunnel end (x = 500)"),
    (506, 300, 2.0, "table-4px-int16-gradient", "tunnel-pilot-b", "valley floor or curvature (x 506, y 300)"),
    # a closed form's "spacing" is 1 px: the edge within 2 px
    (796, 300, 2.0, "closed-form", "bump-map", "valley floor or curvature (x 796, y 300)"),
    (797, 300, 2.0, "closed-form", "bump-map", "screen edge"),
    (400, 477, 2.0, "closed-form", "bump-map", "screen edge"),
    (400, 300, 0.99, "closed-form", "bump-map", ""),
    ("", 300, 2.0, "closed-form", "bump-map", ""),
])
def test_where_names_the_nearest_singular_spot_within_the_tables_reach(x, y, max_lsb, strategy, scene, said):
    row = {"worst_x": str(x), "worst_y": str(y), "max_lsb": str(max_lsb), "strategy": strategy, "scene": scene}
    assert make_report.where(row) == said


# ----------------------------------------------------------- numbers as written


@pytest.mark.parametrize("value, text", [
    (None, "–"), (0, "0"), (0.0, "0"), (1100, "1,100"), (-1234.4, "-1,234"), (999.6, "1000"), (150.0, "150"),
    (34.0, "34"), (0.012222, "0.0122"), (5.5555, "5.56")])
def test_fmt(value, text):
    assert make_report.fmt(value) == text


def test_fmt_takes_its_significant_digits():
    assert make_report.fmt(5.5555, 2) == "5.6"


@pytest.mark.parametrize("size, text", [
    (0, "0"), ("1023", "1023 B"), (1024, "1.0 KiB"), (50000, "48.8 KiB"), (1048575, "1024.0 KiB"),
    (1048576, "1.00 MiB"), (3072000, "2.93 MiB")])
def test_kib(size, text):
    assert make_report.kib(size) == text


def test_p99_below_the_histograms_resolution_is_said_so():
    assert [make_report.p99_text(v) for v in (0.005, 0, 0.01, None)] == ["< 0.01", "0", "0.01", "–"]


def test_ms_at_180_mhz_and_the_pareto_front():
    assert make_report.ms_at_180(180000) == pytest.approx(1.0) and make_report.ms_at_180(None) is None
    # (2, 3) costs more than (1, 2) and is no more accurate; (3, 2) is as accurate as (1, 2) but dearer
    assert make_report.pareto([(3, 2), (2, 3), (1, 2), (4, 0.5), (5, 1)]) == [(1, 2), (4, 0.5)]


def test_each_strategy_has_its_family_and_an_unknown_one_is_drawn_as_a_closed_form():
    assert make_report.family("table-4px-int16-gradient")[0] == "int16-gradient"
    assert make_report.family("table-2px-float-height-cd")[0] == "float-height-cd"
    assert make_report.family("closed-form")[0] == "closed-form"
    assert make_report.family("something-new") == make_report.FAMILIES[0]


# ---------------------------------------------------------------- the report


def test_the_goals_table_says_each_goal_met_or_not_from_the_worst_scene(run):
    goals = [line for line in section(run["text"], "Goals") if line.startswith("| ") and "goal | measured" not in line]
    assert goals == [
        # (8,142 + 327) / 90,000; bump map at 2.00 % is not over 2 %
        "| every built-in scene ≤ 2 % of the 90,000-cycle budget at its worst modelled tick (worst assumptions, "
        "interrupt included) | worst: heightmap-top, 9.41 % (stroke); over: heightmap-top | **no** |",
        "| every built-in scene prepares in ≤ 2 ms of modelled MK66 time (worst assumptions) "
        "| worst: bump-map, 2.01 ms; over: bump-map | **no** |",
        "| every built-in scene's default ≤ 1 LSB max error | worst: heightmap-top, 0.5 LSB | yes |",
        # 1,100 / 90,000 = 1.22 %; the worst single tick of any default, bump map's 4,600
        "| every built-in scene's default ≤ 1,000 M4 instructions per whole tick (mean) | worst: bump-map, 1,100 "
        "(1.22 % of 90,000); worst single tick 4,600 | **no** |",
        # 400,000 / 180 MHz = 2.22 ms
        "| closed-form preparation ≤ 2 ms of M4 time = 360,000 instructions at 180 MHz (1 instruction counted as "
        "1 cycle) | worst: tunnel-pilot-a, 400,000 instructions = 2.22 ms; over: tunnel-pilot-a | **no** |",
        # 150 / 850 = 18 %, evaluation 34 / 200 = 17 %
        "| neutral costs a small fraction of heightmap (whole tick) | 150 / 850 instructions = 18 %; scene "
        "evaluation alone 34 / 200 = 17 % | yes |",
    ]


def test_goals_that_hold_say_yes(tmp_path):
    write_run(tmp_path)
    cycles = make_report.read_plain_csv(str(tmp_path / "cycles.csv"))[:1]  # neutral alone
    assert [row.rsplit("|", 2)[1].strip() for row in make_report.cycle_goal_rows(cycles)] == ["yes", "yes"]
    assert "over: none" in make_report.cycle_goal_rows(cycles)[0]
    cases, trackers = make_report.read_host(str(tmp_path / "host"))
    m4 = make_report.read_m4(str(tmp_path / "m4bench.txt"))
    for cid in ("tunnel-pilot-a/closed-form", "bump-map/closed-form"):
        m4["cases"][cid].update(prepare=3000, tick=900.0)
    m4["cases"]["neutral/closed-form"]["tick"] = 300.0  # 300 / 850 = 35 %: no longer a small fraction
    goals = section(make_report.report(make_report.merge(cases, m4), m4, trackers, args_for(tmp_path)), "Goals")
    assert any(line.startswith("| every built-in scene's default ≤ 1,000 M4") and line.endswith("| yes |")
               for line in goals)
    assert any(line.startswith("| closed-form preparation") and line.endswith("over: none | yes |") for line in goals)
    assert any("= 35 %" in line and line.endswith("| **no** (see *Where the time goes*) |") for line in goals)


def test_the_cycle_tables_add_the_interrupt_to_the_budget_shares_only(run):
    lines = section(run["text"], "Cycles on the MK66 (modelled), per built-in scene")
    assert "estimated from its code at 105–327 cycles" in lines[1]
    # mean (193 + 105) / 900 %, (243 + 327) / 900 %; p99.9 (373 + 105), (448 + 327); worst (724 + 105), (891 + 327)
    assert "| neutral | 126 / 249 / 522 | 193–243 | 373–448 | 724–891 (stroke) | 0.33–0.63 % | 0.53–0.86 % | " \
           "0.92–1.35 % | 2,577, 0.02–0.03 |" in lines
    assert "| bump-map | 832 / 4,382 / 4,474 | 1,334–1,592 | 6,896–8,084 | 1,200–1,473 (mailbox-full) | " \
           "1.60–2.13 % | 7.78–9.35 % | 1.45–2.00 % | 3,164, 1.90–2.01 |" in lines
    assert "| scene | swap | mailbox-full | mailbox-drain | lift-off | no-finger | touch-down |" in lines
    assert "| neutral | 300 / 500 | – / – | – / – | – / – | – / – | – / – |" in lines
    accuracy = section(run["text"], "Accuracy on the target (M4 build under qemu)")
    assert "| neutral | 256 | 0 | 0 / 0 | 0.333 | 0 |" in accuracy


def test_without_the_cycle_model_or_the_accuracy_run_their_sections_are_left_out(run):
    text = make_report.report(run["rows"], run["m4"], run["trackers"],
                              args_for(run["folder"], cycles=None, m4_accuracy=None))
    assert "## Cycles on the MK66" not in text and "## Accuracy on the target" not in text
    assert "modelled MK66 time" not in "\n".join(section(text, "Goals"))
    accuracy_only = make_report.cycles_section(make_report.read_plain_csv(str(run["folder"] / "cycles.csv")), None)
    assert "## Accuracy on the target (M4 build under qemu)" not in accuracy_only


def test_the_defaults_table_has_each_built_in_scene_at_its_default(run):
    lines = section(run["text"], "Built-in scenes at their default")
    # instructions are not cycles: a time from instructions says what it assumes
    assert "| M4 preparation (instr, ms at 180 MHz if 1 instruction = 1 cycle) |" in lines[3]
    assert "| scene | M4 instructions | ms at 180 MHz if 1 instruction = 1 cycle |" in "\n".join(
        section(run["text"], "Scene preparation"))
    rows = [line for line in lines if line.startswith("| ") and not line.startswith("| scene")]
    assert rows[:2] == [
        # 150 / 90,000 = 0.17 %; 2,200 instructions = 0.0122 ms
        "| neutral | 0 | 0 | 34 | 150, 480 | 0.17 % | 2,200, 0.0122 | 3 | 13 |",
        "| heightmap-top | 0.5 | 0.1 | 200 | 850, 4,440 | 0.94 % | 180,000, 1 | 17 | 80 |"]
    assert [r.split(" | ")[0] for r in rows] == ["| neutral", "| heightmap-top", "| tunnel-pilot-a",
                                                 "| frictionmap-top", "| bump-map"]
    # four of the five have no other strategy within 1 LSB that fits; the bump map has its 4 px float table
    assert lines[1].startswith("Every built-in scene defaults to its closed form: it needs no table RAM and is the "
                               "most accurate strategy; for 4 of the 5 built-in scenes it is the only one")
    assert "heightmap-top: only its closed-form is within 1 LSB" in lines[1]
    assert ("bump-map: also within 1 LSB and fitting the Teensy: table-4px-float-gradient (0.9 LSB, "
            "800 instr/tick).") in lines[1]


def test_the_table_saving_compares_the_cheapest_fitting_measured_table_with_the_closed_form(run):
    text = make_report.table_saving_text(run["rows"], True)
    # 800 / 1,100 - 1 = -27 %; 750 / 850 - 1 = -12 % (the 1 px table does not fit, its tick is estimated);
    # 902 / 900 - 1 = +0.2 %: ±0; the frictionmap's only table does not fit; neutral has none
    assert text.startswith("Whole tick with the cheapest measured table that fits, against the closed form (and "
                           "that table's max error): bump-map -27 % (table-4px-float-gradient, 0.9 LSB); "
                           "heightmap-top -12 % (table-4px-int16-gradient, 2 LSB); tunnel-pilot-a ±0 % "
                           "(table-8px-int16-gradient, 1.2 LSB). ")
    # gradient tables 90-100 instructions per evaluation, height + central differences 150
    assert "(90–100 instructions per evaluation), height + central differences 150–150" in text
    assert make_report.table_saving_text(run["rows"], False) == ""


def test_the_error_analysis_counts_where_the_tables_go_wrong(run):
    lines = section(run["text"], "Where the error goes")
    assert lines[1] == ("- Closed forms: at most 0.5 LSB (heightmap-top). The core's max|G| (coarse scan + compass "
                        "search) is within 4.0e-04 of the reference's everywhere, worth at most 0.819 LSB (0.5 x "
                        "relative error x 4095); the rest is float rounding.")
    assert lines[2] == "- Tables over 1 LSB, by where their worst sample sits: screen edge 2, cone apex 1, " \
                       "tunnel end 1 (of 4)."
    assert "(best: heightmap-top table-4px-int16-gradient, 2 LSB); away from it the same table has p99 0.3 LSB." \
           in lines[3]
    assert lines[4].startswith("- Height + central differences: 1 of 1 have their worst sample on the screen edge")
    assert "(heightmap-top/table-4px-float-height-cd: 3 LSB at the edge, 0.7 LSB at least 16 px inside)" in lines[4]
    assert lines[5].endswith("tables smear it over one spacing (1 strategies).")
    assert lines[6].endswith("(best: frictionmap-top table-2px-float-profile, 5 LSB).")


def test_the_error_analysis_takes_the_bump_maps_height_table_as_its_example(run):
    rows = [dict(r) for r in run["rows"]]
    bump = dict(run["by_id"]["heightmap-top/table-4px-float-height-cd"], id="bump-map/table-4px-float-height-cd",
                scene="bump-map", max_lsb="1.5", max_interior_lsb="0.01", where="")
    lines = make_report.error_analysis(rows + [bump])
    assert "Height + central differences: 1 of 2 have their worst sample on the screen edge" in lines[3]
    assert "(bump-map/table-4px-float-height-cd: 1.5 LSB at the edge, 0.01 LSB at least 16 px inside)" in lines[3]
    assert make_report.error_analysis([]) == []


def test_where_the_time_goes_leaves_the_rest_of_the_tick_to_the_pipeline(run):
    lines = section(run["text"], "Where the time goes (M4 instructions per tick)")
    assert "the stopwatch's own 16 instructions" in lines[1]
    table = [line for line in lines if line.startswith("| ")]
    assert table[1:] == [
        # 3,000 per report, a report every 10 ticks
        # timed with filtering on, which neutral (need_filter = false) never runs: not charged to neutral
        "| `Tracker::on_sample` (3,000 per report with filtering, one report every 10 ticks) "
        "| — (not timed without filtering) | 300 |",
        "| `Tracker::on_tick` (neutral: `need_filter = false`; heightmap: filtering, `recommended()`) | 50 | 200 |",
        "| `ScenePlan::amplitude` | — (at preparation) | 200 |",
        "| `AmplitudeMap::scale` | — (at preparation) | 40 |",
        "| `AmplitudeMap::dac_code` | — (at preparation) | 50 |",
        "| `SampleMailbox::take` (about one per tick) | 20 | 20 |",
        # 150 - (50 + 20), neutral's own on_sample included; 850 - (300 + 200 + 200 + 40 + 50 + 20)
        "| rest: `HapticPipeline::tick` itself (slot selection, `TickOutput`, calls; neutral: and its "
        "`on_sample`) | 80 | 40 |",
        "| **whole tick (measured)** | **150** | **850** |"]
    assert ("A tick with no finger on the glass: 106 instructions (`Tracker::on_tick` without a finger alone: 44). "
            "Field elements, one `element_gradient` call each: point sink 44.") in lines


def test_the_tracker_table_has_the_m4_costs_and_the_host_time_of_each_configuration(run):
    lines = section(run["text"], "Tracker update cost")
    assert [line for line in lines if line.startswith("| `")] == [
        "| `thesis()` | 300 | 400 | 480 | 160 | 30.4 |", "| `recommended()` | 520 | 4,080 | 520 | 227,920 | 44.4 |"]
    host_only = make_report.report(run["rows"], None, run["trackers"], args_for(run["folder"], cycles=None))
    assert [line for line in section(host_only, "Tracker update cost") if line.startswith("| `")] == [
        "| `thesis()` | – | – | – | – | 30.4 |", "| `recommended()` | – | – | – | – | 44.4 |"]


def test_the_preparation_tables_per_spacing_and_per_closed_form(run):
    lines = section(run["text"], "Scene preparation")
    assert "| closed form | 180,000 (1 ms) | | | | 0 |" in lines
    # 30,000,000 / 180 MHz = 167 ms; 900,000 = 5 ms; 1,000,000 = 5.56 ms; 48,000 + 0 bytes of int16 gradient
    assert "| 1 px | 30,000,000 (167 ms) | – | – | – | – |" in lines
    assert "| 4 px | – | 900,000 (5 ms) | 1,000,000 (5.56 ms) | – | 46.9 KiB |" in lines
    assert "| 2 px | – | – | – | – | – |" in lines
    # 180,000 / 5,000 evaluations = 36 each; max|G| 4e-4 off; neutral has no field to search
    assert "| heightmap-top | 180,000 | 1 | 5000 | 36 | 4.0e-04 | 90 |" in lines
    assert "| neutral | 2,200 | 0.0122 | – | – | – | 0.06 |" in lines


def test_every_strategy_has_its_row(run):
    lines = section(run["text"], "Every strategy")
    rows = [line for line in lines if line.startswith("| ") and not line.startswith("| id")]
    assert len(rows) == len(HOST)
    assert "| heightmap-top/closed-form **(default)** | 2.0 KiB | yes | 0.5 | < 0.01 | 0.1 | 0.4 |  | 200 | 850 " \
           "| 180,000 | 17 | 90 | yes |" in rows
    assert "| heightmap-top/table-1px-float-gradient | 2.93 MiB | no | 0.8 | 0.2 | 0.1 | 0.8 |  | 90 | ≈740 " \
           "| 30,000,000 | 9 | 9,000 | yes |" in rows
    assert "| heightmap-top/table-4px-int16-gradient | 48.8 KiB | yes | 2 | 0.3 | 0.2 | 2 | cone apex | 100 | 750 " \
           "| 900,000 | 10 | 500 | no |" in rows
    host_only = make_report.report(make_report.merge(make_report.read_host(str(run["folder"] / "host"))[0], None),
                                   None, run["trackers"], args_for(run["folder"], cycles=None))
    assert section(host_only, "Every strategy")[-2].endswith("| – | – | – | 10 | 700 | – |")


@pytest.mark.parametrize("run_line, grid", [
    # x = 0.5 ... 798.5 and y = 0.5 ... 478.5 every px: 799 x 479 = 382,721
    ("# run: full, error grid every 1 px, timed", "x = 0.5, 1.5, … 798.5, y = 0.5 … 478.5 (382,721 points"),
    # every 4 px: x = 0.5 ... 796.5 (200), y = 0.5 ... 476.5 (120): 24,000
    ("# run: full, error grid every 4 px, timed", "x = 0.5, 4.5, … 796.5, y = 0.5 … 476.5 (24,000 points"),
    # every 40 px (--smoke): x 0.5 ... 760.5 (20), y 0.5 ... 440.5 (12): 240
    ("# run: smoke, error grid every 40 px, not timed", "x = 0.5, 40.5, … 760.5, y = 0.5 … 440.5 (240 points"),
    ("# date: 2026-11-30", "on ff-bench's grid (its step not recorded in host_cases.csv, between pixel centres"),
])
def test_the_error_grid_is_the_one_ff_bench_says_it_used(run, run_line, grid):
    host = run["folder"] / "host" / "host_cases.csv"
    host.write_text("".join(run_line + "\n" if line.startswith("# run:") else line
                            for line in host.read_text().splitlines(keepends=True)))
    text = make_report.report(run["rows"], run["m4"], run["trackers"], args_for(run["folder"]))
    assert grid in text.split("## Goals")[0]


def test_the_header_says_how_the_numbers_were_made(run):
    head = run["text"].split("## Goals")[0]
    assert head.startswith("# Benchmarks: run time against error for every evaluation strategy\n")
    assert "(measured at start-up against a loop of known length: 40 instructions per count)" in head
    assert "- **Run**: core at test\n" in head
    # what docs/benchmarks.csv holds: one row per scene and strategy, none of the per-scene cycle, tracker,
    # component or accuracy figures (see write_csv's columns)
    assert ("do not edit by hand. The per-strategy figures (*Built-in scenes at their default*, *Scene "
            "preparation*, *Every strategy*) are in `docs/benchmarks.csv` too, one row per scene and strategy; "
            "the cycle model's, the trackers', *Where the time goes* and the accuracy on the target are only "
            "here.") in head
    host_only = make_report.report(run["rows"], None, run["trackers"], args_for(run["folder"], environment=""))
    assert "known length: not run)" in host_only and "**Run**" not in host_only
    assert "![M4 instructions per tick against max error, one point per strategy](img/benchmarks.png)" \
           in run["text"]
    linked = make_report.report(run["rows"], run["m4"], run["trackers"],
                                args_for(run["folder"], png_link="https://example.org/b.png"))
    assert "(https://example.org/b.png)" in linked


def drawn(rows, have_m4, monkeypatch):
    saved = []
    monkeypatch.setattr(make_report.ff_files, "save_figure", lambda fig, path, *a, **k: saved.append((fig, path, a, k)))
    make_report.plot(rows, "b.png", have_m4)
    assert len(saved) == 1
    return saved[0]


def test_the_figure_has_a_panel_per_scene_its_strategies_and_their_pareto_front(run, monkeypatch):
    fig, path, says, options = drawn(run["rows"], True, monkeypatch)
    assert (path, says, options) == ("b.png", ("tools/bench/make_report.py",
                                               "every evaluation strategy's cost against its error"),
                                     {"dpi": 90, "bbox_inches": "tight"})
    assert [ax.get_title() for ax in fig.axes] == ["heightmap-top", "heightmap-middle", "tunnel-pilot-a",
                                                   "tunnel-pilot-b", "pilot-c-top", "bump-map", "frictionmap-top",
                                                   "familiarisation-path", "general-6"]
    hm = fig.axes[0]
    # per strategy: (M4 tick, max LSB); marker area 12 + 220 sqrt(bytes / 3.1 MB)
    points = [tuple(c.get_offsets()[0]) for c in hm.collections]
    assert points == [(850, 0.5), (750, 2.0), (740, 0.8), (800, 3.0)]
    assert [c.get_sizes()[0] for c in hm.collections] == pytest.approx(
        [12 + 220 * (b / 3.1e6) ** 0.5 for b in (2000, 50000, 3074000, 98000)])
    # hollow: the 1 px float table does not fit a slot
    assert [len(c.get_facecolor()) for c in hm.collections] == [1, 1, 0, 1]
    front, goal_error, goal_ticks = hm.lines
    assert (list(front.get_xdata()), list(front.get_ydata()), front.get_drawstyle()) == ([740, 850], [0.8, 0.5],
                                                                                          "steps-post")
    assert list(goal_error.get_ydata()) == [1.0, 1.0] and list(goal_ticks.get_xdata()) == [1000, 1000]
    assert [t.get_text() for t in hm.texts] == ["closed-form", "4px-int16-gradient"]
    assert hm.get_yscale() == "log" and hm.get_ylim() == (5e-5, 5000)
    assert hm.get_xlabel() == "M4 instructions per whole tick (≈ = estimated)"
    assert hm.get_ylabel() == "max amplitude error, DAC LSB"
    assert all(line.get_visible() for line in hm.xaxis.get_gridlines() + hm.yaxis.get_gridlines())
    assert all(tick.gridline.get_visible() for tick in hm.yaxis.get_minor_ticks())  # the log scale's too
    assert len(fig.axes[8].collections) == 0 and len(fig.axes[8].lines) == 2  # no strategy: no front
    legend = [t.get_text() for t in fig.legends[0].get_texts()]
    assert len(legend) == len(make_report.FAMILIES) + 3 and legend[-1] == "goals: 1 LSB, 1,000 instructions"
    assert fig._suptitle.get_text().startswith("Cost against error for every evaluation strategy")


def test_without_the_m4_the_figure_plots_host_time_and_an_exact_zero_at_the_floor(run, monkeypatch):
    rows = [dict(r, max_lsb="0") if r["id"] == "bump-map/closed-form" else r for r in run["rows"]]
    rows = [dict(r, host_eval_ns="") if r["id"] == "heightmap-top/table-4px-int16-gradient" else r for r in rows]
    fig = drawn(rows, False, monkeypatch)[0]
    bump = fig.axes[5]
    assert [tuple(c.get_offsets()[0]) for c in bump.collections] == [(29, 1e-4), (10, 0.9)]
    # a strategy without a cost is left out, and so is one without an error
    assert [tuple(c.get_offsets()[0]) for c in fig.axes[0].collections] == [(17, 0.5), (9, 0.8), (12, 3.0)]
    rows = [dict(r, max_lsb="") if r["id"] == "heightmap-top/closed-form" else r for r in rows]
    assert [tuple(c.get_offsets()[0]) for c in drawn(rows, False, monkeypatch)[0].axes[0].collections] == [
        (9, 0.8), (12, 3.0)]
    assert len(bump.lines) == 2 and bump.get_xlabel() == "host ns per evaluation"  # no instruction goal


def test_the_whole_report_is_as_it_was(run, monkeypatch):
    """A change detector: every line the checks above leave alone (the prose, each table's header, the
    blank lines between). Rewrite it with `python3 tools/bench/test_make_report_tables.py --update-golden`
    after a deliberate change, and read its diff."""
    monkeypatch.setattr(make_report, "host_cpu", lambda: "a test machine")
    text = make_report.report(run["rows"], run["m4"], run["trackers"], args_for(run["folder"]))
    with open(GOLDEN, encoding="utf-8") as f:
        assert golden_text(text) == f.read()


def test_the_host_cpu_is_the_model_name_linux_reports(monkeypatch):
    try:
        with open("/proc/cpuinfo") as f:
            names = [line.split(":", 1)[1].strip() for line in f if line.startswith("model name")]
    except OSError:
        names = []
    if names:
        assert make_report.host_cpu() == names[0]
    real_open = open

    def no_cpuinfo(path, *args, **kwargs):
        if path == "/proc/cpuinfo":
            raise OSError("no /proc here")
        return real_open(path, *args, **kwargs)
    monkeypatch.setattr("builtins.open", no_cpuinfo)
    monkeypatch.setattr(make_report.platform, "processor", lambda: "")
    assert make_report.host_cpu() == "?"
    monkeypatch.setattr(make_report.platform, "processor", lambda: "arm64")
    assert make_report.host_cpu() == "arm64"


# ------------------------------------------------------------- the whole tool


def make_output_folders(args):
    for path in (args.md, args.csv, args.png):
        os.makedirs(os.path.dirname(path), exist_ok=True)


def test_main_writes_the_report_the_csv_and_the_figure(run, monkeypatch, capsys):
    folder = run["folder"]
    args = args_for(folder)
    make_output_folders(args)
    argv = ["make_report.py", "--host", args.host, "--m4", args.m4, "--md", args.md, "--csv", args.csv,
            "--png", args.png, "--cycles", args.cycles, "--m4-accuracy", args.m4_accuracy, "--environment", "x"]
    monkeypatch.setattr(sys, "argv", argv)
    make_report.main()
    assert capsys.readouterr().out == f"make_report: wrote {args.md}, {args.csv}, {args.png} (11 strategies)\n"
    csv_lines = open(args.csv).read().splitlines()
    assert csv_lines[0] == "# tool: tools/bench/make_report.py"
    assert csv_lines[2] == (f"# input: --host {args.host}, --m4 {args.m4}, --cycles {args.cycles}, "
                            f"--m4-accuracy {args.m4_accuracy}")
    assert csv_lines[3:5] == ["# environment: x", f"# what: every figure of {args.md}, one row per scene and "
                                                  "evaluation strategy"]
    assert len(make_report.read_plain_csv(args.csv)) == 11
    assert open(args.md).read().startswith("# Benchmarks:") and os.path.getsize(args.png) > 0
    from PIL import Image
    with Image.open(args.png) as image:  # the figure names its inputs as the CSV does (docs/tools.md)
        description = image.text["Description"]
    assert description.startswith("every evaluation strategy's cost against its error; "
                                  "tool: tools/bench/make_report.py; date: 20")
    assert description.endswith(f"; input: --host {args.host}, --m4 {args.m4}, --cycles {args.cycles}, "
                                f"--m4-accuracy {args.m4_accuracy}; environment: x")


def test_run_as_a_script_it_finds_its_modules_and_says_a_crashed_harness_in_one_line(tmp_path):
    write_run(tmp_path, m4_done=False)
    args = args_for(tmp_path)
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    r = subprocess.run([sys.executable, TOOL, "--host", args.host, "--m4", args.m4, "--md", args.md, "--csv",
                        args.csv, "--png", args.png], capture_output=True, text=True, env=env, cwd=str(tmp_path))
    assert (r.returncode, r.stdout) == (2, "")  # docs/tools.md: an incomplete input is bad input
    assert r.stderr == f"make_report: {args.m4} is incomplete (no done line): did the harness crash?\n"
    (tmp_path / "whole").mkdir()
    write_run(tmp_path / "whole")
    args = args_for(tmp_path / "whole")
    make_output_folders(args)
    r = subprocess.run([sys.executable, TOOL, "--host", args.host, "--md", args.md, "--csv", args.csv, "--png",
                        args.png], capture_output=True, text=True, env=env, cwd=str(tmp_path))
    assert r.returncode == 0 and r.stdout.startswith(f"make_report: wrote {args.md}"), r.stderr


@pytest.mark.parametrize("done, errors, failures, status, says", [
    # killed midway: an incomplete input, bad input (docs/tools.md)
    (False, (), 0, 2, "is incomplete (no done line): did the harness crash?"),
    # whole, but cases failed on the M4: the tool ran and a check failed
    (True, ("prepare,heightmap-top", "tick,vortex"), 0, 1,
     "the harness reported errors: prepare,heightmap-top; tick,vortex"),
    # whole, but its own checks (a DAC code out of range, a finger lost) failed 3 times
    (True, (), 3, 1, "the harness counted 3 failed checks (its done line)"),
])
def test_a_harness_run_that_crashed_or_failed_writes_nothing(tmp_path, done, errors, failures, status, says):
    write_run(tmp_path, m4_done=done, m4_errors=errors, m4_failures=failures)
    args = args_for(tmp_path)
    make_output_folders(args)
    r = subprocess.run([sys.executable, TOOL, "--host", args.host, "--m4", args.m4, "--md", args.md, "--csv",
                        args.csv, "--png", args.png], capture_output=True, text=True)
    assert (r.returncode, r.stdout) == (status, "")
    assert says in r.stderr and len(r.stderr.splitlines()) == 1, r.stderr
    assert os.listdir(tmp_path / "out") == ["img"] and os.listdir(tmp_path / "out" / "img") == []


def cut(path, lines, fields=None):
    """The file cut short after its first `lines` lines, and `fields` fields into the next one if given."""
    kept = path.read_text().splitlines(keepends=True)
    path.write_text("".join(kept[:lines]) + (",".join(kept[lines].split(",")[:fields]) if fields else ""))


def drop_lines(path, *containing):
    path.write_text("".join(line for line in path.read_text().splitlines(keepends=True)
                            if not any(text in line for text in containing)))


def rewrite_line(path, number, change):
    """The file with its line `number` (from 1) replaced by change(line)."""
    lines = path.read_text().splitlines(keepends=True)
    lines[number - 1] = change(lines[number - 1])
    path.write_text("".join(lines))


def first_fields(line, fields):
    return ",".join(line.split(",")[:fields]) + "\n"


# m4bench.txt as write_run makes it: line 1 m4bench, 2 calibration, 3-13 the 11 cases in M4's order (3 neutral),
# 14-15 the trackers, then the stopwatch, the components and done. host_cases.csv: two '#' lines, the header
# (25 columns), then the rows in HOST's order (4 neutral, 5 heightmap-top/closed-form). cycles.csv: a '#' line,
# the header, then neutral (3), heightmap-top (4), bump-map (5).
@pytest.mark.parametrize("edit, says", [
    # the harness's output cut in a line or at a line's end (killed, a full disk), or edited
    (lambda f: cut(f / "m4bench.txt", 3, fields=9), "{m4}:4: a case line of 9 fields, ff-m4bench writes 15"),
    (lambda f: cut(f / "m4bench.txt", 4), "{m4} is incomplete (no done line): did the harness crash?"),
    (lambda f: cut(f / "m4bench.txt", 0), "{m4} is incomplete (no done line): did the harness crash?"),
    (lambda f: drop_lines(f / "m4bench.txt", "calibration,"), "{m4} is incomplete (no calibration line)"),
    (lambda f: drop_lines(f / "m4bench.txt", ",neutral/closed-form,", ",bump-map/closed-form,"),
     "{m4} is incomplete (no case line for neutral/closed-form, bump-map/closed-form, which {host_cases} has)"),
    (lambda f: rewrite_line(f / "m4bench.txt", 14, lambda line: first_fields(line, 4)),
     "{m4}:14: a tracker line of 4 fields, ff-m4bench writes 5 to 7"),
    (lambda f: rewrite_line(f / "m4bench.txt", 2, lambda line: "calibration,forty\n"),
     "{m4}:2: calibration instructions_per_count 'forty' is not a whole number"),
    (lambda f: rewrite_line(f / "m4bench.txt", 3, lambda line: line.replace(",69632,2048,", ",69632,0,")),
     "{m4}:3: case evaluations is 0: nothing was measured"),
    # ff-bench's CSVs, the cycle model's and ff-m4accuracy's
    (lambda f: rewrite_line(f / "host" / "host_cases.csv", 3, lambda line: line.replace(",max_lsb,", ",max,")),
     "{host_cases}: no column max_lsb"),
    (lambda f: rewrite_line(f / "host" / "host_cases.csv", 4, lambda line: first_fields(line, 10)),
     "{host_cases}:4: 10 fields, the header names 25"),
    (lambda f: rewrite_line(f / "host" / "host_cases.csv", 5, lambda line: line.replace(",1,5000,", ",yes,5000,")),
     "{host_cases}:5: fits_teensy 'yes' is not a whole number"),
    (lambda f: rewrite_line(f / "host" / "host_trackers.csv", 2, lambda line: "config,ns\n"),
     "{host_trackers}: no column host_update_ns"),
    (lambda f: rewrite_line(f / "cycles.csv", 4, lambda line: line.replace(",8142,", ",,")),
     "{cycles}:4: cycles_worst_max '' is not a number"),
    (lambda f: rewrite_line(f / "cycles.csv", 3, lambda line: line.replace(",105,327", ",105,327.5")),
     "{cycles}:3: isr_worst '327.5' is not a whole number"),
    (lambda f: rewrite_line(f / "m4accuracy.csv", 2, lambda line: line.replace(",codes_off", ",off")),
     "{accuracy}: no column codes_off"),
])
def test_an_incomplete_or_malformed_input_is_one_line_exit_2_and_writes_nothing(tmp_path, edit, says):
    write_run(tmp_path)
    edit(tmp_path)
    args = args_for(tmp_path)
    make_output_folders(args)
    r = subprocess.run([sys.executable, TOOL, "--host", args.host, "--m4", args.m4, "--md", args.md, "--csv",
                        args.csv, "--png", args.png, "--cycles", args.cycles, "--m4-accuracy", args.m4_accuracy],
                       capture_output=True, text=True)
    said = says.format(m4=args.m4, host_cases=os.path.join(args.host, "host_cases.csv"),
                       host_trackers=os.path.join(args.host, "host_trackers.csv"), cycles=args.cycles,
                       accuracy=args.m4_accuracy)
    assert (r.returncode, r.stdout, r.stderr) == (2, "", f"make_report: {said}\n")
    assert os.listdir(tmp_path / "out") == ["img"] and os.listdir(tmp_path / "out" / "img") == []


@pytest.mark.parametrize("name", ["m4bench.txt", "host/host_cases.csv", "cycles.csv"])
def test_an_input_that_is_not_utf8_text_is_one_line_exit_2(tmp_path, name):
    write_run(tmp_path)
    (tmp_path / name).write_bytes((tmp_path / name).read_bytes().replace(b"neutral", b"neutr\xe9l"))
    args = args_for(tmp_path)
    make_output_folders(args)
    r = subprocess.run([sys.executable, TOOL, "--host", args.host, "--m4", args.m4, "--md", args.md, "--csv",
                        args.csv, "--png", args.png, "--cycles", args.cycles], capture_output=True, text=True)
    assert (r.returncode, r.stdout) == (2, "")
    assert r.stderr.startswith(f"make_report: {tmp_path / name}: not UTF-8 text (") and len(r.stderr.splitlines()) == 1


def test_an_output_in_a_missing_folder_is_one_line_and_exit_2(tmp_path):
    write_run(tmp_path)
    args = args_for(tmp_path)  # out/ and out/img/ do not exist: not made
    r = subprocess.run([sys.executable, TOOL, "--host", args.host, "--m4", args.m4, "--md", args.md, "--csv",
                        args.csv, "--png", args.png], capture_output=True, text=True)
    assert (r.returncode, r.stdout) == (2, "")
    assert r.stderr == f"make_report: {args.csv}: no such folder: {tmp_path / 'out'}\n"
    assert not os.path.exists(tmp_path / "out")


def test_an_output_that_is_an_input_is_refused_before_anything_is_written(tmp_path):
    write_run(tmp_path)
    args = args_for(tmp_path)
    make_output_folders(args)
    harness = (tmp_path / "m4bench.txt").read_text()
    r = subprocess.run([sys.executable, TOOL, "--host", args.host, "--m4", args.m4, "--md", args.md, "--csv",
                        args.m4, "--png", args.png], capture_output=True, text=True)
    assert (r.returncode, r.stdout) == (2, "")
    assert r.stderr == f"make_report: output {args.m4} is the input {args.m4}: a tool never writes over its own input\n"
    assert (tmp_path / "m4bench.txt").read_text() == harness and os.listdir(tmp_path / "out") == ["img"]


def test_a_run_without_neutral_reports_without_the_comparison_and_writes_all_three_files(tmp_path):
    # scripts/run-benchmarks --filter heightmap: no neutral/closed-form row to set the heightmap against
    write_run(tmp_path)
    host = tmp_path / "host" / "host_cases.csv"
    host.write_text("".join(line for line in host.read_text().splitlines(keepends=True)
                            if not line.startswith("neutral/")))
    m4 = tmp_path / "m4bench.txt"
    m4.write_text("".join(line for line in m4.read_text().splitlines(keepends=True) if ",neutral/" not in line))
    args = args_for(tmp_path)
    make_output_folders(args)
    r = subprocess.run([sys.executable, TOOL, "--host", args.host, "--m4", args.m4, "--md", args.md, "--csv",
                        args.csv, "--png", args.png], capture_output=True, text=True)
    assert r.returncode == 0 and r.stderr == "", r.stderr
    text = open(args.md).read()
    assert section(text, "Where the time goes (M4 instructions per tick)") == [
        "", "No neutral/closed-form row in this run (a filtered run?): the tick's pieces, set against neutral's, "
        "are left out.", ""]
    assert "neutral costs a small fraction" not in text
    assert len(make_report.read_plain_csv(args.csv)) == 10 and os.path.getsize(args.png) > 0


if __name__ == "__main__" and sys.argv[1:] == ["--update-golden"]:
    import tempfile
    import pathlib
    folder = pathlib.Path(tempfile.mkdtemp())
    write_run(folder)
    make_report.host_cpu = lambda: "a test machine"
    cases, trackers = make_report.read_host(str(folder / "host"))
    m4 = make_report.read_m4(str(folder / "m4bench.txt"))
    report = make_report.report(make_report.merge(cases, m4), m4, trackers, args_for(folder))
    os.makedirs(os.path.dirname(GOLDEN), exist_ok=True)
    with open(GOLDEN, "w", encoding="utf-8") as f:
        f.write(golden_text(report))
    print("wrote", GOLDEN)
