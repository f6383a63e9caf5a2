"""Floquet of a hybrid Modelica class in the mode of its operating point.

``MslDrivelines.ModeClutchDriveline`` (tests/msl_models) is the 4-DOF
driveline of Fig. 13 around ``FrictionModeClutch``: MSL's own
``Rotational.Interfaces.PartialFriction`` (Booleans ``free``,
``startForward``, ``startBackward``, ``locked``, the Integer ``mode``
with ``pre()`` and ``initial()``) with MSL Clutch's torque equations and
its ``mu_pos`` table interpolated in Modelica. The linearisation must
find it slipping forward, say so, and give the multipliers of an
independent model: the same driveline written here by hand (Coulomb
friction in forward sliding, ``numpy.interp`` of the table), linearised
by central differences and integrated by scipy.
"""

import os
import re
from pathlib import Path
import subprocess
import sys
import time

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from facts import names

ROOT = Path(__file__).resolve().parents[1]
MODELS = ROOT / "tests" / "msl_models"
MSL = next((folder for folder in [ROOT.parent / "shared" / "msl"] + [
    Path(p) for p in os.environ.get("MODELICAPATH", "").split(os.pathsep)
    if p] if (folder / "Modelica" / "package.mo").is_file()), None)
pytestmark = pytest.mark.skipif(
    MSL is None, reason="the Modelica Standard Library 4.x is not in "
    "../shared/msl nor on MODELICAPATH")
CLASS = "MslDrivelines.ModeClutchDriveline"
#: A falling friction characteristic in the segment of the slip (judder
#: prone: negative slip damping at the mean pressure).
FALLING = {"mu_pos[2,2]": 0.13, "mu_pos[3,2]": 0.03}


def _reference_rhs(values):
    """der([phi1, w1, phi2, w2, phi4, w4, phi3, w3]) of the driveline by
    hand: the clutch slipping forward (w4 > w3) transmits mu(w4 - w3)
    N_c R_m S p(t) from body 4 to body 3, p = p_m + p_f cos(2 pi f t)."""
    v = values
    table = np.array([[0, 0.09], [50, v["mu_pos[2,2]"]],
                      [150, v["mu_pos[3,2]"]], [300, 0.115]])
    factor = v["N_c"] * v["R_m"] * v["S"]
    slip0 = v["w_in"] - v["w_out"]
    torque = np.interp(slip0, table[:, 0], table[:, 1]) * factor * v["p_m"]
    engine = torque + (v["c1"] + v["c2"] + v["c4"]) * v["w_in"]
    load = torque - v["c3"] * v["w_out"]

    def rhs(t, x, p_f):
        phi1, w1, phi2, w2, phi4, w4, phi3, w3 = x
        t12 = v["k12"] * (phi1 - phi2) + v["c12"] * (w1 - w2)
        t24 = v["k24"] * (phi2 - phi4) + v["c24"] * (w2 - w4)
        p = v["p_m"] + p_f * np.cos(2 * np.pi * v["f_dither"] * t)
        clutch = np.interp(w4 - w3, table[:, 0], table[:, 1]) * factor * p
        return np.array([w1, (engine - t12 - v["c1"] * w1) / v["J1"], w2,
                         (t12 - t24 - v["c2"] * w2) / v["J2"], w4,
                         (t24 - clutch - v["c4"] * w4) / v["J4"], w3,
                         (clutch - load - v["c3"] * w3) / v["J3"]])
    return rhs, engine


def _reference_jacobians(values):
    """Jacobian A0 of the hand-written driveline and its p_f part B, by
    central differences at the start values (a steady slip)."""
    rhs, engine = _reference_rhs(values)
    v = values
    # spring deflections of a steady slip: each body's torques balance
    deflections = ((engine - v["c1"] * v["w_in"]) / v["k12"],
                   (engine - (v["c1"] + v["c2"]) * v["w_in"]) / v["k24"])
    x0 = np.array([0, v["w_in"], -deflections[0], v["w_in"],
                   -sum(deflections), v["w_in"], 0, v["w_out"]])
    assert np.abs(rhs(0.0, x0, 0.0)[1::2]).max() < 1e-9   # steady

    def jacobian(p_f_value):
        step = 1e-5 * np.maximum(np.abs(x0), 1.0)
        columns = [(rhs(0.0, x0 + step[k] * e, p_f_value)
                    - rhs(0.0, x0 - step[k] * e, p_f_value)) / (2 * step[k])
                   for k, e in enumerate(np.eye(len(x0)))]
        return np.array(columns).T
    A0 = jacobian(0.0)
    return A0, (jacobian(1e4) - A0) / 1e4


