#!/usr/bin/env python3
"""ff-m4accuracy as run-benchmarks runs it, on hand-made ff-m4trace accuracy
output whose errors are worked out by hand: exit codes (0 ok, 1 a DAC code
more than 1 LSB from the exact one, 2 bad input), the table and the CSV.

The neutral scene renders 0.5 everywhere; after strength 0.8 still 0.5. The
calibration (4000 at 0, 2500 at 0.4, 300 at 1) puts 0.5 at
2500 - (0.1 / 0.6) * 2200 = 2133.33, so code 2133 is 1/3 LSB off and 2135 is
5/3 LSB off.

usage: m4accuracy_cli_test.py path/to/ff-m4accuracy
"""
import csv
import os
import struct
import subprocess
import sys
import tempfile
import unittest

TOOL = None


def bits(f):
    return struct.unpack("<I", struct.pack("<f", f))[0]


def sample(scene, dac, raw=0.5, scaled=0.5, x=100.0, y=200.0):
    return "amplitude,%s,0,%d,%d,%d,%d,%d,%d,%d\n" % (scene, bits(x), bits(y), bits(1.0), bits(0.0), bits(raw),
                                                      bits(scaled), dac)


def run(*args):
    return subprocess.run([str(a) for a in args], capture_output=True, text=True)


class M4Accuracy(unittest.TestCase):
    def setUp(self):
        self._tmp = tempfile.TemporaryDirectory()
        self.tmp = self._tmp.name

    def tearDown(self):
        self._tmp.cleanup()

    def trace(self, text):
        path = os.path.join(self.tmp, "m4accuracy.txt")
        with open(path, "w") as f:
            f.write(text)
        return path

    def csv_rows(self, path):
        with open(path) as f:
            lines = f.read().splitlines()
        meta = dict(l[2:].split(": ", 1) for l in lines if l.startswith("# "))
        return meta, list(csv.DictReader(l for l in lines if not l.startswith("#")))

    def test_a_code_within_rounding_passes_with_its_error_by_hand(self):
        out = os.path.join(self.tmp, "m4accuracy.csv")
        trace = self.trace(sample("neutral", 2133) + "done,0\n")
        res = run(TOOL, trace, "--csv", out)
        self.assertEqual(res.returncode, 0, res.stderr)
        self.assertEqual(res.stdout.splitlines()[:3], [
            "| scene | points | raw amplitude max (LSB) | after strength 0.8 max / RMS (LSB) "
            "| DAC code vs exact, max (LSB) | codes != round(exact) |",
            "|---|---|---|---|---|---|",
            "| neutral | 1 | 0 | 0 / 0 | 0.333 | 0 |"])
        self.assertIn("1 points; worst DAC code 0.333 LSB", res.stdout)
        meta, rows = self.csv_rows(out)
        self.assertTrue(meta["tool"].startswith("ff-m4accuracy "))
        self.assertEqual(meta["input"], trace)
        self.assertEqual(set(meta), {"tool", "date", "input", "what"})
        self.assertEqual(len(rows), 1)
        self.assertEqual(rows[0]["scene"], "neutral")
        self.assertAlmostEqual(float(rows[0]["code_max_lsb"]), 1 / 3, places=5)
        self.assertEqual(rows[0]["codes_off"], "0")
        self.assertEqual(sorted(os.listdir(self.tmp)), ["m4accuracy.csv", "m4accuracy.txt"])  # no .partial

    def test_amplitude_errors_are_in_lsb_of_1_4095(self):
        # raw 0.5 + 8/4095 -> 8 LSB; scaled off by 4 and 0 LSB -> max 4, RMS sqrt(8)
        raw = 0.5 + 8 / 4095
        res = run(TOOL, self.trace(sample("neutral", 2133, raw=raw, scaled=0.5 + 4 / 4095) +
                                   sample("neutral", 2133) + "done,0\n"))
        self.assertEqual(res.returncode, 0, res.stderr)
        row = next(l for l in res.stdout.splitlines() if l.startswith("| neutral |"))
        cells = [c.strip() for c in row.strip("|").split("|")]
        self.assertEqual(cells[1], "2")
        self.assertAlmostEqual(float(cells[2]), 8.0, places=2)  # float rounding of 0.5 + 8/4095
        scaled_max, scaled_rms = (float(v) for v in cells[3].split(" / "))
        self.assertAlmostEqual(scaled_max, 4.0, places=2)
        self.assertAlmostEqual(scaled_rms, 8 ** 0.5, places=2)

    def test_a_code_more_than_1_lsb_off_fails_with_1(self):
        out = os.path.join(self.tmp, "m4accuracy.csv")
        res = run(TOOL, self.trace(sample("neutral", 2133) + sample("neutral", 2135) + "done,0\n"), "--csv", out)
        self.assertEqual(res.returncode, 1, res.stderr)
        self.assertIn("| neutral | 2 | 0 | 0 / 0 | 1.667 | 1 |", res.stdout)
        _, rows = self.csv_rows(out)  # the figures are written even so
        self.assertEqual(rows[0]["codes_off"], "1")

    def test_bad_input_exits_2_with_one_line(self):
        cases = [("", "not a complete ff-m4trace accuracy run"),
                 (sample("neutral", 2133), "not a complete ff-m4trace accuracy run"),  # killed before done
                 ("amplitude,no-such-scene,0,1,2,3,4,5,6,7\ndone,0\n", "malformed line"),
                 ("amplitude,neutral,0,x,2,3,4,5,6,7\ndone,0\n", "malformed number")]
        for text, message in cases:
            res = run(TOOL, self.trace(text))
            self.assertEqual(res.returncode, 2, text)
            self.assertIn(message, res.stderr)
            self.assertEqual(len(res.stderr.strip().splitlines()), 1, res.stderr)

    def test_a_csv_that_cannot_be_written_exits_2_and_leaves_nothing(self):
        trace = self.trace(sample("neutral", 2133) + "done,0\n")
        missing = os.path.join(self.tmp, "missing", "m4accuracy.csv")
        res = run(TOOL, trace, "--csv", missing)
        self.assertEqual(res.returncode, 2)
        self.assertEqual(res.stderr.strip(), "ff-m4accuracy: cannot write %s: No such file or directory" % missing)
        self.assertEqual(os.listdir(self.tmp), ["m4accuracy.txt"])


if __name__ == "__main__":
    TOOL = os.path.abspath(sys.argv[1])
    unittest.main(argv=sys.argv[:1], verbosity=1)
