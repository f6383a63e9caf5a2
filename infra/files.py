"""Writing results atomically, so an interrupted run leaves no partial file.

Every writer goes through :func:`atomic_write`: the data go to a temporary
file beside the target, which replaces the target only once complete, with
the mode the umask gives a new file. Inside :func:`all_or_none` the
files of one command are renamed into place together at its end, none if
any fails (a full disk after the first).

Every file the tool writes carries :data:`MARK` (a CSV's last line, a
TOML's first comment line, PNG/SVG/PDF/PS metadata, an NPZ array name,
the MF4 header comment) with the version and the input digest
(:mod:`infra.provenance`), so
:func:`written_by_us` can tell it from a file of the user's, which a
command replaces only with ``--force`` (:func:`check_output`) and the
Python API only with ``force=True`` (:func:`keeps_foreign_files`).
"""

from contextlib import contextmanager
import functools
import json
import math
import os
import tempfile
from pathlib import Path

import numpy as np

from .errors import JudderError
from .provenance import current

__all__ = ["atomic_write", "all_or_none", "write_text", "save_figure", "to_json", "MARK",
           "NPZ_MARK", "written_by_us", "check_output", "save_npz",
           "keeps_foreign_files", "mark_pdf", "mark_line",
           "check_folder_writable", "decode_text"]

#: Text every file written by the tool carries.
MARK = "written by judder"
#: Name of the array that marks an NPZ file as the tool's.
NPZ_MARK = "written_by_judder"
#: Bytes of the start and of the end of a file searched for the mark.
_MARK_WINDOW = 1 << 20
#: Metadata keys of the figure formats that carry the mark.
_FIGURE_METADATA = {"png": "Software", "pdf": "Creator", "svg": "Creator",
                    "eps": "Creator", "ps": "Creator"}


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
        raise JudderError(f"{path} exists; not overwriting it (`overwrite` "
                          "replaces it)")
    handle, temporary = tempfile.mkstemp(prefix=f".{path.name}.",
                                         suffix=".part", dir=path.parent)
    try:
        with os.fdopen(handle, "wb") as stream:
            write(stream)
            stream.flush()
            os.fsync(stream.fileno())
        # mkstemp creates 0600; a new file gets what the umask allows
        os.chmod(temporary, 0o666 & ~_umask())
        if _BATCHES:
            _BATCHES[-1].append((temporary, path))
        else:
            os.replace(temporary, path)
    except OSError as exc:
        Path(temporary).unlink(missing_ok=True)
        raise JudderError(f"cannot write {path}: {exc.strerror or exc}") \
            from None
    except BaseException:
        Path(temporary).unlink(missing_ok=True)
        raise


#: The files of the open :func:`all_or_none` blocks: (temporary, target).
_BATCHES = []


@contextmanager
def all_or_none():
    """Every file :func:`atomic_write` writes inside the block is renamed
    into place when the block ends, none if it fails: a command's outputs
    are all written or none (a full disk at its second file removes the
    first). Inside another block, the outer one decides."""
    if _BATCHES:
        yield
        return
    batch = []
    _BATCHES.append(batch)
    try:
        yield
        for temporary, path in batch:
            try:
                os.replace(temporary, path)
            except OSError as exc:
                raise JudderError(f"cannot write {path}: "
                                  f"{exc.strerror or exc}") from None
        batch.clear()
    finally:
        _BATCHES.pop()
        for temporary, _ in batch:
            Path(temporary).unlink(missing_ok=True)


def _umask():
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


def written_by_us(path):
    """True if the file at ``path`` carries :data:`MARK` (or is an NPZ
    file with the :data:`NPZ_MARK` array): the tool wrote it."""
    try:
        with open(path, "rb") as stream:
            head = stream.read(_MARK_WINDOW)
            stream.seek(0, os.SEEK_END)
            size = stream.tell()
            stream.seek(max(size - _MARK_WINDOW, len(head)))
            tail = stream.read()
    except OSError:
        return False
    return any(mark in part for part in (head, tail)
               for mark in (MARK.encode(), f"{NPZ_MARK}.npy".encode()))


