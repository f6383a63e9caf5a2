"""Time-domain runs (pysim): signal kernels, cross-check, engagements,
bench emulator."""

import csv
import json
from pathlib import Path
import subprocess
import sys

import numpy as np
import pytest

from infra.errors import JudderError
from sources import get_preset
from pysim.simulation.campaigns import Campaign, pickup_samples, run_campaign
from pysim.bench.signals import (amplitude_spectrum, dither_envelope,
                           free_response_growth, per_period,
                           stroboscopic_growth)

pytest.importorskip("rumoca")
pytest.importorskip("fmpy")

BAR = 1e5


# --- signal kernels against closed forms ---------------------------------

def test_spectrum_of_a_sine():
    t = np.arange(0, 2, 1e-3)
    y = 3.0 * np.sin(2 * np.pi * 50 * t) + 0.1 * t   # trend is removed
    spectrum = amplitude_spectrum(t, y)
    assert spectrum.peak_freq_hz == pytest.approx(50, abs=0.5)
    assert spectrum.peak_amplitude == pytest.approx(3.0, rel=2e-3)


def test_per_period_leaves_out_a_last_period_of_one_sample():
    # 1 s at 1 kHz of 50 Hz: 50 whole periods of 20 samples, and the last
    # sample (t = 1 s, at the crest) alone in a 51st: its "mean" 11 was
    # the spike at the end of every engagement figure
    t = np.arange(1001) * 1e-3
    centre, low, high, mean = per_period(t, 10 + np.cos(2 * np.pi * 50 * t),
                                         1 / 50)
    assert len(centre) == 50
    np.testing.assert_allclose(mean, 10, atol=1e-12)
    np.testing.assert_allclose(high, 11, atol=1e-12)


def test_stroboscopic_growth_of_forced_plus_growing():
    # forced periodic part (dither period) + a growing mode at 17 Hz
    period = 1 / 40
    t = np.arange(0, 3, period / 16)
    x = 5 * np.cos(2 * np.pi * 40 * t) + 1e-3 * np.exp(1.7 * t) * np.cos(
        2 * np.pi * 17 * t)
    fit = stroboscopic_growth(t, [x], period)
    assert fit.rate == pytest.approx(1.7, rel=0.05)


def test_prony_fit_recovers_multipliers_exactly():
    # free response of a known linear recurrence, two signals of four states
    rng = np.random.default_rng(0)
    lam = np.array([1.03 * np.exp(0.7j), 0.95])
    A = np.zeros((4, 4))
    A[:2, :2] = abs(lam[0]) * np.array([[np.cos(0.7), -np.sin(0.7)],
                                        [np.sin(0.7), np.cos(0.7)]])
    A[2, 2], A[3, 3] = 0.95, 0.5
    basis = rng.normal(size=(4, 4))
    M = basis @ A @ np.linalg.inv(basis)
    x = [rng.normal(size=4)]
    for _ in range(200):
        x.append(M @ x[-1])
    x = np.array(x).T
    period = 0.01
    t = np.repeat(np.arange(x.shape[1]) * period, 2)[::2]
    fit = free_response_growth(t, x[:2], period)
    assert fit.rate == pytest.approx(np.log(1.03) / period, rel=1e-8)


def test_pickup_wheel_sampling_rate_and_speed():
    # 1000 rpm on a 41-tooth wheel: 683.3 teeth per second (section 2.2)
    t = np.arange(0, 1, 1e-5)
    angle = 1000 * 2 * np.pi / 60 * t
    times, speed = pickup_samples(t, angle, 41)
    assert len(times) == pytest.approx(1000 / 60 * 41, abs=2)
    np.testing.assert_allclose(speed, 1000, rtol=1e-6)


def test_dither_envelope_growth():
    t = np.arange(0, 2, 1e-4)
    y = np.exp(2.0 * t) * np.sin(2 * np.pi * 100 * t)
    _, rate = dither_envelope(t, y, 100.0, start=0.5, window=0.8)
    assert rate == pytest.approx(2.0, rel=0.02)


