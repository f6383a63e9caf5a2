"""The periodic orbit of the dithered engagement (stability.orbit):
against the closed-form forced response and the Floquet layer where the
orbit is small, and against long engagements of the bench FMU (an
independent integration of the same equations, compiled from Modelica)
where it is not."""

from dataclasses import replace

import numpy as np
import pytest
from numpy.testing import assert_allclose

from sources import get_preset
from infra.units import PA_PER_BAR, RPM_PER_RAD_S
from stability import floquet
from stability.friction import forced_slip_amplitude
from stability.orbit import (continue_orbit, double_period_orbit,
                             periodic_orbit)
from stability.orbit_chart import orbit_chart

BAR = PA_PER_BAR


@pytest.fixture(scope="module")
def bench():
    """The bench engagement of the Appendix set and its linearisation."""
    pytest.importorskip("fmpy")
    from stability.bench import engagement_model
    return engagement_model(get_preset("paper-4dof"))


@pytest.mark.parametrize("freq_hz, p_f_bar", [(60.0, 0.01), (103.0, 0.001),
                                              (206.0, 0.3), (86.0, 0.25)])
def test_small_orbit_is_the_linear_forced_response_and_floquet(
        bench, freq_hz, p_f_bar):
    # where the slip stays on the curve's straight part, the orbit's slip
    # swing is the forced response of Eq. 6 driven by column D of Eq. 9,
    # and its multipliers are the stability layer's (Eq. 10-13)
    model, linear = bench
    orbit = periodic_orbit(model, freq_hz, p_f_bar * BAR)
    assert orbit.success
    assert abs(orbit.slip_harmonics[0]) == pytest.approx(
        forced_slip_amplitude(linear, freq_hz, p_f_bar * BAR), rel=2e-3)
    point = floquet(linear, freq_hz, p_f_bar * BAR)
    assert orbit.kind == point.kind
    assert orbit.growth_rate == pytest.approx(point.growth_rate, abs=2e-2,
                                              rel=1e-2)


def test_orbit_of_tongue_2_is_forced_and_proportional_to_the_dither(bench):
    # at f2 the dither drives mode 2: the T-orbit grows in proportion to
    # p_f from zero (no threshold) and stays stable: forced judder
    model, _ = bench
    branch = continue_orbit(model, 103.0, np.array([0.0, 0.1, 0.2, 0.4])
                            * BAR)
    rpm = np.array([o.dither_amplitude for o in branch.orbits[1:]]) \
        * RPM_PER_RAD_S
    assert branch.complete and not branch.folds
    assert_allclose(rpm / rpm[0], [1, 2, 4], rtol=0.05)
    assert all(o.stable for o in branch.orbits[1:])


def test_period_doubling_gives_a_stable_2t_orbit(bench):
    # tongue 4 (2 f2): the T-orbit loses stability through -1 and a 2T
    # orbit at f/2 takes over, stable, its amplitude growing from the
    # tongue's edge
    model, _ = bench
    t_orbit = periodic_orbit(model, 206.0, 0.5 * BAR)
    assert t_orbit.kind == "double-period" and t_orbit.growth_rate > 1
    doubled = double_period_orbit(model, t_orbit)
    assert doubled is not None and doubled.stable
    assert doubled.subharmonic_share > 0.99
    weaker = double_period_orbit(model, periodic_orbit(model, 206.0,
                                                       0.3 * BAR))
    assert abs(weaker.upstream_harmonics[0]) < abs(
        doubled.upstream_harmonics[0])


#: Settings across tongues 1-4 and stable points, and the component of
#: the upstream speed compared: 'f' (T-orbit) or 'half' (2T orbit).
LONG_RUNS = [(103.0, 0.1, "f"), (103.0, 0.3, "f"), (100.0, 0.3, "f"),
             (106.0, 0.2, "f"), (60.0, 0.5, "f"), (21.0, 0.5, "f"),
             (19.0, 0.3, "f"), (150.0, 0.5, "f"), (206.0, 0.3, "half"),
             (206.0, 0.5, "half"),
             # the bench's own f1 (16.5 Hz) and tongue 3, where the
             # motor reaches its torque limit (680 N m)
             (16.5, 0.3, "f"), (16.5, 0.7, "f"), (33.0, 0.75, "half"),
             (34.0, 0.8, "half")]


