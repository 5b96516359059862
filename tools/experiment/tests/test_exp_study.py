"""ff-experiment with the in-Python fake device and the simulated participant:
trial logic, logs, resume after a kill, device loss, bad usage."""
import json
import os
import signal
import subprocess
import sys
import time

import numpy as np
import pytest

from ffexp import design, device, experiment, geometry, logs

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


def test_killed_mid_trial_resumes_at_first_unfinished_trial(tmp_path):
    env = dict(os.environ, FF_SIM=STANDIN)
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
    after = logs.read_trials(str(tmp_path / "P05"))
    assert [t["trial"] for t in after] == list(range(1, len(done) + 3))
    plan = design.plan(5)
    assert all(t["target"] == plan[t["trial"] - 1]["target"] for t in after)
    events = logs.read_events(str(tmp_path / "P05"))
    assert any(e["event"] == "resume" and int(float(e["trial"])) == len(done) + 1 for e in events)


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
    def factory(spec, root, speed, clock):
        made.append(FlakyDevice(clock))
        return made[0]
    # real time: the loss (0.5 s of wall-clock silence) falls inside trial 2
    assert run_fake(tmp_path, "--trials", "2", "--skip-familiarisation", factory=factory, speed=1) == 0
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


def test_torn_rows_are_cut_before_appending(tmp_path):
    folder = str(tmp_path / "P01")
    log = logs.ParticipantLog(folder)
    log.frame(1, 0.5, 10, 20, 1, 0.3, 0)
    log.close()
    with open(os.path.join(folder, "frames.csv"), "a") as f:
        f.write("1,0.51,11")  # killed mid-row
    assert len(logs.read_frames(folder)["t"]) == 1  # the reader skips the torn row
    log = logs.ParticipantLog(folder)
    log.frame(2, 0.6, 12, 22, 1, 0.3, 0)
    log.close()
    lines = open(os.path.join(folder, "frames.csv")).read().splitlines()
    assert lines[1:] == ["1,0.5,10,20,1,0.3,0", "2,0.6,12,22,1,0.3,0"]


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
    made = []

    def factory(spec, root, speed, clock):
        made.append(NoisyLinkDevice(clock))
        return made[0]
    assert run_fake(tmp_path, "--trials", "1", "--skip-familiarisation", factory=factory) == 0
    errors = [(e["trial"], e["detail"]) for e in logs.read_events(str(tmp_path / "P04")) if e["event"] == "device-error"]
    assert errors == [("1", "datagram refused: bad CRC (3 times)"), ("1", "device error: busy (message type 0x02)")]


def test_propose_exclusions_needs_no_participant_number(tmp_path, capsys):
    from exp_synthetic import write_participant
    folder = write_participant(str(tmp_path), 3, lambda r, s: 0.5)
    with open(os.path.join(folder, "events.csv"), "a") as f:
        f.write("10.0,7,device-lost,test\n")
    assert experiment.main(["--propose-exclusions", folder]) == 0
    path = os.path.join(folder, "exclusions.proposed.csv")
    assert capsys.readouterr().out == (f"ff-experiment: 1 candidate(s) in {path}; review them and copy the ones "
                                       "to drop into exclusions.csv\n")
    assert open(path).read().splitlines()[1] == "7,device,device lost during the trial"


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


class SteppingPacer:
    """Each frame 0.1 s of study time later, none late; a loop that never
    ends fails after 100 s instead of hanging the suite."""

    late_frames = frames = 0

    def __init__(self, now, step=0.1):
        self.now, self.step = now, step

    def wait(self):
        self.now[0] += self.step
        if self.now[0] > 100.0:
            raise AssertionError("still looping after 100 s of study time")
        return 0.0

    def is_late(self, lateness):
        return False


@pytest.fixture
def person_study(tmp_path, monkeypatch):
    """A Study for a person (no simulated participant) on the fake device,
    headless, its study time stepped by the pacer: (study, folder)."""
    monkeypatch.setenv("SDL_VIDEODRIVER", "dummy")
    import pygame
    pygame.display.init()
    pygame.font.init()
    now = [0.0]
    args = experiment.parse(["--device", "fake", "--participant-number", "4", "-o", str(tmp_path)])
    dev = device.FakeDevice(lambda: now[0])
    dev.open()
    folder = str(tmp_path / "P04")
    study = experiment.Study(args, dev, folder, design.plan(4), 1, 0, lambda: now[0], SteppingPacer(now))
    yield study, folder
    study.close()
    pygame.quit()


def test_a_person_sees_the_feedback_for_1_5_s(person_study):
    study, folder = person_study
    assert study.feedback(design.plan(4)[0], True)
    study.close()
    t = logs.read_frames(folder)["t"]
    assert len(t) == 15 and t[0] == pytest.approx(0.1) and t[-1] == pytest.approx(1.5)  # a frame each 0.1 s to 1.5 s


