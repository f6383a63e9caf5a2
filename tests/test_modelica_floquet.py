"""The Floquet layer on systems compiled from Modelica (sources.modelica).

Independent checks: the hand-written Eq. (2)-(9) (stability.model) for
the paper's drivelines, and equations of motion written here by hand for
the geared 5-DOF and the two-clutch examples, integrated with solve_ivp.
"""

import numpy as np
import pytest
from numpy.testing import assert_allclose
from scipy.integrate import solve_ivp

from sources import get_preset
from sources.modelica import ModelicaError, linearize
from infra.errors import ParameterError
from stability import (LinearDriveline, build_driveline, classify,
                       stability_map)
from stability.hill import modal_transfer, real_boundaries
from stability.monodromy import DysonPropagator, monodromy_solve_ivp
from stability.tongues import find_tongues, tongue_boundaries

BAR = 1e5


def _permutation(linear, instances):
    """Rows of Eq. (6)'s ``[theta, theta_dot]`` in the compiler's states."""
    names = list(linear.state_names)
    return ([names.index(f"{i}.phi") for i in instances]
            + [names.index(f"{i}.w") for i in instances])


@pytest.fixture(scope="module")
def four():
    return linearize("Judder.Examples.Driveline4DOF")


@pytest.fixture(scope="module")
def geared():
    return linearize("Judder.Examples.Driveline5DOFGeared")


@pytest.mark.parametrize("preset", ["paper-4dof", "paper-4dof-fitted",
                                    "paper-3dof"])
def test_jacobian_is_eq6_to_round_off(preset):
    params = get_preset(preset)
    model = params.driveline
    linear = linearize(model.modelica_class, values=dict(params.values))
    rows = _permutation(linear, [b.instance for b in model.bodies])
    hand = build_driveline(params)
    for t, freq, p_f in [(0.0, 102.9, 0.3 * BAR), (1.3e-3, 60.0, 1.2 * BAR),
                         (0.02, 18.0, 0.0)]:
        extracted = (linear.A0 + p_f * np.cos(2 * np.pi * freq * t)
                     * linear.B)[np.ix_(rows, rows)]
        eq6 = hand.state_matrix(t, freq, p_f)
        assert_allclose(extracted, eq6, rtol=1e-13, atol=1e-12)
    # two rigid-body angles found from the matrices, one modulated channel
    reduction = LinearDriveline.from_model(linear).reduction
    assert reduction.rigid.shape[1] == 2 and reduction.rank == 1
    assert_allclose(np.sqrt(np.sort(linear.omega2)[-len(model.couplings):]),
                    2 * np.pi * np.array(
                        [f for f in _hand_frequencies(hand)]), rtol=1e-12)


def _hand_frequencies(hand):
    from stability import natural_frequencies
    return natural_frequencies(hand)


def test_map_and_tongues_equal_the_hand_written_model(four, paper4):
    extracted = LinearDriveline.from_model(four)
    freq = np.array([18.94, 37.9, 60.0, 83.94, 102.9, 121.8, 205.8])
    p_f = np.linspace(0.0, 1.5 * BAR, 7)
    ours, theirs = (stability_map(d, freq, p_f) for d in (extracted, paper4))
    assert_allclose(ours.leading, theirs.leading, rtol=1e-10, atol=1e-12)
    assert np.array_equal(ours.kind, theirs.kind)
    assert set(ours.counts()) == set(theirs.counts())
    assert_allclose(ours.natural_frequencies_hz,
                    theirs.natural_frequencies_hz, rtol=1e-12)
    grid = np.arange(10.0, 222.0, 5.0)     # coarse: the tips are refined
    tips = [[(t.number, t.kind, t.tip_freq_hz, t.tip_p_f)
             for t in find_tongues(d, tongue_boundaries(d, grid, 1.5 * BAR))]
            for d in (extracted, paper4)]
    assert [t[:2] for t in tips[0]] == [t[:2] for t in tips[1]]
    assert len(tips[0]) == 6      # the six tongues of Fig. 14
    assert_allclose([t[2:] for t in tips[0]], [t[2:] for t in tips[1]],
                    rtol=1e-9)


