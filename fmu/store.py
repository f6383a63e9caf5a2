"""The one door to FMU files: built, read, unpacked and run here only.

:func:`ensure_fmu` returns the FMU of a Modelica class, built by the
project's compiler (:func:`fmu.build.build_fmu`) when no FMU of its
sources as they stand now exists. FMUs are named by their build key
(:func:`fmu.build.build_key`: the content of every source under the
library roots and the compiler's), never by a class name or a file's
modification time, so two versions of one class never share an FMU. A
class of the project's library is taken from ``build/fmu`` (``make
fmu``) while the FMU there carries the key of the sources; every other
FMU is built into the user's cache (:func:`fmu.cache.cache_folder` of
``"fmu"``, ``KEY/NAME.fmu``), nothing into the install tree.

:func:`model_description` reads an FMU's ``modelDescription.xml``
(fmpy's reader) once per file content; :func:`unpacked` extracts an FMU
once per content into the same cache (``unpacked/DIGEST``), shared by
every process; :func:`simulate` runs it with fmpy's ``simulate_fmu``
from there. Each entry is made in a temporary folder beside it and
renamed into place: of two processes making the same entry one wins and
the other uses it. With ``JUDDER_FMU_CACHE=off`` the entries go to a
temporary folder of the process, removed at its exit.
"""

import atexit
import functools
import hashlib
import os
from pathlib import Path
import shutil
import tempfile

from infra.errors import JudderError

from .cache import cache_folder
from .classes import library_folders

__all__ = ["FmuFileError", "LIBRARY", "BUILT", "ensure_fmu", "digest",
           "model_description", "unpacked", "simulate", "parameter_default"]

ROOT = Path(__file__).resolve().parents[1]
#: The project's Modelica library.
LIBRARY = ROOT / "modelica"
#: Where ``make fmu`` puts the FMUs of the project's library.
BUILT = ROOT / "build" / "fmu"


class FmuFileError(JudderError):
    """An FMU file cannot be read or unpacked; the message names the file
    and fmpy's or zip's reason."""


def ensure_fmu(model_class, version="2.0", library=None):
    """Path of the FMU of a Modelica class, built if none of its sources
    as they stand now exists.

    Parameters
    ----------
    model_class : str
        Full class name, e.g. ``'Judder.Examples.Driveline4DOF'``.
    version : {'2.0', '3.0'}
    library : path or sequence of paths, optional
        A user's package folder (or folders, in order) searched before
        the project's library.

    Returns
    -------
    Path
        ``build/fmu/NAME.fmu`` (``NAME_fmi3.fmu``) for a class of the
        project's library that ``make fmu`` built from the same sources,
        else ``KEY/NAME.fmu`` in the user's cache.

    Raises
    ------
    JudderError
        If no root holds the class, or its build fails.
    """
    from .build import build_key, built_from
    roots = library_folders(library) + [LIBRARY]
    parts = model_class.split(".")
    source = next((root.joinpath(*parts).with_suffix(".mo") for root in roots
                   if root.joinpath(*parts).with_suffix(".mo").exists()),
                  None)
    if source is None:
        raise JudderError(f"model {model_class!r} is not a class of the "
                          f"library in {', '.join(map(str, roots))}")
    name = f"{parts[-1]}{'' if version == '2.0' else '_fmi3'}.fmu"
    key = build_key(model_class, version, roots)
    made = BUILT / name
    if built_from(made) == key:
        return made
    return _entry(_folder(), key, name, lambda folder: _build(
        source, model_class, folder / name, version, roots))


def _build(source, model_class, target, version, roots):
    from .build import build_fmu
    from .frontend import FrontEndError
    try:
        build_fmu(source, model_class, target, version=version, roots=roots)
    except FrontEndError as exc:
        raise JudderError(f"building {target.name} failed: {exc}") from None


