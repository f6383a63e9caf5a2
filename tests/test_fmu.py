"""FMUs built from the Modelica source: validity, fidelity, traceability.

The FMUs are compiled from modelica/ by the project's compiler (rumoca
front end, fmu/ back end, gcc); nothing restates the model in C.
"""

import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET
import zipfile
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from drivelines import get_preset
from stability import build_driveline

pytest.importorskip("rumoca")
fmpy = pytest.importorskip("fmpy")
from fmpy import simulate_fmu  # noqa: E402
from fmpy.validation import validate_fmu  # noqa: E402

from fmu.build import BuildError, build_fmu  # noqa: E402
from fmu.frontend import FrontEndError  # noqa: E402

LIBRARY = Path(__file__).resolve().parents[1] / "modelica"
EXAMPLES = ["Driveline4DOF", "Driveline3DOF", "TestBenchEngagement"]
W_IN = 1000 * 2 * np.pi / 60


def _build(name, folder, version, library=LIBRARY):
    suffix = "" if version == "2.0" else "_fmi3"
    return build_fmu(library / "Judder" / "Examples" / f"{name}.mo",
                     f"Judder.Examples.{name}",
                     folder / f"{name}{suffix}.fmu", version=version,
                     roots=[library]).path


@pytest.fixture(scope="module")
def fmus(tmp_path_factory):
    folder = tmp_path_factory.mktemp("fmu")
    return {(name, version): _build(name, folder, version)
            for name in EXAMPLES for version in ("2.0", "3.0")}


def _eq1(f_dither, p_f, J4=0.122, t_end=1.0):
    """Independent reference: Eq. (1) of the stability layer, scipy."""
    params = get_preset("paper-4dof").replace(J4=J4)
    driveline = build_driveline(params)
    torque = params["mu0"] * params.clutch_factor * params["p_m"]
    x0 = [0, -torque / 3856, -torque / 3856 - torque / 32885, 0,
          W_IN, W_IN, W_IN, 0]
    return solve_ivp(
        lambda t, x: driveline.state_matrix(t, f_dither, p_f) @ x
        + driveline.state_forcing(t, f_dither, p_f, engine_torque=torque,
                                  resistant_torque=torque),
        (0, t_end), x0, method="DOP853", rtol=1e-13, atol=1e-13,
        dense_output=True)


def _relative_error(result, reference):
    y = reference.sol(result["time"])
    worst = 0.0
    for name, row in [("w_upstream", 6), ("w_downstream", 7),
                      ("inertia2.phi", 1), ("inertia1.w", 4)]:
        worst = max(worst, np.abs(result[name] - y[row]).max()
                    / np.abs(y[row]).max())
    return worst


@pytest.mark.parametrize("version", ["2.0", "3.0"])
@pytest.mark.parametrize("name", EXAMPLES)
def test_fmpy_validation_finds_no_problem(fmus, name, version):
    assert validate_fmu(str(fmus[(name, version)])) == []


@pytest.mark.parametrize("version", ["2.0", "3.0"])
def test_fmu_manipulation_toolbox_check(fmus, version):
    fmutool = Path(sys.executable).with_name("fmutool")
    if not fmutool.exists():
        pytest.skip("fmu-manipulation-toolbox is not installed")
    for name in EXAMPLES:
        done = subprocess.run([str(fmutool), "-input",
                               str(fmus[(name, version)]), "-check"],
                              capture_output=True, text=True, timeout=120)
        text = done.stdout + done.stderr
        assert f"compliant with FMI-{version[0]}" in text, text
        assert f"No semantic error against the FMI-{version[0]}" in text, text


@pytest.mark.parametrize("version, kind", [("2.0", "ModelExchange"),
                                           ("2.0", "CoSimulation"),
                                           ("3.0", "ModelExchange")])
def test_4dof_fmu_matches_eq1(fmus, version, kind):
    # 1 s of steady slipping with dither at a stable point (60 Hz, 0.3 bar)
    options = {"relative_tolerance": 1e-12} if kind == "ModelExchange" else {}
    result = simulate_fmu(str(fmus[("Driveline4DOF", version)]),
                          fmi_type=kind, stop_time=1.0, output_interval=1e-3,
                          start_values={"f_dither": 60.0, "p_f": 0.3e5},
                          output=["w_upstream", "w_downstream",
                                  "inertia2.phi", "inertia1.w"], **options)
    assert _relative_error(result, _eq1(60.0, 0.3e5)) < 1e-6


