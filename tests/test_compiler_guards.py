"""The compiler's guards (issue 34): what a hostile tester gave it, each
compiled right or refused with one line naming the file, the variable or
the equations and what is allowed, never a crash, a traceback or a
silently wrong FMU; and the FMU's DefaultExperiment from the built
class's own experiment annotation (issue 30).

Every model here is written by the test into its own folder (rumoca
reads every file of a library folder).
"""

import math
import os
from pathlib import Path
import re
import subprocess
import sys
import time
import xml.etree.ElementTree as ET
import zipfile

import casadi
import numpy as np
import pytest
from numpy.testing import assert_allclose

pytest.importorskip("rumoca")
fmpy = pytest.importorskip("fmpy")

from fmu import backend, limits, rumoca_child  # noqa: E402
from fmu.build import _run, build_fmu  # noqa: E402
from fmu.classes import blank, class_spans  # noqa: E402
from fmu.frontend import (FrontEndError, _experiment,  # noqa: E402
                          load_flat_model)
from facts import names  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(autouse=True)
def _no_cache(monkeypatch):
    monkeypatch.setenv("JUDDER_FMU_CACHE", "off")


def _model(tmp_path, name, text, data=None):
    folder = tmp_path / name
    folder.mkdir()
    path = folder / f"{name}.mo"
    if data is None:
        path.write_text(text)
    else:
        path.write_bytes(data)
    return path


def _cli(*args, **kw):
    """``python -m fmu ...``: (exit status, stderr lines)."""
    env = {**os.environ, "JUDDER_FMU_CACHE": "off", **kw.pop("env", {})}
    done = subprocess.run([sys.executable, "-m", "fmu", *args],
                          capture_output=True, text=True, cwd=ROOT, env=env,
                          timeout=300, **kw)
    return done.returncode, [line for line in done.stderr.splitlines()
                             if line.strip()]


def _one_error(lines):
    assert len(lines) == 1, lines
    assert lines[0].startswith("fmu: error: "), lines
    return lines[0]


def _x_at(fmu_path, stop, name="x"):
    result = fmpy.simulate_fmu(str(fmu_path), stop_time=stop,
                               output=[name], relative_tolerance=1e-10,
                               fmi_type="ModelExchange")
    return result["time"], result[name]


# -- long expressions ---------------------------------------------------

def test_a_sum_of_5000_terms_compiles_and_is_right(tmp_path):
    # 330 terms were a RecursionError in the front end, 5,000 a SIGSEGV
    # of rumoca in the tool's own process
    terms = "+".join(["1e-4"] * 5000)   # k = 0.5
    path = _model(tmp_path, "Long", "model Long\n  Real x(start=1, "
                  f"fixed=true);\nequation\n  der(x) = -x*({terms});\n"
                  "end Long;\n")
    fmu = build_fmu(path, "Long", tmp_path / "Long.fmu").path
    t, x = _x_at(fmu, 1.0)
    assert_allclose(x, np.exp(-0.5 * t), rtol=1e-7)   # x = e^(-k t)


# -- rumoca's crashes, aborts and hangs, in its child ------------------

@pytest.mark.parametrize("code, words", [
    ("import ctypes, sys\n"
     "sys.stderr.write('judder-rumoca: flattening\\n'); sys.stderr.flush()\n"
     "ctypes.string_at(0)\n",
     ["rumoca crashed (SIGSEGV) on M while flattening; ",
      "nothing else is affected"]),
    ("import os, sys\n"
     "sys.stderr.write('judder-rumoca: flattening\\n')\n"
     "sys.stderr.write('memory allocation of 7200000000 bytes failed\\n')\n"
     "sys.stderr.flush(); os.abort()\n",
     ["M needs more memory than the", "available to the compiler while "
      "flattening (it asked for 7.2 GB at once)"]),
])
def test_a_crash_of_rumoca_is_one_error(tmp_path, monkeypatch, code, words):
    path = _model(tmp_path, "M", "model M\nend M;\n")
    monkeypatch.setattr(rumoca_child, "_CHILD", ("-c", code))
    with pytest.raises(FrontEndError) as error:
        rumoca_child.flatten_isolated(path, "M", [path.parent])
    message = str(error.value)
    assert message.startswith(f"{path}: ")
    for word in words:
        assert word in message


def test_a_panic_of_rumoca_is_one_error(tmp_path, monkeypatch):
    # pyo3 raises a Rust panic as PanicException, a BaseException
    path = _model(tmp_path, "M", "model M\nend M;\n")
    monkeypatch.setattr(rumoca_child, "_CHILD", (
        "-c", "import fmu.rumoca_child as child\n"
        "class PanicException(BaseException): pass\n"
        "def flatten(job):\n"
        "    child._stage('flattening')\n"
        "    raise PanicException('index out of bounds')\n"
        "child._flatten = flatten\nchild._child()\n"))
    with pytest.raises(FrontEndError) as error:
        rumoca_child.flatten_isolated(path, "M", [path.parent])
    assert str(error.value) == (
        f"{path}: rumoca failed on M while flattening (PanicException: "
        "index out of bounds); judder ran it in a child process: nothing "
        "else is affected, but rumoca cannot compile this model as written")