def _reference_multipliers(values, freq_hz, p_f):
    """Multipliers of the hand-written driveline: monodromy of (A0 + p_f
    cos B) (:func:`_reference_jacobians`) by scipy's DOP853."""
    A0, B = _reference_jacobians(values)
    omega = 2 * np.pi * freq_hz

    def flow(t, y):
        X = y.reshape(8, 8)
        return ((A0 + p_f * np.cos(omega * t) * B) @ X).ravel()
    end = solve_ivp(flow, (0, 1 / freq_hz), np.eye(8).ravel(),
                    method="DOP853", rtol=1e-12, atol=1e-14).y[:, -1]
    return np.linalg.eigvals(end.reshape(8, 8))


def _distance(a, b):
    """Largest distance between two sets of multipliers, each of ``a``
    paired with the nearest one of ``b`` not yet taken."""
    left, worst = list(b), 0.0
    for z in sorted(a, key=abs, reverse=True):
        k = int(np.argmin([abs(z - w) for w in left]))
        worst = max(worst, abs(z - left.pop(k)))
    return worst


@pytest.fixture
def msl_path(monkeypatch):
    monkeypatch.setenv("MODELICAPATH", str(MSL))


@pytest.mark.parametrize("changes, freq_hz, p_f, dither_effect", [
    ({}, 102.9, 0.3e5, 1e-6), (FALLING, 102.9, 0.3e5, 2e-5),
    (FALLING, 60.0, 0.8e5, 2e-5)])
def test_clutch_with_msl_modes_is_linearised_slipping_forward(
        msl_path, changes, freq_hz, p_f, dither_effect):
    """Mode Forward (startForward, startBackward, free, locked false);
    the 8 multipliers (the rigid-body ones at 1 included) equal the
    hand-written driveline's to 1e-6, where the dither moves them by
    more than ``dither_effect`` (the rising table's slope modulates
    little, the falling one's a lot)."""
    from sources.modelica import ModelicaParameters
    from stability.multipliers import floquet
    from stability.source import build_driveline
    params = ModelicaParameters(CLASS, str(MODELS)).replace(**changes)
    model = params.linear_model()
    assert dict(model.mode) == {
        "clutch.startForward": "false", "clutch.startBackward": "false",
        "clutch.free": "false", "clutch.locked": "false",
        "clutch.mode": "1 (clutch.Forward)"}
    values = {**params.values, "f_dither": freq_hz}
    got = floquet(build_driveline(params), freq_hz, p_f, form="full")
    want = _reference_multipliers(values, freq_hz, p_f)
    assert _distance(got.multipliers, want) < 1e-6
    assert _distance(want, _reference_multipliers(values, freq_hz, 0.0)) \
        > dither_effect


def test_a_point_whose_mode_changes_within_a_dither_period_is_refused(
        msl_path):
    """A dither deeper than the mean pressure frees the clutch (fn <= 0);
    a slip of 0.05 rad/s that a strong dither swings through zero leaves
    forward sliding: both refused, naming the variable, its file:line,
    the two values and the time."""
    from sources.modelica import ModelicaError, linearize
    with pytest.raises(ModelicaError) as freed:
        linearize(CLASS, str(MODELS), {"p_f": 1.2e6})
    names(freed.value, "clutch.free", "FrictionModeClutch.mo:23", "false",
          "true")
    assert 0 < _time_of(freed.value) < 1 / 100.0    # within the period
    with pytest.raises(ModelicaError) as stuck:
        linearize(CLASS, str(MODELS), {"mu_pos[2,1]": 0.01,
                                       "w_out": 104.66975511965977,
                                       "p_f": 3e5})
    names(stuck.value, "clutch.mode", "PartialFriction.mo:69",
          "1 (clutch.Forward)", "0 (clutch.Stuck)")
    # the dither's names are checked before the mode is looked for
    with pytest.raises(ModelicaError) as unknown:
        linearize(CLASS, str(MODELS), frequency="f")
    names(unknown.value, "frequency", "'f'", CLASS)


def _time_of(message):
    """The time a mode change is said to happen at, s."""
    return float(re.search(r"t = ([-+.\de]+) s", str(message)).group(1))


