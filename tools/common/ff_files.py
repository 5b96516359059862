"""Outputs of the Python tools written whole: into NAME.partial, flushed to
disk, then renamed over NAME, so a killed or failed run leaves the old file
(or none), never half a new one (docs/tools.md#files). The C++ tools do the
same through host::OutputFile."""
import contextlib
import errno
import os

# savefig's metadata keys differ per format; these two say what made the file and from what.
_FIGURE_METADATA_KEYS = {"png": ("Software", "Description"), "svg": ("Creator", "Description"),
                         "pdf": ("Creator", "Subject")}


class OutputIsInput(ValueError):
    """An output that names one of the tool's inputs."""


def refuse_overwriting_inputs(outputs, inputs):
    """Raises OutputIsInput if an output is one of the inputs (docs/tools.md: a tool
    never writes over its own input), whatever its name: another relative path, a
    symbolic or a hard link. Call it before writing anything. None is no file."""
    for output in outputs:
        for source in inputs:
            if output is not None and source is not None and _same_file(output, source):
                raise OutputIsInput(f"output {output} is the input {source}: a tool never writes over its own input")


def _same_file(a, b):
    try:
        return os.path.samefile(a, b)
    except OSError:  # one does not exist (yet): only the same path is the same file
        return os.path.abspath(a) == os.path.abspath(b)


def write_whole(path, write, binary=False):
    """Calls write(f) on NAME.partial opened for writing, then renames it to NAME.

    A path that exists and is not a regular file (a FIFO, /dev/null) is written
    straight into: renaming over it would replace the device, not fill it. A
    missing folder is an error (docs/tools.md: exit 2), never made: a mistyped
    path would otherwise leave folders behind; a tool whose output is a folder
    makes that folder itself."""
    mode, text_args = ("wb", {}) if binary else ("w", {"newline": "", "encoding": "utf-8"})
    if os.path.exists(path) and not os.path.isfile(path):
        with _naming(path), open(path, mode, **text_args) as f:
            write(f)
        return
    folder = os.path.dirname(path)
    if folder and not os.path.isdir(folder):
        raise FileNotFoundError(errno.ENOENT, f"no such folder: {folder}", path)
    partial = path + ".partial"
    try:
        with _naming(partial), open(partial, mode, **text_args) as f:
            write(f)
            f.flush()
            os.fsync(f.fileno())
        os.replace(partial, path)
    finally:
        if os.path.exists(partial):
            os.remove(partial)


@contextlib.contextmanager
def _naming(path):
    """A failed write or sync raises an OSError that names no file: this one."""
    try:
        yield
    except OSError as e:
        if e.filename is None:
            e.filename = path
        raise


def error_text(e):
    """An error as a tool's one line says it: the file (if it names one) and
    why (an OSError's reason without its '[Errno N]')."""
    why = getattr(e, "strerror", None) or e
    filename = getattr(e, "filename", None)
    return f"{filename}: {why}" if filename else str(why)


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