def mark_pdf(data):
    """A PDF (bytes) whose ``Creator`` is :data:`MARK`, for a PDF another
    program wrote (Chromium prints the report).

    An incremental update, as the PDF format provides for editing: the
    document information dictionary again, with ``/Creator`` replaced,
    then a cross-reference section for it and a trailer pointing back to
    the previous one (``/Prev``); nothing before is changed. A file
    without a classic trailer gets the mark as a comment at its end.
    """
    import re
    mark = mark_line().removeprefix("# ")
    fallback = data + f"%{mark}\n".encode()
    end = data.rfind(b"startxref")
    at = data.rfind(b"trailer", 0, end)
    found = re.match(rb"startxref\s+(\d+)", data[end:]) if end >= 0 else None
    if at < 0 or found is None:
        return fallback
    trailer = data[at:end]
    size = re.search(rb"/Size\s+(\d+)", trailer)
    root = re.search(rb"/Root\s+(\d+\s+\d+\s+R)", trailer)
    info = re.search(rb"/Info\s+(\d+)\s+(\d+)\s+R", trailer)
    ident = re.search(rb"/ID\s*(\[[^\]]*\])", trailer)
    if size is None or root is None:
        return fallback
    fields = b""
    if info is not None:
        number, generation = int(info.group(1)), int(info.group(2))
        body = re.search(rb"(?<!\d)%d %d obj\s*<<(.*?)>>\s*endobj"
                         % (number, generation), data, re.S)
        if body is not None:
            fields = re.sub(rb"/Creator\s*\((?:\\.|[^\\)])*\)", b"",
                            body.group(1), flags=re.S)
    else:
        number, generation = int(size.group(1)), 0
    offset = len(data) + 1
    update = (b"\n%d %d obj\n<<%s\n/Creator (%s)>>\nendobj\n"
              % (number, generation, fields.strip(), mark.encode()))
    xref = offset - 1 + len(update)
    update += (b"xref\n%d 1\n%010d %05d n \ntrailer\n<</Size %d /Root %s "
               b"/Info %d %d R%s /Prev %s>>\nstartxref\n%d\n%%%%EOF\n"
               % (number, offset, generation,
                  max(int(size.group(1)), number + 1), root.group(1), number,
                  generation, b" /ID " + ident.group(1) if ident else b"",
                  found.group(1), xref))
    return data + update


def keeps_foreign_files(save):
    """Decorate a ``save(self, path, ...)`` method: it gains ``force=False``
    and, without it, refuses to replace a file at ``path`` that the tool
    did not write (:func:`written_by_us`), before writing anything."""
    @functools.wraps(save)
    def guarded(self, path, *args, force=False, **kwargs):
        if not force and Path(path).is_file() and not written_by_us(path):
            raise JudderError(f"{path} exists and judder did not write it; "
                              "not replacing it (`force` replaces it)")
        return save(self, path, *args, **kwargs)
    return guarded


def check_folder_writable(folder, option, text):
    """Refuse ``folder`` (created later if missing) when its nearest
    existing ancestor is a file or cannot be written; ``text`` is what
    the user gave ``option``."""
    place = Path(folder)
    while not place.exists():
        place = place.parent
    if not place.is_dir():
        raise JudderError(f"{option} {text}: {place} is a file, not a "
                          "folder")
    if not os.access(place, os.W_OK | os.X_OK):
        raise JudderError(f"{option} {text}: folder {place} is not "
                          "writable")


def decode_text(data, what, kind="file"):
    """UTF-8 text of the bytes of a file the user named, or JudderError
    naming ``what``, the first byte that is not UTF-8 and the ``kind`` of
    file to save as UTF-8."""
    try:
        text = data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise JudderError(f"{what}: not UTF-8 text (byte "
                          f"0x{data[exc.start]:02x} at offset {exc.start}); "
                          f"save the {kind} as UTF-8") from None
    if "\0" in text:
        raise JudderError(f"{what}: not a text file (NUL bytes); allowed: "
                          "UTF-8 text")
    return text


