#!/usr/bin/env python3
"""ff-replay and ff-scene-render run as a user runs them: a subprocess, files
on disk, exit codes (0 ok, 1 failed check, 2 bad usage or input) and what
they print. Expected values come from the trace files written here (hand
counts), not from the tools.

usage: host_tools_cli_test.py path/to/ff-replay path/to/ff-scene-render
"""
import math
import os
import resource
import signal
import subprocess
import sys
import tempfile
import threading
import unittest

REPLAY = SCENE_RENDER = None
TICK_US = 500


def run(*args, **kwargs):
    return subprocess.run([str(a) for a in args], capture_output=True, text=True, **kwargs)


def write_trace(path, rows, header="t_us,x,y,touch", prefix=""):
    with open(path, "w", newline="") as f:
        f.write(prefix + header + "\n")
        for r in rows:
            f.write(",".join(str(v) for v in r) + "\n")


def stroke(n=200, dt=5000, x0=100.0):
    """n reports every dt us moving right at 100 px/s along y = 240."""
    return [(i * dt, round(x0 + (i * dt * 1e-4) % 600, 3), 240, 1) for i in range(n)]


def read_replay(path):
    meta, header, rows = {}, None, []
    with open(path) as f:
        for line in f:
            line = line.rstrip("\n")
            if line.startswith("#"):
                key, _, value = line[1:].strip().partition(": ")
                meta[key] = value
            elif header is None:
                header = line.split(",")
            else:
                rows.append(dict(zip(header, line.split(","))))
    return meta, header, rows


def read_text(path):
    with open(path) as f:
        return f.read()


def scene_render_meta(*words):
    out = run(SCENE_RENDER, "--step", "100", *words)
    assert out.returncode == 0, out.stderr
    meta = {}
    for line in out.stdout.splitlines():
        if line.startswith("#"):
            key, _, value = line[1:].strip().partition(": ")
            meta[key] = value
    return meta


