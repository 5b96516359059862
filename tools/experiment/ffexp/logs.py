"""The participant folder: what the study writes and the analysis reads.

One folder per participant (P07/):
  session.json  header written once (atomically): who, seed, versions, scene hashes
  frames.csv    one row per 80 Hz frame: monotonic time, finger, force, lateness
  trials.csv    one row per finished trial
  events.csv    device fault/error counters when they change, device lost/back, pauses, resumes
  exclusions.csv  trials a person decided to drop (trial,reason); see exclusions.py

Rows are appended and flushed one by one and the files fsync'ed at each
trial's end (frames and events first, then the trial's row, so a row never
reaches the disk before its frames), so a killed program loses at most the
unfinished trial, which --resume runs again. A new file, folder or rename is
made durable by fsync'ing the folder that holds it. Readers raise LogError
naming the file and line.
"""
import csv
import errno
import io
import json
import math
import os

import ff_files

FORMAT = "ff-experiment-log"
FORMAT_VERSION = 1

FRAME_COLUMNS = ["trial", "t", "x", "y", "touch", "force_n", "late_ms"]
TRIAL_COLUMNS = ["trial", "rendering", "strength", "target", "choice", "hit",
                 "t_enter_start", "t_leave_start", "t_cross", "movement_time",
                 "crossing_y", "late_frames", "ack"]
EVENT_COLUMNS = ["t", "trial", "event", "detail"]

RENDERINGS = ("heightmap", "frictionmap")
STRENGTHS = (1.0, 0.66, 0.33)
TARGETS = ("top", "middle", "bottom")


class LogError(Exception):
    """Bad input: carries the file and line so the user can find it."""

    def __init__(self, path, line, message):
        super().__init__(f"{path}:{line}: {message}" if line else f"{path}: {message}")
        self.path, self.line, self.message = path, line, message


class LogWriteError(Exception):
    """A log file that cannot be written (a full disk, a lost drive): the
    study stops, and what was logged before stays."""

    def __init__(self, path, error):
        super().__init__(f"cannot write {path}: {error.strerror or error}")


# ---------------------------------------------------------------- writing

class CsvAppender:
    """Appends rows to a CSV file, flushing each; fsync() on demand."""

    def __init__(self, path, columns):
        if os.path.exists(path):
            _drop_torn_tail(path)
        fresh = not os.path.exists(path) or os.path.getsize(path) == 0
        self._file = open(path, "a", newline="", encoding="utf-8")
        self._failed = False
        self._writer = csv.writer(self._file, lineterminator="\n")
        if fresh:
            self.append(columns)

    def append(self, row):
        try:
            self._writer.writerow([_cell(v) for v in row])
            self._file.flush()
        except OSError as e:
            self._failed = True
            raise LogWriteError(self._file.name, e) from None

    def fsync(self):
        try:
            self._file.flush()
            os.fsync(self._file.fileno())
        except OSError as e:
            self._failed = True
            raise LogWriteError(self._file.name, e) from None

    def close(self):
        """Syncs and closes; once a write has failed (and said so), only closes."""
        if self._file.closed:
            return
        try:
            if not self._failed:
                self.fsync()
        finally:
            try:
                self._file.close()
            except OSError:
                pass  # the failed write's rest, already reported


def sync_folder(folder):
    """fsync a folder: the names in it (a new file, a rename) survive a power
    cut. A file system that cannot sync a folder is left as it is."""
    if os.name != "posix":
        return
    try:
        fd = os.open(folder, os.O_RDONLY | getattr(os, "O_DIRECTORY", 0))
    except OSError as e:
        raise LogWriteError(folder, e) from None
    try:
        os.fsync(fd)
    except OSError as e:
        if e.errno not in (errno.EINVAL, errno.ENOTSUP, errno.EOPNOTSUPP):
            raise LogWriteError(folder, e) from None
    finally:
        os.close(fd)


def make_folder(folder):
    """os.makedirs, then syncs the parent of each folder it made (parents first)."""
    new = []
    path = os.path.abspath(folder)
    while not os.path.isdir(path) and os.path.dirname(path) != path:
        new.append(path)
        path = os.path.dirname(path)
    os.makedirs(folder, exist_ok=True)
    for made in reversed(new):
        sync_folder(os.path.dirname(made))


def _drop_torn_tail(path):
    """A power cut or a full disk can leave half a row at the end (torn_line):
    cut it off before appending (its trial was unfinished and runs again on
    --resume)."""
    with open(path, "rb+") as f:
        start = _torn_start(f.read())
        if start is not None:
            f.truncate(start)


def _cell(v):
    if isinstance(v, float):
        return f"{v:.6f}".rstrip("0").rstrip(".") if math.isfinite(v) else ""
    if isinstance(v, bool):
        return int(v)
    return "" if v is None else v


