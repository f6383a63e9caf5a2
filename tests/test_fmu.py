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
from numpy.testing import assert_allclose
from scipy.integrate import solve_ivp

from sources import get_preset
from stability import build_driveline

pytest.importorskip("rumoca")
fmpy = pytest.importorskip("fmpy")
from fmpy import simulate_fmu  # noqa: E402
from fmpy.validation import validate_fmu  # noqa: E402

from fmu.build import BuildError, build_fmu  # noqa: E402
from fmu.frontend import FrontEndError  # noqa: E402

LIBRARY = Path(__file__).resolve().parents[1] / "modelica"
EXAMPLES = ["Driveline4DOF", "Driveline3DOF", "TestBenchEngagement",
            "TestBenchFullEngagement", "TestBenchLockUp",
            "TestBenchCurveLockUp", "Driveline4DOFInputs"]
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


def _eq1_pieces(pieces, t_end):
    """Eq. (1) by scipy with the pressure and the engine torque constant
    on each piece: ``pieces`` are (start time, pressure, engine torque);
    a pressure p is p_m + p_f cos(2 pi 0 t) with p_f = p - p_m."""
    params = get_preset("paper-4dof")
    driveline = build_driveline(params)
    torque = params["mu0"] * params.clutch_factor * params["p_m"]
    state = [0, -torque / 3856, -torque / 3856 - torque / 32885, 0,
             W_IN, W_IN, W_IN, 0]
    solutions = []
    for k, (start, pressure, engine) in enumerate(pieces):
        end = pieces[k + 1][0] if k + 1 < len(pieces) else t_end
        p_f = pressure - params["p_m"]
        solution = solve_ivp(
            lambda t, x: driveline.state_matrix(t, 0.0, p_f) @ x
            + driveline.state_forcing(t, 0.0, p_f, engine_torque=engine,
                                      resistant_torque=torque),
            (start, end), state, method="DOP853", rtol=1e-13, atol=1e-13,
            dense_output=True)
        state = solution.y[:, -1]
        solutions.append((start, end, solution.sol))
    return lambda t: np.column_stack([next(
        sol for start, end, sol in solutions if start <= s <= end)(s)
        for s in np.atleast_1d(t)])


def test_input_variant_follows_its_inputs(fmus):
    """Driveline4DOFInputs (clutch_pressure, engine_torque as FMU inputs):
    constant inputs give Driveline4DOF without dither bit for bit; a step
    of each input, on communication points of Co-Simulation, gives Eq. (1)
    integrated piecewise."""
    p_m, torque = 1e6, 0.09 * 8 * 0.075 * 0.01 * 1e6
    names = ["w_upstream", "w_downstream", "inertia2.phi", "inertia1.w",
             "actuation_pressure"]
    fields = [("time", float), ("clutch_pressure", float),
              ("engine_torque", float)]
    constant = np.array([(0.0, p_m, torque), (1.0, p_m, torque)], fields)
    for version in ("2.0", "3.0"):
        variables = {v.name: v for v in fmpy.read_model_description(str(
            fmus[("Driveline4DOFInputs", version)])).modelVariables}
        assert [(n, variables[n].causality, variables[n].unit) for n in
                ("clutch_pressure", "engine_torque")] == [
            ("clutch_pressure", "input", "Pa"),
            ("engine_torque", "input", "N.m")]
        for kind in ("ModelExchange", "CoSimulation"):
            ours = simulate_fmu(str(fmus[("Driveline4DOFInputs", version)]),
                                fmi_type=kind, stop_time=0.5,
                                output_interval=1e-3, input=constant,
                                output=names)
            theirs = simulate_fmu(str(fmus[("Driveline4DOF", version)]),
                                  fmi_type=kind, stop_time=0.5,
                                  output_interval=1e-3, output=names,
                                  start_values={"p_f": 0.0})
            for name in names:
                assert np.array_equal(ours[name], theirs[name]), name
    # +0.5 bar from 0.2 s, +100 N m from 0.4 s; Co-Simulation holds each
    # input over a step, so the table changes just before those points
    steps = np.array([(0.0, p_m, torque), (0.1995, p_m, torque),
                      (0.2, p_m + 0.5e5, torque),
                      (0.3995, p_m + 0.5e5, torque),
                      (0.4, p_m + 0.5e5, torque + 100.0),
                      (1.0, p_m + 0.5e5, torque + 100.0)], fields)
    result = simulate_fmu(str(fmus[("Driveline4DOFInputs", "2.0")]),
                          fmi_type="CoSimulation", stop_time=1.0,
                          output_interval=1e-3, input=steps, output=names)
    reference = _eq1_pieces([(0.0, p_m, torque), (0.2, p_m + 0.5e5, torque),
                             (0.4, p_m + 0.5e5, torque + 100.0)], 1.0)
    y = reference(result["time"])
    for name, row in [("w_upstream", 6), ("w_downstream", 7),
                      ("inertia2.phi", 1), ("inertia1.w", 4)]:
        assert_allclose(result[name], y[row], rtol=0,
                        atol=1e-7 * np.abs(y[row]).max(), err_msg=name)
    # (fmpy records the outputs of a communication point before it sets
    # the inputs there)
    assert_allclose(result["actuation_pressure"],
                    np.where(result["time"] <= 0.2, p_m, p_m + 0.5e5))


