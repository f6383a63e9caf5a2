"""``python -m fmu``: compile Modelica models to FMUs (``make fmu``)."""

import argparse
import json
import math
import re
import sys
from pathlib import Path
import warnings

from infra.errors import EXIT_ERROR, EXIT_OK, JudderError

from .build import DEFAULT_TOLERANCE, build_fmu
from .frontend import FrontEndError, find_class, modelica_path
from .store import LIBRARY
from .units import UnitWarning

#: Package whose examples are built by default.
EXAMPLES_PACKAGE = "Judder.Examples"


def examples(library):
    """Full names of the complete classes in ``library``'s examples
    package, in the order of its ``package.order`` (a partial model, the
    base of several examples, is not built)."""
    folder = library.joinpath(*EXAMPLES_PACKAGE.split("."))
    order = folder / "package.order"
    if not order.exists():
        return []
    return [f"{EXAMPLES_PACKAGE}.{name}"
            for name in order.read_text().split()
            if not re.search(r"^\s*partial\s", (folder / f"{name}.mo")
                             .read_text(encoding="utf-8"), re.M)]


def main(argv=None):
    """Run ``python -m fmu`` under the error contract of every command
    line of the project (:func:`infra.contract.run_guarded`)."""
    from infra.contract import run_guarded
    status = []
    code = run_guarded("fmu", lambda: status.append(_build(argv)))
    return status[0] if status else code


def _build(argv):
    parser = argparse.ArgumentParser(
        prog="python -m fmu",
        description="Compile Modelica models of the Judder library to FMUs: "
                    "NAME.fmu (FMI 2.0, Model Exchange and Co-Simulation) "
                    "and NAME_fmi3.fmu (FMI 3.0, Model Exchange and "
                    "Co-Simulation). "
                    "Co-Simulation integrates with an embedded "
                    "Dormand-Prince 5(4) at the given tolerance.")
    parser.add_argument("models", nargs="*", metavar="CLASS",
                        help="full class names (default: every class of "
                             f"{EXAMPLES_PACKAGE}, as listed in its "
                             "package.order)")
    parser.add_argument("--library", action="append", default=[],
                        metavar="DIR",
                        help="folder holding Modelica packages, or one .mo "
                             "file holding a whole package; repeatable, "
                             "searched before the folders of MODELICAPATH "
                             "and the project's library (default: the "
                             "project's library)")
    parser.add_argument("--out", default="build/fmu", metavar="DIR",
                        help="folder for the FMUs (default build/fmu)")
    parser.add_argument("--fmi", choices=("2.0", "3.0", "both"),
                        default="both", help="FMI version(s) to build")
    parser.add_argument("--tolerance", type=float, default=DEFAULT_TOLERANCE,
                        help="default relative tolerance, also of the "
                             "co-simulation integrator (default %(default)g)")
    parser.add_argument("--author", default="", metavar="NAME",
                        help="the FMUs' author attribute (their version is "
                             "the version annotation of the model's "
                             "top-level package)")
    parser.add_argument("--windows", action="store_true",
                        help="also cross-compile a Windows 64-bit binary "
                             "with mingw-w64 (x86_64-w64-mingw32-gcc)")
    parser.add_argument("--json", action="store_true",
                        help="report as JSON lines")
    parser.add_argument("--show-rewrites", action="store_true",
                        help="list each binding rewritten as an equation "
                             "before rumoca read it (file:line, the "
                             "binding; see docs/compiler.md), in a cached "
                             "copy of its library, never in its folder")
    args = parser.parse_args(argv)
    if not (math.isfinite(args.tolerance) and 0 < args.tolerance < 1):
        print(f"fmu: error: --tolerance {args.tolerance:g} is not allowed; "
              "allowed: a relative tolerance > 0 and < 1 (e.g. 1e-6)",
              file=sys.stderr)
        return EXIT_ERROR
    roots = modelica_path(args.library)
    if LIBRARY not in roots:
        roots.append(LIBRARY)   # Judder's components, for any model
    library = Path(args.library[0]) if args.library else LIBRARY
    names = args.models or examples(library)
    if not names:
        print(f"fmu: error: no class given, and {library} has no "
              f"{EXAMPLES_PACKAGE} package", file=sys.stderr)
        return EXIT_ERROR
    versions = ("2.0", "3.0") if args.fmi == "both" else (args.fmi,)
    try:
        with warnings.catch_warnings(record=True) as said:
            warnings.simplefilter("always", UnitWarning)
            _build_all(args, names, versions, roots, said)
    except FrontEndError as exc:
        raise JudderError(str(exc)) from None
    return EXIT_OK


def _build_all(args, names, versions, roots, said):
    """Build each class in each FMI version; report each FMU, and each
    warning of the build (``said``) once, as ``fmu: warning: ...``."""
    told = set()
    for name in names:
        source, _ = find_class(name, roots)
        for version in versions:
            suffix = "" if version == "2.0" else "_fmi3"
            target = Path(args.out) / f"{name.split('.')[-1]}{suffix}.fmu"
            result = build_fmu(source, name, target, version=version,
                               roots=[r.parent if r.is_file() else r
                                      for r in roots],
                               tolerance=args.tolerance,
                               windows=args.windows,
                               author=args.author)
            report = {"model": name, "fmi": version,
                      "path": str(result.path),
                      "states": result.states,
                      "parameters": result.parameters,
                      "outputs": result.outputs,
                      "seconds": round(result.seconds, 3),
                      "size_bytes": result.size_bytes}
            report["rewrites"] = [
                {"file": r.file, "line": r.line, "name": r.name,
                 "binding": r.binding, "parameter": r.parameter,
                 "kind": r.kind}
                for r in result.rewrites]
            rewritten = f", {len(result.rewrites)} rewrites " \
                "(--show-rewrites lists them)" if result.rewrites and \
                not args.show_rewrites else ""
            print(json.dumps(report) if args.json else
                  f"{result.path}: FMI {version}, {result.states} states,"
                  f" {result.parameters} parameters, {result.outputs} "
                  f"outputs, built in {result.seconds:.2f} s, "
                  f"{result.size_bytes / 1024:.1f} KiB{rewritten}")
            if args.show_rewrites and not args.json and version == \
                    versions[0]:
                for rewrite in result.rewrites:
                    print(f"  rewrote {rewrite}")
        for warning in said:
            text = str(warning.message)
            if not issubclass(warning.category, UnitWarning):
                warnings.showwarning(warning.message, warning.category,
                                     warning.filename, warning.lineno)
            elif text not in told:
                told.add(text)
                print(f"fmu: warning: {text}", file=sys.stderr)
        said.clear()


if __name__ == "__main__":
    sys.exit(main())
