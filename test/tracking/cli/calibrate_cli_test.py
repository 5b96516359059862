#!/usr/bin/env python3
"""ff-track-bench --calibrate as a lab runs it: a resting finger from
ff-tracegen --rest-only, the printed ffctl line, --profile-out, a strokes
file, and bad input (exit 2 with one line). Expected values are the
generator's parameters, not earlier output.

usage: calibrate_cli_test.py path/to/ff-track-bench path/to/ff-tracegen
"""
import csv
import math
import os
import subprocess
import sys
import tempfile
import unittest

BENCH = TRACEGEN = None
FLAGS = ["--white-noise-px", "--correlated-noise-px", "--correlation-time-ms", "--tremor-px", "--tremor-hz",
         "--report-rate-hz", "--jitter-us", "--latency-us"]


def run(*args):
    return subprocess.run([str(a) for a in args], capture_output=True, text=True)


def parse_flags(text):
    words = text.split()
    values = dict(zip(words[0::2], (float(w) for w in words[1::2])))
    assert list(values) == FLAGS, words
    return values


class Calibrate(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls._tmp = tempfile.TemporaryDirectory()
        cls.tmp = cls._tmp.name
        # 1 px white + 0.5 px quantum, 1.5 px tremor at 10 Hz, 200 Hz with 150 us stamp jitter.
        cls.rest = os.path.join(cls.tmp, "rest.csv")
        res = run(TRACEGEN, "--rest-only", "--class", "tremor", "--tremor-hz", 10, "--tremor-hz-max", 10,
                  "--duration", 10, "--seed", 7, "-q", "-o", cls.rest)
        assert res.returncode == 0, res.stderr
        cls.strokes = os.path.join(cls.tmp, "strokes.csv")
        res = run(TRACEGEN, "--class", "tremor", "--duration", 6, "--seed", 7, "-q", "-o", cls.strokes)
        assert res.returncode == 0, res.stderr

    @classmethod
    def tearDownClass(cls):
        cls._tmp.cleanup()

    def calibrate(self, *extra):
        res = run(BENCH, "--calibrate", self.rest, *extra)
        self.assertEqual(res.returncode, 0, res.stderr)
        return res

    def test_rest_only_is_one_finger_resting_at_the_middle(self):
        with open(self.rest) as f:
            rows = [r for r in csv.DictReader(line for line in f if not line.startswith("#")) if r["touch"] == "1"]
        self.assertEqual(len(rows), 2001)
        self.assertEqual({(r["x_true"], r["y_true"]) for r in rows}, {("400", "240")})
        with open(self.rest) as f:
            motion = [line for line in f if line.startswith("# motion: ")]
        self.assertEqual(motion, ["# motion: a finger at rest for 10 s, tremor 1.5 px at 10-10 Hz\n"])

    def test_the_printed_ffctl_line_holds_the_generators_parameters(self):
        out = self.calibrate("--latency-us", 1500).stdout
        ffctl = [line.strip() for line in out.splitlines() if line.strip().startswith("ffctl sensor-profile ")]
        self.assertEqual(len(ffctl), 1, out)
        p = parse_flags(ffctl[0][len("ffctl sensor-profile "):])
        self.assertAlmostEqual(p["--white-noise-px"], math.sqrt(1 + 0.5 ** 2 / 12), delta=0.1)
        self.assertAlmostEqual(p["--tremor-px"], 1.5, delta=0.15)
        self.assertAlmostEqual(p["--tremor-hz"], 10, delta=0.1)
        self.assertEqual(p["--correlated-noise-px"], 0)
        self.assertAlmostEqual(p["--report-rate-hz"], 200, delta=2)
        self.assertAlmostEqual(p["--jitter-us"], 150 * math.sqrt(2), delta=21)
        self.assertEqual(p["--latency-us"], 1500)
        self.assertIn("not measurable from a recording", out)
        # The same flags for ff-replay and ff-track-bench, on the line after its heading.
        lines = out.splitlines()
        same = lines[lines.index("For ff-replay and ff-track-bench:") + 1].strip()
        self.assertEqual(same, ffctl[0][len("ffctl sensor-profile "):])
        for unit in ("| px |", "| ms |", "| Hz |", "| us |"):
            self.assertIn(unit, out)

    def test_the_printed_table_is_the_profile_row_by_row(self):
        out = self.calibrate("--latency-us", 1500).stdout
        lines = out.splitlines()
        p = parse_flags(next(l for l in lines if l.strip().startswith("ffctl sensor-profile ")).strip()[21:])
        start = lines.index("| quantity | estimate | unit | how |")
        self.assertEqual(lines[start + 1], "|---|--:|---|---|")
        rows = [[cell.strip() for cell in line.strip("|").split("|")] for line in lines[start + 2:start + 10]]
        expected = [("white noise (with quantisation), 1 sigma per axis", "--white-noise-px", 2, "px"),
                    ("correlated noise, 1 sigma per axis", "--correlated-noise-px", 2, "px"),
                    ("correlation time", "--correlation-time-ms", 1, "ms"),
                    ("tremor, peak per axis", "--tremor-px", 2, "px"),
                    ("tremor frequency", "--tremor-hz", 2, "Hz"),
                    ("report rate", "--report-rate-hz", 1, "Hz"),
                    ("jitter, 1 sigma of the report interval", "--jitter-us", 0, "us"),
                    ("latency", "--latency-us", 0, "us")]
        self.assertEqual([r[0] for r in rows], [e[0] for e in expected])
        for row, (_, flag, decimals, unit) in zip(rows, expected):
            self.assertEqual(row[2], unit, row)
            self.assertEqual(len(row[1].partition(".")[2]), decimals, row)
            self.assertAlmostEqual(float(row[1]), p[flag], delta=0.51 * 10 ** -decimals + 1e-9, msg=row)
        # No wander in a rest of white noise and tremor; the tremor's peak at the frequency of its flag.
        self.assertTrue(rows[1][3].endswith("(not significant: 0)"), rows[1])
        self.assertTrue(rows[3][3].startswith("cosine term at the spectral peak, %.2f Hz" % p["--tremor-hz"]), rows[3])

    def test_profile_out_has_the_flags_and_a_header(self):
        path = os.path.join(self.tmp, "profile.txt")
        res = self.calibrate("--profile-out", path)
        out = res.stdout
        with open(path) as f:
            lines = f.read().splitlines()
        header = [line for line in lines if line.startswith("#")]
        body = [line for line in lines if not line.startswith("#")]
        self.assertTrue(any(line.startswith("# tool: ff-track-bench") for line in header), header)
        self.assertIn("# input: " + self.rest, header)
        self.assertTrue(any(line.startswith("# date: 20") for line in header), header)
        self.assertEqual(len(body), 1)
        self.assertIn("ffctl sensor-profile " + body[0], out)
        self.assertEqual(res.stderr, "ff-track-bench: profile written to %s\n" % path)
        self.assertFalse(os.path.exists(path + ".partial"))

    def test_the_flags_are_accepted_by_ff_track_bench(self):
        flags = parse_flags(run(BENCH, "--calibrate", self.rest).stdout.splitlines()[-1])
        args = [w for k, v in flags.items() for w in (k, "%g" % v)]
        res = run(BENCH, "--trace", self.strokes, *args)
        self.assertEqual(res.returncode, 0, res.stderr)
        self.assertIn("| recommended() |", res.stdout)

    def test_with_strokes_three_trackers_are_judged(self):
        out = self.calibrate(self.strokes).stdout
        for tracker in ("thesis (ticks + 1-euro, filtered derivative)", "recommended()",
                        "recommended(calibrated profile)"):
            self.assertEqual(sum(line.startswith("| " + tracker + " |") for line in out.splitlines()), 1, tracker)
        self.assertIn("1 judged against their x_true, y_true columns", out)

    def test_what_was_left_out_is_said(self):
        # Glitches, off-screen rows and repeated stamps are left out and said;
        # how many glitches comes from the generator's event column.
        faulty = os.path.join(self.tmp, "faulty.csv")
        res = run(TRACEGEN, "--rest-only", "--duration", 10, "--jumps", 3, "--off-screen", 2, "--duplicates", 3,
                  "--events", "-q", "-o", faulty)
        self.assertEqual(res.returncode, 0, res.stderr)
        with open(faulty) as f:
            events = [r["event"] for r in csv.DictReader(line for line in f if not line.startswith("#"))]
        out = run(BENCH, "--calibrate", faulty).stdout
        self.assertIn("Left out: 2 touch row(s) off the screen or not finite, 3 stamped at or before the one "
                      "before.", out)
        self.assertIn("Left out of the noise: %d report(s) more than " % events.count("jump"), out)
        line = next(l for l in out.splitlines() if l.strip().startswith("ffctl sensor-profile "))
        self.assertEqual(parse_flags(line.strip()[len("ffctl sensor-profile "):])["--correlated-noise-px"], 0.0)
        # A clean recording says neither.
        self.assertNotIn("Left out", self.calibrate().stdout)

    def test_a_drift_is_said_to_be_slower_than_the_fit_can_tell(self):
        # A drift of tau 10 s, far beyond the 100 ms the fit tries: its time constant comes out at that
        # limit, and the table says what that means. A plain rest says only "its time constant".
        drift = os.path.join(self.tmp, "drift.csv")
        res = run(TRACEGEN, "--rest-only", "--duration", 10, "--drift-px", 3, "--seed", 1, "-q", "-o", drift)
        self.assertEqual(res.returncode, 0, res.stderr)
        out = run(BENCH, "--calibrate", drift).stdout
        self.assertIn("| correlation time | 100.0 | ms | its time constant, the longest the fit tries: a slower "
                      "wander (a drift?)", out)
        self.assertNotIn("the longest the fit tries", self.calibrate().stdout)

    def test_bad_input_exits_2_with_one_line(self):
        short = os.path.join(self.tmp, "short.csv")
        self.assertEqual(run(TRACEGEN, "--rest-only", "--duration", 0.5, "-q", "-o", short).returncode, 0)
        cases = [
            ([short], "only 0.50 s of touch reports"),
            ([self.strokes], "the finger is not resting"),
            ([self.rest, "--profile-out", self.rest], "would overwrite the recording"),
            ([self.rest, "--trace", self.strokes], "--calibrate takes none of"),
            ([self.rest, "--classes"], "--calibrate takes none of"),
            ([self.rest, "--class", "white-200hz"], "--calibrate takes none of"),
            ([self.rest, "--tune"], "--calibrate takes none of"),
            ([self.rest, "--write-doc", os.path.join(self.tmp, "doc.md")], "--calibrate takes none of"),
        ]
        for args, message in cases:
            res = run(BENCH, "--calibrate", *args)
            self.assertEqual(res.returncode, 2, (args, res.stderr))
            self.assertIn(message, res.stderr)
            self.assertEqual(len(res.stderr.strip().splitlines()), 1, res.stderr)
            self.assertEqual(res.stdout, "")
        # A profile file that cannot be written: the calibration is printed, the file refused.
        nowhere = os.path.join(self.tmp, "no-such-folder", "profile.txt")
        res = run(BENCH, "--calibrate", self.rest, "--profile-out", nowhere)
        self.assertEqual(res.returncode, 2, res.stderr)
        self.assertIn("cannot write %s: No such file or directory" % nowhere, res.stderr)
        self.assertIn("ffctl sensor-profile ", res.stdout)
        # A recording that is not a trace, at rest or as the strokes: its line and field, one line.
        bad = os.path.join(self.tmp, "bad.csv")
        with open(bad, "w") as f:
            f.write("t_us,x,y,touch\n0,abc,2,1\n")
        for args in ([bad], [self.rest, bad]):
            res = run(BENCH, "--calibrate", *args)
            self.assertEqual(res.returncode, 2, (args, res.stderr))
            self.assertEqual(res.stderr, "ff-track-bench: %s:2:2: x is not a number (got 'abc')\n" % bad, args)
        # A missing file is a usage error: CLI11's line and its pointer to --help.
        res = run(BENCH, "--calibrate", os.path.join(self.tmp, "nope.csv"))
        self.assertEqual(res.returncode, 2)
        self.assertIn("nope.csv", res.stderr.splitlines()[0])


if __name__ == "__main__":
    BENCH, TRACEGEN = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    unittest.main(argv=sys.argv[:1], verbosity=1)