#: Dither settings of the engagement benchmark (benchmarks/bench.py).
OUTSIDE_TONGUES = {"f_dither": 60.0, "p_f": 0.05e5}
TONGUE_2 = {"f_dither": 102.9, "p_f": 0.3e5}
BENCH_OUTPUTS = ["w_upstream", "w_downstream", "slip", "clutch_torque",
                 "actuation_pressure"]


def _engagement(fmus, name, kind, setting, stop_time):
    """A bench engagement, on the 1 ms grid only (fmpy adds event rows);
    the locking clutch's mode counters with it."""
    options = {"relative_tolerance": 1e-8} if kind == "ModelExchange" else {}
    extra = (["clutch.lockups", "clutch.breakaways", "clutch.p_mean",
              "clutch.tau0_max"] if "LockUp" in name else ["clutch.p_mean"])
    result = simulate_fmu(str(fmus[(name, "2.0")]), fmi_type=kind,
                          stop_time=stop_time, output_interval=1e-3,
                          start_values=setting, output=BENCH_OUTPUTS + extra,
                          **options)
    grid = np.arange(round(stop_time / 1e-3) + 1) * 1e-3
    last = np.r_[np.diff(result["time"]) > 0, True]      # after an event
    on_grid = last & (np.abs(result["time"] - np.round(result["time"], 3))
                      < 1e-12)
    result = result[on_grid]
    assert_allclose(result["time"], grid, atol=1e-12)
    return result


@pytest.mark.parametrize("kind, slipping_error", [("ModelExchange", 2e-3),
                                                  ("CoSimulation", 1e-5)])
def test_locking_clutch_engagement_ends_in_lock_up(fmus, kind,
                                                   slipping_error):
    # outside the tongues: the same engagement as WetClutch's
    # (TestBenchFullEngagement) while it
    # slips (there tanh(slip/w_small) = 1; the bound is the integrators'
    # difference, 1.2e-3 rad/s ME at rtol 1e-8, 1e-6 CS), then one lock-up
    # that holds: zero slip, torque within mu0 N_c R_m S p
    locking = _engagement(fmus, "TestBenchLockUp", kind, OUTSIDE_TONGUES, 4.0)
    smooth = _engagement(fmus, "TestBenchFullEngagement", kind,
                         OUTSIDE_TONGUES, 4.0)
    t = locking["time"]
    assert locking["clutch.lockups"][-1] == 1
    assert locking["clutch.breakaways"][-1] == 0
    stuck = locking["clutch.lockups"] > 0.5
    t_lock = t[stuck][0]
    assert 3.2 < t_lock < 3.25 and np.all(stuck[t >= t_lock])
    slipping = (t < t_lock) & (smooth["slip"] > 0.2)
    assert slipping.sum() > 3000
    for name in ("w_upstream", "w_downstream", "clutch_torque"):
        assert np.abs(locking[name] - smooth[name])[slipping].max() \
            < slipping_error, name
    assert np.abs(locking["slip"][stuck]).max() < 1e-11
    # mu0 N_c R_m S p
    capacity = 0.09 * 8 * 0.075 * 0.01 * locking["actuation_pressure"]
    assert np.all(np.abs(locking["clutch_torque"][stuck])
                  < capacity[stuck])
    assert smooth["slip"][-1] > 1e-3     # the smooth clutch still creeps