def test_a_hanging_rumoca_is_stopped(tmp_path, monkeypatch):
    path = _model(tmp_path, "M", "model M\nend M;\n")
    monkeypatch.setattr(rumoca_child, "_CHILD", (
        "-c", "import sys, signal\n"
        "sys.stderr.write('judder-rumoca: loading the libraries\\n')\n"
        "sys.stderr.flush(); signal.pause()\n"))
    monkeypatch.setenv("JUDDER_FLATTEN_TIMEOUT", "1")
    with pytest.raises(FrontEndError) as stopped:
        rumoca_child.flatten_isolated(path, "M", [path.parent])
    names(stopped.value, "rumoca", "M", "1 s", "loading the libraries",
          "allowed")


def test_the_flatten_time_limit_is_checked(monkeypatch):
    monkeypatch.setenv("JUDDER_FLATTEN_TIMEOUT", "-3")
    with pytest.raises(FrontEndError) as refused:
        rumoca_child.time_limit()
    names(refused.value, "JUDDER_FLATTEN_TIMEOUT", "-3", "allowed",
          "seconds > 0")


# -- arrays beyond the limit, refused before allocating ----------------

@pytest.mark.parametrize("n", [100_000_000, 60_000])
def test_a_huge_parameter_array_is_refused_from_the_source(tmp_path, n):
    # n = 1e8 made rumoca ask for 7.2 GB and abort the tool (exit 134)
    path = _model(tmp_path, "Big", f"model Big\n  parameter Integer n={n};\n"
                  "  parameter Real p[n]=fill(1.0,n);\n  Real x(start=1, "
                  "fixed=true);\nequation\n  der(x) = -x*p[1];\nend Big;\n")
    status, lines = _cli("Big", "--library", str(path.parent), "--out",
                         str(tmp_path / "out"))
    assert status == 2
    assert _one_error(lines) == (
        f"fmu: error: {path}:3: p[n]: {n:,} elements (n = {n:,}); allowed: "
        "at most 50,000 elements per array (every element is a variable of "
        "its own; about 3 ms of compiling each)")
    assert not (tmp_path / "out").exists()


def test_an_array_sized_in_another_file_is_refused_from_the_flat_model(
        tmp_path):
    lib = tmp_path / "Lib"
    lib.mkdir()
    (lib / "package.mo").write_text("package Lib\nend Lib;\n")
    (lib / "package.order").write_text("Comp\nTop\n")
    (lib / "Comp.mo").write_text(
        "within Lib;\nmodel Comp\n  parameter Integer n = 2;\n"
        "  parameter Real p[n](each start = 1);\nend Comp;\n")
    (lib / "Top.mo").write_text(
        "within Lib;\nmodel Top\n  Lib.Comp c(n = 60000);\n"
        "  Real x(start=1, fixed=true);\nequation\n  der(x) = -x;\n"
        "end Top;\n")
    with pytest.raises(FrontEndError) as error:
        load_flat_model(lib / "Top.mo", "Lib.Top", roots=[tmp_path])
    assert str(error.value) == (
        f"{lib / 'Comp.mo'}:4: c.p[60000]: 60,000 elements; allowed: at "
        "most 50,000 elements per array (every element is a variable of "
        "its own; about 3 ms of compiling each)")


def test_an_array_within_the_limit_still_compiles(tmp_path):
    path = _model(tmp_path, "Table", "model Table\n  parameter Integer n=3;\n"
                  "  parameter Real p[n] = {0.5, 2, 4};\n  Real x(start=1, "
                  "fixed=true);\nequation\n  der(x) = -p[1]*x;\nend Table;\n")
    limits.check_source_arrays(path, path.read_text())
    flat = load_flat_model(path, "Table")
    names = [v.name for v in flat.variables if v.role == "parameter"]
    assert names == ["p[1]", "p[2]", "p[3]"]


# -- unreadable source ---------------------------------------------------

def test_a_source_that_is_not_utf8_is_an_input_error(tmp_path):
    path = _model(tmp_path, "Latin", None, data=(
        "model Latin\n  // Größe\n  Real x(start=1, fixed=true);\n"
        "equation\n  der(x) = -x;\nend Latin;\n").encode("latin-1"))
    status, lines = _cli("Latin", "--library", str(path.parent), "--out",
                         str(tmp_path / "out"))
    assert status == 2
    assert _one_error(lines) == (
        f"fmu: error: {path}: not UTF-8 text (byte 0xf6 at offset 19, line "
        "2); allowed: UTF-8 text, as Modelica requires (save the file as "
        "UTF-8)")