def check_output(path, option, suffixes=None, force=False):
    """Refuse an output path before any work is done.

    Parameters
    ----------
    path : str or Path
    option : str
        The option naming it (for the message).
    suffixes : collection of str, optional
        Allowed suffixes without the dot (lower case).
    force : bool
        Allow replacing a file the tool did not write.

    Raises
    ------
    JudderError
        If ``path`` is empty, a folder, has an unknown suffix, lies under
        a file, in a folder that cannot be written, or is a file the tool
        did not write (unless ``force``).
    """
    if path is None:
        return
    text = str(path)
    if not text.strip():
        raise JudderError(f"{option} {text!r}: allowed: a file name")
    path = Path(text)
    if path.is_dir() or text.endswith(os.sep):
        raise JudderError(f"{option} {text} is a folder; allowed: a file "
                          "name")
    suffix = path.suffix.lstrip(".").lower()
    if suffixes is not None and suffix not in suffixes:
        raise JudderError(f"{option} {text}: unknown format {suffix!r}; "
                          f"allowed: {', '.join('.' + s for s in sorted(suffixes))}")
    check_folder_writable(path.parent, option, text)
    if path.exists() and not force and not written_by_us(path):
        raise JudderError(f"{option} {text} exists and was not written by "
                          "judder; not replacing it (`force` replaces "
                          "it)")


def mark_line():
    """``# written by judder 0.1.0, inputs sha256:...``: the mark with the
    provenance of the command running."""
    return f"# {MARK} {current().words().removeprefix('judder ')}"


def write_text(path, text, overwrite=True):
    """Write ``text`` (UTF-8) atomically. A CSV file ends with the line
    :func:`mark_line` (its first line stays the header a spreadsheet
    expects; the mark must be the last line, as ``written_by_us`` reads a
    file's end), a TOML file starts with it."""
    suffix = Path(path).suffix.lower()
    if suffix == ".csv":
        text = f"{text}{mark_line()}\n"
    elif suffix == ".toml":
        text = f"{mark_line()}\n{text}"
    atomic_write(path, lambda stream: stream.write(text.encode()), overwrite)


def save_npz(path, arrays):
    """Write arrays as a compressed NPZ file, atomically, with the
    :data:`NPZ_MARK` array and the provenance (``judder_version``,
    ``input_sha256``; empty outside a command)."""
    provenance = current()
    marked = {**arrays, NPZ_MARK: np.array(True),
              "judder_version": np.array(provenance.version),
              "input_sha256": np.array(provenance.input_sha256 or "")}
    atomic_write(path, lambda stream: np.savez_compressed(stream, **marked))


def save_figure(path, figure, dpi=150):
    """Save a matplotlib figure; the format follows the file's suffix
    (PNG, SVG, PDF, PS and EPS carry :data:`MARK` and the provenance in
    their metadata)."""
    suffix = Path(path).suffix.lstrip(".").lower() or "png"
    key = _FIGURE_METADATA.get(suffix)
    metadata = {key: mark_line().removeprefix("# ")} if key else None
    atomic_write(path, lambda stream: figure.savefig(
        stream, format=suffix, dpi=dpi, metadata=metadata))


def to_json(data):
    """JSON text of ``data``; complex numbers become ``[re, im]``, and a
    NaN or infinite number ``null`` (JSON has neither)."""
    def convert(value):
        if isinstance(value, (complex, np.complexfloating)):
            return [float(value.real), float(value.imag)]
        if isinstance(value, np.ndarray):
            return value.tolist()
        if isinstance(value, np.generic):
            return value.item()
        raise TypeError(f"cannot serialise {type(value).__name__}")
    # json turns NaN into the invalid token NaN: convert first, then null it
    plain = json.loads(json.dumps(data, default=convert))
    return json.dumps(_null_non_finite(plain), indent=2, allow_nan=False)


def _null_non_finite(value):
    if isinstance(value, float) and not math.isfinite(value):
        return None
    if isinstance(value, list):
        return [_null_non_finite(v) for v in value]
    if isinstance(value, dict):
        return {k: _null_non_finite(v) for k, v in value.items()}
    return value
