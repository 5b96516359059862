"""Trial exclusions: the file a person writes, and the candidates proposed
from a participant's frames and events."""
import pytest

from ffexp import exclusions, logs


def participant(tmp_path):
    folder = str(tmp_path / "P01")
    log = logs.ParticipantLog(folder)
    logs.write_session(folder, dict(participant=1, seed=1, order="fm-hm"))
    return folder, log


def stroke(log, n, t0, jump=None, back=False, touch=lambda k: 1, gap_after=None):
    """40 frames at 80 Hz along y = 240, 17 px apart (1360 px/s); a jump of
    200 px in y from frame `jump` on (undone 3 frames later with `back`): a
    step of hypot(17, 200) = 200.7 px in 1/80 s."""
    for k in range(40):
        x, y = 60 + 17 * k, 240.0
        if jump is not None and k >= jump and (not back or k < jump + 3):
            y += 200
        t = t0 + k / 80 + (0.6 if gap_after is not None and k > gap_after else 0.0)
        log.frame(n, t, x, y, touch(k), 0.3, 0)
    t_end = t0 + 39 / 80 + (0.6 if gap_after is not None else 0.0)
    log.trial(dict(trial=n, rendering="frictionmap", strength=1.0, target="middle", choice="middle", hit=1,
                   t_enter_start=t0, t_leave_start=t0, t_cross=t_end, movement_time=t_end - t0,
                   crossing_y=240, late_frames=0, ack="ok"))


def test_each_kind_of_candidate(tmp_path):
    folder, log = participant(tmp_path)
    stroke(log, 1, 0.0)
    stroke(log, 2, 1.0, jump=10)
    stroke(log, 3, 2.0, jump=10, back=True)
    log.event(3.1, 4, "device-lost", "test")
    stroke(log, 4, 3.0, jump=10)  # lost and a jump: the device is the reason
    stroke(log, 5, 4.0, gap_after=20, jump=30)  # 0.61 s without a frame, and a jump: the device again
    stroke(log, 6, 6.0, jump=10, touch=lambda k: 0 if 10 <= k < 13 else 1)  # lifted and back where it was
    stroke(log, 7, 7.0, jump=10, touch=lambda k: 0 if k else 1)  # one touching frame
    log.event(8.1, 8, "device-error", "datagram refused: bad CRC (3 times)")
    log.event(8.2, 8, "device-lost", "test")
    stroke(log, 8, 8.0)
    log.close()
    got = {n: (r, d) for n, r, d in exclusions.propose(folder)}
    assert got == {2: ("jump", "jump of 201 px in 12 ms at t=1.125 s"),
                   3: ("two-finger", "jump of 201 px at t=2.125 s and back"),
                   4: ("device", "device lost during the trial"),
                   5: ("device", "no frames for 0.61 s"),
                   8: ("device", "device error during the trial: datagram refused: bad CRC (3 times)")}


def test_a_run_killed_during_a_trial_does_not_flag_its_re_run(tmp_path):
    folder, log = participant(tmp_path)
    stroke(log, 1, 0.0)
    log.event(1.2, 2, "device-lost", "test")  # trial 2's first attempt: the run was killed, no row
    log.event(3.0, 2, "resume", "firmware 1.0")
    stroke(log, 2, 3.5)  # the re-run, clean
    log.event(4.2, 3, "device-error", "datagram refused: bad CRC")
    log.event(4.3, 3, "resume", "firmware 1.0")
    log.event(4.4, 3, "device-lost", "test")  # after the resume, before trial 3 begins: its condition's send
    stroke(log, 3, 5.0)
    log.close()
    assert exclusions.propose(folder) == [(3, "device", "device lost during the trial")]


def test_the_proposal_is_a_file_to_review_and_rename(tmp_path):
    folder, log = participant(tmp_path)
    stroke(log, 1, 0.0, jump=10)
    log.close()
    path = exclusions.write_proposal(folder, exclusions.propose(folder))
    assert path == str(tmp_path / "P01" / "exclusions.proposed.csv")
    with open(path) as f:
        assert f.read() == "trial,reason,detail\n1,jump,jump of 201 px in 12 ms at t=0.125 s\n"
    assert exclusions.read_exclusions(folder) == {}  # proposed is not excluded
    (tmp_path / "P01" / "exclusions.proposed.csv").rename(tmp_path / "P01" / "exclusions.csv")
    assert exclusions.read_exclusions(folder) == {1: "jump"}


def test_the_persons_file(tmp_path):
    (tmp_path / "exclusions.csv").write_text("trial,reason\n3,sneezed\n\n180\n 7 ,\n")
    assert exclusions.read_exclusions(str(tmp_path)) == {3: "sneezed", 180: "", 7: ""}


def test_a_persons_file_saved_without_a_final_newline_keeps_its_last_row(tmp_path):
    # many editors save so; it is not a write cut short, as in the program's own logs
    (tmp_path / "exclusions.csv").write_bytes(b"trial,reason\n3,jump\n12,two-finger")
    assert exclusions.read_exclusions(str(tmp_path)) == {3: "jump", 12: "two-finger"}


@pytest.mark.parametrize("rows, line, what", [
    ("0,x\n", 2, "'0' is not a trial number 1..180"),
    ("1,x\n181,y\n", 3, "'181' is not a trial number 1..180"),
    ("two,x\n", 2, "'two' is not a trial number 1..180"),
    ("-3,x\n", 2, "'-3' is not a trial number 1..180"),
])
def test_a_bad_trial_number_names_its_line(tmp_path, rows, line, what):
    (tmp_path / "exclusions.csv").write_text("trial,reason\n" + rows)
    with pytest.raises(logs.LogError) as e:
        exclusions.read_exclusions(str(tmp_path))
    assert (e.value.line, e.value.message) == (line, what)


def test_a_row_without_its_trial_column_names_its_line(tmp_path):
    (tmp_path / "exclusions.csv").write_text("reason,trial\nsneezed,4\nforgot\n")
    with pytest.raises(logs.LogError) as e:
        exclusions.read_exclusions(str(tmp_path))
    assert (e.value.line, e.value.message) == (3, "no trial number")