def test_another_file_of_the_library_that_is_not_utf8_is_named(tmp_path):
    path = _model(tmp_path, "Good", "model Good\n  Real x(start=1, "
                  "fixed=true);\nequation\n  der(x) = -x;\nend Good;\n")
    other = path.parent / "Bad.mo"
    other.write_bytes(b"model Bad\n  // \xe9\nend Bad;\n")
    with pytest.raises(FrontEndError) as error:
        load_flat_model(path, "Good")
    assert f"{other}: not UTF-8 text (byte 0xe9 at offset 15)" in \
        str(error.value)


# -- algebraic loops -----------------------------------------------------

LOOP = """model {name}
  parameter Real a = {a};
  Real x(start=1, fixed=true);
  Real y;
  Real z;
equation
  der(x) = y;
  a*y + z = -x;
  y + z = 0;
end {name};
"""


def test_a_regular_loop_gives_the_closed_form(tmp_path):
    # a y + z = -x, y + z = 0: y = -x/(a - 1) = -x for a = 2
    path = _model(tmp_path, "Loop", LOOP.format(name="Loop", a=2))
    fmu = build_fmu(path, "Loop", tmp_path / "Loop.fmu").path
    t, x = _x_at(fmu, 1.0)
    assert_allclose(x, np.exp(-t), rtol=1e-7)
    assert_allclose(x[-1], math.exp(-1), rtol=1e-8)


@pytest.mark.parametrize("name, text, words", [
    ("Singular", "model Singular\n  Real x(start=1, fixed=true);\n  Real y;"
     "\n  Real z;\nequation\n  der(x) = -y;\n  y = z + x;\n  z = y - x;\n"
     "end Singular;\n",
     ["Singular.mo:7: 0 = (y-(z+x)); ", "Singular.mo:8: 0 = (z-(y-x)): "
      "this algebraic loop in y, z is singular (rank 1 of 2)"]),
    ("Forced", "model Forced\n  Real x(start=1, fixed=true);\n  Real y;\n"
     "  Real z;\nequation\n  der(x) = y;\n  y + z = -5*x;\n"
     "  2*y + 2*z = -10*x;\nend Forced;\n",
     ["Forced.mo:7: ", "Forced.mo:8: ", "this algebraic loop in y, z is "
      "singular (rank 1 of 2)"]),
    # singular only at the parameter's default, a = 1 (z = -y is an
    # alias, eliminated first: the loop left is line 8 with it put in)
    ("AtStart", LOOP.format(name="AtStart", a=1),
     ["AtStart.mo:8: 0 = (((a*y)-y)+x): this algebraic loop in y is "
      "singular at the start values (rank 0 of 1)"]),
    # y = z; z = y + 5 x forces 0 = 5 x, against x(0) = 1
    ("Contradicted", "model Contradicted\n  Real x(start=1, fixed=true);\n"
     "  Real y;\n  Real z;\nequation\n  der(x) = y;\n  y = z;\n"
     "  z = y + 5*x;\nend Contradicted;\n",
     ["Contradicted.mo:2: x has the fixed start value 1, but ",
      "Contradicted.mo:8: 0 = (-(5*x)) makes it 0 at the start"]),
])
def test_a_singular_loop_is_refused_naming_its_equations(tmp_path, name,
                                                         text, words):
    path = _model(tmp_path, name, text)
    status, lines = _cli(name, "--library", str(path.parent), "--out",
                         str(tmp_path / "out"), "--fmi", "2.0")
    assert status == 2
    line = _one_error(lines)
    for word in words:
        assert word in line
    assert not (tmp_path / "out" / f"{name}.fmu").exists()


def test_a_slope_with_a_zero_column_is_structurally_singular():
    # the slope of y, z after earlier unknowns are substituted: z's
    # column holds only zeros (entries kept in the structure)
    slope = casadi.SX(casadi.Sparsity.dense(2, 2), casadi.SX([1, 1, 0, 0]))
    with pytest.raises(backend.BackEndError) as error:
        backend._check_structure("M.mo:3: 0 = ...", ["y", "z"], slope)
    assert str(error.value) == (
        "M.mo:3: 0 = ...: this algebraic loop in y, z is structurally "
        "singular: its equations do not determine z; allowed: a loop whose "
        "equations each add a condition on its unknowns")
    y, z = casadi.SX.sym("y"), casadi.SX.sym("z")
    backend._check_structure("M.mo:3: 0 = ...", ["y", "z"], casadi.jacobian(
        casadi.vertcat(y - z, z - y), casadi.vertcat(y, z)))   # full


# -- long compiles: estimate, refusal, progress -------------------------

def _chain(tmp_path, bodies):
    lines = [f"model Chain{bodies}", "  parameter Real k = 100;"]
    for i in range(1, bodies + 1):
        lines += [f"  Real phi{i}(start={1 if i == 1 else 0}, fixed=true);",
                  f"  Real w{i}(start=0, fixed=true);"]
    lines.append("equation")
    for i in range(1, bodies + 1):
        left = f"phi{i - 1}" if i > 1 else "0"
        right = f" + k*(phi{i + 1} - phi{i})" if i < bodies else ""
        lines += [f"  der(phi{i}) = w{i};",
                  f"  der(w{i}) = -k*(phi{i} - {left}){right};"]
    lines.append(f"end Chain{bodies};")
    return _model(tmp_path, f"Chain{bodies}", "\n".join(lines) + "\n")


