"""Build an FMU from a Modelica model: front end, back end, C, zip.

:func:`build_fmu` runs the whole chain:

1. rumoca flattens the model (:mod:`fmu.frontend`);
2. the back end turns it into ``der(x) = f(t, x, p)`` (:mod:`fmu.backend`);
3. CasADi writes the C code of ``f``, the outputs, the start values and
   the calculated parameters; ``model_config.h`` holds sizes and defaults;
4. the generic wrapper (``fmu/c``) provides the FMI API: FMI 2.0 Model
   Exchange and Co-Simulation in one FMU, or the same in FMI 3.0;
5. gcc compiles it and the FMU is zipped (with its sources).

Co-Simulation integrates with the embedded Dormand-Prince 5(4) of
``fmu/c/model.c`` under the experiment tolerance (default 1e-10, relative
and absolute), landing exactly on each communication point.
"""

from dataclasses import dataclass
import functools
import hashlib
from importlib import metadata
import json
import os
from pathlib import Path
import shutil
import subprocess
import sys
import tempfile
import threading
import time
import uuid
import zipfile

import casadi

from infra.files import atomic_write

from .backend import Quantity, to_ode
from .cache import sources_digest
from .description import (SOURCES, Layout, build_description,
                          model_description)
from .frontend import FrontEndError, load_flat_model, package_version
from .limits import announce, check_compile, compile_estimate
from .rumoca_child import memory_limit

__all__ = ["BuildError", "BuildResult", "build_fmu", "build_key",
           "built_from", "fmi_headers"]

C_SOURCES = Path(__file__).resolve().parent / "c"
#: Relative (and absolute) tolerance of the co-simulation integrator.
DEFAULT_TOLERANCE = 1e-10
_PLATFORM = {"2.0": "linux64", "3.0": "x86_64-linux"}
_WINDOWS_PLATFORM = {"2.0": "win64", "3.0": "x86_64-windows"}
#: mingw-w64 cross compiler for the optional Windows 64-bit binary.
_WINDOWS_CC = "x86_64-w64-mingw32-gcc"
#: Headers of the FMI core shipped beside its sources (description.SOURCES).
_HEADERS = ("model.h", "instance.h")
#: Start of the zip comment of every FMU built here; the build key
#: (:func:`build_key`) follows.
_KEY_MARK = b"judder sources sha256 "


class BuildError(FrontEndError):
    """The FMU could not be built; says what is missing or wrong."""


@dataclass(frozen=True)
class BuildResult:
    """Outcome of :func:`build_fmu`.

    Attributes
    ----------
    path : Path
        The ``.fmu`` file.
    version : str
    states, parameters, outputs : int
    seconds : float
        Build time.
    size_bytes : int
    rewrites : tuple of fmu.rewrite.Rewrite
        Bindings of the model rewritten as equations before rumoca read
        them (:mod:`fmu.rewrite`), each with its file and line.
    """

    path: Path
    version: str
    states: int
    parameters: int
    outputs: int
    seconds: float
    size_bytes: int
    rewrites: tuple = ()


def fmi_headers():
    """Folder of the FMI 2.0 and 3.0 headers that fmpy ships."""
    import fmpy
    folder = Path(fmpy.__file__).resolve().parent / "c-code"
    if not (folder / "fmi2Functions.h").exists():
        raise BuildError(f"FMI headers not found in {folder}")
    return folder


@functools.lru_cache(maxsize=1)
def _compiler_digest():
    """sha256 of the compiler: its Python and C sources, and the versions
    of rumoca and CasADi it runs."""
    digest = hashlib.sha256()
    here = Path(__file__).resolve().parent
    for source in sorted([*here.glob("*.py"), *C_SOURCES.glob("*.[ch]")]):
        digest.update(source.name.encode() + b"\0" + source.read_bytes())
    for package in ("rumoca", "casadi"):
        digest.update(f"{package} {metadata.version(package)}\n".encode())
    return digest.hexdigest()


