"""The participant folder's writer and readers: what a kill leaves, what a
power cut leaves, and every refusal naming its file and line."""
import errno
import json
import math
import os

import pytest

from ffexp import logs
from full_disk import DiskThatFills

TRIAL = dict(trial=1, rendering="heightmap", strength=0.66, target="top", choice="middle", hit=False,
             t_enter_start=1.0, t_leave_start=1.25, t_cross=3.125, movement_time=1.875, crossing_y=250.0,
             late_frames=0, ack="ok")


def test_every_row_reaches_the_file_as_it_is_written(tmp_path):
    log = logs.ParticipantLog(str(tmp_path))
    assert (tmp_path / "frames.csv").read_text() == "trial,t,x,y,touch,force_n,late_ms\n"
    log.frame(3, 0.0125, 100.5, 240.0, 7, 0.1234567, 0)  # any touch value is a touch
    log.frame(3, 0.025, 101.0, 240.0, 0, math.nan, 4)  # no force reading: an empty cell
    log.event(0.5, 3, "device-lost", "no status for 0.30 s")
    # read by another handle before any close or sync: what a killed program leaves
    assert (tmp_path / "frames.csv").read_text().splitlines()[1:] == ["3,0.0125,100.5,240,1,0.123457,0",
                                                                      "3,0.025,101,240,0,,4"]
    assert (tmp_path / "events.csv").read_text().splitlines()[1] == "0.5,3,device-lost,no status for 0.30 s"
    log.trial(TRIAL)
    assert (tmp_path / "trials.csv").read_text().splitlines()[1] == \
        "1,heightmap,0.66,top,middle,0,1,1.25,3.125,1.875,250,0,ok"
    log.close()
    log.close()  # twice is fine
    assert logs.read_trials(str(tmp_path))[0]["hit"] is False
    assert math.isnan(logs.read_frames(str(tmp_path))["force_n"][1])


def test_each_finished_trial_is_on_disk_and_so_is_a_closed_log(tmp_path, monkeypatch):
    synced = []
    real = os.fsync
    monkeypatch.setattr(logs.os, "fsync", lambda fd: (synced.append(os.readlink(f"/proc/self/fd/{fd}")), real(fd)))
    log = logs.ParticipantLog(str(tmp_path))
    assert synced == [str(tmp_path)]  # the folder, for the three new names in it
    synced.clear()
    log.frame(1, 0.0, 1.0, 2.0, 1, 0.0, 0)
    assert synced == []
    log.trial(TRIAL)
    names = [os.path.basename(p) for p in synced]
    assert sorted(names) == ["events.csv", "frames.csv", "trials.csv"]
    synced.clear()
    log.close()
    assert sorted(os.path.basename(p) for p in synced) == ["events.csv", "frames.csv", "trials.csv"]
    assert all(a._file.closed for a in (log.frames, log.trials, log.events))


class RecordedFile:
    """A log file whose writes are noted in `calls` as they are made."""

    def __init__(self, f, calls):
        self._f, self._calls = f, calls

    def write(self, text):
        self._calls.append(("write", self._f.name, text))
        return self._f.write(text)

    def __getattr__(self, name):
        return getattr(self._f, name)


def test_a_power_cut_never_leaves_a_trial_row_without_its_frames_nor_a_name_unsynced(tmp_path, monkeypatch):
    calls = []
    real_fsync, real_replace, real_open = os.fsync, os.replace, open

    def fsync(fd):
        calls.append(("fsync", os.readlink(f"/proc/self/fd/{fd}")))
        real_fsync(fd)

    def replace(src, dst):
        real_replace(src, dst)
        calls.append(("replace", str(dst)))

    monkeypatch.setattr(os, "fsync", fsync)
    monkeypatch.setattr(os, "replace", replace)
    monkeypatch.setattr(logs, "open", lambda *a, **kw: RecordedFile(real_open(*a, **kw), calls), raising=False)
    root = tmp_path / "logs"  # neither logs/ nor logs/P01 exists yet
    folder = root / "P01"
    logs.write_session(str(folder), dict(participant=1, seed=1, order="fm-hm"))
    synced = [c[1] for c in calls if c[0] == "fsync"]
    assert str(tmp_path) in synced and str(root) in synced  # the new folders' names in their parents
    renamed = calls.index(("replace", str(folder / "session.json")))
    assert ("fsync", str(folder)) in calls[renamed + 1:]  # the rename itself
    calls.clear()
    log = logs.ParticipantLog(str(folder))
    assert ("fsync", str(folder)) == calls[-1]  # after the three new files were made
    calls.clear()
    log.frame(1, 0.5, 10, 20, 1, 0.3, 0)
    log.event(0.6, 1, "counters", "x=1")
    log.trial(TRIAL)
    row = next(i for i, c in enumerate(calls) if c[0] == "write" and c[1].endswith("trials.csv"))
    assert [os.path.basename(c[1]) for c in calls[:row] if c[0] == "fsync"] == ["frames.csv", "events.csv"]
    assert ("fsync", str(folder / "trials.csv")) in calls[row + 1:]
    log.close()