def test_the_compile_estimate_grows_as_the_states(tmp_path):
    # the Jacobian's nonzeros only: a chain's operations grow as its
    # states (written densely they grew as their square)
    from fmu.build import _functions
    estimates = []
    for bodies in (10, 20):
        path = _chain(tmp_path, bodies)
        ode = backend.to_ode(load_flat_model(path, f"Chain{bodies}"))
        assert ode.jacobian()[1].nnz() == 5 * bodies - 2   # tridiagonal
        estimates.append(limits.compile_estimate(_functions(ode)))
    (small, s_small, b_small), (large, s_large, b_large) = estimates
    assert 1.9 < large / small < 2.1
    assert s_large / s_small == pytest.approx((large / small) ** 1.22)
    assert b_large - b_small == pytest.approx(10e3 * (large - small))


def test_a_compile_beyond_the_memory_is_refused_before_gcc(tmp_path):
    path = _chain(tmp_path, 10)
    ode = backend.to_ode(load_flat_model(path, "Chain10"))
    from fmu.build import _functions
    estimate = limits.compile_estimate(_functions(ode))
    with pytest.raises(FrontEndError) as error:
        limits.check_compile("Chain10", 20, estimate, memory=41e6)
    assert str(error.value) == (
        "Chain10: compiling it (20 states, 257 operations in its C code) "
        "would need about 0.0426 GB for gcc, more than the 0.041 GB "
        "available; allowed: a model that fits (about 100 operations)")
    limits.check_compile("Chain10", 20, estimate, memory=1e9)   # fits


def test_the_sparse_jacobian_gives_the_directional_derivatives(tmp_path):
    # the chain's d der(w_i)/d phi_j: -2k on the diagonal, k beside it
    # (-k for the last body), from FMI 2 and FMI 3 forward and adjoint
    from fmpy import extract, read_model_description
    from fmpy.fmi2 import FMU2Model
    from fmpy.fmi3 import FMU3Model
    path = _chain(tmp_path, 4)
    k, n = 100.0, 4
    expected = np.zeros((2 * n, 2 * n + 1))   # knowns: states, then k
    for i in range(n):
        expected[2 * i, 2 * i + 1] = 1.0      # der(phi_i) = w_i
        expected[2 * i + 1, 2 * i] = -2 * k if i < n - 1 else -k
        if i > 0:
            expected[2 * i + 1, 2 * i - 2] = k
        if i < n - 1:
            expected[2 * i + 1, 2 * i + 2] = k
    for version, model in (("2.0", FMU2Model), ("3.0", FMU3Model)):
        fmu = build_fmu(path, "Chain4", tmp_path / f"C{version}.fmu",
                        version=version).path
        md = read_model_description(str(fmu))
        derivatives = [u.variable.valueReference for u in md.derivatives]
        states = [u.variable.derivative.valueReference
                  for u in md.derivatives]
        assert [u.variable.derivative.name for u in md.derivatives] == [
            f"{a}{i}" for i in range(1, n + 1) for a in ("phi", "w")]
        knowns = states + [v.valueReference for v in md.modelVariables
                           if v.name == "k"]
        instance = model(guid=md.guid, unzipDirectory=extract(str(fmu)),
                         modelIdentifier=md.modelExchange.modelIdentifier)
        instance.instantiate()
        if version == "2.0":
            instance.setupExperiment()
        instance.enterInitializationMode()
        instance.exitInitializationMode()
        instance.enterContinuousTimeMode()
        forward = np.array([instance.getDirectionalDerivative(
            derivatives, knowns, list(seed))
            for seed in np.eye(len(knowns))]).T
        assert_allclose(forward[:, :2 * n], expected[:, :2 * n], atol=0)
        if version == "3.0":
            adjoint = np.array([instance.getAdjointDerivative(
                derivatives, knowns, list(seed), nSensitivity=len(knowns))
                for seed in np.eye(len(derivatives))])
            assert_allclose(adjoint, forward, atol=0)
        # d der(w1)/dk at the start: -(2 phi1 - phi2) = -2
        assert forward[1, -1] == -2.0
        instance.terminate()
        instance.freeInstance()


def test_a_compile_beyond_the_time_limit_is_refused(monkeypatch):
    monkeypatch.setenv("JUDDER_MAX_HOURS", "0.001")
    with pytest.raises(FrontEndError) as refused:
        limits.check_compile("M", 300, (98_400, 40.0, 1e8), memory=1e10)
    names(refused.value, "0.0111 h", "0.001 h")