def write_session(folder, header):
    """Writes session.json whole (ff_files.write_whole: partial file, fsync,
    rename); LogWriteError if it cannot be written."""
    data = dict(header)
    data["format"] = FORMAT
    data["format_version"] = FORMAT_VERSION

    def write(f):
        json.dump(data, f, indent=2, sort_keys=True)
        f.write("\n")
    make_folder(folder)  # a folder that cannot be made is bad input, not a write that failed
    path = os.path.join(folder, "session.json")
    try:
        ff_files.write_whole(path, write)
    except OSError as e:  # a full disk, a lost drive: LogWriteError
        raise LogWriteError(path, e) from None
    sync_folder(folder)  # the rename


class ParticipantLog:
    """The writer side: frames, trials and events of one participant."""

    def __init__(self, folder):
        make_folder(folder)
        names = [os.path.join(folder, n) for n in ("frames.csv", "trials.csv", "events.csv")]
        new = not all(os.path.exists(n) for n in names)
        self.frames = CsvAppender(names[0], FRAME_COLUMNS)
        self.trials = CsvAppender(names[1], TRIAL_COLUMNS)
        self.events = CsvAppender(names[2], EVENT_COLUMNS)
        if new:
            try:
                sync_folder(folder)
            except LogWriteError:
                self.close()
                raise

    def frame(self, trial, t, x, y, touch, force_n, late_ms):
        self.frames.append([trial, t, x, y, int(bool(touch)), force_n, late_ms])

    def event(self, t, trial, event, detail=""):
        self.events.append([t, trial, event, detail])

    def trial(self, row):
        """The trial's row, once its frames and events are on disk: a power
        cut never leaves a finished trial without them."""
        self.frames.fsync()
        self.events.fsync()
        self.trials.append([row[c] for c in TRIAL_COLUMNS])
        self.trials.fsync()

    def sync(self):
        for a in (self.frames, self.trials, self.events):
            a.fsync()

    def close(self):
        """Closes all three, then reports the first that could not be written."""
        failed = None
        for a in (self.frames, self.trials, self.events):
            try:
                a.close()
            except LogWriteError as e:
                failed = failed or e
        if failed:
            raise failed


# ---------------------------------------------------------------- reading

def read_session(folder):
    path = os.path.join(folder, "session.json")
    if not os.path.isfile(path):
        raise LogError(path, 0, "missing: not a participant folder of ff-experiment")
    with open(path, "rb") as f:
        text = _text(path, f.read())
    try:
        data = json.loads(text)
    except json.JSONDecodeError as e:
        raise LogError(path, e.lineno, f"not valid JSON ({e.msg})") from None
    if not isinstance(data, dict) or data.get("format") != FORMAT:
        raise LogError(path, 1, f"not an {FORMAT} header")
    if data.get("format_version") != FORMAT_VERSION:
        raise LogError(path, 1, f"log format version {data.get('format_version')!r}; "
                                f"this program reads version {FORMAT_VERSION}")
    for key in ("participant", "seed", "order"):
        if key not in data:
            raise LogError(path, 1, f"header has no '{key}'")
    for key in ("participant", "seed"):
        if not isinstance(data[key], int) or isinstance(data[key], bool) or data[key] < 1:
            raise LogError(path, 1, f"header's '{key}' is {json.dumps(data[key])}, not a positive whole number")
    if not isinstance(data["order"], str):
        raise LogError(path, 1, f"header's 'order' is {json.dumps(data['order'])}, not a text")
    return data


def _text(path, data):
    """The bytes of a log file as text; LogError on the line of the first byte
    that is not UTF-8 (a file saved in another encoding, or damaged)."""
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as e:
        raise LogError(path, data.count(b"\n", 0, e.start) + 1,
                       f"not UTF-8 text (byte 0x{data[e.start]:02x}; save it as UTF-8)") from None


def _torn_start(data):
    """Where a last line without its end starts in data (our writer ends every
    row with one, so it is a write cut short), or None."""
    return data.rfind(b"\n") + 1 if data and not data.endswith(b"\n") else None


def torn_line(path):
    """The number of the file's last line if it has no end: a write cut short
    (a power cut, a full disk), which the appender cuts off before appending
    and the readers leave out, as a trial that did not finish; else None."""
    with open(path, "rb") as f:
        data = f.read()
    return None if _torn_start(data) is None else data.count(b"\n") + 1


def torn_note(path):
    """'PATH:N: the last line has no end (...)' for a tool to finish with what
    becomes of that trial, or None (no such line, or no file)."""
    line = torn_line(path) if os.path.exists(path) else None
    return f"{path}:{line}: the last line has no end (a write cut short)" if line else None