def test_check_and_floquet_say_the_mode_they_used(msl_path):
    """`judder check --modelica` names the mode in its text and JSON,
    `floquet` in its JSON; both refuse a setting that leaves it."""
    from studies.check import check
    from studies.floquet import floquet
    from sources.modelica import ModelicaError, ModelicaParameters
    command = [sys.executable, "-m", "judder", "check", "--modelica", CLASS,
               "--library", str(MODELS), "--freq", "102.9", "--pf", "0.3"]
    done = subprocess.run(command, capture_output=True, text=True, cwd=ROOT,
                          env={**os.environ, "MODELICAPATH": str(MSL)})
    assert done.returncode == 0, done.stderr
    names(done.stdout, "clutch.mode = 1 (clutch.Forward)",
          "clutch.startForward = false")
    params = ModelicaParameters(CLASS, str(MODELS))
    assert check([102.9], [0.3], params).as_dict()["mode"]["clutch.mode"] \
        == "1 (clutch.Forward)"
    assert floquet(102.9, 0.3, params).as_dict()["mode"]["clutch.free"] == \
        "false"
    # a setting whose dither frees the clutch is refused, not analysed
    for study in (lambda: check([102.9], [12.0], params),
                  lambda: floquet(102.9, 12.0, params)):
        with pytest.raises(ModelicaError) as refused:
            study()
        names(refused.value, "clutch.free", "false", "true")


def test_every_library_given_is_searched_in_order():
    """`--library` is repeatable as `python -m fmu`'s: the test models and
    the MSL given as two folders (no MODELICAPATH) find the class and the
    MSL classes it uses; a later folder is not dropped for the first (it
    was: the last --library alone was searched, the class not found).
    A folder that does not exist is named."""
    env = {k: v for k, v in os.environ.items() if k != "MODELICAPATH"}
    command = [sys.executable, "-m", "judder", "eig", "--modelica", CLASS,
               "--library", str(MODELS), "--library", str(MSL)]
    done = subprocess.run(command, capture_output=True, text=True, cwd=ROOT,
                          env=env)
    assert done.returncode == 0, done.stderr
    names(done.stdout, "clutch.mode = 1 (clutch.Forward)")
    missing = ROOT / "tests" / "no such library"
    done = subprocess.run(command[:-1] + [str(missing)], capture_output=True,
                          text=True, cwd=ROOT, env=env)
    assert done.returncode == 2
    names(done.stderr, "--library", str(missing), "folder", ".mo file")


def test_msl_friction_and_backlash_examples_are_refused_in_words(msl_path):
    """On the linearisation path MSL's CoupledClutches (its clutches'
    table objects now computed in Modelica) is refused before flattening
    for what it lacks, a dither, within seconds;
    Backlash's ElastoBacklash (initial(), relations inside relations)
    compiles and its contact relation, which changes within the period,
    is refused in words."""
    from infra.errors import JudderError
    from sources.modelica import ModelicaError, linearize
    started = time.monotonic()
    # its clutches' table objects are computed in Modelica now
    # (fmu.rewrite.inline_tables): what is left is that it has no dither
    with pytest.raises(JudderError, match=(
            r"CoupledClutches\.mo:2: `amplitude` 'p_f' is not declared")):
        linearize("Modelica.Mechanics.Rotational.Examples.CoupledClutches")
    assert time.monotonic() - started < 30
    with pytest.raises(ModelicaError) as relation:
        linearize("Modelica.Mechanics.Rotational.Examples.Backlash",
                  amplitude="elastoBacklash.c", frequency="inertia1.J")
    assert re.search(r"ElastoBacklash2?\.mo:\d+", str(relation.value))
    names(relation.value, "relation")
    assert _time_of(relation.value) >= 0


def test_a_step_is_held_in_the_mode(msl_path):
    """An MSL Blocks.Sources.Step on the engine torque (a relation of
    time, held) beside the clutch's modes: with the step at 10 s the
    class linearises in the same mode to ModeClutchDriveline's Jacobian;
    with the step within the dither period the relation is refused."""
    from sources.modelica import ModelicaError, linearize
    stepped = linearize("MslDrivelines.SteppedModeClutchDriveline",
                        str(MODELS))
    plain = linearize(CLASS, str(MODELS))
    assert stepped.mode == plain.mode
    assert np.array_equal(stepped.A0, plain.A0)
    assert np.array_equal(stepped.B, plain.B)
    with pytest.raises(ModelicaError) as step:
        linearize("MslDrivelines.SteppedModeClutchDriveline", str(MODELS),
                  {"t_step": 0.005})
    assert re.search(r"Sources\.mo:\d+", str(step.value))
    assert _time_of(step.value) == pytest.approx(0.005, abs=1e-3)