def test_the_session_header(tmp_path):
    logs.write_session(str(tmp_path), dict(participant=7, seed=70, order="hm-fm"))
    text = (tmp_path / "session.json").read_text()
    assert text.endswith("}\n")
    assert json.loads(text) == dict(participant=7, seed=70, order="hm-fm", format="ff-experiment-log",
                                    format_version=1)
    assert logs.read_session(str(tmp_path))["participant"] == 7


@pytest.mark.parametrize("text, line, what", [
    ('{"participant": 1,\n "seed": }', 2, "not valid JSON (Expecting value)"),
    ("[1, 2]", 1, "not an ff-experiment-log header"),
    ('{"format": "other"}', 1, "not an ff-experiment-log header"),
    ('{"format": "ff-experiment-log", "format_version": 1, "participant": 1, "order": "fm-hm"}', 1,
     "header has no 'seed'"),
])
def test_a_bad_session_header_names_its_line(tmp_path, text, line, what):
    (tmp_path / "session.json").write_text(text)
    with pytest.raises(logs.LogError) as e:
        logs.read_session(str(tmp_path))
    assert (e.value.path, e.value.line, e.value.message) == (str(tmp_path / "session.json"), line, what)
    assert str(e.value) == f"{tmp_path / 'session.json'}:{line}: {what}"


def trials_file(tmp_path, edit=None, head=None):
    log = logs.ParticipantLog(str(tmp_path))
    log.trial(TRIAL)
    log.trial(dict(TRIAL, trial=2, hit=True))
    log.close()
    lines = (tmp_path / "trials.csv").read_text().splitlines()
    if head:
        lines = [head(line) for line in lines]
    if edit:
        cells = lines[2].split(","); edit(cells); lines[2] = ",".join(cells)
    (tmp_path / "trials.csv").write_text("\n".join(lines) + "\n")
    return str(tmp_path)


def test_trials_read_back_as_written(tmp_path):
    got = logs.read_trials(trials_file(tmp_path))
    assert [(t["trial"], t["hit"], t["strength"], t["late_frames"], t["line"]) for t in got] == \
        [(1, False, 0.66, 0, 2), (2, True, 0.66, 0, 3)]
    assert {k: got[0][k] for k in TRIAL} == TRIAL
    with open(tmp_path / "trials.csv", "a") as f:
        f.write("\n")  # a blank line, as an editor may leave: no row
    assert len(logs.read_trials(str(tmp_path))) == 2
    # columns in another order, one more of a newer writer: read by name
    moved = trials_file(tmp_path / "moved", head=lambda line: ",".join(["note" if line.startswith("trial") else "x"]
                                                             + line.split(",")[::-1]))
    assert [t["trial"] for t in logs.read_trials(moved)] == [1, 2]


def set_cell(name, text):
    return lambda cells: cells.__setitem__(logs.TRIAL_COLUMNS.index(name), text)


@pytest.mark.parametrize("edit, what", [
    (set_cell("trial", "nan"), "column 'trial': 'nan' is not a number"),
    (set_cell("trial", "2.5"), "column 'trial': '2.5' is not a whole number"),
    (set_cell("hit", "inf"), "column 'hit': 'inf' is not a number"),
    (set_cell("late_frames", "1e400"), "column 'late_frames': '1e400' is not a number"),
    (set_cell("movement_time", ""), "column 'movement_time': '' is not a number"),
    (set_cell("crossing_y", "-inf"), "column 'crossing_y': '-inf' is not a number"),
    (set_cell("strength", "0.5"), "column 'strength': 0.5 is not one of the study's strengths"),
    (set_cell("rendering", "vortex"), "unknown rendering 'vortex'"),
    (set_cell("choice", "left"), "column 'choice': unknown target 'left'"),
    (set_cell("trial", "1"), "trial 1 appears twice"),
    (lambda cells: cells.pop(), "truncated row (12 of 13 fields)"),
])
def test_a_bad_trial_row_names_its_line(tmp_path, edit, what):
    with pytest.raises(logs.LogError) as e:
        logs.read_trials(trials_file(tmp_path, edit))
    assert (e.value.line, e.value.message) == (3, what)