class _Terminal:
    def __init__(self, tty):
        self.tty, self.text = tty, ""

    def isatty(self):
        return self.tty

    def write(self, text):
        self.text += text

    def flush(self):
        pass


def test_a_long_compile_is_announced_on_a_terminal_only():
    # the 1500-state chain of the issue: 44,995 operations
    estimate = (44_995, 0.77 * 44.995 ** 1.22, 40e6 + 10e3 * 44_995)
    terminal, pipe = _Terminal(True), _Terminal(False)
    assert limits.announce("Chain750", 1500, estimate, terminal)
    # one line, naming the model, its size and the estimate
    assert terminal.text.startswith("fmu: ") and \
        terminal.text.count("\n") == 1
    names(terminal.text, "Chain750", "1500 states", "44,995", "80 s",
          "0.49 GB", "gcc")
    assert not limits.announce("Chain750", 1500, estimate, pipe)
    assert pipe.text == ""
    assert not limits.announce("Small", 2, (500, 0.2, 4e7), terminal)


def test_a_long_build_says_its_step_on_a_terminal_only():
    from fmu.build import Stages
    terminal, pipe = _Terminal(True), _Terminal(False)
    with Stages("M", delay=0, stream=terminal) as stage:
        stage("flattening (rumoca)")
        deadline = time.monotonic() + 60
        while "M: flattening (rumoca) [00:" not in terminal.text:
            assert time.monotonic() < deadline, terminal.text
            time.sleep(0.05)   # until the status line is shown
        shown = len(terminal.text)
    blank = terminal.text[shown:]
    assert blank.strip() == "" and blank.endswith("\r")   # line cleared
    with Stages("M", delay=0, stream=pipe) as stage:
        stage("flattening (rumoca)")
    assert pipe.text == ""


def test_the_compile_with_a_progress_bar_reports_gcc_errors(tmp_path):
    bad = tmp_path / "bad.c"
    bad.write_text("int f( {\n")
    done = _run(["gcc", "-c", str(bad), "-o", str(tmp_path / "bad.o")],
                seconds=30.0)
    assert done.returncode != 0
    assert "bad.c:1" in done.stderr


# -- the experiment of the class built ----------------------------------

TWO = """package Two
  model First
    Real x(start=1, fixed=true);
  equation
    der(x) = -x;
    annotation(experiment(StopTime=4, Interval=1e-3));
  end First;
  model Second "experiment( StopTime=9 ) in a string is no annotation"
    Real x(start=1, fixed=true);
  equation
    der(x) = -2*x;
    // experiment(StopTime=7)
    annotation(experiment(StopTime=1, Interval=1e-4));
  end Second;
end Two;
"""


def test_the_default_experiment_is_the_built_classs_own(tmp_path):
    folder = tmp_path / "lib"
    folder.mkdir()
    (folder / "Two.mo").write_text(TWO)
    fmu = build_fmu(folder / "Two.mo", "Two.Second", tmp_path / "S.fmu",
                    roots=[folder]).path
    with zipfile.ZipFile(fmu) as archive:
        root = ET.fromstring(archive.read("modelDescription.xml"))
    experiment = root.find("DefaultExperiment").attrib
    assert float(experiment["stopTime"]) == 1.0
    assert float(experiment["stepSize"]) == 1e-4
    assert _experiment(folder / "Two.mo", "Two.First") == {
        "StopTime": 4.0, "Interval": 1e-3}


def test_class_spans_nest_and_skip_short_classes():
    # a function's partial application (MSL Math.Nonlinear) is no class
    text = ("within Lib;\npackage P\n  type T = Real(unit=\"m\");\n"
            "  redeclare model extends M \"end Q;\"\n  end M;\n"
            "  block B\n  equation\n    if true then\n    end if;\n"
            "    y = q(function P.f(w=3), function g());\n"
            "  end B;\nend P;\n")
    spans = class_spans(text)
    assert sorted(spans) == ["Lib.P", "Lib.P.B", "Lib.P.M"]
    begin, end = spans["Lib.P.B"]
    assert text[begin:end] == text[text.index("block B"):
                                   text.index("end B;") + 6]


def _msl():
    for folder in [ROOT.parent / "shared" / "msl"] + [
            Path(p) for p in os.environ.get("MODELICAPATH", "").split(
                os.pathsep) if p]:
        if (folder / "Modelica" / "package.mo").is_file():
            return folder
    return None


@pytest.mark.skipif(_msl() is None, reason="the Modelica Standard Library "
                    "4.x is not in ../shared/msl nor on MODELICAPATH")
def test_msl_modulation_has_its_own_experiment():
    # the first experiment of Blocks/package.mo is another example's
    # (StopTime=4); Modulation's is StopTime=1.0, Interval=0.0001
    source = _msl() / "Modelica" / "Blocks" / "package.mo"
    assert _experiment(source, "Modelica.Blocks.Examples.Modulation") == {
        "StopTime": 1.0, "Interval": 1e-4}


