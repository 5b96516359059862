#!/usr/bin/env python3
"""The trace classes as a user runs them: ff-track-bench --classes / --class
and ff-tracegen --class and the effect options, as subprocesses, with exit
codes (0 ok, 1 failed check, 2 bad usage) and what they print.

usage: trace_classes_cli_test.py path/to/ff-track-bench path/to/ff-tracegen
"""
import csv
import io
import math
import os
import re
import shlex
import subprocess
import sys
import tempfile
import unittest

import tune_log

BENCH = TRACEGEN = None
REPO = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", ".."))
CLASSES = ["white-200hz", "slow-fingers", "tremor", "latency", "correlated-noise",
           "realistic-100hz", "realistic-200hz", "realistic-1khz"]


def run(*args):
    return subprocess.run([str(a) for a in args], capture_output=True, text=True)


def cells_of(line):
    """The cells of a Markdown table row."""
    return [c.strip() for c in line.strip().strip("|").split("|")]


def table_rows(out):
    """{(class, tracker): [cells]} of the per-class table."""
    rows = {}
    for line in out.splitlines():
        cells = cells_of(line)
        if len(cells) == 12 and cells[0] in CLASSES:
            rows[(cells[0], cells[1])] = cells
    return rows


def ratio(cell):
    return float(cell.rstrip("×"))


def table_after(out, header_start):
    """{class: [cells]} of the printed table whose header row starts with these cells."""
    rows, inside = {}, False
    for line in out.splitlines():
        cells = cells_of(line)
        if not line.startswith("|"):
            inside = False
        elif cells[:len(header_start)] == header_start:
            inside = True
        elif inside and cells[0] in CLASSES:
            rows[cells[0]] = cells
    return rows


