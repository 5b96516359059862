"""The study's frame loop (experiment.Study) step by step, on the fake
device with study time stepped by the test: a person's or a scripted
participant's trial, the key screens, the feedback, device loss, Esc."""
import pytest

from ffexp import design, device, experiment, logs


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
    dev.wall = dev.clock  # its silence measured in study time too
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


def _flip_times(study, monkeypatch):
    """The study time of each screen shown (pygame.display.flip), as it happens."""
    flips = []
    monkeypatch.setattr(study.pg.display, "flip", lambda: flips.append(study.clock()))
    return flips


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
    flips = _flip_times(study, monkeypatch)
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


def test_a_key_screen_sends_its_scene_again_after_a_loss(person_study, monkeypatch):
    import pygame
    from ffexp import protocol
    study, folder = person_study
    study.pacer.step = 0.125
    polls = []
    poll = study.dev.poll

    def poll_then_fall_silent():
        polls.append(1)
        study.dev.silent = study.dev.silent or len(polls) == 3
        return poll()
    study.dev.poll = poll_then_fall_silent
    _answers_on_try(study, 2, then=lambda: pygame.event.post(pygame.event.Event(pygame.KEYDOWN, key=pygame.K_SPACE)))
    flips = _flip_times(study, monkeypatch)
    scene = protocol.FAMILIARISATION["bump-map"]
    assert study.key_screen("Bumps", ["Press space."], scene) is True
    assert len(set(flips)) == len(flips)  # one screen a frame: none drawn for the frame the device missed
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
    flips = _flip_times(study, monkeypatch)
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


def test_esc_on_a_key_screen_while_the_device_is_away_stops_it(person_study, monkeypatch):
    study, folder = person_study
    flips = _flip_times(study, monkeypatch)
    _falls_silent_and_esc_follows(study)
    assert study.key_screen("Pause", ["Take a break."]) is False
    study.close()
    assert [e["event"] for e in logs.read_events(folder)] == ["device-lost"]
    assert flips == pytest.approx([0.1, 0.2, 0.3, 0.4, 0.5, 0.7])  # no pause screen after the waiting one


def test_esc_on_a_familiarisation_screen_stops_the_study(person_study):
    study, _ = person_study

    def escape():
        study.stop = True
        return False
    study.keys = escape
    assert study.familiarisation() is False
    assert [c.kind for c in study.dev.conditions] == ["general"]  # the first screen's scene, not the second's


class ScriptedParticipant:
    """A simulated participant whose finger follows path(t) -> (x, y, touching)
    and who finds itself stuck once, at stuck_at: what the Study asks of one."""

    def __init__(self, path, stuck_at=None):
        self.path, self.stuck_at = path, stuck_at
        self.calls = []

    def begin_trial(self, t):
        self.calls.append(("begin", t))

    def started(self, t):
        self.calls.append(("started", t))

    def stuck(self, t):
        if self.stuck_at is not None and t >= self.stuck_at:
            self.stuck_at = None
            return True
        return False

    def feel(self, x, y, amplitude):
        pass

    def finger(self, t):
        x, y, touching = self.path(t)
        return x, y, 0.3, touching

    def end_trial(self):
        self.calls.append(("end", None))

    def presses_key(self, t):
        return False