def build_key(model_name, version, roots, tolerance=DEFAULT_TOLERANCE):
    """Hex sha256 naming the FMU that :func:`build_fmu` makes of
    ``model_name`` from the sources under ``roots`` as they stand now:
    their content (:func:`fmu.cache.sources_digest`), the compiler's
    (its sources and the versions of rumoca and CasADi), the FMI version
    and the tolerance; never a name or a modification time of a file."""
    digest = hashlib.sha256()
    for item in (model_name, version, repr(float(tolerance)),
                 _compiler_digest(), sources_digest(roots)):
        digest.update(item.encode() + b"\0")
    return digest.hexdigest()


def built_from(path):
    """The build key an FMU of :func:`build_fmu` carries (its zip
    comment), or None for another FMU or an unreadable file."""
    try:
        with zipfile.ZipFile(path) as fmu:
            comment = fmu.comment
    except (OSError, zipfile.BadZipFile):
        return None
    return comment[len(_KEY_MARK):].decode("ascii", "replace") \
        if comment.startswith(_KEY_MARK) else None


def _c_array(values):
    """C initialiser; the arrays have one spare element, so never empty."""
    return "{" + ", ".join(repr(float(v)) for v in values or [0.0]) + "}"


def _c_bounds(quantities, which, infinite):
    """C initialiser of the numeric min (or max) of each quantity."""
    values = []
    for q in quantities:
        bound = getattr(q, which)
        try:
            values.append(repr(float(bound)))
        except (TypeError, RuntimeError):   # none, or depends on parameters
            values.append(infinite)
    return "{" + ", ".join(values or ["0.0"]) + "}"


def _config(ode, guid, tolerance):
    layout = Layout(ode)
    tunable = layout.parameters + layout.inputs
    held = ode.relations + ode.discretes + ode.previous + ode.zeros
    defaults = [q.start for q in tunable + held]
    # relation values, discrete variables and their pre() (held between
    # events) follow in p, unbounded
    tunable = tunable + [Quantity("", "", "", None) for _ in held]
    return "\n".join([
        "/* Generated by fmu/build.py: sizes and defaults, no equations. */",
        "#ifndef MODEL_CONFIG_H", "#define MODEL_CONFIG_H",
        f'#define MODEL_GUID "{guid}"',
        f"#define MODEL_NX {len(layout.states)}",
        f"#define MODEL_NP {len(layout.parameters)}",
        f"#define MODEL_NC {len(layout.calculated)}",
        f"#define MODEL_NY {len(layout.outputs) + len(layout.locals)}",
        f"#define MODEL_NYO {len(layout.outputs)}",
        f"#define MODEL_NU {len(layout.inputs)}",
        f"#define MODEL_NR {len(ode.relations)}",
        f"#define MODEL_NW {len(ode.whens)}",
        f"#define MODEL_ND {len(ode.discretes)}",
        f"#define MODEL_NI {len(ode.previous) - len(ode.discretes)}",
        "#define MODEL_WHEN_RELATION {" + ", ".join(
            [str(r) for r, _ in ode.whens] + ["0"]) + "}",
        f"#define MODEL_NA {len(ode.assertions)}",
        "#define MODEL_ASSERT_SIZE "
        f"{len(ode.assertions) + sum(len(a.values) for a in ode.assertions)}",
        "#define MODEL_ASSERT_ERROR {" + ", ".join(
            ["1" if a.error else "0" for a in ode.assertions] + ["0"]) + "}",
        "#define MODEL_ASSERT_MESSAGES {" + ", ".join(
            [json.dumps(_assert_text(a)) for a in ode.assertions]
            + ['""']) + "}",
        "#define MODEL_ASSERTS judder_asserts",
        "#define MODEL_ASSERTS_WORK judder_asserts_work",
        "#define MODEL_DISCRETE_BOOLEAN {" + ", ".join(
            ["1" if q.maximum == 1.0 else "0" for q in ode.discretes]
            + ["0"]) + "}",
        f"#define MODEL_DEFAULT_TOLERANCE {tolerance!r}",
        f"#define MODEL_PARAMETER_DEFAULTS {_c_array(defaults)}",
        "#define MODEL_STATE_NAMES {" + ", ".join(
            [json.dumps(q.name) for q in layout.states] + ['""']) + "}",
        "#define MODEL_PARAMETER_MIN "
        f"{_c_bounds(tunable, 'minimum', '(-INFINITY)')}",
        "#define MODEL_PARAMETER_MAX "
        f"{_c_bounds(tunable, 'maximum', 'INFINITY')}",
        "#define MODEL_ODE judder_ode",
        "#define MODEL_ODE_WORK judder_ode_work",
        "#define MODEL_OUTPUTS judder_outputs",
        "#define MODEL_OUTPUTS_WORK judder_outputs_work",
        "#define MODEL_START judder_start",
        "#define MODEL_START_WORK judder_start_work",
        "#define MODEL_CALCULATED judder_calculated",
        "#define MODEL_CALCULATED_WORK judder_calculated_work",
        "#define MODEL_INDICATORS judder_indicators",
        "#define MODEL_INDICATORS_WORK judder_indicators_work",
        "#define MODEL_RELATIONS judder_relations",
        "#define MODEL_RELATIONS_WORK judder_relations_work",
        "#define MODEL_REINIT judder_reinit",
        "#define MODEL_REINIT_WORK judder_reinit_work",
        "#define MODEL_DISCRETES judder_discretes",
        "#define MODEL_DISCRETES_WORK judder_discretes_work",
        "#define MODEL_JACOBIAN judder_jacobian",
        "#define MODEL_JACOBIAN_WORK judder_jacobian_work",
        "#define MODEL_JACOBIAN_SPARSITY judder_jacobian_sparsity_out",
        f"#define MODEL_JACOBIAN_NNZ {ode.jacobian()[1].nnz()}",
        "#endif", ""])