@pytest.mark.skipif(_msl() is None, reason="the Modelica Standard Library "
                    "4.x is not in ../shared/msl nor on MODELICAPATH")
def test_every_msl_experiment_is_read_for_its_own_class():
    # the 535 experiment annotations of MSL 4.x, each read back from the
    # innermost class that holds it
    checked = 0
    for source in sorted(_msl().rglob("*.mo")):
        text = source.read_text(encoding="utf-8")
        if "experiment" not in text:
            continue
        clean, spans = blank(text), class_spans(text)
        for found in re.finditer(r"\bexperiment\s*\(([^)]*)\)", clean):
            owner = max((begin, name) for name, (begin, end) in spans.items()
                        if begin <= found.start() < end)[1]
            expected = {key: float(value) for key, value in re.findall(
                r"(\w+)\s*=\s*([-+\d.eE]+)", found.group(1))}
            assert _experiment(source, owner) == expected, (source, owner)
            checked += 1
    assert checked > 500


# -- constructs refused from the source, before rumoca ------------------

_LIB = {
    "Lib/package.mo": """within;
package Lib
  import M = Lib.Parts;
  package Types
    connector BoolIn = input Boolean "A Boolean input";
  end Types;
end Lib;
""",
    "Lib/Parts/package.mo": "within Lib;\npackage Parts\nend Parts;\n",
    "Lib/Parts/Counter.mo": """within Lib.Parts;
model Counter "Holds a Boolean through a short type"
  Types.BoolIn on;
  Real x(start = 1, fixed = true);
equation
  der(x) = -x;
end Counter;
""",
    "Lib/Parts/Optional.mo": """within Lib.Parts;
model Optional "A conditional Counter, off by default"
  parameter Boolean use = false;
  Counter counter if use;
  Real y(start = 1, fixed = true);
equation
  der(y) = -y;
end Optional;
""",
    "Lib/Parts/Swappable.mo": """within Lib.Parts;
model Swappable "A replaceable Counter, which a modifier may redeclare"
  replaceable Counter counter;
end Swappable;
""",
    "Lib/Rig.mo": """within Lib;
model Rig
  Real z(start = 1, fixed = true);
  M.Optional optional;
  M.Counter counter(x(start = 2));
equation
  der(z) = -z;
end Rig;
""",
}


def test_a_boolean_is_refused_from_the_source_with_its_components(tmp_path):
    """`Lib.Rig` reaches `Counter`'s Boolean input through an import alias
    (`M.Counter`), a relative name (`Types.BoolIn`, found in the
    enclosing package) and a short connector definition; the refusal
    names the Boolean's line and the component's, without rumoca. The
    conditional `Optional.counter` and the replaceable
    `Swappable.counter` are not followed, so these classes pass."""
    from fmu.precheck import refuse_unsupported
    for name, text in _LIB.items():
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / name).write_text(text)
    with pytest.raises(FrontEndError) as refused:
        refuse_unsupported(tmp_path / "Lib" / "Rig.mo", "Lib.Rig",
                           [tmp_path])
    message = str(refused.value)
    assert re.match(r"\S*Counter\.mo:3: on: Integer, Boolean and discrete "
                    r"variables are not supported \(a Boolean variable\), "
                    r"in counter \(Lib\.Parts\.Counter, \S*Rig\.mo:5\)",
                    message), message
    for name in ("Optional", "Swappable"):
        refuse_unsupported(tmp_path / "Lib" / "Parts" / f"{name}.mo",
                           f"Lib.Parts.{name}", [tmp_path])


def test_a_name_the_class_does_not_declare_is_refused_from_the_source(
        tmp_path):
    """`Lib.Rig` declares `z` and, through `Counter`, `counter.x`; it has
    no `p_f` nor `counter.y`: refused at Rig.mo:2 without rumoca. Below
    a conditional (`optional.counter`) or a replaceable component
    (`Swappable.counter`) the source does not settle the name: it passes
    for the flat model to check."""
    from fmu.precheck import refuse_undeclared
    for name, text in _LIB.items():
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / name).write_text(text)
    refuse_undeclared("Lib.Rig", [tmp_path], {
        "amplitude": "z", "frequency": "counter.x",
        "other": "optional.counter.q"})
    refuse_undeclared("Lib.Parts.Swappable", [tmp_path],
                      {"amplitude": "counter.q"})
    for name in ("p_f", "counter.y"):
        with pytest.raises(FrontEndError) as undeclared:
            refuse_undeclared("Lib.Rig", [tmp_path], {"amplitude": name})
        names(undeclared.value, "Rig.mo:2", "`amplitude`", repr(name),
              "Lib.Rig")


@pytest.mark.skipif(_msl() is None, reason="the Modelica Standard Library "
                    "4.x is not in ../shared/msl nor on MODELICAPATH")