def test_a_short_row_under_a_wider_header(tmp_path):
    # a header with a column more in front: 13 fields are one short of the last one read
    folder = trials_file(tmp_path, head=lambda line: ("note," if line.startswith("trial") else "x,") + line,
                         edit=lambda cells: cells.pop())
    with pytest.raises(logs.LogError) as e:
        logs.read_trials(folder)
    assert (e.value.line, e.value.message) == (3, "truncated row (13 of 14 fields)")
    (tmp_path / "frames.csv").write_text("note,trial,t,x,y,touch,force_n,late_ms\nx,1,0,1,2,1,0.3,0\nx,1,0.1,1,2,1,0.3\n")
    assert list(logs.read_frames(folder)["t"]) == [0.0]  # the torn row is skipped, not an IndexError
    (tmp_path / "frames.csv").write_text("trial,t,x,y,touch,force_n,late_ms\n1,0,1,2,1,0.3,0\n1,0.1,1,2e,1,0.3,0\n")
    with pytest.raises(logs.LogError) as e:
        logs.read_frames(folder)
    assert (e.value.line, e.value.message) == (3, "column 'y': '2e' is not a number")
    (tmp_path / "events.csv").write_text("note,t,trial,event,detail\nx,1,2,device-lost,a\nx,2,2,device-back\n")
    assert [e["event"] for e in logs.read_events(folder)] == ["device-lost"]


def test_a_missing_or_empty_file(tmp_path):
    with pytest.raises(logs.LogError) as e:
        logs.read_trials(str(tmp_path))
    assert str(e.value) == f"{tmp_path / 'trials.csv'}: missing"
    (tmp_path / "frames.csv").write_text("")
    with pytest.raises(logs.LogError) as e:
        logs.read_frames(str(tmp_path))
    assert (e.value.line, e.value.message) == (1, "empty file (no column header)")
    assert logs.read_events(str(tmp_path)) == []  # no events file: nothing happened


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


def test_a_torn_last_row_is_no_row_in_every_reader(tmp_path):
    # A power cut or a full disk can end a file mid-row; our writer ends every
    # row with a newline, so a last line without one is a write cut short.
    log = logs.ParticipantLog(str(tmp_path))
    log.trial(TRIAL)
    log.trial(dict(TRIAL, trial=2))
    log.close()
    path = tmp_path / "trials.csv"
    whole = path.read_text()
    path.write_text(whole[:-1])  # all 13 fields, but without its end nothing says 'ok' was all of the last
    assert [t["trial"] for t in logs.read_trials(str(tmp_path))] == [1]
    path.write_text(whole[:-20])  # cut mid-row: once a 'truncated row' refusal, now the unfinished trial
    assert [t["trial"] for t in logs.read_trials(str(tmp_path))] == [1]
    path.write_text(whole[:-20] + "\n")  # the same row ended: a row, and too short
    with pytest.raises(logs.LogError) as e:
        logs.read_trials(str(tmp_path))
    assert (e.value.line, e.value.message) == (3, "truncated row (9 of 13 fields)")
    (tmp_path / "frames.csv").write_text("trial,t,x,y,touch,force_n,late_ms\n1,0,1,2,1,0.3,0\n1,0.1,1,2,1,0.3,1")
    assert list(logs.read_frames(str(tmp_path))["late_ms"]) == [0.0]  # '1' may be the start of '12'
    (tmp_path / "events.csv").write_text("t,trial,event,detail\n1,2,device-lost,a\n2,2,device-ba")
    assert [e["event"] for e in logs.read_events(str(tmp_path))] == ["device-lost"]


def test_a_log_that_cannot_be_written_says_so_once(tmp_path, monkeypatch):
    disks = []

    def open_on_a_disk(path, *args, **kw):
        disks.append(DiskThatFills(open(path, *args, **kw)))
        return disks[-1]

    monkeypatch.setattr(logs, "open", open_on_a_disk, raising=False)
    log = logs.ParticipantLog(str(tmp_path))
    for d in disks:
        d.room = 0
    with pytest.raises(logs.LogWriteError) as e:
        log.frame(1, 0.5, 10, 20, 1, 0.3, 0)
    assert str(e.value) == f"cannot write {tmp_path / 'frames.csv'}: No space left on device"
    log.close()  # said once: closing the file that failed does not say it again
    assert all(a._file.closed for a in (log.frames, log.trials, log.events))


def test_a_sync_that_fails_is_said_once_and_every_file_is_closed(tmp_path, monkeypatch):
    real = os.fsync
    failing = []

    def fsync(fd):
        if os.path.basename(os.readlink(f"/proc/self/fd/{fd}")) in failing:
            raise OSError(errno.EIO, os.strerror(errno.EIO))
        real(fd)

    monkeypatch.setattr(logs.os, "fsync", fsync)
    log = logs.ParticipantLog(str(tmp_path))
    failing.append("trials.csv")
    with pytest.raises(logs.LogWriteError) as e:
        log.trial(TRIAL)  # the trial's end syncs every file
    assert str(e.value) == f"cannot write {tmp_path / 'trials.csv'}: Input/output error"
    log.close()
    again = logs.ParticipantLog(str(tmp_path))
    failing[:] = ["frames.csv"]  # first of the three to close: the others are closed all the same
    with pytest.raises(logs.LogWriteError) as e:
        again.close()
    assert str(e.value) == f"cannot write {tmp_path / 'frames.csv'}: Input/output error"
    assert all(a._file.closed for a in (again.frames, again.trials, again.events))