def test_studies_over_amplitudes_check_their_own_largest_amplitude(
        msl_path, judder_here):
    """`tongues` searched up to 12 bar (deeper than the mean pressure of
    10 bar) is refused where the dither frees the clutch, though the
    class's own p_f keeps it slipping; `map` says the amplitude it
    checked each frequency at, in text and JSON; `eig` says the mode."""
    import json
    from sources.modelica import ModelicaParameters
    own = ModelicaParameters(CLASS, str(MODELS))
    assert own["p_f"] < own["p_m"] < 12e5
    model = ("--modelica", CLASS, "--library", MODELS)
    status, _, err = judder_here("tongues", *model, "--freq", "100:110:3",
                                 "--pf-max", 12)
    assert status == 2
    names(err, "clutch.free", "FrictionModeClutch.mo:23", "false", "true")
    status, out, err = judder_here("map", *model, "--freq", "100:110:2",
                                   "--pf", "0.1:0.3:2")
    assert status == 0, err
    names(out, "clutch.mode = 1 (clutch.Forward)", "0.3 bar")
    status, out, err = judder_here("map", *model, "--freq", "100:110:2",
                                   "--pf", "0.1:0.3:2", "--json")
    assert json.loads(out)["mode_checked_at_p_f_bar"] == 0.3
    status, out, err = judder_here("eig", *model, "--json")
    assert json.loads(out)["mode"]["clutch.mode"] == "1 (clutch.Forward)"


def test_a_slip_that_grazes_zero_is_caught_between_samples(msl_path,
                                                           monkeypatch):
    """A slip of 0.05 rad/s that the dither swings through zero for a
    moment only (just above the amplitude where it first reaches zero,
    0.7257 bar) is refused at the relation's zero crossing, an event of
    the integrator; 64 samples of the period, without the events, miss
    it. 1 % below that amplitude the mode holds."""
    import casadi
    import sources.mode_check as mode_check
    import sources.modelica as modelica
    params = modelica.ModelicaParameters(CLASS, str(MODELS)).replace(**{
        "mu_pos[2,1]": 0.01, "w_out": 104.66975511965977})
    grazing = 0.72600e5
    params.check_mode(params["f_dither"], 0.99 * grazing)
    with pytest.raises(modelica.ModelicaError) as grazed:
        params.check_mode(params["f_dither"], grazing)
    names(grazed.value, "clutch.mode", "PartialFriction.mo:69",
          "1 (clutch.Forward)", "0 (clutch.Stuck)")
    assert _time_of(grazed.value) == pytest.approx(0.0085, abs=5e-4)

    def no_events(ode):
        return casadi.Function("none", [casadi.SX.sym("t"), casadi.SX.sym(
            "x", len(ode.states)), casadi.SX.sym("p", len(ode.parameters))],
            [casadi.SX(0, 1)])
    monkeypatch.setattr(mode_check, "mode_indicators", no_events)
    params.check_mode(params["f_dither"], grazing)


def test_a_mode_check_without_the_dither_parameter_is_refused_in_words(
        msl_path):
    """A library caller's dither frequency that the class does not have:
    the mode check names it and the parameters allowed (it ended in a
    KeyError of the parameter values)."""
    import sources.modelica as modelica
    params = modelica.ModelicaParameters(CLASS, str(MODELS),
                                         frequency="f_valve")
    with pytest.raises(modelica.ModelicaError) as unknown:
        params.check_mode(100.0, 0.3e5)
    names(unknown.value, "frequency", "'f_valve'", CLASS, "allowed",
          "f_dither")


def test_check_refuses_margins_searched_beyond_the_mode(msl_path,
                                                       judder_here):
    """`check` searches its margins up to `p_max_bar` on the linearisation
    in one mode: where the dither leaves that mode below it (the grazing
    slip leaves Forward from 0.7257 bar), the check is refused naming the
    amplitude and the way out, instead of vouching "stable up to 1.5
    bar"; below the grazing amplitude it answers."""
    from studies.check import check
    from infra.errors import JudderError
    from sources.modelica import ModelicaParameters
    params = ModelicaParameters(CLASS, str(MODELS)).replace(**{
        "mu_pos[2,1]": 0.01, "w_out": 104.66975511965977})
    f = params["f_dither"]
    with pytest.raises(JudderError) as beyond:
        check([f], [0.3], params)
    names(beyond.value, "1 (clutch.Forward)", "0 (clutch.Stuck)",
          f"{f:g} Hz", "150000 Pa", "`p_max_bar`", "1.5 bar", "allowed")
    assert check([f], [0.3], params, p_max_bar=0.7).as_dict()[
        "mode"]["clutch.mode"] == "1 (clutch.Forward)"
    status, _, err = judder_here(
        "check", "--modelica", CLASS, "--library", MODELS, "--set",
        "mu_pos[2,1]=0.01", "--set", "w_out=104.66975511965977", "--freq",
        f"{f:g}", "--pf", "0.3")
    assert status == 2
    names(err, "--pf-max", "allowed")


