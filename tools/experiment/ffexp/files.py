"""Files written whole: into NAME.partial, flushed to disk, then renamed over
NAME, so a killed or failed run leaves the old file (or none), never half a
new one (docs/tools.md#files)."""
import os


def write_whole(path, write, binary=False):
    """Calls write(f) on NAME.partial opened for writing, then renames it to NAME."""
    partial = path + ".partial"
    try:
        with open(partial, "wb" if binary else "w", **({} if binary else {"newline": "", "encoding": "utf-8"})) as f:
            write(f)
            f.flush()
            os.fsync(f.fileno())
        os.replace(partial, path)
    finally:
        if os.path.exists(partial):
            os.remove(partial)


def save_figure(fig, path, **savefig_args):
    """A matplotlib figure as PNG, written whole."""
    write_whole(path, lambda f: fig.savefig(f, format="png", **savefig_args), binary=True)