def test_a_stuck_participant_starts_over_and_the_crossing_is_interpolated_at_x_700(person_study, monkeypatch,
                                                                                   tmp_path):
    import pygame
    study, folder = person_study
    study.pacer.step = 0.125
    study.args.screenshots = str(tmp_path / "shots")
    flips = _flip_times(study, monkeypatch)

    def path(t):  # in the circle, then right at 800 px/s and up at 200 px/s
        x = 60 + max(0.0, t - 0.5) * 800
        return x, 240 - (x - 60) / 4, True
    study.participant = ScriptedParticipant(path, stuck_at=0.3)
    trial = dict(design.plan(4)[0], target="top")
    assert study.run_trial(trial)
    study.close()
    # entered at 0.125, stuck at 0.375 (begun again), entered again at 0.5
    assert study.participant.calls == [("begin", 0.0), ("started", 0.125), ("begin", 0.375), ("started", 0.5),
                                       ("end", None)]
    (row,) = logs.read_trials(folder)
    assert (row["t_enter_start"], row["t_leave_start"], row["t_cross"]) == (0.5, 0.625, 1.375)
    # frames at x = 660 (y 90) and 760 (y 65): at x = 700, 2/5 of the way, y = 80
    assert row["crossing_y"] == 80.0 and row["choice"] == "top" and row["hit"] == 1 and study.score == 1
    # a flip each trial frame but the crossing's, then the simulated participant's 0.4 s of feedback
    assert flips == [0.125 * k for k in range(1, 11)] + [1.5, 1.625, 1.75, 1.875]
    trial_shot = pygame.surfarray.array3d(pygame.image.load(str(tmp_path / "shots" / "trial.png")))
    feedback_shot = pygame.surfarray.array3d(pygame.image.load(str(tmp_path / "shots" / "feedback.png")))
    assert (trial_shot != feedback_shot).any()  # the feedback screen, not the trial's left over


def test_a_finger_that_enters_the_end_zone_without_moving_right_is_taken_where_it_is(person_study):
    study, folder = person_study
    points = {1: (60, 240), 2: (760, 100), 3: (760, 300)}  # frame -> finger: a jump out of the circle, then down

    def path(t):
        x, y = points[min(3, round(t / 0.1))]
        return x, y, True
    study.participant = ScriptedParticipant(path)
    assert study.run_trial(dict(design.plan(4)[0], target="middle"))
    study.close()
    (row,) = logs.read_trials(folder)
    assert row["crossing_y"] == 300.0 and row["choice"] == "middle" and study.score == 1


def test_the_last_touching_frame_is_the_one_interpolated_from(person_study):
    study, folder = person_study
    # frame 5 lifted far away: not a point of the stroke
    points = {1: (60, 240), 2: (160, 240), 3: (460, 200), 4: (660, 100), 5: (400, 460), 6: (760, 70)}

    def path(t):
        k = min(6, round(t / 0.1))
        return (*points[k], k != 5)
    study.participant = ScriptedParticipant(path)
    assert study.run_trial(design.plan(4)[0])
    study.close()
    assert logs.read_trials(folder)[0]["crossing_y"] == 88.0  # 100 + (70 - 100) * 40 / 100, not from (400, 460)


def test_esc_during_the_feedback_stops_it(person_study):
    import pygame
    study, folder = person_study
    pygame.event.post(pygame.event.Event(pygame.KEYDOWN, key=pygame.K_ESCAPE))
    assert study.feedback(design.plan(4)[0], False) is False
    study.close()
    assert len(logs.read_frames(folder)["t"]) == 1


def _scripted_run(study, monkeypatch, *, familiarisation=True, trial_ok=lambda n: True, pause_ok=True):
    """run() with its screens and trials replaced by recorders: what it called, in order."""
    calls = []

    def run_trial(trial):
        calls.append(("trial", trial["trial"]))
        return trial_ok(trial["trial"])

    def key_screen(title, lines, condition=None, shot=None):
        calls.append(("key-screen", title, condition.kind, shot))
        return pause_ok
    monkeypatch.setattr(study, "familiarisation", lambda: calls.append(("familiarisation",)) or familiarisation)
    monkeypatch.setattr(study, "run_trial", run_trial)
    monkeypatch.setattr(study, "key_screen", key_screen)
    return calls


def test_a_run_pauses_after_trial_45_and_ends_on_a_neutral_plate_and_thanks(person_study, monkeypatch, tmp_path):
    import pygame
    study, folder = person_study
    study.args.trials = 90
    study.args.screenshots = str(tmp_path / "shots")
    calls = _scripted_run(study, monkeypatch)
    flips = _flip_times(study, monkeypatch)
    assert study.run() == 0
    assert len(flips) == 1  # the thank-you screen shown
    trials = [c[1] for c in calls if c[0] == "trial"]
    assert calls[0] == ("familiarisation",) and trials == list(range(1, 91)) and study.index == 90
    # a pause after 45 only: after 90 the run ends
    assert calls[46] == ("key-screen", "Pause", "neutral", "pause") and len(calls) == 92
    assert [c.kind for c in study.dev.conditions] == ["neutral"]  # at rest once the study is over
    study.close()
    assert [(e["trial"], e["event"]) for e in logs.read_events(folder)] == [("45", "pause")]
    shot = pygame.image.load(str(tmp_path / "shots" / "done.png"))
    assert any(shot.get_at((x, 160))[:3] != (0, 0, 0) for x in range(250, 550))  # "Thank you!"