def _geared_by_hand(v):
    r"""Eq. (6) of the geared 5-DOF example, written from its diagram.

    State ``[q12, q24, q35, w1, w2, w4, w3, w5]`` with the spring
    deflections ``q12 = th1 - th2``, ``q24 = th2 - th4``, ``q35 = th3/r -
    th5`` (the gear turns the output shaft at ``th3/r``). The clutch's
    slip damping is ``N_c R_m S mu'(w_slip) p_f cos(w t)`` with the slope of
    its friction curve; the mean pressure does not enter (default
    ``mean_pressure_damping = 0``).
    """
    J = np.array([v["J1"], v["J2"], v["J4"], v["J3"], v["J5"]])
    r = v["ratio"]
    slope = (v["mu_max"] - v["mu0"]) / v["w_char"] \
        * (1 - np.tanh(v["w_slip"] / v["w_char"]) ** 2)
    gain = v["N_c"] * v["R_m"] * v["S"] * slope
    # deflection rates: rows of E with q = E th (th = [th1, th2, th4, th3, th5])
    E = np.array([[1, -1, 0, 0, 0], [0, 1, -1, 0, 0], [0, 0, 0, 1 / r, -1]])
    k = np.array([v["k12"], v["k24"], v["k35"]])
    c = np.array([v["c12"], v["c24"], v["c35"]])
    ground = np.diag([v["c1"], v["c2"], v["c4"], v["c3"], v["c5"]])
    C0 = E.T @ np.diag(c) @ E + ground
    e = np.array([0, 0, 1, -1, 0.0])                      # slip = w4 - w3
    A0 = np.block([[np.zeros((3, 3)), E],
                   [-(E.T * k) / J[:, None], -C0 / J[:, None]]])
    B = np.zeros((8, 8))
    B[3:, 3:] = -gain * np.outer(e, e) / J[:, None]
    return A0, B


def _multipliers_by_hand(A0, B, freq, p_f):
    omega = 2 * np.pi * freq

    def rhs(t, y):
        return ((A0 + p_f * np.cos(omega * t) * B) @ y.reshape(8, 8)).ravel()
    sol = solve_ivp(rhs, (0.0, 1.0 / freq), np.eye(8).ravel(),
                    method="DOP853", rtol=1e-13, atol=1e-13)
    return np.linalg.eigvals(sol.y[:, -1].reshape(8, 8))


@pytest.mark.parametrize("freq, p_f, kind", [
    (18.94, 0.2 * BAR, 1),     # single-period at f2
    (37.88, 0.3 * BAR, 2),     # double-period at 2 f2
    (83.94, 0.3 * BAR, 3),     # combination f3 - f2
    (102.88, 0.1 * BAR, 1),    # single-period at f3
    (11.7, 0.4 * BAR, 3),      # combination f2 - f1 (output shaft mode)
    (60.0, 0.3 * BAR, 0)])
def test_geared_5dof_agrees_with_its_equations_by_hand(geared, freq, p_f,
                                                       kind):
    # acceptance of issue 12: multiplier error below 1e-8, kinds identical
    A0, B = _geared_by_hand(geared.values)
    hand = _multipliers_by_hand(A0, B, freq, p_f)
    extracted = LinearDriveline.from_model(geared)
    ours = np.linalg.eigvals(DysonPropagator(
        extracted.periodic_system(), freq, p_f).monodromy([p_f])[0])
    assert len(ours) == len(hand) == 8
    distance = np.abs(ours[:, None] - hand[None, :])
    assert distance.min(axis=1).max() < 1e-8
    assert distance.min(axis=0).max() < 1e-8
    lead = stability_map(extracted, [freq], [p_f]).leading[0, 0]
    assert int(classify(lead)) == int(classify(hand[np.argmax(np.abs(hand))]))
    assert int(classify(lead)) == kind