@pytest.mark.parametrize("kind", ["ModelExchange", "CoSimulation"])
def test_locking_clutch_breaks_away_at_once_inside_tongue_2(fmus, kind):
    # inside tongue 2 the slip swings through zero; at each zero the stuck
    # plates would need more than the capacity, so every lock-up breaks
    # away in its own event iteration and the speeds stay those of
    # WetClutch, whose torque reverses within a few w_small (2e-5 of the
    # largest slip after 358 reversals)
    locking = _engagement(fmus, "TestBenchLockUp", kind, TONGUE_2, 2.0)
    smooth = _engagement(fmus, "TestBenchFullEngagement", kind, TONGUE_2,
                         2.0)
    lockups = locking["clutch.lockups"]
    assert lockups[-1] > 300
    assert_allclose(lockups, locking["clutch.breakaways"], atol=0)
    assert np.abs(locking["slip"] - smooth["slip"]).max() \
        < 1e-4 * np.abs(smooth["slip"]).max()


#: The bench's EVEN clutch (Data.ClutchData, TestBenchEngagement): N_c R_m S
#: (m^3), and the friction curve's mu0, mu_g (s/rad), delta_mu, w_op (rad/s).
NRS = 8 * 0.075 * 0.01
CURVE = {"mu0": 0.09, "mu_g": 0.017, "delta_mu": 0.04,
         "w_op": 84.71975511965977}


def _curve_torque(slip, p, p_mean):
    """The held-slip bench's friction law in closed form (CurveWetClutch,
    mean_pressure_damping m = 0): sign(slip) N_c R_m S (mu(|slip|) (p -
    p_mean) + mu0 p_mean), mu(w) = mu0 + delta_mu tanh(mu_g (w - w_op) /
    delta_mu); with m = 1, or where p = p_mean, mu(|slip|) N_c R_m S p."""
    mu = CURVE["mu0"] + CURVE["delta_mu"] * np.tanh(
        CURVE["mu_g"] * (np.abs(slip) - CURVE["w_op"]) / CURVE["delta_mu"])
    return np.sign(slip) * NRS * (mu * (p - p_mean) + CURVE["mu0"] * p_mean)


@pytest.mark.parametrize("setting", [OUTSIDE_TONGUES, TONGUE_2])
def test_full_engagement_has_the_held_slip_bench_friction_law(fmus,
                                                              setting):
    # issue 41: judder simulate --engagement full (TestBenchCurveLockUp)
    # and the held-slip bench (TestBenchEngagement) run one friction law.
    # The engagement sweeps the slip from 103 rad/s to lock-up; at every
    # slipping sample its torque is the curve's closed form at that slip
    # and pressure, to 1e-9 of the largest torque (the same expression in
    # double precision); stuck, it is within the capacity, the law's
    # torque at zero slip
    full = _engagement(fmus, "TestBenchCurveLockUp", "CoSimulation",
                       setting, 4.0)
    locked = full["clutch.lockups"] - full["clutch.breakaways"]
    slipping = locked < 0.5
    law = _curve_torque(full["slip"], full["actuation_pressure"],
                        full["clutch.p_mean"])
    scale = np.abs(full["clutch_torque"]).max()
    assert_allclose(full["clutch_torque"][slipping], law[slipping], rtol=0,
                    atol=1e-9 * scale)
    swept = full["slip"][slipping & (full["time"] > 0.15)]
    assert swept.max() > 100 and np.abs(swept).min() < 1.0
    mu_stuck = CURVE["mu0"] - CURVE["delta_mu"]      # tanh(36) = 1 - 1e-31
    capacity = NRS * (mu_stuck * (full["actuation_pressure"]
                                  - full["clutch.p_mean"])
                      + CURVE["mu0"] * full["clutch.p_mean"])
    assert_allclose(full["clutch.tau0_max"], capacity, rtol=1e-12)
    assert np.all(np.abs(full["clutch_torque"][~slipping])
                  <= capacity[~slipping] * (1 + 1e-12))
    assert full["clutch.lockups"][-1] >= 1 and locked[-1] == 1
    # the held-slip bench at three slips (w_gearbox = w_motor - slip),
    # the operating slip and both sides of the curve: the same closed
    # form at every sample, its direction tanh(slip/w_small) = 1
    for slip in (20.0, CURVE["w_op"], 100.0):
        held = _engagement(fmus, "TestBenchEngagement", "CoSimulation",
                           {**setting, "w_gearbox": W_IN - slip}, 1.0)
        after_ramp = held["slip"][held["time"] > 0.6]
        assert abs(after_ramp.mean() - slip) < 2 and after_ramp.min() > 1
        assert_allclose(held["clutch_torque"],
                        _curve_torque(held["slip"],
                                      held["actuation_pressure"],
                                      held["clutch.p_mean"]),
                        rtol=0, atol=1e-9 * scale)


