"""Writing results atomically, so an interrupted run leaves no partial file.

Every writer goes through :func:`atomic_write`: the data go to a temporary
file beside the target, which replaces the target only once complete.
"""

import json
import os
import tempfile
from pathlib import Path

import numpy as np

from .errors import JudderError

__all__ = ["atomic_write", "write_text", "save_figure", "to_json"]


def atomic_write(path, write, overwrite=True):
    """Write a file through ``write(binary_file)``, atomically.

    Parameters
    ----------
    path : str or Path
    write : callable
        Called with an open binary file.
    overwrite : bool
        If False, refuse to replace an existing file (user-written inputs).

    Raises
    ------
    JudderError
        If the folder does not exist, or the file exists and ``overwrite``
        is False.
    """
    path = Path(path)
    if not path.parent.is_dir():
        raise JudderError(f"cannot write {path}: folder {path.parent} does "
                          "not exist")
    if not overwrite and path.exists():
        raise JudderError(f"{path} exists; not overwriting it (use --force "
                          "to replace it)")
    handle, temporary = tempfile.mkstemp(prefix=f".{path.name}.",
                                         suffix=".part", dir=path.parent)
    try:
        with os.fdopen(handle, "wb") as stream:
            write(stream)
            stream.flush()
            os.fsync(stream.fileno())
        os.replace(temporary, path)
    except BaseException:
        Path(temporary).unlink(missing_ok=True)
        raise


def write_text(path, text, overwrite=True):
    """Write ``text`` (UTF-8) atomically."""
    atomic_write(path, lambda stream: stream.write(text.encode()), overwrite)


def save_figure(path, figure, dpi=150):
    """Save a matplotlib figure; the format follows the file's suffix."""
    suffix = Path(path).suffix.lstrip(".").lower() or "png"
    atomic_write(path, lambda stream: figure.savefig(stream, format=suffix,
                                                     dpi=dpi))


def to_json(data):
    """JSON text of ``data``; complex numbers become ``[re, im]``."""
    def convert(value):
        if isinstance(value, (complex, np.complexfloating)):
            return [float(value.real), float(value.imag)]
        if isinstance(value, np.ndarray):
            return value.tolist()
        if isinstance(value, np.generic):
            return value.item()
        raise TypeError(f"cannot serialise {type(value).__name__}")
    return json.dumps(data, default=convert, indent=2)