def test_the_window_and_keys_a_person_uses(person_study):
    import pygame
    study, _ = person_study
    assert pygame.display.get_caption()[0] == "frictionfield study"
    assert not pygame.mouse.get_visible()  # the finger is the pointer
    assert study.keys() is False
    for key in (pygame.K_SPACE, pygame.K_RETURN):
        pygame.event.post(pygame.event.Event(pygame.KEYDOWN, key=key))
        assert study.keys() is True and not study.stop
    pygame.event.post(pygame.event.Event(pygame.KEYDOWN, key=pygame.K_a))
    assert study.keys() is False and not study.stop
    pygame.event.post(pygame.event.Event(pygame.KEYDOWN, key=pygame.K_ESCAPE))
    assert study.keys() is False and study.stop
    study.stop = False
    pygame.event.post(pygame.event.Event(pygame.QUIT))
    study.keys()
    assert study.stop  # the window closed


class Mouse:
    """pygame.mouse as the device's USB mouse (or a person's) leaves it."""

    def __init__(self, pos, pressed):
        self.pos, self.pressed = pos, pressed

    def get_pos(self):
        return self.pos

    def get_pressed(self):
        return (self.pressed, False, False)


def test_a_persons_finger_is_the_pointer(person_study, monkeypatch):
    study, _ = person_study
    monkeypatch.setattr(study.pg, "mouse", Mouse((123, 45), True))
    assert study.read_finger(0.0) == (123.0, 45.0, True) and study.dev.finger_at == (123, 45)  # sent to ff-sim
    study.pg.mouse.pressed = False
    assert study.read_finger(0.0) == (123.0, 45.0, False) and study.dev.finger_at is None     # lifted
    study.sim = False  # the device senses the finger itself; its mouse moves only while touched
    study.pg.mouse.pos = (300, 200)
    assert study.read_finger(0.0) == (300.0, 200.0, True) and study.dev.finger_at is None


def test_a_counter_that_changes_is_logged_with_its_new_value(person_study):
    study, folder = person_study
    study.frame(3)
    study.dev.fault_counts[1] = 5
    study.frame(3)
    study.frame(3)  # unchanged: not again
    study.close()
    events = [(e["trial"], e["event"], e["detail"]) for e in logs.read_events(folder)]
    assert events == [("3", "counters", "off_screen=5")]


def _answers_on_try(study, n, then=None):
    """The fake device answers its n-th status query after going silent (then calls `then`)."""
    tries = []
    answer = type(study.dev).query_status.__get__(study.dev)  # the device's own, not an earlier wrapper

    def query_status():
        if study.dev.silent:
            tries.append(study.clock())
            study.dev.silent = len(tries) < n
            if not study.dev.silent and then:
                then()
        return answer()
    study.dev.query_status = query_status
    return tries


def test_while_the_device_is_away_a_person_sees_why_and_esc_stops(person_study, tmp_path, monkeypatch):
    import pygame
    study, folder = person_study
    study.pacer.step = 0.125  # exact in binary: the retry times below are exact too
    study.args.screenshots = str(tmp_path / "shots")
    flips = []
    monkeypatch.setattr(pygame.display, "flip", lambda: flips.append(study.clock()))
    study.dev.silent = True
    tries = _answers_on_try(study, 3)
    syncs = []
    monkeypatch.setattr(study.log, "sync", lambda: syncs.append(len(tries)))
    assert study.wait_for_device(2, "test: unplugged") is True
    assert syncs == [0]  # on disk before waiting: a power cut while it waits loses nothing
    assert tries == [0.125, 0.625, 1.125]  # every 0.5 s, not every frame
    assert flips == [0.125 * k for k in range(1, 10)]  # the message redrawn each frame
    shot = pygame.image.load(str(tmp_path / "shots" / "device_lost.png"))
    assert any(shot.get_at((x, 160))[:3] != (0, 0, 0) for x in range(250, 550))  # its title
    study.dev.silent = True
    _answers_on_try(study, 10 ** 9)  # never answers again
    pygame.event.post(pygame.event.Event(pygame.KEYDOWN, key=pygame.K_ESCAPE))
    assert study.wait_for_device(2, "test: again") is False and study.stop
    study.close()
    assert [(e["event"], e["detail"]) for e in logs.read_events(folder)] == [
        ("device-lost", "test: unplugged"), ("device-back", ""), ("device-lost", "test: again")]