def test_held_slip_bench_and_full_engagement_agree_where_they_meet(fmus):
    # the held-slip bench given the engagement's start (gearbox side at
    # rest, 0.05 s ramp, REV torque 0.006/0.00816 of the EVEN mean torque:
    # S_load = 0.006 m^2) is the full engagement with CurveWetClutch's
    # smooth direction: until the lock-up the two FMUs give the same
    # torque at the same slip and pressure (the slips differ by the
    # integrators' 1e-6 rad/s; the torques by 1e-6 of their 540 N m),
    # outside the tongues as in test_locking_clutch_engagement_ends_in_lock_up
    load_share = 0.006 / (8 * 0.01 * 1e6 / (10 * 0.98e6))
    start = {**OUTSIDE_TONGUES, "w_gearbox": 0.0, "t_ramp": 0.05,
             "load_share": load_share}
    held = _engagement(fmus, "TestBenchEngagement", "CoSimulation", start,
                       3.0)
    full = _engagement(fmus, "TestBenchCurveLockUp", "CoSimulation",
                       OUTSIDE_TONGUES, 3.0)
    assert full["clutch.lockups"][-1] == 0     # still slipping at 3 s
    slipping = full["slip"] > 0.2
    assert slipping.sum() > 2800
    assert np.abs(held["slip"] - full["slip"])[slipping].max() < 1e-5
    assert_allclose(held["actuation_pressure"], full["actuation_pressure"],
                    rtol=1e-12)
    assert np.abs(held["clutch_torque"] - full["clutch_torque"])[
        slipping].max() < 1e-6 * 540


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
    # one parameter default changed in a temporary copy of the library:
    # in the record of Appendix A the example extends
    copy = tmp_path / "modelica"
    shutil.copytree(LIBRARY, copy)
    path = copy / "Judder" / "Data" / "Driveline4DOFData.mo"
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
    # Units.Pressure (displayUnit "bar"), Units.Angle ("deg") and
    # Units.AngularVelocity ("rpm") as an OEM tool shows them: 1 bar =
    # 1e5 Pa, 1 deg = pi/180 rad, 1 rpm = pi/30 rad/s
    from fmpy import read_model_description
    description = read_model_description(str(fmus[("Driveline4DOF",
                                                    version)]))
    variables = {v.name: v for v in description.modelVariables}
    for name, quantity, display in [("p_m", "Pressure", "bar"),
                                    ("actuation_pressure", "Pressure", "bar"),
                                    ("inertia1.phi", "Angle", "deg"),
                                    ("w_upstream", "AngularVelocity", "rpm"),
                                    ("w_in", "AngularVelocity", "rpm")]:
        assert variables[name].quantity == quantity, name
        assert variables[name].displayUnit == display, name
    units = {u.name: {d.name: d.factor for d in u.displayUnits}
             for u in description.unitDefinitions}
    assert units["Pa"] == {"bar": 1e-5}
    assert units["rad"] == pytest.approx({"deg": 180 / np.pi}, rel=1e-15)
    assert units["rad/s"] == pytest.approx({"rpm": 30 / np.pi}, rel=1e-15)


def test_version_is_the_package_annotation(fmus):
    # modelDescription's version is Judder's annotation(version=...); no
    # author is given to the library's FMUs
    from fmpy import read_model_description
    from fmu.frontend import package_version
    assert package_version("Judder.Examples.Driveline4DOF", [LIBRARY]) \
        == "0.1.0"
    for (name, version), path in fmus.items():
        description = read_model_description(str(path))
        assert description.version == "0.1.0", (name, version)
        assert description.author is None, (name, version)
