"""The cycle model's report from costed calls (what cyclemodel.py does after
qemu): nearest-rank percentiles, the harness's labels, the per-scene summary
and the by-function breakdown, on calls written by hand."""
import sys
import unittest
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from cyclemodel import breakdown, label_calls, percentile, summarise  # noqa: E402
from exec_log import CallResult  # noqa: E402
from model import ISR_BEST, ISR_WORST  # noqa: E402

TRACKER_TICK = "_ZN2ff7Tracker4tickEv"  # ff::Tracker::tick()


def row(scene, kind, index, instructions, best, worst, function="tick", functions=None):
    return {"kind": kind, "scene": scene, "index": index, "function": function, "instructions": instructions,
            "cycles_best": best, "cycles_worst": worst, "flash_lines": 0, "functions": functions}


class Percentile(unittest.TestCase):
    def test_nearest_rank(self):
        values = [5, 1, 4, 2, 3]
        # rank ceil(p/100 * 5): p50 -> 3rd, p99 -> 5th, p0 -> the 1st at least
        self.assertEqual([percentile(values, p) for p in (50, 99, 0, 20, 21)], [3, 5, 1, 1, 2])
        self.assertEqual(percentile(list(range(1000, 0, -1)), 99), 990)

    def test_nearest_rank_where_p_times_n_is_whole(self):
        # 99.9 % of 1,000 is rank 999 exactly, though 99.9 / 100 * 1000 is 999.0000000000001 in binary
        # floating point; of 2,000 ticks (a benchmark scene) it is rank 1,998, the third largest.
        self.assertEqual(percentile(list(range(1000, 0, -1)), 99.9), 999)
        self.assertEqual(percentile(list(range(2000, 0, -1)), 99.9), 1998)


class Labels(unittest.TestCase):
    def test_each_call_takes_the_harness_line_in_its_order(self):
        calls = [CallResult("prepare", 5000, 6000, 9000, 40), CallResult("tick", 700, 800, 1500, 12, {"f": [1, 2, 3]})]
        harness = "ff-m4trace\ncall,prepare,heightmap,0\ncall,stroke,heightmap,17\ndone,0\n"
        self.assertEqual(label_calls(calls, harness), [
            row("heightmap", "prepare", 0, 5000, 6000, 9000, "prepare") | {"flash_lines": 40},
            row("heightmap", "stroke", 17, 700, 800, 1500, functions={"f": [1, 2, 3]}) | {"flash_lines": 12}])

    def test_a_count_or_an_order_that_differs_is_an_error(self):
        calls = [CallResult("tick", 1, 1, 1, 0)]
        with self.assertRaisesRegex(RuntimeError, "1 calls traced but the harness announced 2"):
            label_calls(calls, "call,stroke,a,0\ncall,stroke,a,1\n")
        with self.assertRaisesRegex(RuntimeError, "tick where prepare was announced"):
            label_calls(calls, "call,prepare,a,0\n")


class Summary(unittest.TestCase):
    ROWS = [row("warm", "warm-up", 0, 9999, 9999, 99999),                 # not a scene of its own
            row("heightmap", "prepare", 0, 18000, 20000, 36000, "prepare"),
            row("heightmap", "stroke", 1, 700, 800, 1000),
            row("heightmap", "stroke", 2, 710, 820, 1100),
            row("heightmap", "stroke", 3, 720, 840, 1300),
            row("heightmap", "stroke", 4, 690, 780, 900),
            row("heightmap", "touch-down", 5, 900, 1000, 2000),
            row("heightmap", "lift-off", 6, 300, 350, 600),
            row("neutral", "stroke", 0, 100, 110, 200),
            row("neutral", "stroke", 1, 120, 130, 250)]

    def test_per_scene_percentiles_worst_tick_events_and_preparation(self):
        summary = summarise(self.ROWS)
        self.assertEqual([entry["scene"] for entry in summary], ["heightmap", "neutral"])
        heightmap, neutral = summary
        self.assertEqual((heightmap["scene"], heightmap["stroke_ticks"]), ("heightmap", 4))
        self.assertEqual(heightmap["instructions_mean"], (700 + 710 + 720 + 690) / 4)
        # nearest rank of four: p50 the 2nd, p99 and p99.9 the 4th
        self.assertEqual((heightmap["cycles_worst_p50"], heightmap["cycles_worst_p99"],
                          heightmap["cycles_worst_p99.9"]), (1000, 1300, 1300))
        # the max is over every tick of the scene (the touch-down's), not only its strokes
        self.assertEqual((heightmap["instructions_max"], heightmap["cycles_worst_max"]), (900, 2000))
        self.assertEqual(heightmap["worst_tick_kind"], "touch-down")
        self.assertEqual((heightmap["touch-down_cycles_worst"], heightmap["lift-off_instructions"]), (2000, 300))
        self.assertNotIn("swap_cycles_worst", heightmap)
        self.assertEqual((heightmap["prepare_instructions"], heightmap["prepare_ms_worst"]), (18000, 36000 / 180e3))
        self.assertEqual((heightmap["isr_best"], heightmap["isr_worst"]), (ISR_BEST, ISR_WORST))
        self.assertAlmostEqual(heightmap["worst_tick_budget_percent"], 100 * (2000 + ISR_WORST) / 90000)
        self.assertEqual((neutral["cycles_best_mean"], neutral["cycles_worst_max"]), (120, 250))
        self.assertNotIn("prepare_ms_best", neutral)


class Breakdown(unittest.TestCase):
    def test_event_ticks_and_each_scenes_worst_stroke_split_by_function(self):
        split = {TRACKER_TICK: [300, 900, 2], "memcpy": [20, 40, 0]}
        rows = [row("heightmap", "prepare", 0, 1, 1, 1, "prepare", {"x": [1, 1, 1]}),
                row("heightmap", "stroke", 1, 700, 800, 1000, functions={"memcpy": [1, 1, 0]}),
                row("heightmap", "stroke", 2, 720, 840, 1300, functions=split),
                row("heightmap", "after-touch-down", 3, 1, 1, 5000, functions={"memcpy": [9, 9, 9]}),
                row("heightmap", "lift-off", 4, 300, 350, 600, functions={"memcpy": [5, 10, 1]})]
        out = breakdown(rows)
        self.assertEqual([(r["kind"], r["index"], r["function"], r["cycles_worst"]) for r in out], [
            ("lift-off", 4, "memcpy", 10),
            ("stroke", 2, "ff::Tracker::tick()", 900),   # demangled, most expensive first
            ("stroke", 2, "memcpy", 40)])
        self.assertEqual((out[1]["instructions"], out[1]["flash_misses_worst"], out[1]["tick_cycles_worst"]),
                         (300, 2, 1300))


if __name__ == "__main__":
    unittest.main()