def _assert_text(assertion):
    """An assert's message for the C core: ``FILE:LINE: message``, the
    file without its folder, printable ASCII (C string literals)."""
    place = Path(assertion.where.rsplit(":", 1)[0]).name + ":" + \
        assertion.where.rsplit(":", 1)[-1] if ":" in assertion.where \
        else assertion.where
    text = f"{place.replace('%', '%%')}: {assertion.message}"
    return "".join(c if " " <= c <= "~" else "?" for c in text)


def _functions(ode):
    """The CasADi functions whose C code the FMU holds."""
    ode_f, outputs_f, start_f = ode.functions(with_locals=True)
    p = casadi.vertcat(casadi.SX(0, 1), *[q.expression for q in ode.held()])
    calculated = casadi.vertcat(casadi.SX(0, 1),
                                *[q.expression for q in ode.calculated])
    functions = [
        casadi.Function("judder_ode", ode_f.sx_in(), ode_f.call(ode_f.sx_in())),
        casadi.Function("judder_outputs", outputs_f.sx_in(),
                        outputs_f.call(outputs_f.sx_in())),
        casadi.Function("judder_start", start_f.sx_in(),
                        start_f.call(start_f.sx_in())),
        casadi.Function("judder_calculated", [p], [calculated])]
    for function in ode.event_functions() + (ode.jacobian()[0],
                                             ode.assert_function()):
        functions.append(casadi.Function(
            f"judder_{function.name()}", function.sx_in(),
            function.call(function.sx_in())))
    return functions


def _generate_c(functions, folder):
    generator = casadi.CodeGenerator("model_functions.c",
                                     {"with_header": True,
                                      "prefix": "judder_"})
    for function in functions:
        generator.add(function)
    cwd = os.getcwd()
    try:
        os.chdir(folder)
        generator.generate()
    finally:
        os.chdir(cwd)


class Stages:
    """A status line on stderr naming the step of a build and its
    elapsed time, refreshed every half second: a tqdm bar without total,
    shown on a terminal only and only once the build has taken ``delay``
    seconds (a small model's build says nothing).
    ``with Stages(name) as stage: stage("...")``.
    """

    def __init__(self, name, delay=2.0, stream=None):
        from tqdm import tqdm
        self._bar = tqdm(total=None, desc=name, disable=None, leave=False,
                         delay=delay, file=stream or sys.stderr,
                         bar_format="{desc} [{elapsed}]")
        self._name, self._delay, self._shown = name, delay, False
        self._done = threading.Event()
        self._ticker = threading.Thread(target=self._tick, daemon=True)

    def _tick(self):
        started = time.monotonic()
        while not self._done.wait(0.5):
            if time.monotonic() - started >= self._delay:
                self._shown = True
                self._bar.refresh()

    def __enter__(self):
        if not self._bar.disable:
            self._ticker.start()
        return self._stage

    def _stage(self, text):
        self._bar.set_description_str(f"{self._name}: {text}",
                                      refresh=False)

    def __exit__(self, *exc):
        self._done.set()
        if self._ticker.is_alive():
            self._ticker.join()
        if self._shown:   # tqdm clears only what its own updates showed
            self._bar.display(msg="")
            self._bar.fp.write("\r")
            self._bar.fp.flush()
        self._bar.close()
        return False


