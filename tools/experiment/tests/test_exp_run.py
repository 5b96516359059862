"""ff-experiment run whole through its main(), on the in-Python fake device
with the simulated participant: the plan and the rules, resume after a kill,
device loss, what is opened is closed, and every failure one line."""
import errno
import json
import os
import signal
import subprocess
import sys
import time

import numpy as np
import pytest

from ffexp import design, device, experiment, geometry, logs
from full_disk import DiskThatFills

HERE = os.path.dirname(os.path.abspath(__file__))
TOOL = os.path.join(HERE, "..", "ff-experiment")
STANDIN = os.path.join(HERE, "standin_ff_sim.py")


def run_fake(tmp_path, *extra, factory=None, speed=8):
    argv = ["--device", "fake", "--participant", "sim", "--speed", str(speed), "--participant-number", "4",
            "-o", str(tmp_path), *extra]
    return experiment.main(argv, factory)


def test_trials_follow_the_plan_and_the_rules(tmp_path):
    assert run_fake(tmp_path, "--trials", "6", "--screenshots", str(tmp_path / "shots")) == 0
    folder = tmp_path / "P04"
    trials = logs.read_trials(str(folder))
    plan = design.plan(4)
    assert [t["trial"] for t in trials] == [1, 2, 3, 4, 5, 6]
    frames = logs.read_frames(str(folder))
    for t, p in zip(trials, plan):
        assert (t["rendering"], t["strength"], t["target"]) == (p["rendering"], p["strength"], p["target"])
        assert t["choice"] == geometry.choice(t["crossing_y"])
        assert t["hit"] == (t["choice"] == t["target"])
        assert t["movement_time"] == pytest.approx(t["t_cross"] - t["t_leave_start"], abs=1e-5)
        assert t["t_enter_start"] <= t["t_leave_start"] < t["t_cross"]
        mine = frames["trial"] == t["trial"]
        # the finger was in the start circle at t_enter and past x = 700 at t_cross
        at_cross = mine & (frames["t"] == pytest.approx(t["t_cross"], abs=5e-6))
        assert np.all(frames["x"][at_cross] > geometry.END_ZONE_X)
    session = json.loads((folder / "session.json").read_text())
    assert session["order"] == "hm-fm" and session["protocol_version"] == 2 and len(session["scene_hashes"]) == 20
    for name in ("familiarisation_1", "familiarisation_2", "trial", "feedback"):
        assert (tmp_path / "shots" / f"{name}.png").exists()


def test_refuses_to_overwrite_and_resumes(tmp_path, capsys):
    assert run_fake(tmp_path, "--trials", "2") == 0
    assert run_fake(tmp_path, "--trials", "3") == 2
    assert "--resume" in capsys.readouterr().err
    assert run_fake(tmp_path, "--trials", "4", "--resume") == 0
    assert [t["trial"] for t in logs.read_trials(str(tmp_path / "P04"))] == [1, 2, 3, 4]


def test_a_torn_trial_row_runs_that_trial_again(tmp_path, capsys):
    # A power cut while trial 3's row was written: its row has no end.
    assert run_fake(tmp_path, "--trials", "3") == 0
    trials = tmp_path / "P04" / "trials.csv"
    trials.write_text(trials.read_text()[:-12])
    capsys.readouterr()
    assert run_fake(tmp_path, "--trials", "4", "--resume") == 0
    assert f"ff-experiment: {trials}:4: the last line has no end (a write cut short): trial 3 runs again\n" \
        in capsys.readouterr().err
    assert [t["trial"] for t in logs.read_trials(str(tmp_path / "P04"))] == [1, 2, 3, 4]
    assert len(trials.read_text().splitlines()) == 5  # the header and four whole rows: the torn one cut off
    events = logs.read_events(str(tmp_path / "P04"))
    assert any(e["event"] == "resume" and int(float(e["trial"])) == 3 for e in events)