def test_report_of_a_class_without_tongues_says_so_and_names_its_mode(
        msl_path, judder_here, tmp_path):
    """`judder report` of ModeClutchDriveline (no tongue up to 1.5 bar):
    the mode it is linearised in, in the HTML and the JSON, as `map`
    words it; a sentence instead of an empty tip table, with the map's
    largest growth rate, that of the hand-written driveline without
    dither (the slowest decay of its Jacobian, the angles' zero
    eigenvalues left out); no ranking of 'tongue None' and no empty
    sensitivity figure; the map's panels say they are stable, without a
    colour bar over nothing, and the legends of the map and of the
    advised design's map list only what they draw."""
    import html
    import json
    from studies import _report_sections as sections
    from sources.modelica import ModelicaParameters
    drawn = []
    embed = sections._png

    def keep(fig, *args, **kwargs):
        drawn.append({
            "notes": [t.get_text() for ax in fig.axes for t in ax.texts],
            "axes": len(fig.axes),
            "legends": [[t.get_text() for t in ax.get_legend().get_texts()]
                        for ax in fig.axes if ax.get_legend()]})
        return embed(fig, *args, **kwargs)
    out = tmp_path / "report.html"
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(sections, "_png", keep)
        status, printed, err = judder_here(
            "report", "--modelica", CLASS, "--library", MODELS,
            "--grid=10:220:40", "--map-freq=5:250:30", "--map-pf=0:1.5:7",
            "--sensitivity", "c12", "--out", out, "--json")
    assert status == 0, err
    data = json.loads(printed)
    assert data["mode"]["clutch.mode"] == "1 (clutch.Forward)"
    assert data["mode_checked_at_p_f_bar"] == 1.5
    assert data["tongues"] == []
    page = html.unescape(out.read_text())
    assert "is linearised in the mode clutch.mode = 1 (clutch.Forward), " \
        "clutch.startForward = false" in page
    assert "held at each frequency's largest amplitude, 1.5 bar" in page
    A0, _ = _reference_jacobians(ModelicaParameters(CLASS, str(MODELS))
                                 .values)
    rates = np.linalg.eigvals(A0).real
    slowest = rates[np.abs(rates) > 1e-9].max()
    assert f"No tongue reaches 1.5 bar between 10 and 220 Hz: no stability " \
        f"boundary, so no tip to tabulate. The largest growth rate on the " \
        f"map is {slowest:.3g} 1/s (every point decays)." in page
    assert "<th>unstable from p_f [bar]</th>" not in page
    assert "None" not in page
    assert "c12 halved and doubled (Fig. 17, 18): no tongue of the " \
        "nominal driveline reaches 1.5 bar between 10 and 220 Hz, so there " \
        "is no tongue tip to rank. Nor does any tongue reach it" in page
    assert "No judder-relevant tongue is in the window" in page
    # the map and the advice figure; no sensitivity figure
    assert data["figures"][0].startswith("Stability map")
    assert not any(title.startswith("Sensitivity")
                   for title in data["figures"])
    assert drawn[0]["axes"] == 2                      # no colour bar
    assert drawn[0]["notes"] == [
        "stable at every point: every multiplier inside the unit circle\n"
        "(no tongue reaches 1.5 bar)", "no unstable point: the leading "
        f"multiplier's growth rate is\n{slowest:.3g} 1/s (decays)"]
    # the legends list only what is drawn: no slow growth, no judder
    # line, no boundaries of the given design
    assert drawn[0]["legends"] == [["stable"]]
    assert drawn[1]["legends"][-1] == ["stable", "operating range"]


