"""A log file on a disk that fills up, as Python's buffered files behave on
one: a write waits in the buffer; a flush that no longer fits in the room
left fails with ENOSPC and keeps what it could not write."""
import errno
import math
import os


class DiskThatFills:
    def __init__(self, f, room=math.inf):
        self._f, self.name, self.pending, self.room = f, f.name, "", room

    def write(self, text):
        self.pending += text
        return len(text)

    def flush(self):
        if len(self.pending) > self.room:
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
        self.room -= len(self.pending)
        self._f.write(self.pending)
        self.pending = ""
        self._f.flush()

    def close(self):
        try:
            self.flush()
        finally:
            self._f.close()

    def __getattr__(self, name):  # fileno, closed: the real file's
        return getattr(self._f, name)
