"""The FMUs pysim runs: built from modelica/ by the project's compiler.

:func:`ensure_fmu` returns the FMU of a class of the library (the
registry names them: :attr:`drivelines.DrivelineModel.modelica_class`),
compiling it (as ``make fmu`` does) when it is missing or older than the
Modelica library or the compiler.
"""

from pathlib import Path

from fmu.classes import library_folders
from infra.errors import JudderError

__all__ = ["ensure_fmu", "FMU_DIR", "LIBRARY"]

ROOT = Path(__file__).resolve().parents[2]
LIBRARY = ROOT / "modelica"
FMU_DIR = ROOT / "build" / "fmu"


def _newest_source(library=None):
    sources = list(LIBRARY.rglob("*.mo")) + list(LIBRARY.rglob("package.order"))
    for folder in library_folders(library):
        sources += list(folder.rglob("*.mo"))
    sources += list((ROOT / "fmu").rglob("*.py")) + list(
        (ROOT / "fmu" / "c").glob("*.[ch]"))
    return max(p.stat().st_mtime for p in sources)


def ensure_fmu(model_class, version="2.0", folder=None, library=None):
    """Path of the FMU of a class of the library, built if stale.

    Parameters
    ----------
    model_class : str
        Full class name, e.g. ``'Judder.Examples.Driveline4DOF'``.
    version : {'2.0', '3.0'}
    folder : path, optional
        Where FMUs live (default ``build/fmu`` of the repository).
    library : path or sequence of paths, optional
        A user's package folder (or folders, in order) searched before
        the project's library (FMUs of its classes go to
        ``<folder>/user``).
    """
    from fmu.build import build_fmu
    from fmu.frontend import FrontEndError
    folder = Path(folder or FMU_DIR) / ("user" if library else "")
    suffix = "" if version == "2.0" else "_fmi3"
    target = folder / f"{model_class.rsplit('.', 1)[-1]}{suffix}.fmu"
    roots = library_folders(library) + [LIBRARY]
    source = next((root.joinpath(*model_class.split(".")).with_suffix(".mo")
                   for root in roots if root.joinpath(
                       *model_class.split(".")).with_suffix(".mo").exists()),
                  None)
    if source is None:
        raise JudderError(f"model {model_class!r} is not a class of the "
                          f"library in {', '.join(map(str, roots))}")
    if not target.exists() or \
            target.stat().st_mtime < _newest_source(library):
        try:
            build_fmu(source, model_class, target,
                      version=version, roots=roots)
        except FrontEndError as exc:
            raise JudderError(f"building {target.name} failed: {exc}") \
                from None
    return target