def _entry(folder, key, name, make):
    """``folder/KEY/NAME`` (``folder/KEY`` for an empty name), made by
    ``make(staging)`` in a temporary folder beside it renamed to ``KEY``
    unless another process was first."""
    target = folder / key / name
    if target.exists():
        return target
    staging = Path(tempfile.mkdtemp(prefix=f".{key}-", dir=folder))
    try:
        make(staging)
        os.rename(staging, folder / key)
    except OSError:
        if not target.exists():      # not a process that was first
            raise
    finally:
        shutil.rmtree(staging, ignore_errors=True)
    return target


@functools.lru_cache(maxsize=1)
def _scratch():
    """The folder of the process when the cache is off, removed at its
    exit."""
    folder = tempfile.mkdtemp(prefix="judder-fmu-cache-")
    atexit.register(shutil.rmtree, folder, ignore_errors=True)
    return Path(folder)


def _folder():
    folder = cache_folder("fmu")
    if folder is None:
        return _scratch()
    folder.mkdir(parents=True, exist_ok=True)
    return folder


def digest(path):
    """Hex sha256 of an FMU file's content: the key of its description
    and its unpacked folder.

    Remembered per process for the file as it stands (its inode, size,
    modification and change times): an FMU replaced or rewritten is
    read again.
    """
    stat = Path(path).stat()
    return _digest(str(Path(path).resolve()), stat.st_ino, stat.st_size,
                   stat.st_mtime_ns, stat.st_ctime_ns)


@functools.lru_cache(maxsize=64)
def _digest(path, *_stat):
    with open(path, "rb") as stream:
        return hashlib.file_digest(stream, "sha256").hexdigest()


def model_description(path):
    """The FMU's model description (fmpy's ``ModelDescription``), read
    once per file content.

    Raises
    ------
    FmuFileError
        If the file is not a readable FMU.
    """
    try:
        key = digest(path)
    except OSError as exc:
        raise FmuFileError(f"{path}: not a readable FMU "
                           f"({exc.strerror or exc})") from None
    return _description(key, str(path))


@functools.lru_cache(maxsize=16)
def _description(key, path):
    from fmpy import read_model_description
    try:
        return read_model_description(path)
    except Exception as exc:       # fmpy raises zip, XML and schema errors
        # all of it on one line: a validation error's first line is only
        # "Failed to validate modelDescription.xml:"
        reason = " ".join(str(exc).split())[:300] or type(exc).__name__
        raise FmuFileError(f"{path}: not a readable FMU ({reason})") \
            from None


def unpacked(path):
    """The folder the FMU is extracted into, once per file content.

    Returns
    -------
    str
        ``unpacked/DIGEST`` of the cache (:func:`digest`).

    Raises
    ------
    FmuFileError
        If the file cannot be read or extracted.
    """
    from fmpy import extract
    path = Path(path)
    try:
        key = digest(path)
        folder = _folder() / "unpacked"
        folder.mkdir(exist_ok=True)
    except OSError as exc:
        raise FmuFileError(f"{path}: cannot be extracted "
                           f"({exc.strerror or exc})") from None

    def extract_into(folder):
        try:
            extract(str(path), unzipdir=str(folder))
        except Exception as exc:       # zip errors of a broken archive
            raise FmuFileError(f"{path}: cannot be extracted ({exc})") \
                from None
    return str(_entry(folder, key, "", extract_into))


def parameter_default(path, name):
    """Default (start) value of an FMU parameter, SI.

    Raises
    ------
    JudderError
        If the FMU has no variable ``name``.
    """
    description = model_description(path)
    for variable in description.modelVariables:
        if variable.name == name:
            return float(variable.start)
    raise JudderError(f"{description.modelName} has no parameter {name!r}")


def simulate(path, **options):
    """fmpy's ``simulate_fmu`` of the FMU, from its unpacked folder and
    its model description (neither made again).

    Parameters
    ----------
    path : path
    **options
        Of ``fmpy.simulate_fmu`` (``fmi_type``, ``start_values``,
        ``stop_time``, ``output_interval``, ``output``, ...).

    Returns
    -------
    numpy structured array
        fmpy's result: ``time`` and the recorded variables.
    """
    from fmpy import simulate_fmu
    return simulate_fmu(unpacked(path), model_description=model_description(
        path), **options)