def test_a_full_disk_stops_the_study_and_resume_goes_on(tmp_path, capsys, monkeypatch):
    def frames_fill_up(path, *args, **kw):
        f = open(path, *args, **kw)
        return DiskThatFills(f, room=25000) if path.endswith("frames.csv") else f
    monkeypatch.setattr(logs, "open", frames_fill_up, raising=False)
    assert run_fake(tmp_path, "--trials", "6") == 1
    out, err = capsys.readouterr()
    frames = tmp_path / "P04" / "frames.csv"
    assert err == f"ff-experiment: cannot write {frames}: No space left on device\n"  # once, and no traceback
    assert out.rstrip().endswith("; continue with --resume")
    done = [t["trial"] for t in logs.read_trials(str(tmp_path / "P04"))]
    assert 1 <= len(done) < 6 and done == list(range(1, len(done) + 1))
    monkeypatch.undo()  # space freed
    assert run_fake(tmp_path, "--trials", "6", "--resume") == 0
    assert [t["trial"] for t in logs.read_trials(str(tmp_path / "P04"))] == [1, 2, 3, 4, 5, 6]


def test_a_log_that_fails_as_it_closes_says_so_and_exits_1(tmp_path, capsys, monkeypatch):
    real, frames_syncs = os.fsync, []

    def fsync(fd):  # frames.csv's second sync, when the log closes after trial 1, fails
        if os.readlink(f"/proc/self/fd/{fd}").endswith("frames.csv"):
            frames_syncs.append(fd)
            if len(frames_syncs) > 1:
                raise OSError(errno.EIO, os.strerror(errno.EIO))
        real(fd)

    monkeypatch.setattr(logs.os, "fsync", fsync)
    assert run_fake(tmp_path, "--trials", "1") == 1
    assert capsys.readouterr().err == (f"ff-experiment: cannot write {tmp_path / 'P04' / 'frames.csv'}: "
                                       "Input/output error; the log holds every finished trial before it; "
                                       "continue with --resume\n")
    assert [t["trial"] for t in logs.read_trials(str(tmp_path / "P04"))] == [1]


