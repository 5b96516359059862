"""The whole 180-trial study, headless, through the real ff-sim (the
firmware on the host, same UDP protocol), then ff-analyse on its logs.
With FF_REFRESH_DOC_IMAGES=1 it also refreshes the screenshots of
docs/experiment.md (a test run never writes into the tree otherwise)."""
import os
import shutil
import subprocess
import sys
import time
from collections import Counter

import numpy as np
os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")
import pygame  # noqa: E402
import pytest

from ffexp import design, geometry, logs

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.abspath(os.path.join(HERE, "..", "..", ".."))
FF_SIM = os.path.join(REPO, "build", "native", "tools", "sim", "ff-sim")
TOOL = os.path.join(HERE, "..", "ff-experiment")
ANALYSE = os.path.join(HERE, "..", "ff-analyse")
DOC_IMAGES = os.path.join(REPO, "docs", "img", "experiment")
SPEED = 10
WALL_LIMIT_S = 120


@pytest.fixture(scope="module")
def study(tmp_path_factory):
    if not os.access(FF_SIM, os.X_OK):
        pytest.fail(f"ff-sim is not built ({FF_SIM} missing): cmake --build --preset native --target ff-sim")
    out = tmp_path_factory.mktemp("study")
    env = {k: v for k, v in os.environ.items() if k != "FF_SIM"}
    start = time.monotonic()
    r = subprocess.run([sys.executable, TOOL, "--device", "sim", "--participant", "sim", "--speed", str(SPEED),
                        "--participant-number", "1", "--age", "30", "--gender", "x", "--handedness", "right",
                        "-o", str(out), "--screenshots", str(out / "shots")],
                       env=env, capture_output=True, text=True, timeout=300)
    wall = time.monotonic() - start
    print(f"\n180-trial headless study through ff-sim: {wall:.1f} s wall; {r.stdout.strip()}")
    assert r.returncode == 0, r.stderr
    return out, wall


def test_runs_in_under_two_minutes(study):
    assert study[1] < WALL_LIMIT_S


def test_logs_hold_the_whole_design(study):
    folder = str(study[0] / "P01")
    session = logs.read_session(folder)
    assert session["order"] == "fm-hm" and session["device"].startswith("sim:")
    assert session["firmware_version"] and session["protocol_version"] == 2
    assert session["sensor_profile"]["report_rate_hz"] == 200.0  # asked of the firmware: its default
    trials = logs.read_trials(folder)
    plan = design.plan(1)
    assert [t["trial"] for t in trials] == list(range(1, 181))
    assert all((t["rendering"], t["strength"], t["target"]) == (p["rendering"], p["strength"], p["target"])
               for t, p in zip(trials, plan))
    assert Counter((t["rendering"], t["strength"], t["target"]) for t in trials) == Counter(
        {(r, s, g): 10 for r in logs.RENDERINGS for s in logs.STRENGTHS for g in logs.TARGETS})
    assert all(t["ack"] == "ok" and t["movement_time"] > 0 for t in trials)
    assert all(t["choice"] == geometry.choice(t["crossing_y"]) for t in trials)
    frames = logs.read_frames(folder)
    assert np.all(np.diff(frames["t"]) >= 0)
    assert np.nanmax(frames["force_n"]) > 0.1  # the participant's press came back from the load-cell path
    events = logs.read_events(folder)
    assert [int(float(e["trial"])) for e in events if e["event"] == "pause"] == [45, 90, 135]
    # everything ff-sim sent was understood (its Samples stream too) and nothing refused
    assert [e["detail"] for e in events if e["event"] == "device-error"] == []
    # the participant chooses by the amplitude ff-sim rendered: the frictionmap
    # at full strength must be found far above chance
    fm = [t["hit"] for t in trials if t["rendering"] == "frictionmap" and t["strength"] == 1.0]
    assert np.mean(fm) > 0.6


def test_trial_screen_screenshot(study):
    shot = study[0] / "shots" / "trial.png"
    img = pygame.image.load(str(shot))
    assert img.get_size() == (geometry.WIDTH, geometry.HEIGHT)
    px = lambda x, y: tuple(img.get_at((x, y)))[:3]
    for target in ("top", "middle", "bottom"):  # the three white paths
        y = int(round(float(geometry.path_y(400, target))))
        assert max(px(400, y + d) for d in (-1, 0, 1)) == (255, 255, 255)
    assert px(400, 190) == (0, 0, 0) and px(400, 290) == (0, 0, 0)  # black between them
    assert px(60, 240) == (200, 200, 200)  # start circle
    assert px(750, 240) == (200, 200, 200)  # end zone
    if os.environ.get("FF_REFRESH_DOC_IMAGES") == "1":
        os.makedirs(DOC_IMAGES, exist_ok=True)
        for name in os.listdir(study[0] / "shots"):
            shutil.copy(study[0] / "shots" / name, os.path.join(DOC_IMAGES, name))


def test_analysis_of_the_simulated_study(study, tmp_path):
    r = subprocess.run([sys.executable, ANALYSE, str(study[0] / "P01"), "-o", str(tmp_path / "report")],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    assert (tmp_path / "report" / "fig15_learning.png").exists()
    assert "one participant: no group statistics" in (tmp_path / "report" / "summary.md").read_text()
    if os.environ.get("FF_REFRESH_DOC_IMAGES") == "1":
        shutil.copy(tmp_path / "report" / "participant_1.png", os.path.join(DOC_IMAGES, "report_participant.png"))


def test_python_codec_against_the_cpp_codec_in_ff_sim():
    """Every condition the study sends is acknowledged by the firmware's C++
    decoder, and the condition it then reports (its C++ encoder) is byte for
    byte the payload the Python encoder wrote."""
    if not os.access(FF_SIM, os.X_OK):
        pytest.fail(f"ff-sim is not built ({FF_SIM} missing): cmake --build --preset native --target ff-sim")
    from ffexp import device, protocol
    dev = device.SimDevice(FF_SIM)
    try:
        status = dev.open()
        assert status.firmware_version > 0
        conditions = [protocol.Condition(r, t, s) for r in logs.RENDERINGS for s in logs.STRENGTHS for t in logs.TARGETS]
        conditions += list(protocol.FAMILIARISATION.values()) + [protocol.Condition("neutral")]
        for c in conditions:
            ack = dev.set_condition(c)
            assert ack.ok and ack.command == protocol.SET_CONDITION
            assert dev.query_condition() == c.payload(), c
    finally:
        dev.close()