# --- the FMU against the Floquet layer ------------------------------------

def test_crosscheck_on_tongues_2_5_6():
    from studies.crosscheck import crosscheck_study
    # grid spanning tongue 5 (84 Hz), tongue 2 (103 Hz), tongue 6 (122 Hz)
    check = crosscheck_study(get_preset("paper-4dof"),
                             np.linspace(80, 126, 24),
                             np.array([0.2, 0.45, 0.7]) * BAR, duration=3.0)
    unstable = [p for p in check.points if p.floquet_unstable]
    kinds = {p.floquet_kind for p in unstable}
    assert {"single-period", "combination"} <= kinds
    assert len(unstable) >= 8 and len(unstable) < len(check.points)
    assert check.agreement >= 0.95
    assert check.max_rate_error(above=1.0) < 0.05
    for p in check.points:
        assert p.agree or p.reason


# --- bench emulator ---------------------------------------------------------

def test_campaign_files_index_and_resume(tmp_path):
    campaign = Campaign(freq_hz=(60.0, 102.9), p_f_bar=(0.05,),
                        engine_rpm=(1000.0, 1500.0), duration=0.5)
    rows = run_campaign(campaign, get_preset("paper-4dof"), tmp_path,
                        workers=2)
    assert [r["status"] for r in rows] == ["ok"] * 4
    with open(tmp_path / "index.csv", newline="") as stream:
        index = list(csv.DictReader(stream))
    assert [r["run_id"] for r in index] == [r["run_id"] for r in rows]
    first = tmp_path / f"{rows[0]['run_id']}.csv"
    text = first.read_text()
    assert "# dither_frequency_hz: 60.0" in text
    assert "n_upstream [rpm]" in text
    from asammdf import MDF
    mdf = MDF(tmp_path / f"{rows[3]['run_id']}.mf4")
    upstream = mdf.get("n_upstream")
    assert upstream.unit == "rpm"
    # 1500 rpm on 41 teeth: about 1025 samples per second
    assert len(upstream.samples) == pytest.approx(0.5 * 1500 / 60 * 41,
                                                  rel=0.05)
    assert json.loads(mdf.header.comment.split("<TX>")[1].split("</TX>")[0]
                      .replace("&quot;", '"'))["engine_speed_rpm"] == 1500
    # resume: a deleted file is made again, the others are kept
    first.unlink()
    stamp = (tmp_path / f"{rows[1]['run_id']}.csv").stat().st_mtime
    run_campaign(campaign, get_preset("paper-4dof"), tmp_path, workers=1)
    assert first.exists()
    assert (tmp_path / f"{rows[1]['run_id']}.csv").stat().st_mtime == stamp


# --- command line -----------------------------------------------------------

def _judder(*args):
    return subprocess.run([sys.executable, "-m", "judder", *args],
                          capture_output=True, text=True, timeout=600)


def test_simulate_cli_json_and_outputs(tmp_path):
    out, plot = tmp_path / "run.csv", tmp_path / "run.png"
    # double-period tongue 4 at 2 f2 = 205.8 Hz: the f/2 component grows
    # as the Floquet exponent of the bench's linearisation says (2.61 1/s)
    proc = _judder("simulate", "--freq", "205.8", "--pf", "0.3",
                   "--duration", "2", "--compare", "--out", str(out),
                   "--plot", str(plot), "--json")
    assert proc.returncode == 0, proc.stderr
    data = json.loads(proc.stdout)
    judder, reference = data["runs"]
    assert judder["peak_at_dither_frequency"]
    assert judder["judder"] and judder["judder_kind"] == "double-period"
    assert judder["floquet_kind"] == "double-period"
    assert judder["judder_growth_per_s"] == pytest.approx(
        judder["floquet_exponent_per_s"], rel=0.1)
    assert reference["label"] == "without dither"
    assert reference["judder"] is None
    assert "w_upstream [rad/s]" in out.read_text()
    assert plot.read_bytes()[:4] == b"\x89PNG"


