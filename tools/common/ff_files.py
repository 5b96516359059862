"""Outputs of the Python tools written whole: into NAME.partial, flushed to
disk, then renamed over NAME, so a killed or failed run leaves the old file
(or none), never half a new one (docs/tools.md#files). The C++ tools do the
same through host::OutputFile."""
import os

# savefig's metadata keys differ per format; these two say what made the file and from what.
_FIGURE_METADATA_KEYS = {"png": ("Software", "Description"), "svg": ("Creator", "Description"),
                         "pdf": ("Creator", "Subject")}


def write_whole(path, write, binary=False):
    """Calls write(f) on NAME.partial opened for writing, then renames it to NAME.

    A path that exists and is not a regular file (a FIFO, /dev/null) is written
    straight into: renaming over it would replace the device, not fill it."""
    mode, text_args = ("wb", {}) if binary else ("w", {"newline": "", "encoding": "utf-8"})
    if os.path.exists(path) and not os.path.isfile(path):
        with open(path, mode, **text_args) as f:
            write(f)
        return
    folder = os.path.dirname(path)
    if folder:
        os.makedirs(folder, exist_ok=True)
    partial = path + ".partial"
    try:
        with open(partial, mode, **text_args) as f:
            write(f)
            f.flush()
            os.fsync(f.fileno())
        os.replace(partial, path)
    except OSError as e:
        if e.filename is None:  # a failed write or sync names no file: this one
            e.filename = partial
        raise
    finally:
        if os.path.exists(partial):
            os.remove(partial)


def error_text(e):
    """An OSError as a tool's one line says it: the file (if it names one) and why."""
    return f"{e.filename}: {e.strerror or e}" if e.filename else str(e.strerror or e)


def save_figure(fig, path, software=None, description=None, **savefig_args):
    """A matplotlib figure written whole, in the format its name ends with (PNG
    unless .svg or .pdf), saying which tool made it and from what."""
    extension = os.path.splitext(path)[1][1:].lower()
    file_format = extension if extension in _FIGURE_METADATA_KEYS else "png"
    metadata = {}
    software_key, description_key = _FIGURE_METADATA_KEYS[file_format]
    if software:
        metadata[software_key] = software
    if description:
        metadata[description_key] = description
    write_whole(path, lambda f: fig.savefig(f, format=file_format, metadata=metadata, **savefig_args), binary=True)