@pytest.mark.parametrize("name, line, dither", [
    ("Rotational.Examples.Backlash", "Rotational/Examples/Backlash.mo:2",
     ()),
    ("Translational.Examples.PreLoad", "Translational/Examples/PreLoad.mo:2",
     ()),
    ("Translational.Examples.ElastoGap",
     "Translational/Examples/ElastoGap.mo:2",
     ("--dither-amplitude", "elastoGap1.c", "--dither-frequency",
      "mass1.mm")),
    ("Blocks.Examples.SlewRateLimiter", "Blocks/package.mo:397", ())])
def test_msl_examples_without_a_dither_are_refused_before_flattening(
        judder_here, monkeypatch, name, line, dither):
    """MSL examples the linearisation in one mode compiles (their
    Booleans, initial() and relations are read) but which have no dither
    parameter: `judder check --modelica` refuses them from the source,
    at the class's file:line, never reaching rumoca (12-30 s)."""
    import fmu.frontend
    cls = ("Modelica.Blocks.Examples.SlewRateLimiter" if "Blocks" in name
           else f"Modelica.Mechanics.{name}")
    monkeypatch.setenv("MODELICAPATH", str(_msl()))

    def flatten(*args, **kwargs):
        raise AssertionError("rumoca flattened the class")
    monkeypatch.setattr(fmu.frontend, "_flatten", flatten)
    started = time.monotonic()
    status, _, err = judder_here(
        "check", "--modelica", cls, "--library", _msl(), "--freq", 100,
        "--pf", 0.3, *dither)
    assert time.monotonic() - started < 10
    missing = dither[-1] if dither else "p_f"
    option = "--dither-frequency" if dither else "--dither-amplitude"
    assert status == 2, err
    names(err, f"{line}:", option, repr(missing), cls)


@pytest.mark.skipif(_msl() is None, reason="the Modelica Standard Library "
                    "4.x is not in ../shared/msl nor on MODELICAPATH")
@pytest.mark.parametrize("amplitude, frequency, option, name, bound", [
    ("amplitude", "sine.f", "--dither-frequency", "sine.f", "f"),
    ("sine.amplitude", "f", "--dither-amplitude", "sine.amplitude",
     "amplitude")])
def test_a_dither_name_the_class_binds_is_refused_before_flattening(
        judder_here, monkeypatch, amplitude, frequency, option, name, bound):
    """`judder eig --modelica Rotational.Examples.First --dither-frequency
    sine.f`: First declares `Sine sine(amplitude=amplitude, f=f)`, so
    sine.f is calculated from f, not tunable; refused from the source at
    the modification's line, naming the parameter to give, without
    rumoca's flatten (it was refused after it: 17 s of CPU cold)."""
    import fmu.frontend
    monkeypatch.setenv("MODELICAPATH", str(_msl()))

    def flatten(*args, **kwargs):
        raise AssertionError("rumoca flattened the class")
    monkeypatch.setattr(fmu.frontend, "_flatten", flatten)
    cls = "Modelica.Mechanics.Rotational.Examples.First"
    started = time.monotonic()
    status, _, err = judder_here(
        "eig", "--modelica", cls, "--library", _msl(), "--dither-amplitude",
        amplitude, "--dither-frequency", frequency)
    assert time.monotonic() - started < 10
    assert status == 2, err
    names(err, "Rotational/Examples/First.mo:34:", option, repr(name),
          cls, "allowed", repr(bound))


def test_bindings_to_the_class_parameters_are_read_from_the_source(
        tmp_path):
    """A parameter bound to an expression of the class's own parameters
    (declared so, or by a component's modification, with `final`) is
    refused; one bound to a number, a name of a class extended or a
    component without a modification passes to the flat model."""
    from fmu.precheck import refuse_bound
    _model(tmp_path, "Rig", """
model Rig
  model Part
    parameter Real k = 1;
    parameter Real d = 2;
  end Part;
  parameter Real a = 1 "a number";
  parameter Real b = 2*a + sin(a) "calculated";
  parameter Real c = Modelica.Constants.pi;
  Part p(k = 3, final d = b/2);
  Part q;
  Real x(start = a);
equation
  der(x) = -x;
end Rig;
""")
    roots = [tmp_path / "Rig"]
    for passes in ("a", "c", "p.k", "q.k", "q.d", "x", "p.k.z"):
        refuse_bound("Rig", roots, {"frequency": passes})
    with pytest.raises(FrontEndError) as bound:
        refuse_bound("Rig", roots, {"amplitude": "b"})
    names(bound.value, "Rig.mo:8", "`amplitude`", "'b'", "2*a + sin(a)",
          "allowed")
    with pytest.raises(FrontEndError) as bound:
        refuse_bound("Rig", roots, {"amplitude": "a", "frequency": "p.d"})
    names(bound.value, "Rig.mo:10", "`frequency`", "'p.d'", "b/2")


#: What a refusal of an MSL brake must name: the library's locking clutch
#: with one flange on a Fixed.
_USE_BRAKE = ("Judder.Components.LockingWetClutch", "flange_b",
              "Judder.Components.Fixed")