def test_slip_speed_is_a_map_parameter(geared):
    # the friction curve's slope at the operating slip is the paper's
    # mu_g, and the boundary amplitudes scale as 1/mu_g: w_slip set so
    # that the slope is 0.02 s/rad needs half the dither of the slope 0.01
    def tip(w_slip):
        linear = linearize("Judder.Examples.Driveline5DOFGeared",
                           values={"w_slip": w_slip})
        system = LinearDriveline.from_model(linear).periodic_system()
        return real_boundaries(modal_transfer(system), [102.88])[0, 0]
    v = geared.values
    top = (v["mu_max"] - v["mu0"]) / v["w_char"]

    def slip_for(slope):
        return v["w_char"] * np.arctanh(np.sqrt(1 - slope / top))
    assert tip(slip_for(0.01)) == pytest.approx(2 * tip(slip_for(0.02)),
                                                rel=1e-9)
    assert tip(2.0) < tip(3.0)     # a faster slip: a flatter curve


def test_two_clutches_give_a_rank_two_modulation():
    linear = linearize("Judder.Examples.Driveline4DOFTwoClutches")
    assert LinearDriveline.from_model(linear).reduction.rank == 2
    v = linear.values
    # by hand: Eq. (6) of the 4-DOF model plus the REV clutch's modulated
    # slip damping on body 3 (it slips against the housing)
    params = get_preset("paper-4dof")
    hand = build_driveline(params)
    rows = _permutation(linear, [b.instance for b in params.driveline.bodies])
    freq, p_f, t = 102.9, 0.4 * BAR, 1.7e-3
    eq6 = hand.state_matrix(t, freq, p_f)
    rev = (v["dither_share_rev"] * p_f * np.cos(2 * np.pi * freq * t)
           * v["mu_g_rev"] * params.clutch_factor / params["J3"])
    eq6[7, 7] -= rev
    assert_allclose((linear.A0 + p_f * np.cos(2 * np.pi * freq * t)
                     * linear.B)[np.ix_(rows, rows)], eq6, rtol=1e-13,
                    atol=1e-12)
    # the rank-2 engines: Dyson against solve_ivp, Hill against the
    # monodromy (a multiplier at +1 at Hill's boundary amplitude)
    system = LinearDriveline.from_model(linear).periodic_system()
    dyson = DysonPropagator(system, freq, 1.5 * BAR).monodromy([p_f, BAR])
    direct = monodromy_solve_ivp(system, freq, [p_f, BAR], rtol=1e-12,
                                 atol=1e-14)
    assert_allclose(dyson, direct, atol=1e-9)
    boundary = real_boundaries(modal_transfer(system), [freq])[0, 0]
    lam = np.linalg.eigvals(monodromy_solve_ivp(system, freq, [boundary],
                                                rtol=1e-12, atol=1e-14)[0])
    assert np.abs(lam - 1).min() < 1e-7


def _user_model(tmp_path, body):
    package = tmp_path / "MyLib"
    package.mkdir()
    (package / "package.mo").write_text(
        'package MyLib "A user library"\nend MyLib;\n')
    (package / "package.order").write_text("Oscillator\n")
    (package / "Oscillator.mo").write_text(f"""within MyLib;
model Oscillator "One body on a spring, damping modulated by a dither"
  parameter Real p_f(min=0)=1 "Dither amplitude";
  parameter Real f_dither(min=0)=10 "Dither frequency";
  parameter Real k(min=0)=100 "Stiffness per unit mass";
  parameter Real f_n(min=0)=sqrt(k)/(2*3.141592653589793) "Natural frequency";
  Real x(start=1, fixed=true) "Position";
  Real v(start=0, fixed=true) "Speed";
equation
  der(x) = v;
  der(v) = -k*x - {body}*v;
end Oscillator;
""")
    return str(tmp_path)


@pytest.mark.parametrize("body, message", [
    ("(1 + p_f^2*cos(2*3.141592653589793*f_dither*time))", "not affine"),
    ("(1 + p_f*sin(2*3.141592653589793*f_dither*time))", "does not enter"),
    ("(1 + p_f*cos(2*3.141592653589793*f_dither*time) + 0.1*time)",
     "changes with time")])
def test_a_model_outside_the_form_is_refused(tmp_path, body, message):
    library = _user_model(tmp_path, body)
    with pytest.raises(ModelicaError, match=message):
        linearize("MyLib.Oscillator", library=library)


