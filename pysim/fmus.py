"""The FMUs pysim runs: built from modelica/ by the project's compiler.

:func:`ensure_fmu` returns the FMU of an example model, compiling it (as
``make fmu`` does) when it is missing or older than the Modelica library
or the compiler.
"""

from pathlib import Path

from stability.errors import JudderError

__all__ = ["ensure_fmu", "FMU_DIR", "LIBRARY"]

ROOT = Path(__file__).resolve().parents[1]
LIBRARY = ROOT / "modelica"
FMU_DIR = ROOT / "build" / "fmu"


def _newest_source():
    sources = list(LIBRARY.rglob("*.mo")) + list(LIBRARY.rglob("package.order"))
    sources += list((ROOT / "fmu").rglob("*.py")) + list(
        (ROOT / "fmu" / "c").glob("*.[ch]"))
    return max(p.stat().st_mtime for p in sources)


def ensure_fmu(model, version="2.0", folder=None):
    """Path of the FMU of ``Judder.Examples.<model>``, built if stale.

    Parameters
    ----------
    model : str
        ``'Driveline4DOF'``, ``'Driveline3DOF'`` or ``'TestBenchEngagement'``.
    version : {'2.0', '3.0'}
    folder : path, optional
        Where FMUs live (default ``build/fmu`` of the repository).
    """
    from fmu.build import build_fmu
    from fmu.frontend import FrontEndError
    folder = Path(folder or FMU_DIR)
    suffix = "" if version == "2.0" else "_fmi3"
    target = folder / f"{model}{suffix}.fmu"
    source = LIBRARY / "Judder" / "Examples" / f"{model}.mo"
    if not source.exists():
        raise JudderError(f"model {model!r} is not an example of the Judder "
                          "library")
    if not target.exists() or target.stat().st_mtime < _newest_source():
        try:
            build_fmu(source, f"Judder.Examples.{model}", target,
                      version=version, roots=[LIBRARY])
        except FrontEndError as exc:
            raise JudderError(f"building {target.name} failed: {exc}") \
                from None
    return target