@pytest.mark.parametrize("freq_hz, p_f_bar, component", LONG_RUNS)
def test_orbit_is_the_long_engagement_steady_state(bench, freq_hz, p_f_bar,
                                                   component):
    # the bench FMU run for 8 s; over its last 1.5 s the upstream speed's
    # Fourier amplitude at f (or f/2) against the orbit's at the run's
    # mean slip (the dither's rectified torque moves it at 103 Hz)
    from studies.bench import bench_fmu
    from pysim.simulation.runs import run_fmu
    model, _ = bench
    params = get_preset("paper-4dof")
    run = run_fmu(bench_fmu(params)[1], freq_hz, p_f_bar * BAR,
                  params=params, duration=8.0,
                  output_interval=min(1e-3, 1 / (20 * freq_hz)))
    late = run.time >= run.time[-1] - 1.5
    t, speed = run.time[late], run["w_upstream"][late]
    at = freq_hz if component == "f" else freq_hz / 2
    window = np.hanning(len(t))
    measured = 2 * abs(np.sum(window * (speed - speed.mean())
                              * np.exp(-2j * np.pi * at * t))) / window.sum()
    orbit = periodic_orbit(replace(model, slip=float(
        run["slip"][late].mean())), freq_hz, p_f_bar * BAR)
    if component == "half":
        orbit = double_period_orbit(model, orbit)
        predicted = abs(orbit.upstream_harmonics[0])
    else:
        predicted = orbit.dither_amplitude
    assert orbit.stable         # the engagement settles on it
    assert predicted == pytest.approx(measured, rel=0.05)


def test_predicted_chart_has_tongue_2_forced_and_tongues_5_6_parametric(
        bench):
    model, _ = bench
    chart = orbit_chart(model, np.arange(80.0, 125.0, 1.0),
                        np.array([0.1, 0.3, 0.5]) * BAR,
                        limit=30 / RPM_PER_RAD_S, min_growth=1.0)
    mechanism = dict(zip(chart.freq_hz, chart.mechanism[:, -1]))
    assert mechanism[103.0] == 1                      # forced
    assert mechanism[86.0] == 2 and mechanism[119.0] == 2  # parametric
    assert mechanism[95.0] == 0 and mechanism[112.0] == 0
    onsets = chart.onsets() / BAR
    assert onsets[chart.freq_hz == 103.0][0] == pytest.approx(0.1)