def test_simulate_full_engagement_to_lock_up(tmp_path):
    # --engagement full: TestBenchCurveLockUp (test_fmu.py checks its
    # friction law is the held-slip bench's): outside the tongues (60 Hz)
    # the gearbox side comes up from rest and the clutch locks up at 3.21
    # s and stays locked; inside tongue 2 (102.9 Hz, 0.3 bar) the dither
    # drives f2 while the slip passes its mode, 61 lock-ups break away
    # (measured 61), and the last holds at 3.27 s: forced judder of 183
    # rpm while slipping (the straight line of Eq. 5 gives 1094 rpm and
    # never locks, test_simulate_full_linear_law_names_its_law)
    # (one --out holds one run: the 60 Hz run, 102.9 Hz as its comparison)
    from pysim.bench._csv import read
    out = tmp_path / "run.csv"
    proc = _judder("simulate", "--engagement", "full", "--freq", "60",
                   "--compare", "102.9", "--pf", "0.3", "--duration", "3.5",
                   "--out", str(out), "--json")
    assert proc.returncode == 0, proc.stderr
    data = json.loads(proc.stdout)
    assert data["model"] == "TestBenchCurveLockUp"
    assert data["run_kind"] == "engagement"
    assert data["friction_law"] == "curve (mu0, mu_g at w_op, delta_mu)"
    outside, inside = data["runs"]
    assert 3.2 < outside["lock_up_time_s"] < 3.25
    assert outside["lockups"] == 0
    assert abs(outside["final_slip_rad_s"]) < 1e-9
    assert outside["judder"] is False and outside["floquet_kind"] == "stable"
    # the motor's 1000 rpm less what the gearbox side gained in the ramp
    assert 0.9 * np.pi * 1000 / 30 < outside["slip_at_ramp_end_rad_s"] \
        < np.pi * 1000 / 30
    assert 3.25 < inside["lock_up_time_s"] < 3.3
    assert 40 < inside["lockups"] < 80
    assert inside["judder"] and inside["mechanism"] == "forced"
    assert inside["oscillation_rpm"] == pytest.approx(183, rel=0.05)
    # the run's CSV (the first run) read back as an acquisition: slipping
    # until the lock-up time reported, then stuck; its header names the
    # run's kind and friction law
    _, metadata, raws = read(out, ["slip", "clutch.lockups"])
    assert metadata["freq_hz"] == 60
    assert metadata["run_kind"] == "engagement"
    assert metadata["friction_law"] == "curve (mu0, mu_g at w_op, delta_mu)"
    time, slip, _ = raws["slip"]
    stuck = raws["clutch.lockups"][1] > 0.5
    assert time[stuck][0] == pytest.approx(outside["lock_up_time_s"])
    assert np.all(slip[time < outside["lock_up_time_s"] - 0.01] > 0.1)


def test_simulate_full_linear_law_names_its_law():
    # --engagement full-linear-law: TestBenchLockUp, the straight line of
    # Eq. 5 over the whole slip. Inside tongue 2 its dither torque ((mu0 +
    # mu_g slip) N_c R_m S p_f, 14-17 times the curve's at 85-105 rad/s)
    # makes the slip swing through zero: every lock-up breaks away
    # and the slipping engagement judders at 1094 rpm; the text and JSON
    # say which law ran
    proc = _judder("simulate", "--engagement", "full-linear-law", "--freq",
                   "102.9", "--pf", "0.3", "--duration", "2", "--json")
    assert proc.returncode == 0, proc.stderr
    data = json.loads(proc.stdout)
    assert data["model"] == "TestBenchLockUp"
    assert (data["run_kind"], data["friction_law"]) == (
        "engagement", "straight line, Eq. 5")
    inside, = data["runs"]
    assert inside["lock_up_time_s"] is None and inside["lockups"] > 300
    assert inside["judder"] and inside["mechanism"] == "forced"
    assert inside["oscillation_rpm"] > 500
    text = _judder("simulate", "--engagement", "full-linear-law", "--freq",
                   "60", "--pf", "0.05", "--duration", "1").stdout
    head = text.splitlines()[0]
    assert "full engagement to lock-up" in head
    assert "straight line, Eq. 5" in head and "TestBenchLockUp" in head