def _run(command, seconds=None):
    """Run the C compiler; with ``seconds`` (its estimate), a progress bar
    on stderr over the estimate (tqdm, shown on a terminal only, as the
    project's commands show theirs)."""
    if seconds is None:
        return subprocess.run(command, capture_output=True, text=True)
    from tqdm import tqdm
    with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err, \
            tqdm(total=round(seconds), desc="gcc", unit="s", disable=None,
                 file=sys.stderr, bar_format="{desc}: {percentage:3.0f}%|"
                 "{bar}| {n:.0f}/{total:.0f} s estimated") as bar:
        proc = subprocess.Popen(command, stdout=out, stderr=err)
        started = time.monotonic()
        try:
            while True:
                try:
                    proc.wait(timeout=0.5)
                    break
                except subprocess.TimeoutExpired:
                    bar.update(min(time.monotonic() - started, bar.total)
                               - bar.n)
        finally:
            if proc.poll() is None:   # Ctrl-C, SIGTERM
                proc.kill()
                proc.wait()
        err.seek(0)
        return subprocess.CompletedProcess(
            command, proc.returncode, "",
            err.read().decode("utf-8", "replace"))


def _compile(folder, version, identifier, windows=False, seconds=None):
    """Shared library of the FMU: Linux with gcc (``CC``), or Windows
    64-bit with mingw-w64 (``windows=True``); ``seconds``: the estimate
    of a long compile, for its progress bar."""
    if windows:
        compiler, library = _WINDOWS_CC, folder / f"{identifier}.dll"
        flags = ["-shared", "-O2", "-static-libgcc"]
        hint = "install mingw-w64 (Debian: gcc-mingw-w64-x86-64)"
    else:
        compiler = os.environ.get("CC", "gcc")
        library = folder / f"{identifier}.so"
        flags = ["-shared", "-fPIC", "-O2", "-fvisibility=hidden"]
        hint = "install gcc (or set CC)"
    if shutil.which(compiler) is None:
        raise BuildError(f"C compiler {compiler!r} not found: {hint} to "
                         "build FMUs")
    command = [compiler, *flags, "-std=c99", f"-I{folder}", f"-I{C_SOURCES}",
               f"-I{fmi_headers()}", str(folder / "model_functions.c"),
               *[str(C_SOURCES / name) for name in SOURCES[version][1:]],
               "-o", str(library), "-lm"]
    done = _run(command, seconds)
    if done.returncode != 0:
        raise BuildError(f"{compiler} failed for {identifier}:\n"
                         f"{done.stderr.strip()}")
    return library