class TrackBenchClasses(unittest.TestCase):
    def test_every_class_has_the_thesis_pipeline_and_recommended(self):
        res = run(BENCH, "--classes", "--duration", "2")
        self.assertEqual(res.returncode, 0, res.stderr)
        rows = table_rows(res.stdout)
        self.assertEqual(len(rows), 3 * len(CLASSES), res.stdout)
        for name in CLASSES:
            thesis = rows[(name, "thesis")]
            # The baseline's ratios to itself are 1; the others are value / baseline.
            self.assertEqual(thesis[6], "1.00×")
            for tracker in ("recommended()", "recommended(profile)"):
                row = rows[(name, tracker)]
                self.assertAlmostEqual(ratio(row[6]), float(row[5]) / float(thesis[5]), delta=0.02)
                self.assertEqual(thesis[11], row[11])  # the same traces for all
        self.assertIn("moves above 4 mm/s", res.stdout)
        self.assertIn("Generated traces, not a sensor", res.stdout)

    def test_white_200hz_at_10_mm_s_is_the_standard_tables_low_noise_rows(self):
        # The same six traces two ways: the class machinery and the standard set.
        classes = run(BENCH, "--class", "white-200hz", "--moving-above", "50", "--duration", "4")
        standard = run(BENCH, "--duration", "4")
        self.assertEqual(classes.returncode, 0, classes.stderr)
        self.assertEqual(standard.returncode, 0, standard.stderr)
        rows = table_rows(classes.stdout)
        self.assertEqual(len(rows), 3)
        # The standard table tells recommended() each level's noise: the class's profile row.
        for tracker, standard_name in (("thesis", "thesis (ticks + 1-euro, filtered derivative)"),
                                       ("recommended(profile)", "recommended()")):
            line = next(l for l in standard.stdout.splitlines() if l.startswith("| %s | low |" % standard_name))
            cells = cells_of(line)
            mine = rows[("white-200hz", tracker)]
            self.assertEqual(mine[2], cells[4])  # lag
            self.assertEqual(mine[3], cells[2])  # position RMSE
            self.assertEqual(mine[5], cells[7])  # heightmap amplitude RMS
            self.assertEqual(mine[7], cells[9])  # frictionmap amplitude RMS

    def test_write_doc_fills_its_own_markers(self):
        with tempfile.TemporaryDirectory() as tmp:
            doc = os.path.join(tmp, "doc.md")
            with open(doc, "w") as f:
                f.write("# T\n<!-- track-bench:begin -->\nmain table\n<!-- track-bench:end -->\n"
                        "<!-- track-bench-classes:begin -->\nold\n<!-- track-bench-classes:end -->\nafter\n")
            res = run(BENCH, "--class", "latency", "--duration", "2", "--write-doc", doc)
            self.assertEqual(res.returncode, 0, res.stderr)
            with open(doc) as f:
                text = f.read()
            self.assertIn("main table", text)  # the other table untouched
            self.assertNotIn("\nold\n", text)
            self.assertIn("| latency | recommended() |", text)
            self.assertTrue(text.endswith("<!-- track-bench-classes:end -->\nafter\n"))
            self.assertEqual(res.stderr.splitlines()[-1], "ff-track-bench: table written to " + doc)
            self.assertEqual(os.listdir(tmp), ["doc.md"])  # written through doc.md.partial, renamed

    def test_csv_holds_the_tables_figures_with_metadata(self):
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "classes.csv")
            res = run(BENCH, "--class", "white-200hz", "--class", "tremor", "--duration", "3", "--csv", path)
            self.assertEqual(res.returncode, 0, res.stderr)
            with open(path) as f:
                lines = f.read().splitlines()
            self.assertFalse(os.path.exists(path + ".partial"))
        # A progress line per class as it starts, the file's name at the end.
        self.assertEqual([l for l in res.stderr.splitlines() if l.startswith("ff-track-bench: ")],
                         ["ff-track-bench: class white-200hz: generating 6 traces of 3 s...",
                          "ff-track-bench: class tremor: generating 6 traces of 3 s...",
                          "ff-track-bench: figures written to " + path])
        meta = [l for l in lines if l.startswith("#")]
        self.assertTrue(any(l.startswith("# tool: ff-track-bench --classes") for l in meta), meta)
        self.assertTrue(any("3 s each" in l for l in meta), meta)
        rows = list(csv.DictReader(l for l in lines if not l.startswith("#")))
        self.assertEqual([(r["class"], r["tracker"]) for r in rows],
                         [(c, t) for c in ("white-200hz", "tremor")
                          for t in ("thesis", "recommended()", "recommended(profile)")])
        table = table_rows(res.stdout)
        for r in rows:
            cells = table[(r["class"], r["tracker"])]
            self.assertEqual("%.2f" % float(r["lag_ms"]), cells[2])
            self.assertEqual("%.3f" % float(r["heightmap_rms"]), cells[5])
            self.assertEqual("%.2f×" % float(r["heightmap_vs_thesis"]), cells[6])
            self.assertEqual("%.3f" % float(r["rest_rms"]), cells[9])
            # The unfaded error only where it was measured: the shipping rows.
            self.assertEqual(r["unfaded_heightmap_rms"] != "", r["tracker"] == "recommended(profile)")
            self.assertNotEqual(r["floor_1.0px_rms"], "")
            # The lookahead bound per class, on every row; more lookahead, less error.
            bound = [float(r["lookahead_%s_rms" % k]) for k in ("0ms", "10ms", "30ms", "100ms")]
            self.assertEqual(bound, sorted(bound, reverse=True), r["class"])
            self.assertNotEqual(r["lookahead_whole_rms"], "")
            # Anchored at rest by a perfect start detector, but causal: above the whole-stroke smoother.
            self.assertGreater(float(r["anchored_0ms_rms"]), float(r["lookahead_whole_rms"]), r["class"])
            # Told all but the direction: under the anchored bound and the tracker here (a floor on average over
            # strokes turned at random, not a strict bound: direction_bound.hpp).
            self.assertGreater(float(r["direction_bound_rms"]), 0.0, r["class"])
            self.assertLess(float(r["direction_bound_rms"]), float(r["anchored_0ms_rms"]), r["class"])
            self.assertLess(float(r["direction_bound_rms"]), float(r["heightmap_rms"]), r["class"])
            # Told only the standstills: above nothing, under the shipping tracker (heading_bound.hpp).
            self.assertGreater(float(r["heading_bound_rms"]), 0.0, r["class"])
            if r["tracker"] == "recommended(profile)":
                self.assertLess(float(r["heading_bound_rms"]), float(r["heightmap_rms"]), r["class"])
        self.assertIn("| white-200hz | %.3f |" % float(rows[0]["heightmap_rms"]), res.stdout)  # the bound's table
        # Five tables, each after a blank line (or a paragraph would swallow it in Markdown).
        printed = res.stdout.splitlines()
        headers = [i for i, line in enumerate(printed) if line.startswith("| class |")]
        self.assertEqual(len(headers), 5, res.stdout)
        self.assertEqual(headers[0], 0)
        self.assertTrue(all(printed[i - 1] == "" for i in headers[1:]), res.stdout)
        # The start floors: the error of a tracker blind for the first d px after each standstill grows with d; the
        # shipping tracker's cells are the class table's, faded and never faded.
        floors = table_after(res.stdout, ["class", "thesis HM amp RMS", "floor, direction from 0.5 px"])
        bounds = table_after(res.stdout, ["class", "thesis HM amp RMS", "recommended(profile)", "causal, 0 ms ahead"])
        self.assertEqual(sorted(floors), ["tremor", "white-200hz"])
        for r in rows:
            floor = [float(r["floor_%spx_rms" % d]) for d in ("0.5", "1.0", "2.0")]
            self.assertTrue(0.0 < floor[0] < floor[1] < floor[2], (r["class"], floor))
            # The heading model's three runs are three: told the standstills, ended by the full fit, by the
            # tracker's own predictor (the only ones that count ends).
            self.assertGreater(int(r["predicted_ends_found"]), 0, r["class"])
            self.assertNotEqual(r["predicted_ends_rms"], r["heading_bound_rms"], r["class"])
            self.assertGreater(int(r["tracker_ends_found"]), 0, r["class"])
            self.assertNotEqual(r["tracker_ends_rms"], r["predicted_ends_rms"], r["class"])
            if r["tracker"] == "thesis":
                for per_class in (floors, bounds):
                    self.assertEqual(per_class[r["class"]][1], table[(r["class"], "thesis")][5])
            if r["tracker"] != "recommended(profile)":
                continue
            cells = table[(r["class"], r["tracker"])]
            shipping = "%s (%s)" % (cells[5], cells[6])
            self.assertEqual(floors[r["class"]][5], shipping)
            self.assertEqual(bounds[r["class"]][2], shipping)
            self.assertEqual(floors[r["class"]][6].split()[0], "%.3f" % float(r["unfaded_heightmap_rms"]))
        self.assertIn("whole stroke (RTS)", res.stdout)
        self.assertIn("causal, anchored at rest", res.stdout)
        self.assertIn("told all but each stroke's direction", res.stdout)
        self.assertIn("told when each stroke starts", res.stdout)

    def test_dump_ticks_writes_the_classes_six_traces_with_metadata(self):
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "tremor.csv")
            res = run(BENCH, "--class", "tremor", "--duration", "2", "--direction-q", "60", "--dump-ticks", path)
            self.assertEqual(res.returncode, 0, res.stderr)
            names = ["tremor.csv"] + ["tremor.csv.%d" % i for i in range(1, 6)]
            self.assertEqual(sorted(os.listdir(tmp)), sorted(names))  # no .partial left behind
            traces, tremor_hz = set(), set()
            for name in names:
                with open(os.path.join(tmp, name)) as f:
                    lines = f.read().splitlines()
                meta = dict(l[2:].split(": ", 1) for l in lines if l.startswith("# "))
                self.assertEqual(set(meta), {"tool", "date", "trace", "tracker", "sensor_profile", "what"}, name)
                self.assertTrue(meta["tool"].startswith("ff-track-bench --dump-ticks "))
                self.assertTrue(meta["trace"].startswith("tremor "), meta["trace"])
                self.assertIn("direction q 60,", meta["tracker"])  # the options' tracker, not the default
                traces.add(meta["trace"])
                flags = meta["sensor_profile"].split()
                tremor_hz.add(float(flags[flags.index("--tremor-hz") + 1]))
                rows = list(csv.DictReader(l for l in lines if not l.startswith("#")))
                self.assertGreater(len(rows), 1000, name)  # 2 s of 500 us ticks and more
                steps = {int(b["t_us"]) - int(a["t_us"]) for a, b in zip(rows, rows[1:])}
                self.assertEqual(steps, {500}, name)
                for r in rows:
                    self.assertTrue(0.0 <= float(r["hm"]) <= 1.0 and 0.0 <= float(r["hm_ideal"]) <= 1.0, r)
            self.assertEqual(len(traces), 6)
            # Each trace is told its own tremor, drawn in 8-12 Hz (docs/tracking.md#trace-classes).
            self.assertEqual(len(tremor_hz), 6)
            self.assertTrue(all(8.0 <= hz <= 12.0 for hz in tremor_hz), tremor_hz)
            breakdown = os.path.join(REPO, "tools", "track_bench", "standstill_breakdown.py")
            res = run(sys.executable, breakdown, *[os.path.join(tmp, n) for n in names])
            self.assertEqual(res.returncode, 0, res.stderr)

    def test_a_dump_or_doc_that_cannot_be_written_exits_2_and_leaves_nothing(self):
        with tempfile.TemporaryDirectory() as tmp:
            res = run(BENCH, "--class", "latency", "--duration", "2",
                      "--dump-ticks", os.path.join(tmp, "missing", "d.csv"))
            self.assertEqual(res.returncode, 2)
            self.assertEqual(res.stderr.strip().splitlines()[-1],
                             "ff-track-bench: cannot write %s: No such file or directory"
                             % os.path.join(tmp, "missing", "d.csv"))
            self.assertEqual(res.stdout, "")  # refused before the class is evaluated
            # The CSV is written after the tables are printed.
            res = run(BENCH, "--class", "latency", "--duration", "2", "--csv", os.path.join(tmp, "missing", "c.csv"))
            self.assertEqual(res.returncode, 2)
            self.assertEqual(res.stderr.splitlines()[-1],
                             "ff-track-bench: cannot write %s: No such file or directory"
                             % os.path.join(tmp, "missing", "c.csv"))
            self.assertIn("| latency | thesis |", res.stdout)
            res = run(BENCH, "--class", "latency", "--duration", "2", "--write-doc", tmp)  # a folder
            self.assertEqual(res.returncode, 2)
            self.assertIn("cannot write %s: Is a directory" % tmp, res.stderr)
            self.assertEqual(os.listdir(tmp), [])
            # The doc is written whole through doc.md.partial, then renamed: where the partial
            # file cannot be made (a folder in its way here), the doc stays as it was.
            doc = os.path.join(tmp, "doc.md")
            with open(doc, "w") as f:
                f.write("kept\n")
            os.mkdir(doc + ".partial")
            res = run(BENCH, "--class", "latency", "--duration", "2", "--write-doc", doc)
            self.assertEqual(res.returncode, 2)
            with open(doc) as f:
                self.assertEqual(f.read(), "kept\n")

    def test_bad_usage_exits_2(self):
        res = run(BENCH, "--csv", "x.csv")
        self.assertEqual(res.returncode, 2)
        self.assertIn("--csv needs --classes", res.stderr)
        self.assertEqual(run(BENCH, "--class", "no-such-class").returncode, 2)
        res = run(BENCH, "--classes", "--trace", __file__)
        self.assertEqual(res.returncode, 2)
        self.assertIn("--classes", res.stderr)

    def test_a_value_that_is_not_a_finite_number_is_a_usage_error(self):
        # CLI11's range checks let nan through (every comparison with it is
        # false): --duration nan crashed ff-tracegen, --rate nan hung it,
        # --jitter-us nan wrote stamps near 2^63; ff-track-bench took
        # --white-noise-px nan and fell back to the default profile quietly.
        for tool, args in ((TRACEGEN, ["--duration", "nan"]), (TRACEGEN, ["--rate", "nan"]),
                           (TRACEGEN, ["--jitter-us", "NaN"]), (TRACEGEN, ["--noise-px", "inf"]),
                           (TRACEGEN, ["--duration", "1e999"]), (BENCH, ["--class", "white-200hz", "--white-noise-px", "nan"])):
            res = run(tool, *args, "-q") if tool is TRACEGEN else run(tool, *args)
            self.assertEqual(res.returncode, 2, args)
            self.assertIn(args[-1], res.stderr)  # inf is out of every range already; nan is caught after
            if args[-1].lower() == "nan":
                self.assertEqual(res.stderr.splitlines()[-1].split(": ", 1)[1], f"{args[-2]} {args[-1]}: not a finite number")

    def test_counts_seeds_and_start_times_outside_their_ranges_are_refused_not_wrapped(self):
        # -1 wrapped to 2^64 - 1 (the same trace as 2^64, which CLI11 clamped);
        # --start-us -1 wrote stamps wrapping from 2^64 - 1; 5,000,000 gaps hung.
        for args in (["--seed", "-1"], ["--seed", "18446744073709551616"], ["--start-us", "-1"],
                     ["--start-us", str(2**53 + 1)], ["--missing", "5000000"], ["--lifts", "1000000"]):
            res = run(TRACEGEN, *args, "-q", "--duration", "1")
            self.assertEqual(res.returncode, 2, args)
            self.assertIn(args[0], res.stderr)
        self.assertEqual(run(TRACEGEN, "--seed", str(2**53), "-q", "--duration", "1").returncode, 0)

    def test_truth_ticks_into_the_trace_itself_is_refused(self):
        with tempfile.TemporaryDirectory() as d:
            trace = os.path.join(d, "t.csv")
            res = run(TRACEGEN, "-q", "--duration", "1", "-o", trace, "--truth-ticks", os.path.join(d, ".", "t.csv"))
            self.assertEqual(res.returncode, 2)
            self.assertIn("is the trace's own file", res.stderr)
            self.assertFalse(os.path.exists(trace))

    def test_frontier_sweeps_the_fade_and_marks_its_pareto_front(self):
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "frontier.csv")
            res = run(BENCH, "--frontier", "--class", "white-200hz", "--class", "realistic-200hz", "--duration", "2",
                      "--csv", path)
            self.assertEqual(res.returncode, 0, res.stderr)
            with open(path) as f:
                lines = f.read().splitlines()
        meta = [l for l in lines if l.startswith("#")]
        self.assertTrue(any(l.startswith("# tool: ff-track-bench --frontier") for l in meta), meta)
        self.assertTrue(any(l.startswith("# date: ") for l in meta), meta)
        rows = list(csv.DictReader(l for l in lines if not l.startswith("#")))
        for name in ("white-200hz", "realistic-200hz"):
            points = [r for r in rows if r["class"] == name]
            self.assertEqual(len(points), 40)
            shipping = [r for r in points if r["shipping"] == "1"]
            self.assertEqual([(r["rest_sigmas"], r["moving_sigmas"]) for r in shipping], [("2.50", "5.00")])
            self.assertEqual(points[0]["heightmap_goal"], "0.35" if name == "white-200hz" else "0.45")
            # The front, by brute force here: no other point at most as high on both and lower on one.
            hm = [float(r["heightmap_vs_thesis"]) for r in points]
            rest = [float(r["rest_rms"]) for r in points]
            for i, r in enumerate(points):
                beaten = any(hm[j] <= hm[i] and rest[j] <= rest[i] and (hm[j] < hm[i] or rest[j] < rest[i])
                             for j in range(len(points)))
                self.assertEqual(r["pareto"], "0" if beaten else "1", (name, r))
            # The table's shipping cell is the CSV's shipping row.
            cell = "%.2f× at %.3f (2.5 / 5.0 σ)" % (float(shipping[0]["heightmap_vs_thesis"]),
                                                   float(shipping[0]["rest_rms"]))
            self.assertIn("| %s | %s |" % (name, cell), res.stdout)
        self.assertIn("both goals by some fade", res.stdout)
        self.assertIn("Generated traces, not a sensor", res.stdout)

    def test_frontier_takes_no_recording_and_no_tuning(self):
        for extra in (("--trace", __file__), ("--tune",)):
            res = run(BENCH, "--frontier", *extra)
            self.assertEqual(res.returncode, 2, extra)
            self.assertIn("--frontier works on generated traces", res.stderr)