def test_user_library_and_bad_names(tmp_path):
    library = _user_model(
        tmp_path, "(1 + p_f*cos(2*3.141592653589793*f_dither*time))")
    linear = linearize("MyLib.Oscillator", library=library,
                       values={"p_f": 0.5})
    # Mathieu-like oscillator: A0 = [[0, 1], [-100, -1]], B = -e2 e2^T
    assert_allclose(linear.A0, [[0, 1], [-100, -1]])
    assert_allclose(linear.B, [[0, 0], [0, -1]])
    assert LinearDriveline.from_model(linear).reduction.rigid.shape[1] == 0
    with pytest.raises(ParameterError, match="not a tunable parameter"):
        linearize("MyLib.Oscillator", library=library, values={"J9": 1.0})
    with pytest.raises(ParameterError, match=">= 0"):
        linearize("MyLib.Oscillator", library=library, values={"p_f": -1.0})
    with pytest.raises(ModelicaError, match="not found"):
        linearize("MyLib.Nothing", library=library)


def test_a_library_of_one_file(tmp_path):
    # --library MyLib.mo, one file holding the whole package, as python
    # -m fmu takes it: it was refused ("is not a folder")
    folder = _user_model(
        tmp_path, "(1 + p_f*cos(2*3.141592653589793*f_dither*time))")
    package = tmp_path / "MyLib"
    single = tmp_path / "MyLib.mo"
    single.write_text(
        'package MyLib "A user library"\n'
        + (package / "Oscillator.mo").read_text().replace(
            "within MyLib;\n", "") + "end MyLib;\n")
    linear = linearize("MyLib.Oscillator", library=str(single),
                       values={"p_f": 0.5})
    assert_allclose(linear.A0, [[0, 1], [-100, -1]])
    assert_allclose(linear.B, [[0, 0], [0, -1]])
    with pytest.raises(ModelicaError, match=r"`library` '.*MyLib/package"
                       r"\.order' is neither a folder nor a \.mo file"):
        linearize("MyLib.Oscillator",
                  library=(folder, str(package / "package.order")))


def _cli(*args):
    import subprocess
    import sys
    return subprocess.run([sys.executable, "-m", "judder", *args],
                          capture_output=True, text=True, timeout=120)


def test_cli_modelica_keeps_the_json_fields():
    import json
    ours = _cli("floquet", "--freq", "102.9", "--pf", "0.3", "--modelica",
                "Judder.Examples.Driveline4DOF", "--set", "c12=10", "--json")
    theirs = _cli("floquet", "--freq", "102.9", "--pf", "0.3", "--set",
                  "c12=10", "--driveline", "chain", "--json")
    assert ours.returncode == theirs.returncode == 0, ours.stderr
    ours, theirs = json.loads(ours.stdout), json.loads(theirs.stdout)
    assert set(ours) == set(theirs)
    assert ours["model"] == "Judder.Examples.Driveline4DOF"
    assert ours["driveline"] == theirs["driveline"] == "chain"
    assert ours["kind"] == theirs["kind"]
    assert ours["leading_abs"] == pytest.approx(theirs["leading_abs"],
                                                rel=1e-12)


@pytest.mark.parametrize("args, message", [
    (["--modelica", "Judder.Examples.Driveline4DOF", "--set", "k99=1"],
     "'k99' is not a tunable parameter"),
    (["--modelica", "Judder.Examples.Driveline4DOF", "--preset",
      "paper-4dof"], "replaces --preset"),
    # given without a class, they were ignored and the preset's map drawn
    (["--library", "examples/modelica"], "--library is for a --modelica "
     "class; allowed: no --library with a preset"),
    (["--dither-frequency", "f"], "--dither-frequency is for a --modelica "
     "class or an --fmu")])
def test_cli_modelica_refuses_in_one_line(args, message):
    proc = _cli("floquet", "--freq", "100", "--pf", "0.1", *args)
    assert proc.returncode == 2
    assert message in proc.stderr and "Traceback" not in proc.stderr