def test_a_condition_refused_by_silence_is_sent_once_the_device_answers(person_study):
    from ffexp import protocol
    study, folder = person_study
    study.dev.silent = True
    tries = _answers_on_try(study, 2)
    ack = study.send(protocol.Condition("heightmap", "top", 0.5), 7)
    assert ack.ok and [c.kind for c in study.dev.conditions] == ["heightmap"] and len(tries) == 2
    study.dev.silent = True
    _answers_on_try(study, 10 ** 9)
    import pygame
    pygame.event.post(pygame.event.Event(pygame.KEYDOWN, key=pygame.K_ESCAPE))
    assert study.send(protocol.Condition("frictionmap", "top", 0.5), 8) is None  # Esc while it waits
    study.close()
    assert [(e["trial"], e["event"]) for e in logs.read_events(folder)] == [
        ("7", "device-lost"), ("7", "device-back"), ("8", "device-lost")]


def test_a_key_screen_sends_its_scene_again_after_a_loss(person_study):
    import pygame
    from ffexp import protocol
    study, folder = person_study
    study.pacer.step = 0.125
    study.dev.wall, study.dev.last_heard = study.clock, 0.0  # silence measured in study time
    polls = []
    poll = study.dev.poll

    def poll_then_fall_silent():
        polls.append(1)
        study.dev.silent = study.dev.silent or len(polls) == 3
        return poll()
    study.dev.poll = poll_then_fall_silent
    _answers_on_try(study, 2, then=lambda: pygame.event.post(pygame.event.Event(pygame.KEYDOWN, key=pygame.K_SPACE)))
    scene = protocol.FAMILIARISATION["bump-map"]
    assert study.key_screen("Bumps", ["Press space."], scene) is True
    assert study.dev.conditions == [scene, scene]  # the device may have restarted: told again
    study.close()
    assert [(e["event"], e["detail"]) for e in logs.read_events(folder)] == [
        ("device-lost", "fake sent nothing for 0.5 s"), ("device-back", "")]  # seen as silence, then sent again


class StrokingMouse(Mouse):
    """A person's finger: in the start circle until 0.5 s, then right at 800 px/s along y = 240."""

    def __init__(self, clock):
        super().__init__((60, 240), True)
        self.clock = clock

    def get_pos(self):
        return (60 + max(0.0, self.clock() - 0.5) * 800, 240)


def test_a_persons_trial_from_start_circle_to_end_zone(person_study, monkeypatch):
    study, folder = person_study
    study.pacer.step = 0.125
    monkeypatch.setattr(study.pacer, "is_late", lambda lateness: True, raising=False)
    monkeypatch.setattr(study.pg, "mouse", StrokingMouse(study.clock))
    trial = design.plan(4)[0]
    assert study.run_trial(trial)
    study.close()
    (row,) = logs.read_trials(folder)
    # frames every 0.125 s: in the circle at 0.125, out of it (x > 90) at 0.625, x = 660 at 1.25 and 760 at 1.375
    assert (row["t_enter_start"], row["t_leave_start"], row["t_cross"]) == (0.125, 0.625, 1.375)
    assert row["crossing_y"] == 240.0 and row["choice"] == "middle" and row["hit"] == int(trial["target"] == "middle")
    assert row["late_frames"] == 11 and row["movement_time"] == 0.75 and row["ack"] == "ok"


def test_a_trial_whose_condition_cannot_be_sent_ends_the_run(person_study):
    import pygame
    study, folder = person_study
    study.dev.silent = True
    _answers_on_try(study, 10 ** 9)
    pygame.event.post(pygame.event.Event(pygame.KEYDOWN, key=pygame.K_ESCAPE))
    assert study.run_trial(design.plan(4)[0]) is False
    study.close()
    assert logs.read_trials(folder) == []


def test_the_feedback_field_is_rendered_once_per_condition(person_study):
    study, _ = person_study
    trial = design.plan(4)[0]
    field = study.field(trial)
    assert field is not None and study.field(dict(trial)) is field


def test_a_key_screen_shows_its_message_and_the_amplitude(person_study, tmp_path, monkeypatch):
    import pygame
    from ffexp import protocol, screen
    study, _ = person_study
    study.args.screenshots = str(tmp_path / "shots")
    flips = []
    monkeypatch.setattr(pygame.display, "flip", lambda: flips.append(1))
    study.dev.amplitude = 1.0
    answered = []

    def keys():
        answered.append(1)
        return len(answered) > 3
    study.keys = keys
    assert study.key_screen("Pause", ["Take a break."], protocol.Condition("neutral"), "pause") is True
    assert len(flips) == 3
    shot = pygame.image.load(str(tmp_path / "shots" / "pause.png"))
    assert any(shot.get_at((x, 160))[:3] != (0, 0, 0) for x in range(250, 550))  # the title
    assert tuple(shot.get_at((int(screen.geometry.END_ZONE_X) - 100, screen.geometry.HEIGHT - 20)))[:3] == (80, 140, 255)


def test_esc_on_a_familiarisation_screen_stops_the_study(person_study):
    study, _ = person_study

    def escape():
        study.stop = True
        return False
    study.keys = escape
    assert study.familiarisation() is False
    assert [c.kind for c in study.dev.conditions] == ["general"]  # the first screen's scene, not the second's