def test_a_start_that_is_not_a_steady_slip_names_the_acceleration(
        msl_path):
    """w_in = 200 rad/s puts the slip in the table's third segment while
    the class's T_c extrapolates the second: body 4 starts with the
    acceleration (T_c - mu(200) N_c R_m S p_m) / J4, named as the
    derivative of its speed (it was 'd/dt der(inertia4.w)', the
    derivative of a derivative). A state whose derivative is no state (a
    speed without its angle) is named by how fast its derivative
    changes."""
    from sources.modelica import (ModelicaError, ModelicaParameters,
                                  check_no_acceleration, linearize)
    v = ModelicaParameters(CLASS, str(MODELS)).values
    slip = 200.0 - v["w_out"]
    T_c = (v["mu_pos[2,2]"] + (v["mu_pos[3,2]"] - v["mu_pos[2,2]"])
           * (slip - v["mu_pos[2,1]"]) / (v["mu_pos[3,1]"] - v["mu_pos[2,1]"])
           ) * v["N_c"] * v["R_m"] * v["S"] * v["p_m"]
    mu = np.interp(slip, [v[f"mu_pos[{k},1]"] for k in range(1, 5)],
                   [v[f"mu_pos[{k},2]"] for k in range(1, 5)])
    accel = (T_c - mu * v["N_c"] * v["R_m"] * v["S"] * v["p_m"]) / v["J4"]
    with pytest.raises(ModelicaError) as accelerating:
        linearize(CLASS, str(MODELS), {"w_in": 200.0})
    names(accelerating.value, "steady slip", "der(inertia4.w)",
          f"{accel:.3g}")
    # an oscillator [phi, w] started at phi = 0 with speed 2: der(w) is 0
    # at the start but changes at -k 2 = -8 per second
    A0 = np.array([[0.0, 1.0], [-4.0, -0.5]])
    with pytest.raises(ModelicaError) as changing:
        check_no_acceleration("m", ["phi", "w"], A0, np.array([2.0, 0.0]),
                              ModelicaError)
    names(changing.value, "der(w)", "-8")
    check_no_acceleration("m", ["phi", "w"], A0, np.zeros(2), ModelicaError)


def test_sensitivity_checks_the_mode_at_each_changed_set(msl_path):
    """The slip of 0.05 rad/s holds Forward up to 0.7 bar at f_dither
    (it grazes zero from 0.7257 bar), and so it does with J1 halved or
    doubled; with k24 halved the dither swings it through zero below 0.7
    bar. The sensitivity study is refused naming that change, where it
    checked the nominal set only and compared tongues the changed set
    does not have."""
    from studies.sensitivity import sensitivity
    from sources.modelica import ModelicaError, ModelicaParameters
    params = ModelicaParameters(CLASS, str(MODELS)).replace(**{
        "mu_pos[2,1]": 0.01, "w_out": 104.66975511965977})
    f = params["f_dither"]
    assert sensitivity(["J1"], [f], 0.7, parameters=params).cases == 3
    with pytest.raises(ModelicaError) as changed:
        sensitivity(["J1", "k24"], [f], 0.7, parameters=params)
    names(changed.value, f"k24 = {params['k24'] / 2:g}", CLASS,
          "clutch.mode", "PartialFriction.mo:69", "1 (clutch.Forward)",
          "0 (clutch.Stuck)", f"{f:g} Hz", "70000 Pa")


def test_a_changed_set_in_another_mode_is_refused():
    """A study's changed set linearised in another mode than the nominal
    one is refused naming the variable and both values (the mode is read
    from the linearisation; the checks of the dither pass here)."""
    from dataclasses import dataclass, replace
    from sources.dither_modes import check_modes_of_changes
    from sources.modelica import ModelicaError

    @dataclass(frozen=True)
    class Values:
        model = "Rig"
        mode: tuple = (("clutch.mode", "1 (clutch.Forward)"),
                       ("clutch.free", "false"))

        def check_mode(self, freq_hz, p_f):
            pass

        def replace(self, **change):
            return self if "J1" in change else replace(self, mode=(
                ("clutch.mode", "-1 (clutch.Backward)"),
                ("clutch.free", "false")))

        def linear_model(self):
            return self
    check_modes_of_changes(Values(), [{"J1": 2.0}], [100.0], 1.0)
    with pytest.raises(ModelicaError) as other:
        check_modes_of_changes(Values(), [{"J1": 2.0}, {"w_out": 300.0}],
                               [100.0], 1.0)
    names(other.value, "w_out = 300", "Rig", "clutch.mode",
          "-1 (clutch.Backward)", "1 (clutch.Forward)")