def test_cli_fit_recovers_the_slip_speed_of_a_modelica_class(tmp_path,
                                                             geared):
    # a boundary of the geared 5-DOF class at w_slip = 2.6 rad/s; the fit
    # from the class's default 2 rad/s finds it again
    from sources.modelica import ModelicaParameters
    import json
    truth = ModelicaParameters("Judder.Examples.Driveline5DOFGeared",
                               values={"w_slip": 2.6})
    freq = np.linspace(96.0, 110.0, 8)
    measured = tongue_boundaries(build_driveline(truth), freq,
                                 1.5 * BAR).stability_boundary / BAR
    path = tmp_path / "boundary.csv"
    path.write_text("freq_hz,p_f_bar\n" + "".join(
        f"{float(f)!r},{float(p)!r}\n" for f, p in zip(freq, measured)))
    proc = _cli("fit", "--modelica", "Judder.Examples.Driveline5DOFGeared",
                "--boundary", str(path), "--fit", "w_slip", "--starts", "1",
                "--workers", "1", "--min-growth", "0", "--json")
    assert proc.returncode == 0, proc.stderr
    data = json.loads(proc.stdout)
    assert data["model"] == "Judder.Examples.Driveline5DOFGeared"
    assert data["fitted"]["w_slip"]["start"] == 2.0
    assert data["fitted"]["w_slip"]["value"] == pytest.approx(2.6, rel=1e-6)


def test_cli_params_file_round_trip(tmp_path):
    import json
    path = tmp_path / "geared.toml"
    saved = _cli("params", "--modelica", "Judder.Examples.Driveline5DOFGeared",
                 "--set", "w_slip=3", "--save", str(path))
    assert saved.returncode == 0, saved.stderr
    # dotted names (housing.phi0) come back as they were written
    proc = _cli("floquet", "--modelica", "Judder.Examples.Driveline5DOFGeared",
                "--param-file", str(path), "--freq", "102.88", "--pf", "0.1",
                "--json")
    assert proc.returncode == 0, proc.stderr
    linear = linearize("Judder.Examples.Driveline5DOFGeared",
                       values={"w_slip": 3.0})
    lam = np.linalg.eigvals(DysonPropagator(
        LinearDriveline.from_model(linear).periodic_system(), 102.88,
        0.1 * BAR).monodromy([0.1 * BAR])[0])
    assert json.loads(proc.stdout)["leading_abs"] == pytest.approx(
        np.abs(lam).max(), rel=1e-12)


def test_crosscheck_fmu_of_the_rank_two_class_against_its_floquet_rates():
    # the two views of one Modelica class: its FMU's free response (two
    # runs, w_in 1 rad/s apart) grows at the Floquet exponent of the
    # system linearised from the same class
    from sources.modelica import ModelicaParameters
    from studies.crosscheck import crosscheck_study
    params = ModelicaParameters("Judder.Examples.Driveline4DOFTwoClutches")
    check = crosscheck_study(params, [105.0], [0.1 * BAR, 0.5 * BAR],
                             workers=1)
    assert [p.floquet_kind for p in check.points] == ["stable",
                                                      "single-period"]
    assert all(p.agree for p in check.points)
    for point in check.points:
        assert point.fitted_rate == pytest.approx(point.floquet_rate,
                                                  rel=1e-3)


def test_one_map_linearises_the_class_once(monkeypatch, capsys):
    # issue 22: the memory check, the two estimates and the map each built
    # the driveline of the same class and values, 4 linearisations for one
    # 3x3 map; now one (w_slip set to a value no other test uses, so no
    # earlier linearisation is reused)
    import json
    import sources.modelica
    from judder.cli import main
    calls = []
    linearize_once = sources.modelica.linearize

    def counted(*args, **kwargs):
        calls.append(args[0])
        return linearize_once(*args, **kwargs)
    monkeypatch.setattr(sources.modelica, "linearize", counted)
    status = main(["map", "--modelica", "Judder.Examples.Driveline5DOFGeared",
                   "--set", "w_slip=3.0625", "--freq", "10:200:3",
                   "--pf", "0:1:3", "--json"])
    assert status == 0
    assert json.loads(capsys.readouterr().out)["max_leading_abs"] > 1
    assert calls == ["Judder.Examples.Driveline5DOFGeared"]