class TuneOnAClass(unittest.TestCase):
    """The grid search: many evaluations of what TrackBenchClasses checks once."""

    def test_tune_on_a_class_logs_every_candidate_and_adds_the_best_as_the_profile_row(self):
        res = run(BENCH, "--class", "white-200hz", "--tune", "--duration", "2")
        self.assertEqual(res.returncode, 0, res.stderr)
        # The class goals are the bounds: chatter <= 0.01, |lag| <= 1 ms, frictionmap <= 0.8x.
        tune_log.check(self, res.stderr, rest_bound=0.01, max_lag_ms=1.0, max_fm_ratio=0.8, levels=1)
        self.assertEqual(len(table_rows(res.stdout)), 3)


def read_trace(text):
    return list(csv.DictReader(line for line in io.StringIO(text) if not line.startswith("#")))


def read_metadata(text):
    """The '# key: value' lines, in order."""
    return [tuple(line[2:].rstrip("\n").split(": ", 1)) for line in io.StringIO(text) if line.startswith("# ")]


class TracegenClasses(unittest.TestCase):
    def test_a_class_is_reproducible_and_carries_its_effects(self):
        a = run(TRACEGEN, "-q", "--class", "realistic-1khz", "--seed", "4", "--duration", "3")
        b = run(TRACEGEN, "-q", "--class", "realistic-1khz", "--seed", "4", "--duration", "3")
        self.assertEqual(a.returncode, 0, a.stderr)
        self.assertEqual(a.stdout, b.stdout)
        rows = read_trace(a.stdout)
        self.assertIn("x_tremor", rows[0])
        touch = [r for r in rows if r["touch"] == "1"]
        span_s = (int(touch[-1]["t_us"]) - int(touch[0]["t_us"])) * 1e-6
        self.assertAlmostEqual((len(touch) - 1) / span_s, 1000.0, delta=20.0)  # 1 kHz
        # Tremor of 1 px peak: |x_tremor| <= 1 (written to 0.001 px).
        self.assertLessEqual(max(abs(float(r["x_tremor"])) for r in touch), 1.0005)

    def test_white_200hz_is_the_plain_model_with_zforce_quantum(self):
        a = run(TRACEGEN, "-q", "--class", "white-200hz", "--seed", "3", "--duration", "2")
        b = run(TRACEGEN, "-q", "--quantise", "zforce", "--seed", "3", "--duration", "2")
        self.assertEqual(a.returncode, 0, a.stderr)
        rows = [line for line in a.stdout.splitlines() if not line.startswith("#")]
        self.assertEqual(rows, [line for line in b.stdout.splitlines() if not line.startswith("#")])
        self.assertGreater(len(rows), 300)
        # The same settings in words; only the command and the class name differ.
        settings = lambda text: [m for m in read_metadata(text) if m[0] not in ("command", "class")]
        self.assertEqual(settings(a.stdout), settings(b.stdout))

    def test_metadata_says_how_the_trace_was_made(self):
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "t.csv")
            res = run(TRACEGEN, "-q", "--class", "realistic-200hz", "--seed", "4", "--duration", "2",
                      "--late", "1", "-o", path)
            self.assertEqual(res.returncode, 0, res.stderr)
            self.assertEqual(os.listdir(tmp), ["t.csv"])  # no .partial left
            with open(path) as f:
                text = f.read()
        lines = text.splitlines()
        meta = dict(read_metadata(text))
        self.assertTrue(meta["tool"].startswith("ff-tracegen "))
        self.assertEqual(meta["command"], "ff-tracegen -q --class realistic-200hz --seed 4 --duration 2 "
                                          "--late 1 -o " + path)
        self.assertEqual(meta["seed"], "4")
        self.assertEqual(meta["class"], "realistic-200hz")
        # The class's numbers (docs/tracking.md#trace-classes), as the trace was made with them.
        for words in ("200 Hz", "noise 0.5 px", "quantum 0.5 px", "latency 1000-3000 us", "period jitter 100 us",
                      "correlated noise 1.5 px (tau 30 ms)", "drift 2 px (tau 10 s)"):
            self.assertIn(words, meta["sensor"])
        for words in ("slow strokes 10 %", "hesitations 20 %", "reversals 30 %", "tremor 1 px at 8-12 Hz"):
            self.assertIn(words, meta["motion"])
        self.assertIn("late 1,", meta["faults"])
        self.assertTrue(lines[0].startswith("# tool: "))
        self.assertTrue(lines[-1].startswith("# summary: "))
        rows = read_trace(text)
        summary = dict(kv.split("=") for kv in meta["summary"].split())
        self.assertEqual(int(summary["rows"]), len(rows))
        self.assertEqual(int(summary["late"]), 1)
        self.assertEqual(int(summary["lift-off"]), sum(1 for r in rows if r["touch"] == "0"))
        self.assertTrue(8.0 <= float(summary["tremor_hz"]) <= 12.0)

    def test_the_summary_on_stderr_and_the_progress_line(self):
        # Every stroke planned for 100 mm/s: the mean and the largest peak are 100 mm/s.
        res = subprocess.run([TRACEGEN, "--strategy", "along", "--speed-min", "100", "--speed-max", "100",
                              "--seed", "2", "--duration", "3", "--progress", "-o", os.devnull], capture_output=True)
        stderr = res.stderr.decode()  # as bytes: text mode would turn each \r into \n
        self.assertEqual(res.returncode, 0, stderr)
        self.assertRegex(stderr, r"ff-tracegen: \d+ strokes, peak speed mean 100 mm/s, max 100 mm/s; 0 rests, 0 lifts\n")
        # The progress line is redrawn in place and ends with a newline at 100 %.
        self.assertIn("\rff-tracegen: planning and sampling   0%\rff-tracegen: planning and sampling 100%\n", stderr)
        self.assertIn("ff-tracegen: rows by kind: touch-down=1 lift-off=1\n", stderr)
        # With tremor: its amplitude and the frequency drawn, as the file's summary has it.
        res = run(TRACEGEN, "--class", "tremor", "--seed", "2", "--duration", "1")
        self.assertEqual(res.returncode, 0, res.stderr)
        tremor_hz = float(dict(kv.split("=") for kv in dict(read_metadata(res.stdout))["summary"].split())["tremor_hz"])
        self.assertIn("tremor 1.50 px at %.1f Hz;" % tremor_hz, res.stderr)

    def test_noise_px_and_quantum_px_override_the_named_levels(self):
        # No noise at all, though --noise high asks for 2.5 px: each report is the truth.
        res = run(TRACEGEN, "-q", "--noise", "high", "--noise-px", "0", "--seed", "4", "--duration", "2")
        self.assertEqual(res.returncode, 0, res.stderr)
        rows = [r for r in read_trace(res.stdout) if r["touch"] == "1"]
        self.assertGreater(len(rows), 300)
        self.assertTrue(all((r["x"], r["y"]) == (r["x_true"], r["y_true"]) for r in rows))
        # A 2 px step, though --quantise zforce asks for 0.5 px: every coordinate a multiple of 2.
        res = run(TRACEGEN, "-q", "--quantise", "zforce", "--quantum-px", "2", "--seed", "4", "--duration", "2")
        rows = [r for r in read_trace(res.stdout) if r["touch"] == "1"]
        self.assertTrue(all(float(r["x"]) % 2.0 == 0.0 and float(r["y"]) % 2.0 == 0.0 for r in rows))
        self.assertTrue(any(float(r["x"]) % 4.0 == 2.0 for r in rows))

    def test_paths_keeps_the_along_strategy_on_one_path(self):
        # docs/spec.md#paths: from y = 240 at the start, the top path rises to y = 40, the
        # bottom one falls to 440; the finger strays at most 18 px off (+ 5 px sigma at the start).
        for path, inside in (("top", lambda y: y <= 270.0), ("bottom", lambda y: y >= 210.0)):
            res = run(TRACEGEN, "-q", "--strategy", "along", "--paths", path, "--seed", "3", "--duration", "20")
            self.assertEqual(res.returncode, 0, res.stderr)
            ys = [float(r["y_true"]) for r in read_trace(res.stdout) if r["touch"] == "1"]
            self.assertTrue(all(inside(y) for y in ys), path)
            self.assertGreater(max(abs(y - 240.0) for y in ys), 150.0, path)  # it went along the path

    def test_class_is_read_first_in_either_spelling_and_help_has_examples(self):
        a = run(TRACEGEN, "-q", "--seed", "5", "--duration", "1", "--class", "correlated-noise")
        b = run(TRACEGEN, "-q", "--seed", "5", "--duration", "1", "--class=correlated-noise")
        self.assertEqual(a.returncode, 0, a.stderr)
        self.assertEqual(read_trace(a.stdout), read_trace(b.stdout))
        self.assertIn("correlated noise 1.5 px", dict(read_metadata(b.stdout))["sensor"])
        help_text = run(TRACEGEN, "--help").stdout
        self.assertIn("Examples:\n  ff-tracegen --strategy along", help_text)
        self.assertIn("realistic-1khz: every effect at 1 kHz", help_text)  # each class with what it is

    def test_the_recorded_command_reads_back_as_typed(self):
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "it's a trace.csv")  # a space and a single quote
            args = ["-q", "--duration", "1", "-o", path, "--truth-ticks", os.path.join(tmp, 'say "ticks".csv')]
            res = run(TRACEGEN, *args)
            self.assertEqual(res.returncode, 0, res.stderr)
            with open(path) as f:
                command = dict(read_metadata(f.read()))["command"]
        self.assertEqual(shlex.split(command), ["ff-tracegen"] + args)

    def test_an_output_that_cannot_be_written_is_refused_and_a_device_is_written_into(self):
        with tempfile.TemporaryDirectory() as tmp:
            missing = os.path.join(tmp, "no-such-folder", "t.csv")
            res = run(TRACEGEN, "-q", "--duration", "1", "-o", missing)
            self.assertEqual(res.returncode, 2)
            self.assertEqual(res.stderr, "ff-tracegen: cannot write %s: No such file or directory\n" % missing)
            res = run(TRACEGEN, "-q", "--duration", "1", "-o", tmp)  # a folder
            self.assertEqual(res.returncode, 2)
            self.assertEqual(res.stderr, "ff-tracegen: cannot write %s: Is a directory\n" % tmp)
            self.assertEqual(os.listdir(tmp), [])
        res = run(TRACEGEN, "-q", "--duration", "1", "-o", os.devnull)
        self.assertEqual(res.returncode, 0, res.stderr)
        self.assertFalse(os.path.exists(os.devnull + ".partial"))
        res = run(TRACEGEN, "-q", "--duration", "1", "-o", "/dev/full")  # every write fails: a full disk
        self.assertEqual(res.returncode, 2)
        self.assertEqual(res.stderr, "ff-tracegen: cannot write /dev/full: No space left on device\n")
        with tempfile.TemporaryDirectory() as tmp:
            res = run(TRACEGEN, "-q", "--duration", "1", "-o", os.path.join(tmp, "t.csv"),
                      "--truth-ticks", os.path.join(tmp, "no-such-folder", "ticks.csv"))
            self.assertEqual(res.returncode, 2)
            missing = os.path.join(tmp, "no-such-folder", "ticks.csv")
            self.assertIn("cannot write %s: No such file or directory" % missing, res.stderr)
            res = run(TRACEGEN, "-q", "--duration", "1", "-o", os.path.join(tmp, "t.csv"), "--truth-ticks", "/dev/full")
            self.assertEqual(res.returncode, 2)
            self.assertIn("ff-tracegen: cannot write /dev/full: No space left on device\n", res.stderr)

    def test_truth_ticks_carry_the_traces_metadata_and_show_progress(self):
        with tempfile.TemporaryDirectory() as tmp:
            trace, ticks = os.path.join(tmp, "t.csv"), os.path.join(tmp, "ticks.csv")
            res = subprocess.run([TRACEGEN, "--seed", "6", "--duration", "1", "--progress", "-o", trace,
                                  "--truth-ticks", ticks], capture_output=True)
            self.assertEqual(res.returncode, 0, res.stderr)
            self.assertIn("\rff-tracegen: truth at ticks 100%\n", res.stderr.decode())
            with open(ticks) as f:
                text = f.read()
        meta = read_metadata(text)
        self.assertEqual(meta[0][0], "tool")
        self.assertEqual(meta[1], ("what", "the true finger at every 500 us tick of the trace " + trace))
        self.assertEqual(dict(meta)["seed"], "6")
        header = [line for line in text.splitlines() if not line.startswith("#")][0]
        self.assertEqual(header, "t_us,x_true,y_true,vx_true,vy_true,touch")

    def test_options_change_the_class_they_follow(self):
        base = read_trace(run(TRACEGEN, "-q", "--class", "latency", "--seed", "2", "--duration", "2").stdout)
        none = read_trace(run(TRACEGEN, "-q", "--class", "latency", "--noise", "none", "--quantise", "none",
                              "--seed", "2", "--duration", "2").stdout)
        self.assertEqual(len(base), len(none))
        # Without noise and quantum only the latency separates report and truth: at most
        # 3 ms of a finger that moves under 2000 px/s.
        for r in none:
            if r["touch"] == "1":
                self.assertLess(math.hypot(float(r["x"]) - float(r["x_true"]), float(r["y"]) - float(r["y_true"])), 6.5)

    def test_correlated_noise_option_and_help(self):
        res = run(TRACEGEN, "-q", "--correlated-noise-px", "2", "--correlated-tau-ms", "40", "--noise", "none",
                  "--seed", "1", "--duration", "30")
        self.assertEqual(res.returncode, 0, res.stderr)
        rows = [r for r in read_trace(res.stdout) if r["touch"] == "1"]
        e = [float(r["x"]) - float(r["x_true"]) for r in rows]
        mean = sum(e) / len(e)
        var = sum((x - mean) ** 2 for x in e) / (len(e) - 1)
        # ~6000 reports, ~6000 * (1 - 0.88) / (1 + 0.88) ~ 380 independent ones: variance to ~7 %.
        self.assertAlmostEqual(var, 4.0, delta=1.2)
        lag1 = sum((e[i] - mean) * (e[i + 1] - mean) for i in range(len(e) - 1)) / (var * (len(e) - 1))
        self.assertAlmostEqual(lag1, math.exp(-5.0 / 40.0), delta=0.03)
        help_text = run(TRACEGEN, "--help").stdout
        for option in ("--class", "--slow-strokes", "--hesitations", "--reversals", "--tremor-px",
                       "--latency-spread-us", "--period-jitter-us", "--correlated-noise-px", "--drift-px"):
            self.assertIn(option, help_text)
        for name in CLASSES:
            self.assertIn(name, help_text)

    def test_each_bundled_trace_is_what_its_recorded_command_makes(self):
        traces = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "traces")
        bundled = sorted(f for f in os.listdir(traces) if f.startswith("gen_") and not f.endswith(".golden.csv"))
        self.assertEqual(len(bundled), 5)
        for name in bundled:
            with open(os.path.join(traces, name)) as f:
                stored = f.read()
            command = shlex.split(dict(read_metadata(stored))["command"])
            self.assertEqual(command[0], "ff-tracegen")
            self.assertEqual(command[command.index("-o") + 1], name)
            with tempfile.TemporaryDirectory() as tmp:
                made_path = os.path.join(tmp, name)
                command[command.index("-o") + 1] = made_path
                res = run(TRACEGEN, *command[1:])
                self.assertEqual(res.returncode, 0, res.stderr)
                with open(made_path) as f:
                    made = f.read()
            without_command = lambda text: [l for l in text.splitlines() if not l.startswith("# command: ")]
            self.assertEqual(without_command(made), without_command(stored), name)

    def test_faults_without_room_are_named_in_the_metadata_and_warned_of(self):
        # 40 gaps cannot fit into 1 s of reports, each with 8 ordinary reports
        # on either side: the trace says how many it holds, and so does stderr,
        # also with -q. Gaps are counted from the stamps (a step over 1.5 periods).
        res = run(TRACEGEN, "-q", "--duration", "1", "--missing", "40")
        self.assertEqual(res.returncode, 0, res.stderr)
        meta = dict(read_metadata(res.stdout))
        self.assertEqual(meta["faults"].split(",")[0], "missing 40")
        placed = re.fullmatch(r"missing (\d+) of 40 \(no room for the rest\)", meta["faults-placed"])
        self.assertIsNotNone(placed, meta["faults-placed"])
        touching = [int(r["t_us"]) for r in read_trace(res.stdout) if r["touch"] == "1"]
        gaps = sum(1 for a, b in zip(touching, touching[1:]) if b - a > 7500)
        self.assertEqual(gaps, int(placed.group(1)))
        self.assertLess(gaps, 40)
        self.assertIn(f"warning: not every fault found a site (missing {gaps} of 40)", res.stderr)
        # Room for all: neither the line nor the warning.
        res = run(TRACEGEN, "-q", "--duration", "10", "--missing", "3", "--jumps", "2")
        self.assertEqual(res.returncode, 0, res.stderr)
        self.assertNotIn("faults-placed", dict(read_metadata(res.stdout)))
        self.assertEqual(res.stderr, "")

    def test_rest_only_refuses_the_options_about_strokes(self):
        for option in (["--rests", "2"], ["--lifts", "1"], ["--strategy", "along"], ["--slow-strokes", "0.5"],
                       ["--speed-max", "100"]):
            res = run(TRACEGEN, "-q", "--rest-only", *option)
            self.assertEqual(res.returncode, 2, option)
            self.assertIn(option[0], res.stderr)
            self.assertIn("--rest-only", res.stderr)
            self.assertEqual(res.stdout, "")
        # A class's own stroke settings are not the user's: --rest-only takes the class's sensor.
        self.assertEqual(run(TRACEGEN, "-q", "--rest-only", "--class", "realistic-200hz", "--duration", "2").returncode, 0)

    def test_bad_values_exit_2(self):
        self.assertEqual(run(TRACEGEN, "--class", "no-such-class").returncode, 2)
        self.assertEqual(run(TRACEGEN, "--slow-strokes", "1.5").returncode, 2)
        res = run(TRACEGEN, "--tremor-hz", "12", "--tremor-hz-max", "8")
        self.assertEqual(res.returncode, 2)
        self.assertIn("--tremor-hz-max", res.stderr)


if __name__ == "__main__":
    BENCH, TRACEGEN = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    unittest.main(argv=sys.argv[:1] + sys.argv[3:], verbosity=1)  # optional: test classes to run