def test_simulate_names_the_held_slip_bench_run(tmp_path):
    # the default run holds the slip and never engages: its text, JSON and
    # figure title say "held-slip bench run" and its friction law, never
    # "engagement"; a run without dither is titled by its label alone
    from judder import api
    from judder.commands.simulate import _run_title
    result = api.simulate(104, 0.05, parameters=get_preset("paper-4dof"),
                          duration=1.0, compare="none")
    data = result.as_dict()
    assert data["model"] == "TestBenchEngagement"
    assert (data["run_kind"], data["friction_law"]) == (
        "held_slip", "curve (mu0, mu_g at w_op, delta_mu)")
    title = _run_title(result)
    assert "held-slip bench run" in title and "engagement" not in title
    assert "curve (mu0, mu_g at w_op, delta_mu)" in title
    figure = result.figure(title=title)
    texts = [ax.get_title() for ax in figure.axes]
    assert "without dither" in texts and not any(
        "no dither" in t for t in texts)
    # the pressure's right-axis label ends inside the figure, with room
    figure.canvas.draw()
    renderer = figure.canvas.get_renderer()
    right = max(ax.yaxis.label.get_window_extent(renderer).x1
                for ax in figure.axes)
    assert right < figure.bbox.x1 - 0.1 * figure.dpi
    import matplotlib.pyplot as plt
    plt.close(figure)
    proc = _judder("simulate", "--freq", "104", "--pf", "0.05",
                   "--duration", "1")
    assert proc.returncode == 0, proc.stderr
    head = proc.stdout.splitlines()[0]
    assert head.startswith("held-slip bench run") and "curve" in head


@pytest.mark.parametrize("args, words", [
    (["simulate", "--freq", "-5", "--pf", "0.1"], ["--freq", ">= 0.001"]),
    (["simulate", "--freq", "100", "--pf", "0.1", "--engagement", "full",
      "--model", "3dof"], ["4-DOF"]),
    (["simulate", "--freq", "100", "--pf", "0.1", "--bench", "w_motor=x"],
     ["--bench"]),
    (["simulate", "--freq", "100", "--pf", "0.1", "--bench", "w_moter=1"],
     ["w_moter", "w_motor"]),
    (["simulate", "--freq", "100", "--pf", "0.1", "--out", "a.txt"],
     [".csv", ".mf4"]),
    (["simulate", "--freq", "100", "--pf", "0.1", "--model", "3dof"],
     ["4-DOF"]),
    # the bench's times have allowed ranges: t_engage = -1 was run from
    # -0.5 s (issue 44, item 12); a ramp that ends after the run is refused
    (["simulate", "--freq", "100", "--pf", "0.1", "--bench", "t_engage=-1"],
     ["--bench", "t_engage", "-1", "at least 0 s"]),
    (["orbit", "--freq", "100", "--pf", "0.1", "--bench", "t_ramp=-0.1"],
     ["--bench", "t_ramp", "-0.1", "at least 0 s"]),
    (["simulate", "--freq", "100", "--pf", "0.1", "--bench", "t_engage=5"],
     ["--bench", "t_engage + t_ramp", "5.5 s", "4 s", "--duration"]),
    # one --out file for two runs kept the first only, silently (issue 44,
    # item 5): refused before any run, naming both options and the runs
    (["simulate", "--freq", "19,105", "--pf", "0.3", "--out", "e.csv"],
     ["--out", "--freq", "19", "105"]),
    (["campaign", "--out", "x", "--temperatures", "99-100"], ["99-100"]),
])
def test_time_domain_commands_refuse_bad_input(args, words):
    proc = _judder(*args)
    assert proc.returncode == 2, proc.stderr
    assert "Traceback" not in proc.stderr
    for word in words:
        assert word in proc.stderr