@pytest.mark.parametrize("kwargs, trials_run, index", [
    (dict(familiarisation=False), [], 0),
    (dict(trial_ok=lambda n: n != 3), [1, 2, 3], 2),
    (dict(pause_ok=False), list(range(1, 46)), 45),
], ids=["esc-in-familiarisation", "esc-in-trial-3", "esc-in-the-pause"])
def test_a_run_stopped_anywhere_returns_1_and_sends_nothing_more(person_study, monkeypatch, kwargs, trials_run, index):
    study, _ = person_study
    study.args.trials = 60
    calls = _scripted_run(study, monkeypatch, **kwargs)
    assert study.run() == 1
    assert [c[1] for c in calls if c[0] == "trial"] == trials_run and study.index == index
    assert study.dev.conditions == []


def test_a_resumed_run_skips_the_familiarisation(person_study, monkeypatch):
    study, _ = person_study
    study.args.trials, study.args.resume = 2, True
    calls = _scripted_run(study, monkeypatch)
    assert study.run() == 0 and calls == [("trial", 1), ("trial", 2)]


def _falls_silent_and_esc_follows(study):
    """The fake device falls silent at the study's first frame and never
    answers again; Esc once the study notices."""
    poll = study.dev.poll

    def silent_from_the_first_poll():
        study.dev.silent = True
        return poll()
    study.dev.poll = silent_from_the_first_poll
    _answers_on_try(study, 10 ** 9)

    def keys():
        study.stop = study.stop or study.dev.lost()
        return False
    study.keys = keys


def test_esc_while_the_device_is_away_during_a_trial_ends_it_without_a_restart(person_study):
    study, folder = person_study
    _falls_silent_and_esc_follows(study)
    assert study.run_trial(design.plan(4)[0]) is False
    study.close()
    assert [e["event"] for e in logs.read_events(folder)] == ["device-lost"] and logs.read_trials(folder) == []


def test_esc_while_the_device_is_away_during_the_feedback_ends_it(person_study, monkeypatch):
    study, folder = person_study
    flips = _flip_times(study, monkeypatch)
    _falls_silent_and_esc_follows(study)
    assert study.feedback(design.plan(4)[0], True) is False
    study.close()
    assert [e["event"] for e in logs.read_events(folder)] == ["device-lost"]
    # feedback frames to 0.5 s, lost at 0.6 s, the waiting screen at 0.7 s, and no feedback drawn after it
    assert flips == pytest.approx([0.1, 0.2, 0.3, 0.4, 0.5, 0.7])


def test_a_device_back_during_the_feedback_lets_it_finish(person_study, monkeypatch):
    study, folder = person_study
    poll = study.dev.poll
    study.dev.poll = lambda: setattr(study.dev, "silent", study.dev.silent or study.clock() < 0.25) or poll()
    tries = _answers_on_try(study, 1)
    flips = _flip_times(study, monkeypatch)
    assert study.feedback(design.plan(4)[0], True) is True
    study.close()
    assert [e["event"] for e in logs.read_events(folder)] == ["device-lost", "device-back"] and len(tries) == 1
    assert len(set(flips)) == len(flips) and flips[-1] >= 1.5


def test_esc_during_a_trial_ends_it(person_study, monkeypatch):
    import pygame
    study, folder = person_study
    monkeypatch.setattr(study.pg, "mouse", StrokingMouse(study.clock))
    pygame.event.post(pygame.event.Event(pygame.KEYDOWN, key=pygame.K_ESCAPE))
    assert study.run_trial(design.plan(4)[0]) is False
    study.close()
    assert logs.read_trials(folder) == [] and len(logs.read_frames(folder)["t"]) == 1