def build_fmu(mo_file, model_name, out_file, version="2.0", roots=(),
              tolerance=DEFAULT_TOLERANCE, windows=False, author=""):
    """Compile a Modelica model into an FMU.

    Parameters
    ----------
    mo_file : path
        ``.mo`` file of the model.
    model_name : str
        Full class name, e.g. ``Judder.Examples.Driveline4DOF``.
    out_file : path
        The ``.fmu`` to write (replaced atomically).
    version : {'2.0', '3.0'}
        FMI 2.0 or FMI 3.0, each Model Exchange and Co-Simulation.
    roots : sequence of paths
        Library folders (default: the folder of ``mo_file``).
    tolerance : float
        Default tolerance, also the co-simulation integrator's.
    windows : bool
        Also cross-compile a Windows 64-bit binary with mingw-w64.
    author : str
        The FMU's ``author`` attribute (left out when empty). Its
        ``version`` is the ``version`` annotation of the model's top-level
        package (Modelica has no author annotation).

    Returns
    -------
    BuildResult

    Raises
    ------
    BuildError, FrontEndError
        Missing compiler, errors in the Modelica source (with rumoca's
        diagnostics), or a model the back end cannot handle.
    """
    if version not in SOURCES:
        raise BuildError(f"FMI version {version!r}; allowed: "
                         f"{', '.join(SOURCES)}")
    started = time.perf_counter()
    # before the sources are read: an edit during the build makes the
    # FMU stale, never a stale FMU look fresh
    key = build_key(model_name, version, list(roots) or [Path(mo_file).parent],
                    tolerance)
    with Stages(model_name) as stage:
        stage("flattening (rumoca)")
        flat = load_flat_model(mo_file, model_name, roots=roots, hybrid=True)
        stage(f"reducing {len(flat.residuals)} equations to an ODE")
        ode = to_ode(flat)
        if version == "2.0" and not any((
                ode.states, ode.parameters, ode.calculated, ode.outputs,
                ode.locals, ode.aliases, ode.inputs)):
            # FMI 2.0's schema needs one ScalarVariable at least
            raise BuildError(f"{model_name} has no variable; allowed for "
                             "FMI 2.0: a model with one variable at least "
                             "(FMI 3.0 has its time: build it as FMI 3.0)")
        stage("estimating the C code")
        functions = _functions(ode)
    estimate = compile_estimate(functions)
    check_compile(model_name, len(ode.states), estimate, memory_limit())
    long = announce(model_name, len(ode.states), estimate)
    seconds = estimate[1] if long else None
    identifier = model_name.split(".")[-1]
    out_file = Path(out_file)
    with tempfile.TemporaryDirectory(prefix="judder-fmu-") as tmp:
        folder = Path(tmp)
        _generate_c(functions, folder)
        code = (folder / "model_functions.c").read_bytes()
        guid = "{" + str(uuid.UUID(hashlib.md5(
            code + model_name.encode() + version.encode()).hexdigest())) + "}"
        (folder / "model_config.h").write_text(_config(ode, guid, tolerance))
        description = model_description(
            ode, version, identifier, guid, tolerance, author=author,
            model_version=package_version(
                model_name, list(roots) or [Path(mo_file).parent]))
        library = _compile(folder, version, identifier, seconds=seconds)
        dll = _compile(folder, version, identifier, windows=True,
                       seconds=seconds) if windows else None

        def write_zip(stream):
            with zipfile.ZipFile(stream, "w", zipfile.ZIP_DEFLATED) as fmu:
                fmu.comment = _KEY_MARK + key.encode()
                entry = zipfile.ZipInfo("modelDescription.xml",
                                        time.localtime()[:6])
                entry.external_attr = 0o644 << 16   # not writestr's 0600
                entry.compress_type = zipfile.ZIP_DEFLATED
                fmu.writestr(entry, description)
                if version == "3.0":
                    entry = zipfile.ZipInfo("sources/buildDescription.xml",
                                            time.localtime()[:6])
                    entry.external_attr = 0o644 << 16
                    entry.compress_type = zipfile.ZIP_DEFLATED
                    fmu.writestr(entry, build_description(identifier))
                fmu.write(library, f"binaries/{_PLATFORM[version]}/"
                                   f"{identifier}.so")
                if dll is not None:
                    fmu.write(dll, f"binaries/{_WINDOWS_PLATFORM[version]}/"
                                   f"{identifier}.dll")
                for source in ("model_functions.c", "model_functions.h",
                               "model_config.h"):
                    fmu.write(folder / source, f"sources/{source}")
                for source in SOURCES[version][1:] + _HEADERS:
                    fmu.write(C_SOURCES / source, f"sources/{source}")
        # the folder is made with its first file: a failed build leaves
        # no empty folder behind
        out_file.parent.mkdir(parents=True, exist_ok=True)
        atomic_write(out_file, write_zip)
    # the temporary file of atomic_write is private (0600); an FMU is a
    # normal file, readable as the umask allows
    umask = os.umask(0)
    os.umask(umask)
    out_file.chmod(0o666 & ~umask)
    return BuildResult(path=out_file, version=version,
                       states=len(ode.states),
                       parameters=len(ode.parameters),
                       outputs=len(ode.outputs),
                       seconds=time.perf_counter() - started,
                       size_bytes=out_file.stat().st_size,
                       rewrites=tuple(flat.rewrites))