def test_killed_mid_trial_resumes_at_first_unfinished_trial(tmp_path):
    # as from a shell: not told to hide pygame's greeting (in-process runs set that for this process)
    env = {k: v for k, v in os.environ.items() if k != "PYGAME_HIDE_SUPPORT_PROMPT"}
    env["FF_SIM"] = STANDIN
    cmd = [sys.executable, TOOL, "--device", "sim", "--participant", "sim", "--speed", "8",
           "--participant-number", "5", "-o", str(tmp_path)]
    # Its own process group, killed whole: the ff-sim stand-in it started must not outlive the test.
    p = subprocess.Popen(cmd + ["--trials", "20"], env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                         start_new_session=True)
    trials = tmp_path / "P05" / "trials.csv"
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline:
        if trials.exists() and len(trials.read_text().splitlines()) >= 4:  # header + 3 trials
            break
        time.sleep(0.05)
    time.sleep(0.15)  # into the next trial
    os.killpg(p.pid, signal.SIGKILL)
    p.wait()
    done = [t["trial"] for t in logs.read_trials(str(tmp_path / "P05"))]
    assert 3 <= len(done) < 20
    r = subprocess.run(cmd + ["--trials", str(len(done) + 2), "--resume"], env=env, capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, r.stderr
    assert "pygame-ce" not in r.stdout  # pygame's greeting is not the study's output
    after = logs.read_trials(str(tmp_path / "P05"))
    assert [t["trial"] for t in after] == list(range(1, len(done) + 3))
    plan = design.plan(5)
    assert all(t["target"] == plan[t["trial"] - 1]["target"] for t in after)
    events = logs.read_events(str(tmp_path / "P05"))
    assert any(e["event"] == "resume" and int(float(e["trial"])) == len(done) + 1 for e in events)


class InterruptedDevice(device.FakeDevice):
    """Ctrl-C 1.25 s (100 frames) into trial 1, after the finger has left the start circle."""

    def __init__(self, clock):
        super().__init__(clock)
        self.polls = 0

    def poll(self):
        if self.conditions:
            self.polls += 1
            if self.polls == 100:
                raise KeyboardInterrupt
        return super().poll()


def test_a_resumed_run_never_mixes_the_interrupted_runs_frames_into_the_trial(tmp_path):
    import csv
    from ffexp import exclusions, metrics
    folder = tmp_path / "P04"
    assert run_fake(tmp_path, "--trials", "3", "--skip-familiarisation",
                    factory=lambda spec, root, speed, clock: InterruptedDevice(clock)) == 1
    assert logs.read_trials(str(folder)) == []
    with open(folder / "frames.csv") as f:
        first_run = len(f.read().splitlines()) - 1
    assert first_run >= 99
    assert run_fake(tmp_path, "--trials", "1", "--resume") == 0
    with open(folder / "frames.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    times = [float(r["t"]) for r in rows]
    assert all(b >= a for a, b in zip(times, times[1:]))  # the clock never goes back across runs
    resumed = min(times[first_run:])
    assert resumed > max(times[:first_run])
    trial = logs.read_trials(str(folder))[0]
    t, x, y = metrics.movement_samples(logs.read_frames(str(folder)), trial)
    mine = [float(r["t"]) for r in rows[first_run:] if r["trial"] == "1" and r["touch"] == "1"
            and trial["t_leave_start"] <= float(r["t"]) <= trial["t_cross"]]
    assert len(t) > 0 and list(t) == mine and t.min() >= resumed  # only the resumed run's frames
    assert exclusions.propose(str(folder)) == []  # no jump from one run's finger to the other's


def _one(made, device_class=None, **kw):
    """A device factory that makes a device_class (ClosingDevice by default) and keeps it in `made`."""
    def factory(spec, root, speed, clock):
        made.append((device_class or ClosingDevice)(clock, **kw))
        return made[-1]
    return factory


class FlakyDevice(device.FakeDevice):
    """Falls silent for one wall-clock second during trial 2."""

    def __init__(self, clock):
        super().__init__(clock)
        self.silence = None      # wall clock
        self.silence_study = None  # the same in study time

    def set_condition(self, condition):
        ack = super().set_condition(condition)
        if len([c for c in self.conditions if c.kind != "general" and c.kind != "neutral"]) == 2 and self.silence is None:
            self.silence = (self.wall() + 0.1, self.wall() + 1.1)
            speed = 1
            self.silence_study = (self.clock() + 0.1 * speed, self.clock() + 1.1 * speed)
        return ack

    def _silent_now(self):
        return self.silence is not None and self.silence[0] <= self.wall() < self.silence[1]

    def poll(self):
        self.silent = self._silent_now()
        return super().poll()

    def query_status(self):
        self.silent = self._silent_now()
        return super().query_status()


def test_device_loss_pauses_and_restarts_the_trial(tmp_path, capsys):
    made = []
    # real time: the loss (0.5 s of wall-clock silence) falls inside trial 2
    assert run_fake(tmp_path, "--trials", "2", "--skip-familiarisation", factory=_one(made, FlakyDevice), speed=1) == 0
    assert "study paused (trial 2)" in capsys.readouterr().err
    ev = [e["event"] for e in logs.read_events(str(tmp_path / "P04"))]
    assert ev.index("device-lost") < ev.index("device-back") < ev.index("trial-restart")
    frames = logs.read_frames(str(tmp_path / "P04"))
    lost = made[0].silence_study
    during = (frames["t"] > lost[0] + device.LOST_AFTER_S + 0.05) & (frames["t"] < lost[1] - 0.05)
    assert not np.any(during)  # nothing logged while the device was away
    assert [t["trial"] for t in logs.read_trials(str(tmp_path / "P04"))] == [1, 2]


def test_bad_usage_is_one_line(tmp_path):
    r = subprocess.run([sys.executable, TOOL, "-o", str(tmp_path)], capture_output=True, text=True)
    assert r.returncode == 2 and "--participant-number" in r.stderr and "Traceback" not in r.stderr
    r = subprocess.run([sys.executable, TOOL, "--device", "udp:", "--participant-number", "1", "-o", str(tmp_path)],
                       capture_output=True, text=True)
    assert r.returncode == 2 and "udp:HOST" in r.stderr and "Traceback" not in r.stderr


def test_the_devices_sensor_profile_is_in_the_session_and_a_change_is_logged(tmp_path, capsys):
    from ffexp import protocol
    assert run_fake(tmp_path, "--trials", "1", "--skip-familiarisation") == 0
    assert "default sensor profile" in capsys.readouterr().out
    session = json.loads((tmp_path / "P04" / "session.json").read_text())
    assert session["sensor_profile"] == {"white_noise_px": 1.0, "correlated_noise_px": 0.0,
                                         "correlation_time_ms": 0.0, "tremor_px": 0.0, "report_rate_hz": 200.0,
                                         "jitter_us": 150.0, "latency_us": 0,
                                         "tremor_hz": 0.0}
    # resumed on a device told another sensor: logged, and said
    def calibrated(spec, root, speed, clock):
        d = device.FakeDevice(clock)
        d.profile = protocol.SensorProfile(1.5, 1.0, 30.0, 1.0, 100.0, 200.0, 2000)
        return d
    assert run_fake(tmp_path, "--trials", "2", "--skip-familiarisation", "--resume", factory=calibrated) == 0
    out = capsys.readouterr()
    assert "default sensor profile" not in out.out and "sensor profile differs" in out.err
    changed = [e for e in logs.read_events(str(tmp_path / "P04")) if e["event"] == "sensor-profile-changed"]
    assert len(changed) == 1 and "latency_us=2000" in changed[0]["detail"] and "white_noise_px=1.5" in changed[0]["detail"]
    # the session's header keeps what the study started with
    assert json.loads((tmp_path / "P04" / "session.json").read_text())["sensor_profile"]["latency_us"] == 0


class NoisyLinkDevice(device.FakeDevice):
    """Refuses three datagrams and hears one unasked device Error on its tenth poll."""

    polls = 0

    def poll(self):
        self.polls += 1
        if self.polls == 10:
            self.errors += ["datagram refused: bad CRC"] * 3 + ["device error: busy (message type 0x02)"]
        return super().poll()


def test_refused_datagrams_and_device_errors_are_logged_once_a_frame(tmp_path):
    assert run_fake(tmp_path, "--trials", "1", "--skip-familiarisation", factory=_one([], NoisyLinkDevice)) == 0
    errors = [(e["trial"], e["detail"]) for e in logs.read_events(str(tmp_path / "P04")) if e["event"] == "device-error"]
    assert errors == [("1", "datagram refused: bad CRC (3 times)"), ("1", "device error: busy (message type 0x02)")]


def test_propose_exclusions_needs_no_participant_number(tmp_path, capsys):
    from exp_synthetic import write_participant
    folder = write_participant(str(tmp_path), 3, lambda r, s: 0.5)
    seventh = logs.read_trials(folder)[6]
    with open(os.path.join(folder, "events.csv"), "a") as f:  # during trial 7
        f.write(f"{seventh['t_enter_start'] + 0.1},7,device-lost,test\n")
    assert experiment.main(["--propose-exclusions", folder]) == 0
    path = os.path.join(folder, "exclusions.proposed.csv")
    assert capsys.readouterr().out == (f"ff-experiment: 1 candidate(s) in {path}; review them and copy the ones "
                                       "to drop into exclusions.csv\n")
    assert open(path).read().splitlines()[1] == "7,device,device lost during the trial"


def test_propose_exclusions_on_an_events_file_with_a_bad_trial_is_one_line(tmp_path, capsys):
    from exp_synthetic import write_participant
    folder = write_participant(str(tmp_path), 3, lambda r, s: 0.5)
    with open(os.path.join(folder, "events.csv"), "a") as f:
        f.write("10.0,seven,device-lost,test\n")  # line 2, under the header
    assert experiment.main(["--propose-exclusions", folder]) == 2
    assert capsys.readouterr().err == (f"ff-experiment: {os.path.join(folder, 'events.csv')}:2: "
                                       "column 'trial': 'seven' is not a number\n")


def test_resume_on_a_log_that_is_not_utf8_is_one_line(tmp_path, capsys):
    assert run_fake(tmp_path, "--trials", "2", "--skip-familiarisation") == 0
    trials = tmp_path / "P04" / "trials.csv"
    trials.write_bytes(trials.read_bytes().replace(b"ok\n", b"\xe9\n", 1))  # line 2
    capsys.readouterr()
    assert run_fake(tmp_path, "--trials", "3", "--resume") == 2
    assert capsys.readouterr().err == f"ff-experiment: {trials}:2: not UTF-8 text (byte 0xe9; save it as UTF-8)\n"


@pytest.mark.parametrize("argv, why", [
    (["--device", "udp:10.0.0.7", "--speed", "2"], "--speed is for --device sim"),
    (["--speed", "0"], "--speed is for --device sim"),
    (["--trials", "0"], "--trials must be in 1..180"),
    (["--trials", "181"], "--trials must be in 1..180"),
], ids=["speed-udp", "speed-zero", "no-trials", "too-many-trials"])
def test_bad_options_are_refused_before_anything_starts(tmp_path, capsys, argv, why):
    with pytest.raises(SystemExit) as stop:
        experiment.main(argv + ["--participant-number", "1", "-o", str(tmp_path)])
    assert stop.value.code == 2 and why in capsys.readouterr().err and not os.listdir(tmp_path)


class ClosingDevice(device.FakeDevice):
    """A fake device that remembers being closed, and can fail to open."""

    def __init__(self, clock, fail_open=None):
        super().__init__(clock)
        self.fail_open, self.closed = fail_open, 0

    def open(self):
        if self.fail_open:
            raise self.fail_open
        return super().open()

    def close(self):
        self.closed += 1




def test_a_finished_run_closes_the_device_the_log_and_pygame_and_sums_up(tmp_path, capsys, monkeypatch):
    import pygame
    closed_logs = []
    close = logs.ParticipantLog.close
    monkeypatch.setattr(logs.ParticipantLog, "close", lambda self: closed_logs.append(1) or close(self))
    pygame.quit()  # what a fresh process starts with: the run initialises what it uses
    made = []
    assert run_fake(tmp_path, "--trials", "2", "--skip-familiarisation", factory=_one(made)) == 0
    assert made[0].closed == 1 and closed_logs and not pygame.display.get_init() and not pygame.font.get_init()
    hits = sum(t["hit"] for t in logs.read_trials(str(tmp_path / "P04")))
    last = capsys.readouterr().out.splitlines()[-1]
    assert last.startswith(f"ff-experiment: {tmp_path / 'P04'}: 2 of 180 trials, score {hits}, ")
    assert last.endswith(" late frames of " + last.split(" of ")[-1]) and "--resume" not in last


def test_a_device_that_refuses_a_condition_stops_the_run(tmp_path, capsys):
    made = []

    def factory(spec, root, speed, clock):
        d = _one(made)(spec, root, speed, clock)
        d.refuse = True
        return d
    assert run_fake(tmp_path, "--trials", "2", "--skip-familiarisation", factory=factory) == 1
    out = capsys.readouterr()
    assert "ff-experiment: condition refused (prepare status 3)" in out.err
    assert out.out.splitlines()[-1].endswith("; continue with --resume") and ": 0 of 180 trials" in out.out
    assert made[0].closed == 1 and logs.read_trials(str(tmp_path / "P04")) == []


@pytest.mark.parametrize("error, code, says", [
    (device.DeviceLost("udp:10.0.0.7:5000 does not answer status"), 1, "does not answer status"),
    (device.DeviceRefused("status refused"), 1, "status refused"),
    (KeyboardInterrupt(), 1, "interrupted; the log holds every finished trial; continue with --resume"),
])
def test_a_device_that_cannot_be_opened_is_closed_and_said(tmp_path, capsys, error, code, says):
    made = []
    assert run_fake(tmp_path, factory=_one(made, fail_open=error)) == code
    assert says in capsys.readouterr().err and made[0].closed == 1
    assert not (tmp_path / "P04" / "session.json").exists()


def test_an_output_folder_that_cannot_be_made_is_one_line_and_closes_the_device(tmp_path, capsys):
    (tmp_path / "logs").write_text("a file, not a folder")
    made = []
    assert experiment.main(["--device", "fake", "--participant", "sim", "--participant-number", "4",
                            "-o", str(tmp_path / "logs")], _one(made)) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"ff-experiment: {tmp_path / 'logs' / 'P04'}") and "Not a directory" in err
    assert made[0].closed == 1


def test_a_full_disk_as_the_session_is_created_exits_1(tmp_path, capsys, monkeypatch):
    import ff_files
    real = ff_files.write_whole

    def disk_full(path, write, binary=False):
        def fill(f):
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
        return real(path, fill, binary)
    monkeypatch.setattr(ff_files, "write_whole", disk_full)
    made = []
    assert run_fake(tmp_path, factory=_one(made)) == 1  # a log that cannot be written: 1, not bad input
    session = tmp_path / "P04" / "session.json"
    assert capsys.readouterr().err == f"ff-experiment: cannot write {session}: No space left on device\n"
    assert not session.exists() and not (tmp_path / "P04" / "session.json.partial").exists()
    assert made[0].closed == 1


def test_a_sim_that_does_not_start_is_one_line(tmp_path, capsys):
    def factory(spec, root, speed, clock):
        raise device.DeviceLost("ff-sim did not start: no ready line within 10 s")
    assert run_fake(tmp_path, factory=factory) == 1
    assert capsys.readouterr().err == "ff-experiment: ff-sim did not start: no ready line within 10 s\n"


def test_the_simulated_participant_runs_headless_unless_shown(tmp_path, monkeypatch):
    for name in ("SDL_VIDEODRIVER", "SDL_AUDIODRIVER"):
        monkeypatch.delenv(name, raising=False)

    def no_device(spec, root, speed, clock):
        raise ValueError("stop here")
    assert run_fake(tmp_path, "--show", factory=no_device) == 2
    assert "SDL_VIDEODRIVER" not in os.environ  # a window for the experimenter to watch
    assert run_fake(tmp_path, factory=no_device) == 2
    assert os.environ["SDL_VIDEODRIVER"] == os.environ["SDL_AUDIODRIVER"] == "dummy"


def test_no_display_for_the_window_is_one_line(tmp_path, capsys, monkeypatch):
    import pygame
    pygame.quit()
    monkeypatch.setenv("SDL_VIDEODRIVER", "no-such-driver")
    made = []
    assert run_fake(tmp_path, "--show", factory=_one(made)) == 2
    assert "cannot open the study window" in capsys.readouterr().err and made[0].closed == 1


@pytest.mark.parametrize("edit, why", [
    (lambda s: dict(s, participant=5), "another participant's folder"),
    (lambda s: dict(s, plan=s["plan"][::-1]), "its trial order differs from this program's"),
], ids=["other-participant", "other-plan"])
def test_resume_refuses_a_folder_that_is_not_this_participants(tmp_path, capsys, edit, why):
    assert run_fake(tmp_path, "--trials", "1", "--skip-familiarisation") == 0
    path = tmp_path / "P04" / "session.json"
    path.write_text(json.dumps(edit(json.loads(path.read_text()))))
    capsys.readouterr()
    assert run_fake(tmp_path, "--trials", "2", "--resume") == 2
    assert capsys.readouterr().err == f"ff-experiment: {path}:1: {why}\n"
    assert len(logs.read_trials(str(tmp_path / "P04"))) == 1


def test_resume_with_nothing_left_to_run_says_so(tmp_path, capsys):
    assert run_fake(tmp_path, "--trials", "2", "--skip-familiarisation") == 0
    capsys.readouterr()
    events = (tmp_path / "P04" / "events.csv").read_text()
    assert run_fake(tmp_path, "--trials", "2", "--resume") == 0
    assert capsys.readouterr().out == f"ff-experiment: {tmp_path / 'P04'}: trials 1-2 of 180 are done; nothing to run up to --trials 2\n"
    assert (tmp_path / "P04" / "events.csv").read_text() == events  # no device was opened


def test_a_persons_study_has_no_simulated_participant(tmp_path, monkeypatch):
    monkeypatch.setenv("SDL_VIDEODRIVER", "dummy")
    seen = []
    monkeypatch.setattr(experiment.Study, "run", lambda self: seen.append(self.participant) or 1)
    assert run_fake(tmp_path, "--participant", "human") == 1
    assert seen == [None]