class Case(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        self.tmp = self.dir.name

    def tearDown(self):
        self.dir.cleanup()

    def path(self, name):
        return os.path.join(self.tmp, name)


class ReplayOutput(Case):
    def test_metadata_header_and_present_column(self):
        trace, out = self.path("t.csv"), self.path("r.csv")
        # 100 reports (0.495 s), then the finger lifts: idle ticks follow.
        write_trace(trace, stroke(100) + [(500000, "", "", 0)])
        words = ["--scene", "heightmap", "--target", "top", "--strength", "0.66"]
        res = run(REPLAY, trace, "-o", out, "--extra-ms", "400", *words)
        self.assertEqual(res.returncode, 0, res.stderr)
        meta, header, rows = read_replay(out)
        self.assertEqual(header, ["t_us", "x", "y", "vx", "vy", "amplitude", "dac", "present"])
        for key in ("tool", "date", "input", "scene", "scene_hash", "tracker", "sensor_profile", "strength", "calibration",
                    "summary"):
            self.assertIn(key, meta)
        self.assertTrue(meta["tool"].startswith("ff-replay "))
        self.assertEqual(meta["scene"], "--scene heightmap --target top --strength 0.66")
        self.assertEqual(meta["input"], f"t.csv ({os.path.getsize(trace)} bytes)")
        self.assertEqual(meta["calibration"], "linear")
        # The same words give the same hash in the other tool (one definition).
        self.assertEqual(meta["scene_hash"], scene_render_meta(*words)["scene_hash"])
        self.assertNotEqual(meta["scene_hash"], scene_render_meta("--scene", "heightmap")["scene_hash"])
        present = [r["present"] for r in rows]
        self.assertEqual(present[0], "1")
        self.assertEqual(present[-1], "0")  # lifted at 0.5 s, 0.4 s of idle ticks
        self.assertEqual(len(rows), (500000 + 400000) // TICK_US + 1)
        self.assertIn(f"ticks={len(rows)} samples=101 rejected=0", meta["summary"])

    def test_the_trackers_are_told_the_sensor_profile_given(self):
        trace = self.path("t.csv")
        write_trace(trace, stroke(100))
        runs = {}
        for name, extra in (("default", []), ("late", ["--latency-us", "3000", "--tremor-px", "1", "--tremor-hz", "9.5"]),
                            ("thesis", ["--tracker", "thesis"]),
                            ("thesis-late", ["--tracker", "thesis", "--latency-us", "3000"])):
            out = self.path(name + ".csv")
            res = run(REPLAY, "-q", trace, "-o", out, *extra)
            self.assertEqual(res.returncode, 0, res.stderr)
            runs[name] = read_replay(out)
        self.assertEqual(runs["default"][0]["sensor_profile"],
                         "--white-noise-px 1 --correlated-noise-px 0 --correlation-time-ms 0 --tremor-px 0 "
                         "--tremor-hz 0 --report-rate-hz 200 --jitter-us 150 --latency-us 0 (default)")
        self.assertIn("--tremor-px 1 --tremor-hz 9.5", runs["late"][0]["sensor_profile"])
        self.assertIn("--latency-us 3000", runs["late"][0]["sensor_profile"])
        # Reports dated 3 ms earlier: the tracker puts the finger further along at each tick.
        self.assertNotEqual(runs["default"][2], runs["late"][2])
        # The thesis pipeline takes no profile: the same output, and says so.
        self.assertEqual(runs["thesis"][2], runs["thesis-late"][2])
        self.assertEqual(runs["thesis-late"][0]["sensor_profile"], "not used by the thesis pipeline")
        for bad in (["--tremor-hz", "25"], ["--correlated-noise-px", "2", "--correlation-time-ms", "-1"]):
            self.assertEqual(run(REPLAY, trace, "-o", self.path("bad.csv"), *bad).returncode, 2, bad)

    def test_a_recordings_sensor_profile_line_is_used_unless_flags_are_given(self):
        # ffctl record writes "# sensor-profile FLAGS" before the header: the
        # profile the device's tracker used.
        recorded = "--latency-us 3000 --tremor-px 1 --tremor-hz 9.5"
        rec = self.path("rec.csv")
        write_trace(rec, stroke(100), prefix=f"# ffctl 0.1.0 record -o rec.csv\n# sensor-profile {recorded}\n")
        plain = self.path("plain.csv")
        write_trace(plain, stroke(100))
        runs = {}
        for name, trace, extra in (("rec", rec, []), ("flags", plain, recorded.split()),
                                   ("override", rec, ["--latency-us", "0"]), ("plain", plain, [])):
            out = self.path(name + ".out.csv")
            res = run(REPLAY, "-q", trace, "-o", out, *extra)
            self.assertEqual(res.returncode, 0, res.stderr)
            runs[name] = read_replay(out)
        self.assertTrue(runs["rec"][0]["sensor_profile"].endswith("(the recording's sensor-profile line)"))
        self.assertIn("--latency-us 3000", runs["rec"][0]["sensor_profile"])
        self.assertEqual(runs["rec"][2], runs["flags"][2])  # as if its flags were typed
        self.assertEqual(runs["override"][2], runs["plain"][2])  # a flag given: the line is not used at all
        self.assertTrue(runs["override"][0]["sensor_profile"].endswith("(command line)"))
        # A line the options refuse is bad input, with the way out.
        for bad in ("--tremor-hz 25", "--correlated-noise-px 2", "--wobble 3"):
            write_trace(rec, stroke(10), prefix=f"# sensor-profile {bad}\n")
            res = run(REPLAY, rec, "-o", self.path("bad.csv"))
            self.assertEqual(res.returncode, 2, bad)
            self.assertIn("its sensor-profile line", res.stderr)
            self.assertEqual(len(res.stderr.strip().splitlines()), 1, res.stderr)

    def test_the_timing_options_are_in_the_metadata(self):
        trace, out = self.path("t.csv"), self.path("r.csv")
        write_trace(trace, stroke(20))
        self.assertEqual(run(REPLAY, "-q", trace, "-o", out, "--extra-ms", "250", "--max-gap-s", "2.5").returncode, 0)
        self.assertEqual(read_replay(out)[0]["timing"],
                         "each report at the first tick at or after its stamp, --extra-ms 250, --max-gap-s 2.5")
        write_trace(trace, [r + (r[0] + 700,) for r in stroke(20)], header="t_us,x,y,touch,taken_us")
        self.assertEqual(run(REPLAY, "-q", trace, "-o", out).returncode, 0)
        self.assertTrue(read_replay(out)[0]["timing"].startswith("each report at the tick that took it"))

    def test_a_byte_order_mark_is_accepted(self):
        plain, bom = self.path("plain.csv"), self.path("bom.csv")
        write_trace(plain, stroke(50))
        write_trace(bom, stroke(50), prefix="\ufeff")
        a, b = self.path("a.csv"), self.path("b.csv")
        self.assertEqual(run(REPLAY, "-q", plain, "-o", a).returncode, 0)
        res = run(REPLAY, "-q", bom, "-o", b)
        self.assertEqual(res.returncode, 0, res.stderr)
        self.assertEqual(read_replay(a)[2], read_replay(b)[2])

    def test_never_overwrites_its_input(self):
        trace = self.path("a.csv")
        write_trace(trace, stroke(20))
        before = read_text(trace)
        os.symlink(trace, self.path("link.csv"))
        for out in (trace, self.path("link.csv"), os.path.join(self.tmp, ".", "a.csv")):
            res = run(REPLAY, trace, "-o", out)
            self.assertEqual(res.returncode, 2, out)
            self.assertIn("input", res.stderr)
        res = run(REPLAY, "a.csv", "-o", "./a.csv", cwd=self.tmp)  # relative paths
        self.assertEqual(res.returncode, 2)
        self.assertEqual(read_text(trace), before)

    def test_a_bad_row_fails_with_its_line_and_leaves_no_output(self):
        trace, out = self.path("t.csv"), self.path("r.csv")
        write_trace(trace, stroke(20) + [(200000, "abc", 1, 1)])
        res = run(REPLAY, trace, "-o", out)
        self.assertEqual(res.returncode, 2)
        self.assertIn("t.csv:22:2", res.stderr)
        self.assertFalse(os.path.exists(out))
        self.assertFalse(os.path.exists(out + ".partial"))

    def test_usage_errors_exit_2_and_help_exits_0(self):
        trace = self.path("t.csv")
        write_trace(trace, stroke(5))
        self.assertEqual(run(REPLAY, "--help").returncode, 0)
        self.assertEqual(run(REPLAY, trace, "--no-such-option").returncode, 2)
        self.assertEqual(run(REPLAY).returncode, 2)
        missing = self.path("missing.csv")
        res = run(REPLAY, missing)
        self.assertEqual(res.returncode, 2)
        self.assertEqual(res.stderr, "ff-replay: %s: cannot open: No such file or directory\n" % missing)
        res = run(REPLAY, self.tmp)
        self.assertEqual(res.returncode, 2)
        self.assertEqual(res.stderr, "ff-replay: %s: is a folder, not a file\n" % self.tmp)
        res = run(REPLAY, trace, "--screen", "800")
        self.assertEqual(res.returncode, 2)
        self.assertIn("--screen '800': expected WxH", res.stderr)
        for out, why in ((self.tmp, "Is a directory"), (self.path("missing/r.csv"), "No such file or directory")):
            res = run(REPLAY, trace, "-o", out)
            self.assertEqual(res.returncode, 2, out)
            self.assertIn(f"cannot write {out}: {why}\n", res.stderr)
        res = run(REPLAY, trace, "--tracker", "psychic")
        self.assertEqual(res.returncode, 2)
        self.assertIn("unknown tracker 'psychic': recommended, thesis", res.stderr)
        res = run(REPLAY, trace, "--derivative", "sideways")
        self.assertEqual(res.returncode, 2)
        self.assertIn("--derivative is filtered or raw", res.stderr)

    def test_a_value_that_is_not_a_finite_number_is_a_usage_error(self):
        trace = self.path("t.csv")
        write_trace(trace, stroke(5))
        for tool, args in ((REPLAY, [trace, "--extra-ms", "nan"]), (REPLAY, [trace, "--white-noise-px", "nan"]),
                           (REPLAY, [trace, "--strength", "-inf"]), (SCENE_RENDER, ["--step", "nan"]),
                           (SCENE_RENDER, ["--direction", "nan"])):
            res = run(tool, *args)
            self.assertEqual(res.returncode, 2, args)
            self.assertEqual(res.stderr, f"{os.path.basename(tool)}: {args[-2]} {args[-1]}: not a finite number\n")
        # A file may be called nan: positional arguments are names, not numbers.
        write_trace(self.path("nan"), stroke(5))
        self.assertEqual(run(REPLAY, "-q", self.path("nan"), "-o", self.path("r.csv")).returncode, 0)
        # A recording's sensor-profile line is held to the same rule.
        write_trace(trace, stroke(5), prefix="# sensor-profile --white-noise-px nan\n")
        res = run(REPLAY, trace, "-o", self.path("r.csv"))
        self.assertEqual(res.returncode, 2)
        self.assertIn("--white-noise-px nan: not a finite number", res.stderr)

    def test_scene_render_into_a_full_disk_exits_2(self):
        with open("/dev/full", "w") as full:
            res = subprocess.run([SCENE_RENDER, "--step", "10"], stdout=full, stderr=subprocess.PIPE, text=True)
        self.assertEqual(res.returncode, 2)
        self.assertEqual(res.stderr, "ff-scene-render: cannot write standard output: No space left on device\n")

    def test_a_header_without_the_columns_names_the_file_and_line(self):
        trace = self.path("t.csv")
        write_trace(trace, [(0, 1, 2)], header="time,x,y", prefix="# from a logger\n")
        res = run(REPLAY, trace, "-o", self.path("r.csv"))
        self.assertEqual(res.returncode, 2)
        self.assertIn("t.csv:2: header must name the columns t_us, x, y and touch", res.stderr)

    def test_a_trace_without_rows_is_refused(self):
        trace, out = self.path("t.csv"), self.path("r.csv")
        write_trace(trace, [], prefix="# the logger stopped at once\n")
        res = run(REPLAY, trace, "-o", out)
        self.assertEqual(res.returncode, 2)
        self.assertIn("t.csv: no samples after the header", res.stderr)
        self.assertFalse(os.path.exists(out))

    def test_a_full_disk_is_said_and_leaves_no_output(self):
        trace, out = self.path("t.csv"), self.path("r.csv")
        write_trace(trace, stroke(200))

        def disk_of_4_kb():  # in the child: files may not grow past 4 kB
            signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
            resource.setrlimit(resource.RLIMIT_FSIZE, (4096, resource.getrlimit(resource.RLIMIT_FSIZE)[1]))

        res = run(REPLAY, "-q", trace, "-o", out, preexec_fn=disk_of_4_kb)
        self.assertEqual(res.returncode, 2)
        self.assertIn(f"cannot write {out}: File too large\n", res.stderr)  # EFBIG: the limit stands in for ENOSPC
        self.assertFalse(os.path.exists(out))
        self.assertFalse(os.path.exists(out + ".partial"))

    def test_a_fifo_is_written_directly(self):
        # -o to a named pipe (a plot reading live, a compressor): the rows go
        # straight in, no temporary file beside it.
        trace, fifo = self.path("t.csv"), self.path("rows.fifo")
        write_trace(trace, stroke(20))
        os.mkfifo(fifo)
        received = []
        reader = threading.Thread(target=lambda: received.append(open(fifo).read()), daemon=True)
        reader.start()
        res = run(REPLAY, "-q", trace, "-o", fifo, timeout=60)
        reader.join(60)
        self.assertEqual(res.returncode, 0, res.stderr)
        lines = received[0].splitlines()
        self.assertIn("t_us,x,y,vx,vy,amplitude,dac,present", lines)
        rows = [line for line in lines if line and not line.startswith("#")][1:]
        self.assertEqual(len(rows), (19 * 5000 + 100000) // TICK_US + 1)  # the last report + --extra-ms 100

    def test_the_derivative_choice_reaches_the_thesis_filter(self):
        # The thesis' 1-euro filter sets its cutoff from the derivative, so the
        # two choices filter a stroke differently.
        trace = self.path("t.csv")
        write_trace(trace, stroke(60))
        rows = {}
        for derivative in ("filtered", "raw"):
            out = self.path(derivative + ".csv")
            res = run(REPLAY, "--tracker", "thesis", "--derivative", derivative, trace, "-o", out)
            self.assertEqual(res.returncode, 0, res.stderr)
            self.assertIn("  events/faults: touch_down=1\n", res.stderr)  # one finger, down once
            meta, _, rows[derivative] = read_replay(out)
            self.assertEqual(meta["tracker"], f"thesis (derivative {derivative})")
        self.assertNotEqual([r["x"] for r in rows["filtered"]], [r["x"] for r in rows["raw"]])


class BoundedReplay(Case):
    def test_a_stamp_2_pow_31_ahead_ends_the_output_at_the_last_plausible_report(self):
        trace, out = self.path("t.csv"), self.path("r.csv")
        rows = stroke(401)  # 0 .. 2 s
        rows.append((rows[-1][0] + 2 ** 31, 300, 240, 1))
        write_trace(trace, rows)
        res = run(REPLAY, trace, "-o", out)
        self.assertEqual(res.returncode, 0, res.stderr)
        # Header on line 1, 0 .. 2 s on lines 2 .. 402, the jump on 403.
        self.assertIn(f"ff-replay: {trace}:403: time jump from t_us 2000000 (line 402) to {2000000 + 2 ** 31}",
                      res.stderr)
        meta, _, ticks = read_replay(out)
        self.assertEqual(len(ticks), 2000000 // TICK_US + 1 + 100000 // TICK_US)  # 2 s + 100 ms extra
        self.assertIn("rows_left_out=1", meta["summary"])
        self.assertEqual(run(REPLAY, "--strict", "-q", trace, "-o", out).returncode, 1)

    def test_two_logs_joined_end_the_output_where_the_clock_steps_back(self):
        # The first log 1 .. 2 s, then a second whose clock starts again at 0:
        # the second used to arrive all at once (mailbox_overflow) after the first.
        trace, out = self.path("t.csv"), self.path("r.csv")
        first = [(1_000_000 + t, x, y, touch) for t, x, y, touch in stroke(201)]
        write_trace(trace, first + stroke(50))
        res = run(REPLAY, trace, "-o", out)
        self.assertEqual(res.returncode, 0, res.stderr)
        # Header on line 1, the first log on lines 2 .. 202, the restart on 203.
        self.assertIn(f"ff-replay: {trace}:203: the clock steps back from t_us 2000000 (line 202) to 0",
                      res.stderr)
        self.assertIn("50 rows left out", res.stderr)
        self.assertNotIn("mailbox_overflow", res.stderr)
        meta, _, ticks = read_replay(out)
        self.assertEqual(len(ticks), 1000000 // TICK_US + 1 + 100000 // TICK_US)  # 1 s + 100 ms extra
        self.assertIn("samples=201 rejected=0 rows_left_out=50", meta["summary"])
        self.assertEqual(run(REPLAY, "--strict", "-q", trace, "-o", out).returncode, 1)

    @unittest.skipIf(os.environ.get("FF_SANITIZED"), "AddressSanitizer's quarantine keeps freed memory")
    def test_memory_does_not_grow_with_the_trace(self):
        def peak_kib(n):
            trace = self.path(f"t{n}.csv")
            write_trace(trace, stroke(n, dt=1000, x0=100.0))
            probe = ("import resource, subprocess, sys; subprocess.run(sys.argv[1:], check=True);"
                     "print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)")
            res = run(sys.executable, "-c", probe, REPLAY, "-q", trace, "-o", os.devnull)
            self.assertEqual(res.returncode, 0, res.stderr)
            return int(res.stdout)
        small, large = peak_kib(2000), peak_kib(400000)
        # Holding 400 k rows would take about 16 MB more (40 bytes a row).
        self.assertLess(large - small, 4000, f"peak RSS {small} KiB for 2 k rows, {large} KiB for 400 k rows")


class ScreenAndStrict(Case):
    def test_a_trace_in_other_coordinates_is_scaled_or_reported(self):
        trace, out = self.path("t.csv"), self.path("r.csv")
        # The same stroke in 4096 x 4096 sensor units: x 512 .. 1536, y 2048.
        write_trace(trace, [(t, round(x * 4096 / 800, 3), round(y * 4096 / 480, 3), 1) for t, x, y, _ in stroke(200)])
        res = run(REPLAY, trace, "-o", out)
        self.assertEqual(res.returncode, 0)
        self.assertRegex(res.stderr, r"samples 200: used \d+, rejected [1-9]\d*")
        self.assertIn("--screen", res.stderr)
        res = run(REPLAY, "-q", "--strict", trace, "-o", out)
        self.assertEqual(res.returncode, 1)
        self.assertRegex(res.stderr, r"rejected [1-9]")  # the count, also with -q
        res = run(REPLAY, "--strict", "--screen", "4096x4096", trace, "-o", out)
        self.assertEqual(res.returncode, 0, res.stderr)
        self.assertIn("samples 200: used 200, rejected 0", res.stderr)
        meta, _, rows = read_replay(out)
        self.assertEqual(meta["screen"], "4096x4096 scaled to 800x480")
        last = [r for r in rows if r["present"] == "1"][-1]
        self.assertAlmostEqual(float(last["y"]), 240.0, delta=0.5)  # back in screen pixels


class SceneWords(Case):
    def scene(self, text):
        path = self.path("scene.txt")
        with open(path, "w") as f:
            f.write(text)
        return path

    def test_a_scene_file_implies_the_file_scene(self):
        path = self.scene("rendering constant\nconstant 0.25\n")
        meta = scene_render_meta("--scene-file", path)
        self.assertEqual(meta["needs"], "nothing")
        self.assertTrue(meta["scene"].startswith("--scene file --scene-file "))
        trace, out = self.path("t.csv"), self.path("r.csv")
        write_trace(trace, stroke(20))
        self.assertEqual(run(REPLAY, "-q", "--scene-file", path, trace, "-o", out).returncode, 0)
        _, _, rows = read_replay(out)
        self.assertTrue(all(abs(float(r["amplitude"]) - 0.25) < 1e-6 for r in rows if r["present"] == "1"))

    def test_refused_scene_words_exit_2_with_a_reason(self):
        good = self.scene("rendering constant\nconstant 0.25\n")
        empty = self.path("empty.txt")
        open(empty, "w").close()
        seven = self.path("seven.txt")
        with open(seven, "w") as f:
            f.write("rendering constant\nconstant 7\n")
        cases = [
            (["--scene", "heightmap", "--scene-file", good], "drop one"),
            (["--scene-file", good, "--scene", "neutral"], "drop one"),
            (["--scene-file", self.tmp], "is a folder, not a file"),
            (["--scene-file", empty], "no directives"),
            (["--scene-file", seven], "constant 7 is outside [0, 1]"),
            (["--strength", "1.5"], "strength must be in (0, 1], got 1.5"),
            (["--idle-amplitude", "-1"], "outside [0, 1]"),
            (["--scene", "tunnel-converging", "--width-end", "0"], "--width-end"),
        ]
        trace = self.path("t.csv")
        write_trace(trace, stroke(5))
        for words, says in cases:
            for tool in ([SCENE_RENDER], [REPLAY, trace, "-o", self.path("o.csv")]):
                res = run(*tool, *words)
                self.assertEqual(res.returncode, 2, f"{tool[0]} {words}")
                self.assertIn(says, res.stderr, f"{tool[0]} {words}")


class SceneRender(SceneWords):
    def test_a_texture_samples_its_closed_form(self):
        # h sin(2 pi x / L) sin(2 pi y / L), L = 100, h = 3: max|G| = 2 pi h / L,
        # reached across x = L/4 at y = 0 (all of it along y); (gx, gy) = G / (2 max|G|).
        path = self.scene("rendering directional\nelement texture wavelength 100 100 height 3\n")
        res = run(SCENE_RENDER, "--scene-file", path, "--step", "25")
        self.assertEqual(res.returncode, 0, res.stderr)
        lines = res.stdout.splitlines()
        meta = {l[1:].strip().partition(": ")[0]: l[1:].strip().partition(": ")[2] for l in lines if l.startswith("#")}
        body = [l for l in lines if not l.startswith("#")]
        self.assertEqual(body[0], "x,y,gx,gy,amplitude")
        self.assertAlmostEqual(float(meta["max_gradient"]), 2 * math.pi * 3 / 100, places=5)
        self.assertEqual(meta["needs"], "position+direction")
        rows = {(float(r[0]), float(r[1])): [float(v) for v in r[2:]] for r in (l.split(",") for l in body[1:])}
        self.assertEqual(len(rows), 32 * 20)  # x 0..775, y 0..475: the screen is 0..799 x 0..479 px
        gx, gy, _ = rows[(25.0, 0.0)]
        self.assertAlmostEqual(gx, 0.0, places=4)
        self.assertAlmostEqual(abs(gy), 0.5, places=4)
        self.assertEqual(rows[(0.0, 0.0)][:2], [0.0, 0.0])

    def test_a_scene_the_core_refuses_exits_2_with_its_reason(self):
        # A float gradient table at 1 px is 800 x 480 x 8 bytes: over the core's budget.
        path = self.scene("rendering directional\nevaluation table 1 float gradient\n"
                          "element texture wavelength 100 100 height 3\n")
        res = run(SCENE_RENDER, "--scene-file", path)
        self.assertEqual(res.returncode, 2)
        self.assertEqual(res.stderr, "ff-scene-render: cannot prepare the scene: table larger than the RAM budget\n")
        self.assertEqual(res.stdout, "")


if __name__ == "__main__":
    REPLAY, SCENE_RENDER = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    unittest.main(argv=sys.argv[:1], verbosity=1)