def test_envelope_of_a_class_with_modes_is_refused_saying_why(
        msl_path, judder_here, tmp_path):
    """The envelope would need the mode checked at each of its parameter
    sets and frequencies; it checked the nominal set only. Refused,
    naming the mode and what to use instead."""
    ranges = tmp_path / "ranges.toml"
    ranges.write_text("[parameters]\nJ4 = [0.1, 0.14]\n")
    status, _, err = judder_here(
        "envelope", "--modelica", CLASS, "--library", MODELS, "--ranges",
        ranges, "--freq", "95:110:4")
    assert status == 2
    names(err, CLASS, "clutch.mode = 1 (clutch.Forward)", "allowed",
          "judder sensitivity")


def test_report_says_why_its_sensitivity_is_missing(msl_path, judder_here,
                                                    tmp_path):
    """A report whose sensitivity study is refused (k24 halved leaves the
    slip's mode below 0.7 bar at 101.9 Hz) keeps its other sections and
    says in this one why it is missing, in the HTML and the JSON."""
    import html
    import json
    out = tmp_path / "report.html"
    status, printed, err = judder_here(
        "report", "--modelica", CLASS, "--library", MODELS, "--set",
        "mu_pos[2,1]=0.01", "--set", "w_out=104.66975511965977",
        "--grid=101.9:103.9:3", "--map-freq=101.9:103.9:3",
        "--map-pf=0:0.7:5", "--sensitivity", "J1,k24", "--out", out,
        "--json")
    assert status == 0, err
    data = json.loads(printed)
    assert "sensitivity_ranking" not in data
    assert data["sensitivity_error"].startswith(
        f"with k24 = 16442.5: {CLASS}: clutch.mode ")
    page = html.unescape(out.read_text())
    assert re.search(r"What moves the tongues: sensitivity</h2><p><b>Not "
                     r"computed</b>: with k24 = 16442\.5: .* changes from 1 "
                     r"\(clutch\.Forward\) to 0 \(clutch\.Stuck\) at t = ",
                     page)
    assert "The driveline and its parameters" in page


#: The slip of 0.05 rad/s that the dither swings through zero from
#: 0.7257 bar at f_dither (test_a_slip_that_grazes_zero_is_caught_...).
GRAZING = {"mu_pos[2,1]": 0.01, "w_out": 104.66975511965977}


def test_settings_checked_together_name_the_first_that_fails(msl_path):
    """Many dither settings checked in one call (integrated together, in
    batches of settings sorted by frequency) give the verdict of each
    checked alone: the first setting in the order given that leaves the
    mode is named, with the time it leaves it to 4 digits; settings that
    hold pass together as alone."""
    import sources.modelica as modelica
    params = modelica.ModelicaParameters(CLASS, str(MODELS)).replace(
        **GRAZING)
    freqs = np.linspace(150.0, 60.0, 40)   # not in the batches' order
    alone = []
    for f in freqs:
        try:
            modelica.check_mode(params.class_name, params.library,
                                params.values, "f_dither", "p_f", f, 0.7e5)
        except modelica.ModelicaError as error:
            alone.append(str(error))
    assert 0 < len(alone) < len(freqs)    # some hold, some leave the mode
    modelica._PASSED.clear()
    with pytest.raises(modelica.ModelicaError) as together:
        params.check_mode(freqs, np.full(len(freqs), 0.7e5))
    assert str(together.value) == alone[0]
    holding = [f for f in freqs if f"{f:g} Hz" not in " ".join(alone)]
    modelica._PASSED.clear()
    params.check_mode(holding, 0.7e5)


def test_simulate_and_crosscheck_check_the_mode_at_their_settings(
        msl_path):
    """`simulate` and `crosscheck` answer with the Floquet verdict of the
    linearisation in one mode at each setting they run: the grazing slip
    at 1 bar leaves Forward (its own p_f of 0.3 bar keeps it), and both
    are refused naming that setting, where simulate ended in the FMU's
    'fmi2DoStep failed' and crosscheck ran every point."""
    from studies.crosscheck import crosscheck
    from studies.simulate import simulate
    from sources.modelica import ModelicaError, ModelicaParameters
    params = ModelicaParameters("MslDrivelines.ModeClutchBench",
                                str(MODELS)).replace(**GRAZING)
    f = params["f_dither"]
    leaves = ("clutch.mode", "PartialFriction.mo:69", "1 (clutch.Forward)",
              "0 (clutch.Stuck)", f"{f:g} Hz", "100000 Pa")
    with pytest.raises(ModelicaError) as run:
        simulate(f, 1.0, parameters=params, duration=0.2)
    names(run.value, *leaves)
    with pytest.raises(ModelicaError) as crossed:
        crosscheck([f], [0.3, 1.0], parameters=params, duration=0.2,
                   workers=1)
    names(crossed.value, *leaves)


