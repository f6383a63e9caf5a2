"""Where a result came from: the tool's version and a digest of its inputs.

A design review asks which version produced a number and from what; the
answer travels with every output (the ``--json`` text, the files of
:mod:`infra.files`, the report's header) as a :class:`Provenance`.

The digest (:func:`input_digest`) is the SHA-256 of what determines a
command's result: the command, its option values (the parameter set's
preset, ``--set`` changes, grids, methods...) and the bytes of every
input file or folder an option names; not the names of its outputs nor
where the input files lie. The parameter values follow from these and the
version, which is recorded beside the digest.

The command line computes it once per command and holds it for the
command's duration (:func:`recorded`); the writers read it
(:func:`current`). Outside a command (the Python API) an output carries
the version alone.
"""

import contextlib
import contextvars
from dataclasses import dataclass
import hashlib
import json
from pathlib import Path

__all__ = ["Provenance", "tool_version", "input_digest", "file_digest",
           "recorded", "current"]


@dataclass(frozen=True)
class Provenance:
    """The tool's version and the inputs' digest (None outside a command)."""

    version: str
    input_sha256: str = None

    def as_dict(self):
        return {"judder_version": self.version,
                "input_sha256": self.input_sha256}

    def words(self):
        """One line: ``judder 0.1.0, inputs sha256:...``."""
        return (f"judder {self.version}"
                + ("" if self.input_sha256 is None
                   else f", inputs sha256:{self.input_sha256}"))


def tool_version():
    """The installed package's version (``pyproject.toml``)."""
    from importlib.metadata import PackageNotFoundError, version
    try:
        return version("judder")
    except PackageNotFoundError:
        return "unknown (not installed: run make setup)"


def input_digest(command, options):
    """SHA-256 (hex) of a command's inputs.

    Parameters
    ----------
    command : str
        The command's name.
    options : dict
        Option name -> value (JSON-able, NumPy arrays as lists). A string
        value naming an existing file contributes the file's bytes
        instead of its name, a folder its files' relative names and bytes;
        a ``period:FILE`` value (a measured dither period) its file's.

    Returns
    -------
    str
        64 hex digits; equal for equal inputs wherever the files lie.

    Examples
    --------
    >>> a = input_digest("map", {"freq": [5.0, 250.0], "set": []})
    >>> a == input_digest("map", {"set": [], "freq": [5.0, 250.0]})
    True
    >>> a == input_digest("map", {"freq": [5.0, 251.0], "set": []})
    False
    """
    plain = {name: _content(value) for name, value in options.items()}
    text = json.dumps({"command": command, "options": plain},
                      sort_keys=True, default=_jsonable)
    return hashlib.sha256(text.encode()).hexdigest()


def _content(value):
    """``value``, or for a path of an input file or folder the digest of
    its bytes."""
    if isinstance(value, (list, tuple)):
        return [_content(v) for v in value]
    if not isinstance(value, (str, Path)) or not str(value):
        return value
    text = str(value)
    head = "period:" if text.startswith("period:") else ""
    path = Path(text[len(head):])
    # a device or a pipe (/dev/zero) has no end to hash: its name stands
    if path.is_file() or path.is_dir():
        return head + "sha256:" + _bytes_digest(path)
    return value


def file_digest(path):
    """``'sha256:...'`` of a file's or folder's bytes (as
    :func:`input_digest` takes an option's file), or None where there is
    no such file or folder: what a command read beside the files its
    options name (the acquisitions an index lists)."""
    path = Path(path)
    if path.is_file() or path.is_dir():
        return "sha256:" + _bytes_digest(path)
    return None


def _bytes_digest(path):
    digest = hashlib.sha256()
    files = ([path] if path.is_file() else
             sorted(p for p in path.rglob("*") if p.is_file()))
    for file in files:
        if file != path:
            digest.update(str(file.relative_to(path)).encode() + b"\0")
        with open(file, "rb") as stream:
            for block in iter(lambda: stream.read(1 << 20), b""):
                digest.update(block)
    return digest.hexdigest()


def _jsonable(value):
    if hasattr(value, "tolist"):
        return value.tolist()
    return repr(value)


_CURRENT = contextvars.ContextVar("provenance", default=None)


@contextlib.contextmanager
def recorded(provenance):
    """Make ``provenance`` what :func:`current` returns inside the block
    (a command's duration)."""
    token = _CURRENT.set(provenance)
    try:
        yield provenance
    finally:
        _CURRENT.reset(token)


def current():
    """The provenance of the command running, else the version alone."""
    return _CURRENT.get() or Provenance(tool_version())