def test_orbit_command_gives_the_chart_and_a_branch(tmp_path):
    # the command line: a small predicted chart as JSON and NPZ, and one
    # frequency continued in p_f as CSV; a bad value is one clear line
    import json
    import subprocess
    import sys
    pytest.importorskip("fmpy")
    out = tmp_path / "chart.npz"
    proc = subprocess.run(
        [sys.executable, "-m", "judder", "orbit", "--freq", "100:106:4",
         "--pf", "0.1:0.3:3", "--out", str(out), "--json"],
        capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    data = json.loads(proc.stdout)
    assert data["mode"] == "chart" and data["counts"]["forced"] >= 1
    with np.load(out) as npz:
        assert npz["settled_rpm"].shape == (4, 3)
        assert npz["judder"].sum() == sum(
            v for k, v in data["counts"].items() if k != "none")
    branch = tmp_path / "branch.csv"
    proc = subprocess.run(
        [sys.executable, "-m", "judder", "orbit", "--freq", "206", "--pf",
         "0.1,0.3,0.5", "--out", str(branch), "--json"],
        capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    rows = json.loads(proc.stdout)["orbits"]
    assert [r["mechanism"] for r in rows] == [None, "parametric",
                                              "parametric"]
    assert rows[2]["double_period"]["stable"]
    assert branch.read_text().splitlines()[0].startswith("freq_hz,p_f_bar")
    proc = subprocess.run(
        [sys.executable, "-m", "judder", "orbit", "--freq", "103", "--pf",
         "0.3", "--limit", "-5"], capture_output=True, text=True,
        timeout=300)
    assert proc.returncode == 2
    assert "--limit" in proc.stderr and "Traceback" not in proc.stderr


def test_a_drive_that_never_reaches_its_limit_leaves_the_orbit(bench):
    # the balance with the drive's channel (its torque limit far away,
    # 1e9 N m) is the slip-only balance but for the mean of the driven
    # bodies, which the torque the dither rectifies shifts by -drift / D
    # (closed form of the mean balance without the limit; 0.002 rad/s at
    # 103 Hz, 0.3 bar): the orbit moves by that little
    from dataclasses import replace as changed
    model, _ = bench
    free = changed(model, drive_limit=np.inf)
    far = changed(model, drive_limit=1e9)
    assert not free.limited_drive and far.limited_drive
    for freq_hz, p_f_bar in ((103.0, 0.3), (206.0, 0.5), (60.0, 0.3)):
        a = periodic_orbit(free, freq_hz, p_f_bar * BAR)
        b = periodic_orbit(far, freq_hz, p_f_bar * BAR)
        assert b.mean_shift == pytest.approx(
            -b.drift_torque / model.drive_damping, rel=1e-6)
        assert b.dither_amplitude == pytest.approx(a.dither_amplitude,
                                                   rel=2e-5)
        assert abs(b.multipliers[0]) == pytest.approx(abs(a.multipliers[0]),
                                                      rel=1e-6)


def test_the_limit_cuts_the_motor_torque_as_the_fmu_does(bench):
    # at the bench's f1 the motor saturates at +680 N m: its mean torque
    # is held by a slower drive (the orbit's mean shift, rad/s)
    model, _ = bench
    orbit = periodic_orbit(model, 16.5, 0.3 * BAR)
    assert orbit.drive_saturated and orbit.mean_shift < -0.1
    assert not periodic_orbit(model, 60.0, 0.3 * BAR).drive_saturated


def test_a_point_that_did_not_converge_has_no_verdict(tmp_path):
    # orbit --freq 103 --pf 2:9:4: the balance at 6.67 bar does not
    # converge (an iterate of 8 124 rpm) and was a normal CSV row, stable,
    # judder True (issue 44, item 6): marked, with no kind and no verdict
    import csv
    import json
    import subprocess
    import sys
    pytest.importorskip("fmpy")
    out = tmp_path / "o.csv"
    proc = subprocess.run(
        [sys.executable, "-m", "judder", "orbit", "--freq", "103", "--pf",
         "2:9:4", "--out", str(out), "--json"],
        capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stderr
    rows = json.loads(proc.stdout)["orbits"]
    lost = [r for r in rows if not r["success"]]
    assert lost, "the grid no longer holds a point that does not converge"
    for row in lost:
        assert row["converged"] is False
        assert row["judder"] is None and row["verdict"] is None
        assert row["kind"] is None and row["mechanism"] is None
    table = list(csv.DictReader(line for line in out.read_text()
                                .splitlines() if not line.startswith("#")))
    assert [r["converged"] for r in table] == [
        str(r["success"]) for r in rows]
    for row in table:
        if row["converged"] == "False":
            assert row["judder"] == "" and row["kind"] == ""


def test_a_chart_counts_no_verdict_where_the_balance_did_not_converge(
        tmp_path):
    # orbit --freq 100:106:4 --pf 2:8:4 counted its non-converged points
    # as "none" (no judder) in the JSON and the NPZ (issue 44, item 6)
    from studies.orbit import OrbitResult
    from stability.orbit_chart import OrbitChart
    shape = (2, 2)
    converged = np.array([[True, True], [True, False]])
    chart = OrbitChart(
        freq_hz=np.array([100.0, 102.0]), p_f=np.array([2.0, 4.0]) * BAR,
        forced_amplitude=np.array([[50.0, 60.0], [1.0, np.nan]]),
        half_amplitude=np.zeros(shape),
        settled_amplitude=np.array([[50.0, 60.0], [1.0, np.nan]]),
        growth_rate=np.full(shape, -0.1),
        kind=np.array([["stable", "stable"], ["stable", ""]]),
        quasi_periodic=np.zeros(shape, dtype=bool),
        drift_torque=np.zeros(shape),
        judder=np.array([[True, True], [False, False]]),
        mechanism=np.array([[1, 1], [0, 0]], dtype=np.int8),
        limit=30 / RPM_PER_RAD_S, min_growth=1.0, converged=converged)
    assert chart.counts() == {"none": 1, "forced": 2, "parametric": 0,
                              "both": 0}
    assert chart.not_converged() == 1
    result = OrbitResult(params=get_preset("paper-4dof"), mode="chart",
                         orbits=[], doubled=[], quasi=[], folds=[],
                         chart=chart, limit_rpm=30.0, min_growth=1.0,
                         seconds=1.0, model=type("M", (), {"slip": 84.7}))
    assert result.as_dict()["not_converged"] == 1
    assert "1 without a verdict" in result.text()
    result.save(tmp_path / "c.npz")
    with np.load(tmp_path / "c.npz") as npz:
        assert_allclose(npz["converged"], converged)
    result.save(tmp_path / "c.csv")
    lines = (tmp_path / "c.csv").read_text().splitlines()
    last = dict(zip(lines[0].split(","), lines[4].split(",")))
    assert last["converged"] == "False"
    assert last["judder"] == last["mechanism"] == last["kind"] == ""


def test_a_period_too_long_for_the_monodromy_is_refused_in_words():
    # orbit --freq 0.001 (the lower bound of --freq): the monodromy over
    # 1000 s overflows; it ended in an internal LinAlgError, exit 1
    # (issue 44, item 7)
    import subprocess
    import sys
    pytest.importorskip("fmpy")
    proc = subprocess.run(
        [sys.executable, "-m", "judder", "orbit", "--freq", "0.001", "--pf",
         "0.1"], capture_output=True, text=True, timeout=600)
    assert proc.returncode == 2, proc.stderr
    assert "internal error" not in proc.stderr
    assert "--freq" in proc.stderr and "0.001" in proc.stderr
    assert "allowed" in proc.stderr


@pytest.mark.parametrize("setting, side, zeta, limit", [
    (60.0, 1, 0.02, 5.0), (140.0, 0, 0.02, 5.0),
    # a peak 0.1 % wide, the limit 0.09 % from its top: the walk's steps
    # shrink with the slope and do not step over it
    (60.0, 1, 0.0005, 500.0), (140.0, 0, 0.0005, 500.0)])
def test_forced_limit_frequencies_finds_a_resonance_from_either_side(
        setting, side, zeta, limit):
    # closed form: a damped oscillator's response |H| = 1 / sqrt((1 -
    # r^2)^2 + (2 zeta r)^2), r = f / 100 Hz; walking away from the
    # resonance it never reaches the limit
    from scipy.optimize import brentq
    from stability.orbit_chart import forced_limit_frequencies

    def amplitude(f):
        r = f / 100.0
        return 1.0 / np.hypot(1 - r * r, 2 * zeta * r)
    exact = (brentq(lambda f: amplitude(f) - limit, 60.0, 100.0)
             if side else brentq(lambda f: amplitude(f) - limit, 100.0,
                                 140.0))
    found = forced_limit_frequencies(amplitude, setting, limit,
                                     setting / 2, setting * 4)
    assert found[side][1] == "forced"
    assert found[side][0] == pytest.approx(exact, abs=1e-3)   # xtol, Hz
    away = found[1 - side]
    assert away == (setting / 2 if side else setting * 4, "end")