def _rows(path, columns, written_by_hand=False):
    """Yields (line number, row, column index, complete) for each row, complete
    when it reaches the last column read; checks the column header. A torn last
    line is not a row, unless the file is written_by_hand: an editor may save
    the last row without its end."""
    if not os.path.isfile(path):
        raise LogError(path, 0, "missing")
    with open(path, "rb") as f:
        data = f.read()
    torn = None if written_by_hand or _torn_start(data) is None else data.count(b"\n") + 1
    reader = csv.reader(io.StringIO(_text(path, data), newline=""))

    def next_row():
        try:
            return next(reader)
        except csv.Error as e:  # a field over the csv module's size limit, a NUL byte
            raise LogError(path, reader.line_num, f"not a CSV row ({e})") from None
    try:
        head = next_row()
    except StopIteration:
        raise LogError(path, 1, "empty file (no column header)") from None
    missing = [c for c in columns if c not in head]
    if missing:
        raise LogError(path, 1, f"missing column(s): {', '.join(missing)}")
    index = {c: head.index(c) for c in columns}
    last = max(index.values())
    while True:
        try:
            row = next_row()
        except StopIteration:
            return
        if not row or reader.line_num == torn:
            continue
        yield reader.line_num, row, index, len(row) > last


def _number(path, line, name, text):
    """A finite number: a trial's fields are never empty, nan or inf."""
    try:
        v = float(text)
    except ValueError:
        v = math.nan
    if not math.isfinite(v):
        raise LogError(path, line, f"column '{name}': '{text}' is not a number")
    return v


def _whole(path, line, name, text):
    v = _number(path, line, name, text)
    if v != int(v):
        raise LogError(path, line, f"column '{name}': '{text}' is not a whole number")
    return int(v)


def read_trials(folder):
    """Finished trials as a list of dicts, in trial order. Checks every field."""
    path = os.path.join(folder, "trials.csv")
    out = []
    for line, row, idx, complete in _rows(path, TRIAL_COLUMNS):
        if not complete:
            raise LogError(path, line, f"truncated row ({len(row)} of {max(idx.values()) + 1} fields)")
        get = {c: row[i] for c, i in idx.items()}
        t = {}
        t["trial"] = _whole(path, line, "trial", get["trial"])
        for c in ("rendering", "target", "choice", "ack"):
            t[c] = get[c]
        if t["rendering"] not in RENDERINGS:
            raise LogError(path, line, f"unknown rendering '{t['rendering']}'")
        for c in ("target", "choice"):
            if t[c] not in TARGETS:
                raise LogError(path, line, f"column '{c}': unknown target '{t[c]}'")
        t["strength"] = _number(path, line, "strength", get["strength"])
        if not any(math.isclose(t["strength"], s) for s in STRENGTHS):
            raise LogError(path, line, f"column 'strength': {get['strength']} is not one of the study's strengths")
        t["hit"] = bool(_whole(path, line, "hit", get["hit"]))
        for c in ("t_enter_start", "t_leave_start", "t_cross", "movement_time", "crossing_y"):
            t[c] = _number(path, line, c, get[c])
        t["late_frames"] = _whole(path, line, "late_frames", get["late_frames"])
        t["line"] = line
        out.append(t)
    seen = set()
    for t in out:
        if t["trial"] in seen:
            raise LogError(path, t["line"], f"trial {t['trial']} appears twice")
        seen.add(t["trial"])
    return out


def read_frames(folder):
    """Frames as numpy columns. A row with too few fields (a kill mid-write,
    never resumed) is skipped; a field that is not a number is an error."""
    import numpy as np
    path = os.path.join(folder, "frames.csv")
    cols = {c: [] for c in FRAME_COLUMNS}
    for line, row, idx, complete in _rows(path, FRAME_COLUMNS):
        if not complete:
            continue
        values = []
        for c, i in idx.items():
            try:
                values.append(float(row[i]) if row[i] != "" else math.nan)
            except ValueError:
                raise LogError(path, line, f"column '{c}': '{row[i]}' is not a number") from None
        for c, v in zip(idx, values):
            cols[c].append(v)
    return {c: np.asarray(v, dtype=float) for c, v in cols.items()}


def last_time(folder):
    """The latest time in frames.csv and events.csv (0 if none): a resumed
    run's clock starts after it, so times never go back across runs and a
    killed run's frames cannot fall into a re-run trial's interval."""
    last = 0.0
    for name in ("frames.csv", "events.csv"):
        path = os.path.join(folder, name)
        if not os.path.isfile(path) or os.path.getsize(path) == 0:
            continue
        for line, row, idx, _ in _rows(path, ["t"]):
            last = max(last, _number(path, line, "t", row[idx["t"]]))
    return last


def read_events(folder):
    path = os.path.join(folder, "events.csv")
    if not os.path.isfile(path):
        return []
    out = []
    for line, row, idx, complete in _rows(path, EVENT_COLUMNS):
        if not complete:
            continue
        out.append(dict({c: row[i] for c, i in idx.items()}, line=line))
    return out