def test_a_simulation_of_several_runs_writes_none_without_naming_one(
        tmp_path):
    # SimulationResult.save of two settings asked for wrote the first one
    # as if it were all (issue 44, item 5): refused, or the run named
    from types import SimpleNamespace

    from studies.simulate import SimulationResult
    time = np.linspace(0.0, 1.0, 5)
    runs = [(f"dither at {f} Hz",
             SimpleNamespace(freq_hz=f, p_f=3e4, time=time,
                             signals={"slip": time * f}, start_values={}))
            for f in (19.0, 105.0)]
    result = SimulationResult(runs=runs, summaries=[{}, {}], fmu="x.fmu",
                              model_class="Judder.Examples.Bench", start=0.0,
                              signals={"slip": "rad/s"}, asked=2)
    with pytest.raises(JudderError) as refused:
        result.save(tmp_path / "both.csv")
    for fact in ("`freq_hz`", "2 runs", "19", "105", "`run`"):
        assert fact in str(refused.value)
    assert not (tmp_path / "both.csv").exists()
    result.save(tmp_path / "second.csv", run=1)
    assert "105" in (tmp_path / "second.csv").read_text()


def test_a_failed_run_is_recorded_and_the_campaign_goes_on(tmp_path,
                                                           monkeypatch):
    import pysim.simulation.campaigns
    # a temperature case that cannot be run (below absolute zero); run
    # here, where the patched table is seen (Dask's worker processes are
    # spawned: they import the unpatched module)
    monkeypatch.setitem(pysim.simulation.campaigns.TEMPERATURES, "85-90", -300.0)
    campaign = Campaign(freq_hz=(60.0,), p_f_bar=(0.05,),
                        temperatures=("65-70", "85-90"), duration=0.3,
                        formats=("csv",))
    rows = run_campaign(campaign, get_preset("paper-4dof"), tmp_path,
                        workers=1)
    status = {r["oil_temperature"]: r for r in rows}
    assert status["65-70"]["status"] == "ok"
    assert status["85-90"]["status"] == "failed"
    assert "absolute zero" in status["85-90"]["message"]
    with open(tmp_path / "index.csv", newline="") as stream:
        assert len(list(csv.DictReader(stream))) == 2


def test_simulate_names_whose_linearisation_its_floquet_line_is():
    # at 105 Hz, 0.2 bar the example driveline alone grows at 0.563 1/s
    # (judder check --driveline chain); the bench's linearisation, with
    # its speed control's damping and its friction curve at the slip, at
    # +0.17 1/s, which judder check gives by default: the line says which
    # it gives (issue 33: "Floquet at this point"; issue 41: one view)
    from judder import api
    from judder.commands.simulate import _engagement_line
    from studies.inputs import load_parameters
    example = load_parameters(param_file=Path(__file__).parents[1]
                              / "examples" / "driveline.toml")
    run = api.simulate(105, 0.2, parameters=example, duration=1.0)
    summary = run.summaries[0]
    assert summary["floquet_exponent_per_s"] == pytest.approx(0.17,
                                                              abs=0.005)
    chain = api.check([105], [0.2], example, sensitivity=(),
                      driveline="chain").records()[0]
    assert chain["growth_rate_per_s"] == pytest.approx(0.563, abs=5e-4)
    check = api.check([105], [0.2], example, sensitivity=()).records()[0]
    assert check["growth_rate_per_s"] == pytest.approx(
        summary["floquet_exponent_per_s"], rel=1e-9)
    assert ("; Floquet of the bench's linearisation (judder check's view "
            "of the bench): single-period (+0.17 1/s)") in \
        _engagement_line(summary)
