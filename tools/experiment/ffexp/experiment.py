"""ff-experiment: runs the 180-trial study (docs/experiment.md)."""
import argparse
import dataclasses
import datetime
import hashlib
import os
import sys
import time

import ff_files

from . import VERSION, design, device as devices, exclusions, geometry, logs, protocol

REPO_ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", ".."))
FEEDBACK_S = 1.5
SIM_FEEDBACK_S = 0.4
STATUS_RETRY_S = 0.5
RESUME_GAP_S = 1.0  # a resumed run's clock starts this long after the last time logged

EPILOG = """\
examples:
  ff-experiment --device udp:192.168.1.177 --participant-number 7 --age 31 --gender f --handedness right -o logs
  ff-experiment --device sim --participant-number 1 -o logs        (finger = mouse, button held = touching)
  ff-experiment --device sim --participant sim --speed 10 --participant-number 1 -o logs   (headless)
  ff-experiment --resume --device udp:192.168.1.177 --participant-number 7 -o logs
  ff-experiment --propose-exclusions logs/P07

Keys: space ends the familiarisation and pause screens; Esc stops (the log
is complete up to the last finished trial; continue with --resume).
Exit codes: 0 study finished, 1 stopped before the end, 2 bad usage or input.
"""


def parse(argv):
    ap = argparse.ArgumentParser(prog="ff-experiment", description="Run the frictionfield 180-trial study.",
                                 epilog=EPILOG, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--device", default="sim", help="udp:HOST[:PORT] (the Teensy), sim (ff-sim on this computer) or fake")
    ap.add_argument("--participant", choices=("human", "sim"), default="human",
                    help="who touches the screen: a person (mouse / the device's USB mouse) or the simulated participant (headless)")
    ap.add_argument("--participant-number", type=int, help="positive integer: seeds the order; odd starts with the frictionmap")
    ap.add_argument("--age", default="")
    ap.add_argument("--gender", default="")
    ap.add_argument("--handedness", default="")
    ap.add_argument("-o", "--output", default="logs", help="folder of participant folders (P07/ is created in it)")
    ap.add_argument("--resume", action="store_true", help="continue an interrupted participant at the first unfinished trial")
    ap.add_argument("--speed", type=float, default=1.0, help="simulated time per wall second (sim device only; ff-sim --speed)")
    ap.add_argument("--trials", type=int, default=design.TRIALS, help="stop after this trial (tests, demos)")
    ap.add_argument("--skip-familiarisation", action="store_true")
    ap.add_argument("--screenshots", metavar="DIR", help="save one PNG of each screen here")
    ap.add_argument("--show", action="store_true", help="open a window even with --participant sim")
    ap.add_argument("--propose-exclusions", metavar="LOG_DIR", help="write LOG_DIR/exclusions.proposed.csv and exit")
    args = ap.parse_args(argv)
    if args.propose_exclusions:
        return args
    if args.participant_number is None or args.participant_number < 1:
        ap.error("--participant-number N (a positive integer) is required")
    if args.speed <= 0 or (args.speed != 1.0 and args.device not in ("sim", "fake")):
        ap.error("--speed is for --device sim (or fake) only: a real device runs in real time")
    if not 1 <= args.trials <= design.TRIALS:
        ap.error(f"--trials must be in 1..{design.TRIALS}")
    return args


def condition_for(trial):
    return protocol.Condition(trial["rendering"], trial["target"], trial["strength"])


def scene_hashes():
    """sha256 of each condition's SetCondition payload: what the device was told."""
    out = {}
    for r in logs.RENDERINGS:
        for s in logs.STRENGTHS:
            for t in logs.TARGETS:
                out[f"{r}/{t}/{s:g}"] = hashlib.sha256(protocol.Condition(r, t, s).payload()).hexdigest()[:16]
    for name, c in protocol.FAMILIARISATION.items():
        out[name] = hashlib.sha256(c.payload()).hexdigest()[:16]
    return out


class Study:
    """The frame loop: input, device, trial logic, log, screen."""

    def __init__(self, args, dev, folder, plan, first_trial, score, clock, pacer, participant=None):
        import pygame
        from . import screen
        self.pg = pygame
        self.args, self.dev, self.plan = args, dev, plan
        self.clock, self.pacer, self.participant = clock, pacer, participant
        self.log = logs.ParticipantLog(folder)
        self.surface = pygame.display.set_mode((geometry.WIDTH, geometry.HEIGHT))
        pygame.display.set_caption("frictionfield study")
        pygame.mouse.set_visible(False)
        self.screen = screen.Screen(self.surface)
        self.index = first_trial - 1
        self.score = score
        self.shots = set()
        self.fields = {}
        self.scene_render = os.path.join(REPO_ROOT, "build", "native", "tools", "scene_render", "ff-scene-render")
        self.sim = isinstance(dev, devices.SimDevice) or args.device == "fake"
        self.stop = False

    # ---------------------------------------------------------------- helpers
    def screenshot(self, name):
        if self.args.screenshots and name not in self.shots:
            os.makedirs(self.args.screenshots, exist_ok=True)
            self.pg.image.save(self.surface, os.path.join(self.args.screenshots, f"{name}.png"))
            self.shots.add(name)

    def keys(self):
        """True if space/return was pressed; sets self.stop on Esc or window close."""
        pressed = False
        for e in self.pg.event.get():
            if e.type == self.pg.QUIT or (e.type == self.pg.KEYDOWN and e.key == self.pg.K_ESCAPE):
                self.stop = True
            elif e.type == self.pg.KEYDOWN and e.key in (self.pg.K_SPACE, self.pg.K_RETURN):
                pressed = True
        if self.participant is not None and self.participant.presses_key(self.clock()):
            pressed = True
        return pressed

    def read_finger(self, now):
        if self.participant is not None:
            x, y, f, touch = self.participant.finger(now)
        else:
            x, y = self.pg.mouse.get_pos()
            touch = self.pg.mouse.get_pressed()[0] if self.sim else True
            f = 0.3 if touch else 0.0
        if self.sim:
            if touch:
                self.dev.finger(x, y, f)
            else:
                self.dev.finger_up()
        return float(x), float(y), bool(touch)

    def frame(self, trial_number):
        """One paced frame: returns (now, x, y, touch, lateness), or None when
        the device is lost (after pausing until it is back)."""
        lateness = self.pacer.wait()
        now = self.clock()
        x, y, touch = self.read_finger(now)
        changed = self.dev.poll()
        if self.dev.lost():
            return None  # stale force, no device: log nothing
        if changed:
            self.log.event(now, trial_number, "counters", " ".join(f"{k}={v}" for k, v in sorted(changed.items())))
        for text, count in self.dev.take_errors().items():
            self.log.event(now, trial_number, "device-error", text if count == 1 else f"{text} ({count} times)")
        if self.participant is not None:
            self.participant.feel(x, y, self.dev.amplitude)
        self.log.frame(trial_number, now, x, y, touch, self.dev.force_n, lateness * 1000.0)
        return now, x, y, touch, lateness

    def flip(self):
        self.pg.display.flip()

    # ---------------------------------------------------------------- device loss
    def wait_for_device(self, trial_number, why):
        """Pause with a clear message until the device answers again."""
        now = self.clock()
        self.log.event(now, trial_number, "device-lost", why)
        self.log.sync()
        print(f"ff-experiment: {why}; study paused (trial {trial_number})", file=sys.stderr)
        next_try = 0.0
        while not self.stop:
            self.pacer.wait()
            self.keys()
            self.screen.message("Device not answering", [why, "The study is paused and continues by itself",
                                                          "when the device answers. Esc stops (then --resume)."])
            self.screenshot("device_lost")
            self.flip()
            if self.clock() >= next_try:
                next_try = self.clock() + STATUS_RETRY_S
                try:
                    self.dev.query_status()
                    self.log.event(self.clock(), trial_number, "device-back", "")
                    return True
                except (devices.DeviceLost, devices.DeviceRefused):
                    pass
        return False

    def device_lost(self, trial_number):
        return self.wait_for_device(trial_number, f"{self.dev.name} sent nothing for {devices.LOST_AFTER_S:.1f} s")

    def send(self, condition, trial_number):
        while not self.stop:
            try:
                return self.dev.set_condition(condition)
            except devices.DeviceLost as e:
                if not self.wait_for_device(trial_number, str(e)):
                    return None
        return None

    # ---------------------------------------------------------------- screens
    def key_screen(self, title, lines, condition=None, shot=None):
        if condition is not None:
            self.send(condition, 0)  # None only when stopped: the loop below does not run
        while not self.stop:
            if self.frame(0) is None:
                if self.device_lost(0) and condition is not None:
                    self.send(condition, 0)  # the device may have restarted
                continue  # no frame to draw; Esc while it was away ends the loop
            if self.keys():
                return True
            self.screen.message(title, lines, self.dev.force_n)
            if self.sim:
                self.screen.amplitude_bar(self.dev.amplitude)
            if shot:
                self.screenshot(shot)
            self.flip()
        return False

    def familiarisation(self):
        screens = [("Familiarisation 1/2: a winding slippery path",
                    ["Explore the screen with your index finger.", "Press lightly: the bar top right turns red above 0.5 N.",
                     "Press space to continue."], "familiarisation-path"),
                   ("Familiarisation 2/2: bumps", ["Explore the screen: it feels like bumps.", "Press space to start."],
                    "bump-map")]
        for i, (title, lines, scene) in enumerate(screens):
            if not self.key_screen(title, lines, protocol.FAMILIARISATION[scene], f"familiarisation_{i + 1}"):
                return False
        return True

    def field(self, trial):
        key = (trial["rendering"], trial["target"], trial["strength"])
        if key not in self.fields:
            from . import screen
            self.fields[key] = screen.field_surface(self.scene_render, *key)
        return self.fields[key]

    # ---------------------------------------------------------------- one trial
    def run_trial(self, trial):
        n, total = trial["trial"], design.TRIALS
        ack = self.send(condition_for(trial), n)  # None only when stopped: the loop below does not run
        state = "wait-start"  # t_enter and t_leave are set as it moves on
        late = 0
        prev = None
        if self.participant is not None:
            self.participant.begin_trial(self.clock())
        while not self.stop:
            f = self.frame(n)
            if f is None:
                if not self.device_lost(n):
                    return False
                self.log.event(self.clock(), n, "trial-restart", "device was lost")
                return self.run_trial(trial)  # the condition again, from the start circle
            now, x, y, touch, lateness = f
            if self.pacer.is_late(lateness):
                late += 1
            self.keys()
            if touch and state == "wait-start" and geometry.in_start(x, y):
                state, t_enter = "in-start", now
                if self.participant is not None:
                    self.participant.started(now)
            elif state == "in-start" and touch and not geometry.in_start(x, y):
                state, t_leave = "moving", now
            elif state == "moving" and touch and geometry.in_end_zone(x):
                crossing_y = y
                if prev is not None and prev[0] < x:
                    crossing_y = prev[1] + (y - prev[1]) * (geometry.END_ZONE_X - prev[0]) / (x - prev[0])
                chosen = geometry.choice(crossing_y)
                hit = chosen == trial["target"]
                self.score += int(hit)
                self.log.trial(dict(trial, choice=chosen, hit=int(hit), t_enter_start=t_enter, t_leave_start=t_leave,
                                    t_cross=now, movement_time=now - t_leave, crossing_y=crossing_y,
                                    late_frames=late, ack="ok" if ack.ok else "refused"))
                return self.feedback(trial, hit)
            prev = (x, y) if touch else prev
            if self.participant is not None and self.participant.stuck(now):
                self.participant.begin_trial(now)
                state = "wait-start"
            self.screen.trial(n, total, self.score, self.dev.force_n, self.dev.amplitude if self.sim else None)
            if state == "moving" and x > 200:
                self.screenshot("trial")
            self.flip()
        return False

    def feedback(self, trial, hit):
        if self.participant is not None:
            self.participant.end_trial()
        end = self.clock() + (SIM_FEEDBACK_S if self.participant is not None else FEEDBACK_S)
        field = self.field(trial)
        while not self.stop and self.clock() < end:
            if self.frame(trial["trial"]) is None:
                self.device_lost(trial["trial"])  # the feedback goes on when it is back; Esc ends the loop
                continue
            self.keys()
            self.screen.feedback(trial["trial"], design.TRIALS, self.score, self.dev.force_n, hit, trial["target"], field)
            self.screenshot("feedback")
            self.flip()
        return not self.stop

    def run(self):
        if not self.args.resume and not self.args.skip_familiarisation and self.index == 0:
            if not self.familiarisation():
                return 1
        while self.index < min(len(self.plan), self.args.trials):
            trial = self.plan[self.index]
            if not self.run_trial(trial):
                return 1
            self.index += 1
            n = trial["trial"]
            if n in design.PAUSE_AFTER and self.index < self.args.trials:
                self.log.event(self.clock(), n, "pause", "")
                if not self.key_screen("Pause", [f"{n} of {design.TRIALS} trials done. Take a break.",
                                                 "Press space to continue."], protocol.Condition("neutral"), "pause"):
                    return 1
        self.send(protocol.Condition("neutral"), 0)
        self.thank_you()
        return 0

    def thank_you(self):
        self.screen.message("Thank you!", [f"Score {self.score} of {self.index}"])
        self.screenshot("done")
        self.flip()

    def close(self):
        self.log.close()


def prepare_folder(args):
    """Participant folder, plan, first trial and score; new or resumed."""
    folder = os.path.join(args.output, f"P{args.participant_number:02d}")
    plan = design.plan(args.participant_number)
    if args.resume:
        session = logs.read_session(folder)
        if session["participant"] != args.participant_number:
            raise logs.LogError(os.path.join(folder, "session.json"), 1, "another participant's folder")
        if session.get("plan") != [[t["rendering"], t["strength"], t["target"]] for t in plan]:
            raise logs.LogError(os.path.join(folder, "session.json"), 1, "its trial order differs from this program's")
        trials = os.path.join(folder, "trials.csv")
        done = logs.read_trials(folder) if os.path.exists(trials) else []
        finished = {t["trial"] for t in done}
        first = next((t["trial"] for t in plan if t["trial"] not in finished), design.TRIALS + 1)
        torn = logs.torn_note(trials)
        if torn:  # the appender cuts it off when the log reopens
            print(f"ff-experiment: {torn}: trial {first} runs again", file=sys.stderr)
        return folder, plan, first, sum(t["hit"] for t in done), session
    if os.path.exists(os.path.join(folder, "session.json")):
        raise logs.LogError(folder, 0, "already has a session: continue it with --resume, or choose another folder")
    return folder, plan, 1, 0, None


def run(argv, device_factory=None):
    args = parse(argv)
    if args.propose_exclusions:
        c = exclusions.propose(args.propose_exclusions)
        path = exclusions.write_proposal(args.propose_exclusions, c)
        print(f"ff-experiment: {len(c)} candidate(s) in {path}; review them and copy the ones to drop into exclusions.csv")
        return 0
    folder, plan, first, score, session = prepare_folder(args)
    if first > args.trials:
        print(f"ff-experiment: {folder}: trials 1-{first - 1} of {design.TRIALS} are done; nothing to run"
              + (f" up to --trials {args.trials}" if first <= design.TRIALS else ""))
        return 0
    headless = args.participant == "sim" and not args.show
    if headless:
        os.environ["SDL_VIDEODRIVER"] = "dummy"
        os.environ["SDL_AUDIODRIVER"] = "dummy"
    os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")
    speed = args.speed
    # A resumed run's clock starts 1 s after the last time logged: times never go back, so a killed
    # run's frames (same trial number) cannot fall into the re-run trial's interval.
    start = logs.last_time(folder) + RESUME_GAP_S if args.resume else 0.0
    origin = time.monotonic()
    def clock():
        return start + (time.monotonic() - origin) * speed
    try:
        dev = (device_factory or devices.open_device)(args.device, REPO_ROOT, speed, clock)
    except ValueError as e:
        print(f"ff-experiment: {e}", file=sys.stderr)
        return 2
    except devices.DeviceLost as e:  # ff-sim did not start
        print(f"ff-experiment: {e}", file=sys.stderr)
        return 1
    try:
        return run_on(dev, args, folder, plan, first, score, session, clock)
    finally:
        dev.close()  # whatever happened after it was made: ff-sim must not outlive the study


def run_on(dev, args, folder, plan, first, score, session, clock):
    """The study on the device run() made: opened, session header, window, trials, summary."""
    import pygame
    from .pacing import Pacer
    try:
        status = dev.open()
    except (devices.DeviceLost, devices.DeviceRefused) as e:
        print(f"ff-experiment: {e}", file=sys.stderr)
        return 1
    profile = dataclasses.asdict(dev.sensor_profile)
    if dev.sensor_profile == protocol.SensorProfile():
        print("ff-experiment: the device's tracker uses the default sensor profile, not one measured on this "
              "sensor (docs/tracking.md#calibration, ffctl sensor-profile)")
    if session is None:
        try:
            logs.write_session(folder, dict(
                participant=args.participant_number, age=args.age, gender=args.gender, handedness=args.handedness,
                seed=args.participant_number, order=design.order_name(args.participant_number),
                program_version=VERSION, firmware_version=status.firmware, protocol_version=protocol.VERSION,
                device=dev.name, participant_kind=args.participant, speed=args.speed,
                started=datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
                scene_hashes=scene_hashes(), plan=[[t["rendering"], t["strength"], t["target"]] for t in plan],
                sensor_profile=profile))
        except logs.LogWriteError as e:  # a full disk: nothing was logged, so there is nothing to resume
            print(f"ff-experiment: {e}", file=sys.stderr)
            return 1
    participant = None
    if args.participant == "sim":
        from .participant import SimParticipant
        participant = SimParticipant(seed=args.participant_number)
    pygame.font.init()  # the display starts with the window; fonts do not
    try:
        try:
            study = Study(args, dev, folder, plan, first, score, clock, Pacer(time_scale=args.speed), participant)
        except pygame.error as e:  # no display to open the window on
            print(f"ff-experiment: cannot open the study window: {e} (--participant sim runs without one)",
                  file=sys.stderr)
            return 2
        try:
            if args.resume:
                study.log.event(clock(), first, "resume", f"firmware {status.firmware}")
                if session.get("sensor_profile") not in (None, profile):
                    # The device was told another sensor (or restarted with the default): the trials from here differ.
                    detail = " ".join(f"{k}={v:g}" for k, v in profile.items())
                    study.log.event(clock(), first, "sensor-profile-changed", detail)
                    print(f"ff-experiment: the device's sensor profile differs from the session's; logged: {detail}",
                          file=sys.stderr)
            code = study.run()
        except (devices.DeviceRefused, logs.LogWriteError) as e:
            print(f"ff-experiment: {e}", file=sys.stderr)
            code = 1
        finally:
            study.close()
    finally:
        pygame.quit()
    print(f"ff-experiment: {folder}: {study.index} of {design.TRIALS} trials, score {study.score}, "
          f"{study.pacer.late_frames} late frames of {study.pacer.frames}"
          + ("" if code == 0 else "; continue with --resume"))
    return code


def main(argv=None, device_factory=None):
    try:
        return run(sys.argv[1:] if argv is None else argv, device_factory)
    except logs.LogError as e:
        print(f"ff-experiment: {e}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("ff-experiment: interrupted; the log holds every finished trial; continue with --resume", file=sys.stderr)
        return 1
    except logs.LogWriteError as e:  # closing the log after the study stopped
        print(f"ff-experiment: {e}; the log holds every finished trial before it; continue with --resume",
              file=sys.stderr)
        return 1
    except OSError as e:
        print(f"ff-experiment: {ff_files.error_text(e)}", file=sys.stderr)
        return 2