def test_tunable_parameters_have_units_and_descriptions(fmus):
    with zipfile.ZipFile(fmus[("Driveline4DOF", "2.0")]) as fmu:
        root = ET.fromstring(fmu.read("modelDescription.xml"))
    variables = {v.get("name"): v for v in root.iter("ScalarVariable")}
    expected_units = {"f_dither": "Hz", "p_f": "Pa", "p_m": "Pa",
                      "J1": "kg.m2", "J4": "kg.m2", "k12": "N.m/rad",
                      "k24": "N.m/rad", "c12": "N.m.s/rad", "c3": "N.m.s/rad",
                      "mu0": "1", "mu_g": "s/rad",
                      "mean_pressure_damping": "1"}
    for name, unit in expected_units.items():
        v = variables[name]
        assert v.get("causality") == "parameter"
        assert v.get("variability") == "tunable"
        assert v.get("description")
        assert v.find("Real").get("unit") == unit
    outputs = {n for n, v in variables.items()
               if v.get("causality") == "output"}
    assert {"w_upstream", "w_downstream", "slip", "clutch_torque",
            "actuation_pressure"} <= outputs


def test_changed_source_changes_the_fmu(tmp_path):
    # one parameter default changed in a temporary copy of the library
    copy = tmp_path / "modelica"
    shutil.copytree(LIBRARY, copy)
    path = copy / "Judder" / "Examples" / "Driveline4DOF.mo"
    text = path.read_text()
    assert "parameter Units.Inertia J4=0.122" in text
    path.write_text(text.replace("parameter Units.Inertia J4=0.122",
                                 "parameter Units.Inertia J4=0.2"))
    fmu = _build("Driveline4DOF", tmp_path, "2.0", library=copy)
    result = simulate_fmu(str(fmu), fmi_type="CoSimulation", stop_time=1.0,
                          output_interval=1e-3,
                          start_values={"f_dither": 60.0},
                          output=["w_upstream", "w_downstream",
                                  "inertia2.phi", "inertia1.w"])
    assert _relative_error(result, _eq1(60.0, 0.3e5, J4=0.2)) < 1e-6
    assert _relative_error(result, _eq1(60.0, 0.3e5, J4=0.122)) > 1e-3


def test_missing_compiler_is_a_clear_error(tmp_path, monkeypatch):
    monkeypatch.setenv("CC", "no-such-compiler")
    with pytest.raises(BuildError, match="C compiler 'no-such-compiler'"):
        _build("Driveline3DOF", tmp_path, "2.0")


def test_modelica_mistake_names_file_and_line(tmp_path):
    copy = tmp_path / "modelica"
    shutil.copytree(LIBRARY, copy)
    path = copy / "Judder" / "Examples" / "Driveline3DOF.mo"
    path.write_text(path.read_text().replace("equation", "equaton", 1))
    with pytest.raises(FrontEndError) as info:
        _build("Driveline3DOF", tmp_path, "2.0", library=copy)
    assert "Driveline3DOF.mo:" in str(info.value)
    assert "unexpected `connect`" in str(info.value)
    assert not list(tmp_path.glob("*.fmu"))


@pytest.mark.filterwarnings("ignore::pytest.PytestUnraisableExceptionWarning")
@pytest.mark.parametrize("version, kind", [("2.0", "ModelExchange"),
                                           ("2.0", "CoSimulation"),
                                           ("3.0", "ModelExchange")])
def test_out_of_range_and_non_finite_are_errors(fmus, version, kind):
    # J1 = -1 is outside J's declared min = 0: refused by fmi2SetReal /
    # fmi3SetFloat64; J4 = 0 is allowed but makes der(inertia4.w) = x/0
    fmu = str(fmus[("Driveline4DOF", version)])
    messages = []
    with pytest.raises(Exception, match="status 3"):
        simulate_fmu(fmu, fmi_type=kind, stop_time=0.01,
                     start_values={"J1": -1.0},
                     logger=lambda *args: messages.append(args[-1]))
    assert any(b"outside its declared range [0, inf]" in m
               for m in messages), messages
    messages.clear()
    with pytest.raises(Exception):
        simulate_fmu(fmu, fmi_type=kind, stop_time=0.01,
                     start_values={"J4": 0.0},
                     logger=lambda *args: messages.append(args[-1]))
    assert any(b"not finite" in m for m in messages), messages


@pytest.mark.parametrize("version", ["2.0", "3.0"])
def test_display_units_and_quantities(fmus, version):
    # Units.Pressure (displayUnit "bar") and Units.Angle ("deg") as an OEM
    # tool shows them: 1 bar = 1e5 Pa, 1 deg = pi/180 rad
    from fmpy import read_model_description
    description = read_model_description(str(fmus[("Driveline4DOF",
                                                    version)]))
    variables = {v.name: v for v in description.modelVariables}
    for name, quantity, display in [("p_m", "Pressure", "bar"),
                                    ("actuation_pressure", "Pressure", "bar"),
                                    ("inertia1.phi", "Angle", "deg"),
                                    ("w_upstream", "AngularVelocity", None)]:
        assert variables[name].quantity == quantity, name
        assert variables[name].displayUnit == display, name
    units = {u.name: {d.name: d.factor for d in u.displayUnits}
             for u in description.unitDefinitions}
    assert units["Pa"] == {"bar": 1e-5}
    assert units["rad"] == pytest.approx({"deg": 180 / np.pi}, rel=1e-15)