_USE_CLUTCH = ("Judder.Components.LockingWetClutch",
               "Judder.Components.SlippingClutch")
_NONE = "no replacement"


@pytest.mark.skipif(_msl() is None, reason="the Modelica Standard Library "
                    "4.x is not in ../shared/msl nor on MODELICAPATH")
@pytest.mark.parametrize("model, hybrid, words", [
    ("Rotational.Components.Brake", False, _USE_BRAKE),
    ("Rotational.Examples.Friction", False,
     ("for Clutch", "for Brake") + _USE_CLUTCH + _USE_BRAKE),
    ("Rotational.Components.LossyGear", False,
     (_NONE, "Judder.Components.IdealGear", "lossless")),
    ("Rotational.Examples.Backlash", False,
     ("ElastoBacklash", "ElastoBacklash2", _NONE, "backlash")),
    ("Translational.Examples.Brake", False, (_NONE, "rotational"))])
def test_msl_refusals_name_the_replacement_or_say_there_is_none(
        model, hybrid, words):
    """A refused MSL friction, gear or backlash component names what the
    Judder library has instead: a brake is its locking clutch with one
    flange fixed; for a one-way clutch, a lossy gear and backlash it says
    there is none; a model holding a clutch and a brake names both (the
    brake's was the clutch's wording, the others named nothing)."""
    from fmu.precheck import refuse_unsupported
    from fmu.classes import find_class
    name = f"Modelica.Mechanics.{model}"
    source, _ = find_class(name, [_msl()])
    with pytest.raises(FrontEndError) as refused:
        refuse_unsupported(source, name, [_msl()], hybrid=hybrid)
    names(refused.value, *words)


def test_every_replacement_named_is_in_the_judder_library():
    """Each Judder class a refusal names exists in modelica/Judder."""
    from fmu.precheck import REPLACEMENTS
    named = set(re.findall(r"Judder\.Components\.(\w+)",
                           " ".join(REPLACEMENTS.values())))
    assert named >= {"LockingWetClutch", "SlippingClutch", "Fixed",
                     "IdealGear", "Damper"}
    folder = ROOT / "modelica" / "Judder" / "Components"
    for name in named:
        assert f"model {name} " in (folder / f"{name}.mo").read_text()


@pytest.mark.skipif(_msl() is None, reason="the Modelica Standard Library "
                    "4.x is not in ../shared/msl nor on MODELICAPATH")
@pytest.mark.parametrize("model", ["Modelica.Mechanics.Rotational."
                                   "Components.Clutch", "My.OwnClutch",
                                   "My.Rig"])
def test_msl_clutch_with_its_table_passes_the_source_check(tmp_path, model):
    """For `--modelica` (Booleans and pre() pass) MSL's Clutch, its table
    object given in the model, passes the source check within seconds
    (fmu.rewrite.inline_tables computes its lookups in Modelica): given
    itself, through a class of one's own that extends it and through a
    component of that class. (Without Booleans, and for a table read
    from a file, the refusals with the project's replacement remain:
    the test above and tests/test_fmu_msl_clutches.py.)"""
    from fmu.precheck import refuse_unsupported
    (tmp_path / "My").mkdir()
    (tmp_path / "My" / "package.mo").write_text(
        "package My\n"
        "  model OwnClutch\n"
        "    extends Modelica.Mechanics.Rotational.Components.Clutch;\n"
        "  end OwnClutch;\n"
        "  model Rig\n"
        "    OwnClutch clutch;\n"
        "  end Rig;\n"
        "end My;\n")
    roots = [tmp_path, _msl()]
    path = (_msl() / "Modelica" / "Mechanics" / "Rotational" / "Components"
            / "Clutch.mo") if model.startswith("Modelica") else \
        tmp_path / "My" / "package.mo"
    started = time.monotonic()
    refuse_unsupported(path, model, roots, hybrid=True)
    assert time.monotonic() - started < 10


@pytest.mark.parametrize("files, name, chain", [
    ({"Recursive.mo": "model Recursive extends Recursive; end Recursive;\n"},
     "Recursive", "Recursive extends Recursive"),
    ({"A.mo": "model A extends B; end A;\n",
      "B.mo": "model B extends A; end B;\n"}, "A", "A extends B extends A"),
])
def test_a_class_that_extends_itself_is_refused_in_words(
        tmp_path, capsys, files, name, chain):
    # judder ... --modelica Recursive ended in an internal RecursionError,
    # exit 1 (issue 44, item 12); python -m fmu already refused it
    from judder.cli import main
    for file, text in files.items():
        (tmp_path / file).write_text(text)
    for command in (["eig"], ["simulate", "--freq", "100", "--pf", "0.1"]):
        status = main(command + ["--modelica", name, "--library",
                                 str(tmp_path)])
        err = capsys.readouterr().err
        assert status == 2, err
        assert "internal error" not in err
        for fact in (f"{name}.mo:1", "extends itself", chain, "allowed"):
            assert fact in err