def test_fit_checks_the_mode_of_the_fitted_set_at_each_frequency(
        msl_path, monkeypatch):
    """The fitted set's boundaries are searched at each measured
    frequency up to twice `p_max_bar`: a fitted set whose slip the dither
    swings through zero below it is refused, naming the frequency and
    the amplitude (the fit itself is stood in for: the class has no
    tongue to fit)."""
    import stability.fit
    from studies.fit import fit
    from sources.modelica import ModelicaError, ModelicaParameters
    params = ModelicaParameters(CLASS, str(MODELS))
    fitted = params.replace(**GRAZING)

    class Fitted:
        params = fitted

    monkeypatch.setattr(stability.fit, "fit_boundary",
                        lambda *args, **kwargs: Fitted())
    f = params["f_dither"]
    with pytest.raises(ModelicaError) as fitted_set:
        fit([f, 110.0, 120.0], [0.2, 0.25, 0.3], p_max_bar=0.4,
            parameters=params)
    names(fitted_set.value, "1 (clutch.Forward)", "0 (clutch.Stuck)",
          f"{f:g} Hz", "80000 Pa")
    fit([f, 110.0, 120.0], [0.2, 0.25, 0.3], p_max_bar=0.3,
        parameters=params)


def test_an_operating_point_on_a_switching_surface_is_refused(msl_path):
    """A relay `past = phi > phi_switch` started at rest exactly on
    phi_switch: the mode (past false, stiffness k) held over the period,
    and the linearisation answered on one side of the relay; it is
    refused naming the relation, its file:line and its sides' value. Off
    the surface the relay's side is linearised (stiffness 2k). So for
    the relay written in the torque equation, a relation held between
    events (RelayTorque). The MSL
    clutch started without slip is named at the relation of its slip,
    where it was refused as a mode change at t = 1e-11 s."""
    from sources.modelica import ModelicaError, ModelicaParameters, linearize
    relay = "MslDrivelines.RelaySurface"
    with pytest.raises(ModelicaError) as surface:
        linearize(relay, str(MODELS))
    names(surface.value, "switching surface", "(0<(phi-phi_switch))", "past",
          "RelaySurface.mo:16", "true", "false")
    past = linearize(relay, str(MODELS), {"phi_switch": -0.1})
    assert dict(past.mode) == {"past": "true"}
    assert past.A0[1, 0] == -2 * 1000 / 0.1
    # the relay written in the torque (a relation held between events)
    with pytest.raises(ModelicaError) as torque:
        linearize("MslDrivelines.RelayTorque", str(MODELS))
    names(torque.value, "switching surface", "RelayTorque.mo:16",
          "(0<(phi-phi_switch))")
    held = linearize("MslDrivelines.RelayTorque", str(MODELS),
                     {"phi_switch": -0.1})
    assert held.A0[1, 0] == -2 * 1000 / 0.1
    w_in = ModelicaParameters(CLASS, str(MODELS))["w_in"]
    with pytest.raises(ModelicaError) as no_slip:
        linearize(CLASS, str(MODELS), {"w_out": w_in})
    names(no_slip.value, "(0<(inertia4.w-inertia3.w))", "clutch.mode",
          "PartialFriction.mo:69", "1 (clutch.Forward)", "0 (clutch.Stuck)")


def test_advise_checks_the_mode_where_it_decides_its_windows(msl_path):
    """`advise` decides its safe windows on a frequency grid up to the
    amplitude it searches (1.6 bar here): the grazing slip leaves Forward
    there and the advice is refused, naming the first setting (it
    answered from the Forward linearisation, checked at the class's own
    p_f and f_dither only). The nominal class holds there."""
    from studies.advise import advise
    from sources.modelica import ModelicaError, ModelicaParameters
    params = ModelicaParameters(CLASS, str(MODELS))
    with pytest.raises(ModelicaError) as windows:
        advise(params.replace(**GRAZING), design=False)
    names(windows.value, "1 (clutch.Forward)", "0 (clutch.Stuck)",
          "55 Hz", "160000 Pa")
    assert advise(params, design=False).sets == 1
