"""Benchmarks: each prints one JSON object on its own line.

Every benchmark runs the fast path and its baseline in the same run, and
reports ``name``, ``points``, ``seconds``, ``baseline_seconds``,
``speedup`` and ``max_error``. Run with ``make bench``; pass benchmark
names to run only those.
"""

import json
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
from threadpoolctl import threadpool_limits

from drivelines import get_model
from sources import get_preset
from stability import build_driveline
from stability.multipliers import leading_multipliers
from stability.maps import stability_map
from stability.monodromy import monodromy_solve_ivp
from stability.tongues import find_tongues, tongue_boundaries

BAR = 1e5
#: The map of the issue: 300 frequencies x 150 amplitudes, 4-DOF.
MAP_FREQ = np.linspace(5.0, 250.0, 300)
MAP_PF = np.linspace(0.0, 1.5, 150) * BAR
#: Subset of that grid integrated point by point (baseline and reference).
SUBSET = (slice(0, None, 25), slice(0, None, 30))
#: Tolerances of the baseline and of the reference integration.
BASELINE_TOL = {"rtol": 1e-10, "atol": 1e-12}
REFERENCE_TOL = {"rtol": 1e-13, "atol": 1e-15}


def _timed(function, *args, **kwargs):
    start = time.perf_counter()
    result = function(*args, **kwargs)
    return result, time.perf_counter() - start


def _cpu_seconds():
    """CPU seconds (user + system) of this process and of its ended
    children (rumoca's child process, gcc)."""
    import os
    times = os.times()
    return times.user + times.system + times.children_user + \
        times.children_system


def _pointwise_leading(system, freqs, amplitudes, tol):
    """Leading |multiplier| by solve_ivp at every point, shape (nf, np)."""
    out = np.empty((len(freqs), len(amplitudes)))
    for i, freq in enumerate(freqs):
        _, lead = leading_multipliers(
            monodromy_solve_ivp(system, freq, amplitudes, **tol))
        out[i] = np.abs(lead)
        print(f"  solve_ivp {tol['rtol']:.0e}: {i + 1}/{len(freqs)}",
              file=sys.stderr, end="\r")
    print(file=sys.stderr)
    return out


def _subset_baseline(system):
    """Reference and timed baseline (per-point solve_ivp) on the subset of
    the map grid: ``(freqs, amps, reference, baseline, baseline_seconds)``."""
    freqs, amps = MAP_FREQ[SUBSET[0]], MAP_PF[SUBSET[1]]
    reference = _pointwise_leading(system, freqs, amps, REFERENCE_TOL)
    baseline, baseline_seconds = _timed(_pointwise_leading, system, freqs,
                                        amps, BASELINE_TOL)
    return freqs, amps, reference, baseline, baseline_seconds


def bench_floquet_maps():
    """Dyson engine against per-point solve_ivp on the 4-DOF map."""
    driveline = build_driveline(get_preset("paper-4dof"))
    freqs, amps, reference, baseline, baseline_seconds = _subset_baseline(
        driveline.periodic_system())
    points = len(freqs) * len(amps)
    subset_map, seconds = _timed(stability_map, driveline, freqs, amps)
    yield {"name": "floquet-map-4dof-same-points", "points": points,
           "seconds": seconds, "baseline_seconds": baseline_seconds,
           "speedup": baseline_seconds / seconds,
           "max_error": float(np.abs(subset_map.leading_abs
                                     - reference).max()),
           "baseline_max_error": float(np.abs(baseline - reference).max()),
           "baseline": f"solve_ivp DOP853 rtol={BASELINE_TOL['rtol']:g} per "
                       "point", "reference": "solve_ivp DOP853 "
                       f"rtol={REFERENCE_TOL['rtol']:g}"}

    full, seconds = _timed(stability_map, driveline, MAP_FREQ, MAP_PF)
    full_points = full.kind.size
    extrapolated = baseline_seconds / points * full_points
    yield {"name": "floquet-map-4dof-300x150", "points": full_points,
           "seconds": seconds, "baseline_seconds": extrapolated,
           "baseline_extrapolated": True,
           "speedup": extrapolated / seconds,
           "max_error": float(np.abs(full.leading_abs[SUBSET]
                                     - reference).max()),
           "target_seconds": 10.0, "target_error": 1e-6,
           "note": f"baseline time scaled from the {points} points above, "
                   "which lie on this grid; error checked on those points"}


#: Boundary benchmark: 500 frequencies over 10-220 Hz up to 1.5 bar, and
#: points inside tongues 1-6 where the baseline bisects.
TONGUE_FREQ = np.linspace(10.0, 220.0, 500)
TONGUE_P_MAX = 1.5 * BAR
BISECTION_FREQ = np.array([18.0, 20.0, 37.9, 84.0, 100.0, 102.9, 110.0,
                           121.8, 205.0, 208.0])


def _bisect_lowest_unstable(system, freq, p_max, rel_tol=1e-9):
    """Baseline: lowest unstable p_f by bisection on per-point solve_ivp."""
    def unstable(p):
        _, lead = leading_multipliers(
            monodromy_solve_ivp(system, freq, [p], **BASELINE_TOL))
        return abs(lead[0]) > 1.0
    grid = np.linspace(0.0, p_max, 16)
    first = next(i for i, p in enumerate(grid) if unstable(p))
    low, high = grid[first - 1], grid[first]
    while high - low > rel_tol * high:
        mid = (low + high) / 2
        low, high = (low, mid) if unstable(mid) else (mid, high)
    return (low + high) / 2


def bench_tongue_boundaries():
    """Hill + Brent boundaries against per-point solve_ivp bisection."""
    driveline = build_driveline(get_preset("paper-4dof"))
    system = driveline.periodic_system()
    baseline, baseline_seconds = _timed(
        lambda: np.array([_bisect_lowest_unstable(system, f, TONGUE_P_MAX)
                          for f in BISECTION_FREQ]))
    check = tongue_boundaries(driveline, BISECTION_FREQ, TONGUE_P_MAX)
    error = np.abs(check.stability_boundary - baseline) / baseline

    def fast():
        boundaries = tongue_boundaries(driveline, TONGUE_FREQ, TONGUE_P_MAX)
        return boundaries, find_tongues(driveline, boundaries)
    (boundaries, tongues), seconds = _timed(fast)
    extrapolated = baseline_seconds / len(BISECTION_FREQ) * len(TONGUE_FREQ)
    yield {"name": "tongue-boundaries-4dof-500", "points": len(TONGUE_FREQ),
           "seconds": seconds, "baseline_seconds": extrapolated,
           "baseline_extrapolated": True, "speedup": extrapolated / seconds,
           "max_error": float(error.max()),
           "error_unit": "relative, lowest unstable p_f",
           "max_boundary_multiplier_error": boundaries.max_multiplier_error,
           "tongues": len(tongues), "target_seconds": 5.0,
           "note": f"baseline: bisection to 1e-9 on solve_ivp (rtol "
                   f"{BASELINE_TOL['rtol']:g}) at {len(BISECTION_FREQ)} "
                   "frequencies inside tongues 1-6, scaled to 500; seconds "
                   "include labelling and tip refinement"}


def _best_of(repeats, function):
    """Result and the shortest of ``repeats`` timed runs."""
    runs = [_timed(function) for _ in range(repeats)]
    return runs[0][0], min(seconds for _, seconds in runs)


def bench_tongue_solvers():
    """All six boundaries at 500 frequencies: Hill-Newton against today's
    per-frequency Hill + Brent on the monodromy ('scan'), same run."""
    driveline = build_driveline(get_preset("paper-4dof"))

    def boundaries(solver, check):
        return tongue_boundaries(driveline, TONGUE_FREQ, TONGUE_P_MAX,
                                 solver=solver, check=check)
    old, old_seconds = _best_of(2, lambda: boundaries("scan", True))
    new, new_seconds = _best_of(3, lambda: boundaries("hill", False))
    checked, checked_seconds = _best_of(1, lambda: boundaries("hill", True))
    _, old_tips_seconds = _best_of(2, lambda: find_tongues(driveline, old))
    tongues, new_tips_seconds = _best_of(3, lambda: find_tongues(driveline,
                                                                 new))
    both = np.isfinite(old.amplitude) & np.isfinite(new.amplitude)
    mismatch = int(np.count_nonzero(np.isfinite(old.amplitude)
                                    != np.isfinite(new.amplitude)))
    error = (np.abs(new.amplitude - old.amplitude)[both]
             / old.amplitude[both]).max()
    yield {"name": "tongue-boundaries-4dof-500-hill",
           "points": len(TONGUE_FREQ), "seconds": new_seconds,
           "baseline_seconds": old_seconds,
           "speedup": old_seconds / new_seconds,
           "max_error": float(error),
           "error_unit": "relative p_f, Hill-Newton vs scan, every point",
           "points_found_by_one_only": mismatch,
           "checked_seconds": checked_seconds,
           "max_boundary_multiplier_error": checked.max_multiplier_error,
           "baseline_max_boundary_multiplier_error":
               old.max_multiplier_error,
           "with_tips_seconds": new_seconds + new_tips_seconds,
           "baseline_with_tips_seconds": old_seconds + old_tips_seconds,
           "tips": [[t.number, round(t.tip_freq_hz, 3),
                     round(t.tip_p_f / BAR, 3)] for t in tongues],
           "target_seconds": 0.1,
           "note": "seconds: the six boundaries (three lowest curves) at "
                   "500 frequencies by stability.hill, without the "
                   "monodromy check (best of 3); baseline: today's solver "
                   "'scan' with its check (best of 2); checked_seconds: Hill "
                   "plus the monodromy check of every point; with_tips: "
                   "plus labelling and tip refinement"}


ENGAGEMENT = {"f_dither": 60.0, "p_f": 0.05e5}
#: Inside tongue 2 (issue 11): the stiff case of the smooth clutch.
ENGAGEMENT_TONGUE_2 = {"f_dither": 102.9, "p_f": 0.3e5}


def bench_engagement():
    """One 2 s bench engagement, outside and inside tongue 2: fmpy ME and
    CS of the smooth clutch (WetClutch) and of the event-locking one
    (LockingWetClutch) against scipy on the smooth clutch's equations."""
    from fmu.backend import to_ode
    from fmu.frontend import load_flat_model
    from fmu.store import LIBRARY, ensure_fmu

    bench_class = SMOOTH_BENCH_CLASS
    fmus = {"": str(ensure_fmu(bench_class)),
            "-locking": str(ensure_fmu(LOCKING_BENCH_CLASS))}
    ode = to_ode(load_flat_model(
        LIBRARY.joinpath(*bench_class.split(".")).with_suffix(".mo"),
        bench_class, roots=[LIBRARY]))
    yield from _engagement_runs(fmus, ode, ENGAGEMENT, "")
    yield from _engagement_runs(fmus, ode, ENGAGEMENT_TONGUE_2, "-tongue2")


#: The bench engagement with the EVEN clutch locking by events, and the
#: same engagement with the smooth clutch: the pair with the straight line
#: of Eq. 5 (``judder simulate --engagement full-linear-law``), kept for
#: its timings' history; ``--engagement full`` runs the held-slip bench's
#: curve (TestBenchCurveLockUp), which has no smooth twin here.
LOCKING_BENCH_CLASS = "Judder.Examples.TestBenchLockUp"
SMOOTH_BENCH_CLASS = "Judder.Examples.TestBenchFullEngagement"


def _engagement_runs(fmus, ode, setting, label):
    """Records of one dither ``setting`` (model parameters): the scipy
    DOP853 baseline, then fmpy Model Exchange and Co-Simulation of each
    FMU of ``fmus`` (clutch label -> path; '' is the smooth clutch, the
    others report their time against it too)."""
    from fmu.store import simulate
    from scipy.integrate import solve_ivp

    f, outputs, start = ode.functions()
    p = ode.parameter_vector(**setting)
    times = np.linspace(0.0, 2.0, 2001)
    names = [o.name for o in ode.outputs]

    def scipy_run():
        sol = solve_ivp(lambda t, x: np.asarray(f(t, x, p)).ravel(),
                        (0.0, 2.0), np.asarray(start(p)).ravel(),
                        method="DOP853", rtol=1e-8, atol=1e-8, t_eval=times)
        return np.array([np.asarray(outputs(t, x, p)).ravel()[
            names.index("w_upstream")] for t, x in zip(sol.t, sol.y.T)])
    reference, baseline_seconds = _timed(scipy_run)
    smooth = {}
    for clutch, fmu_path in fmus.items():
        for kind, options in (("ModelExchange", {"relative_tolerance": 1e-8}),
                              ("CoSimulation", {})):
            result, seconds = _timed(
                simulate, fmu_path, fmi_type=kind, stop_time=2.0,
                output_interval=1e-3, start_values=setting,
                output=["w_upstream"], **options)
            # the locking FMU adds a row before and after each event
            _, last = np.unique(result["time"][::-1], return_index=True)
            rows = result[len(result) - 1 - last]
            error = np.abs(np.interp(times, rows["time"], rows["w_upstream"])
                           - reference).max() / np.abs(reference).max()
            record = {
                "name": f"engagement-2s{label}{clutch}-fmpy-{kind}",
                "points": 1, "seconds": seconds,
                "baseline_seconds": baseline_seconds,
                "speedup": baseline_seconds / seconds,
                "max_error": float(error),
                "error_unit": "relative, upstream speed, vs the scipy run",
                "f_dither_hz": setting["f_dither"],
                "p_f_bar": setting["p_f"] / BAR,
                "note": f"{Path(fmu_path).stem} FMU (fmu/ compiler) through "
                        "fmpy; baseline: scipy DOP853 rtol 1e-8 on the "
                        "smooth clutch's equations (the back end's CasADi "
                        "ODE)"}
            if clutch:
                record["smooth_clutch_seconds"] = smooth[kind]
                record["vs_smooth_clutch"] = seconds / smooth[kind]
                record["note"] += ("; max_error includes the difference "
                                   "between the two clutches")
            else:
                smooth[kind] = seconds
            yield record


#: The 12-state driveline of a user's package (issue 12): rank-2 dither.
MODELICA_CLASS = "BenchLib.Driveline6DOF"
MODELICA_LIBRARY = Path(__file__).resolve().parents[1] / "examples" / "modelica"


def _linear_map(linear):
    """The 300 x 150 map of a linearised driveline
    (:class:`sources.modelica.LinearPeriodicModel`) by the Dyson
    engine, against per-point solve_ivp on the subset, scaled: the fields
    of a record shared by the Modelica and FMU benchmarks."""
    from stability import LinearDriveline

    driveline = LinearDriveline.from_model(linear)
    freqs, amps, reference, baseline, baseline_seconds = _subset_baseline(
        driveline.periodic_system())
    points = len(freqs) * len(amps)
    full, seconds = _timed(stability_map, driveline, MAP_FREQ, MAP_PF)
    extrapolated = baseline_seconds / points * full.kind.size
    return {"points": full.kind.size, "seconds": seconds,
            "baseline_seconds": extrapolated, "baseline_extrapolated": True,
            "speedup": extrapolated / seconds,
            "max_error": float(np.abs(full.leading_abs[SUBSET]
                                      - reference).max()),
            "baseline_max_error": float(np.abs(baseline - reference).max()),
            "states": len(linear.state_names),
            "reduced_states": len(driveline.reduction.A0),
            "modulation_rank": driveline.reduction.rank,
            "baseline_note": f"baseline: solve_ivp DOP853 rtol "
                             f"{BASELINE_TOL['rtol']:g} on {points} points "
                             "of the grid, scaled; error against rtol "
                             f"{REFERENCE_TOL['rtol']:g} on those points"}


def bench_modelica_map():
    """300 x 150 map of a 12-state Modelica driveline: the Dyson engine on
    the system compiled and linearised from Modelica, against per-point
    solve_ivp on the same system."""
    from sources.modelica import linearize

    linear, compile_seconds = _timed(linearize, MODELICA_CLASS,
                                     str(MODELICA_LIBRARY))
    record = _linear_map(linear)
    baseline_note = record.pop("baseline_note")
    yield {"name": "floquet-map-modelica-12-states-300x150", **record,
           "compile_and_linearise_seconds": compile_seconds,
           "target_seconds": 5.0,
           "note": f"{MODELICA_CLASS} from {MODELICA_LIBRARY.name}/; "
                   + baseline_note}


def bench_fmu_map():
    """300 x 150 map of the 4-DOF driveline read from its FMU's
    directional derivatives (sources.fmus), against per-point
    solve_ivp on the same system; how far the FMU's system is from the
    symbolic one."""
    from sources.fmus import linearize_fmu
    from sources.modelica import linearize
    from fmu.store import ensure_fmu

    model_class = get_model("4dof").modelica_class
    path = ensure_fmu(model_class)
    linear, read_seconds = _timed(linearize_fmu, path)
    symbolic = linearize(model_class)
    record = _linear_map(linear)
    baseline_note = record.pop("baseline_note")
    yield {"name": "floquet-map-fmu-4dof-300x150", **record,
           "read_jacobians_seconds": read_seconds,
           "max_system_difference_vs_symbolic": float(max(
               np.abs(linear.A0 - symbolic.A0).max()
               / np.abs(symbolic.A0).max(),
               np.abs(linear.B - symbolic.B).max()
               / np.abs(symbolic.B).max())),
           "note": f"{path.name} (fmu/ compiler) through fmpy's "
                   "fmi2GetDirectionalDerivative; "
                   + baseline_note}


#: Envelope benchmark: the ranges of examples/ranges.toml around the
#: fitted set, the dither window 60-200 Hz (2 Hz steps) up to the valve's
#: 0.7 bar, judder-relevant growth (1/s).
ENVELOPE_FREQ = np.linspace(60.0, 200.0, 71)
ENVELOPE_P_MAX_BAR = 0.7
#: Samples of the 1- and 2-worker runs, and of the target envelope.
ENVELOPE_SAMPLES = 200
ENVELOPE_TARGET_SAMPLES = 1000


def _envelope(samples, workers):
    """An envelope on ``workers``: result, seconds, and the seconds the
    local cluster took to start (before)."""
    import math
    from pathlib import Path

    from infra.parallel import cluster, parallel_map
    from judder import api
    ranges = Path(__file__).resolve().parents[1] / "examples" / "ranges.toml"
    with cluster(workers=workers):
        _, startup = _timed(lambda: list(parallel_map(
            math.sqrt, [1.0] * 2 * workers)))
        result, seconds = _timed(
            api.envelope, ranges, ENVELOPE_FREQ, ENVELOPE_P_MAX_BAR,
            samples=samples, parameters=get_preset("paper-4dof-fitted"),
            workers=workers)
    return result, seconds, startup


def bench_envelope():
    """Envelope on 1 and 2 workers (same run, same result), and the
    1000-sample envelope: measured when BENCH_ENVELOPE_FULL=1, else
    scaled from the 2-worker run."""
    import os
    serial, serial_seconds, _ = _envelope(ENVELOPE_SAMPLES, 1)
    parallel, seconds, startup = _envelope(ENVELOPE_SAMPLES, 2)
    a, b = serial.envelope, parallel.envelope
    same = all(np.array_equal(getattr(a, n), getattr(b, n), equal_nan=True)
               for n in ("amplitude", "refined", "probability"))
    sets = len(a.ok) + 1                       # with the nominal set
    frequencies = len(ENVELOPE_FREQ) * sets
    yield {"name": f"envelope-{ENVELOPE_SAMPLES}-workers-1-vs-2",
           "points": sets, "seconds": seconds,
           "baseline_seconds": serial_seconds,
           "speedup": serial_seconds / seconds,
           "max_error": 0.0 if same else float("inf"),
           "error_unit": "0 if the 2-worker arrays equal the serial ones",
           "seconds_per_boundary_frequency": serial_seconds / frequencies,
           "cluster_start_seconds": startup,
           "load_average": os.getloadavg()[0],
           "note": f"{sets} parameter sets (8 vertices, nominal) x "
                   f"{len(ENVELOPE_FREQ)} frequencies and the refinement; "
                   "seconds without starting the local Dask cluster "
                   "(cluster_start_seconds, once per command)"}
    target_sets = ENVELOPE_TARGET_SAMPLES + 8 + 1
    full = os.environ.get("BENCH_ENVELOPE_FULL") == "1"
    if full:
        big, big_seconds, startup = _envelope(ENVELOPE_TARGET_SAMPLES, 2)
        convergence = big.envelope.convergence
    else:
        big_seconds = seconds / sets * target_sets
        convergence = None
    big_seconds += startup
    yield {"name": f"envelope-{ENVELOPE_TARGET_SAMPLES}-samples",
           "points": target_sets, "seconds": big_seconds,
           "measured": full,
           "baseline_seconds": serial_seconds / sets * target_sets,
           "baseline_extrapolated": True,
           "speedup": serial_seconds / sets * target_sets / big_seconds,
           "max_error": 0.0 if same else float("inf"),
           "target_seconds": 60.0, "convergence": convergence,
           "load_average": os.getloadavg()[0],
           "note": "2 workers, cluster start included; baseline: the serial run above scaled to "
                   f"{target_sets} sets" + ("" if full else
                   "; seconds scaled from the 2-worker run (set "
                   "BENCH_ENVELOPE_FULL=1 to measure)")}


#: Set points of the bench-data chart benchmark: 31 frequencies x 8
#: amplitudes = 248 acquisitions, as issue 19 measured.
CHART_FREQ = np.linspace(200.0, 212.0, 31)
CHART_PF = np.linspace(0.05, 0.4, 8)


def _acquisition(folder, index, freq_hz, p_f_bar, rng):
    """One engagement as a bench records it, without its dither setting:
    a 41-tooth pick-up with 0.5 rpm noise upstream (forced response at f,
    and a double-period judder growing where p_f > 0.2 bar), 1 kHz
    pressure, the downstream pick-up; a dither frequency read 1e-3 Hz off
    its set point, as an estimate would be."""
    from pysim.simulation.campaigns import pickup_samples
    from pysim.simulation.export import write_csv
    fine = np.arange(0.0, 3.0, 2e-5)
    on = fine > 0.6
    growth = 3.0 * (p_f_bar - 0.2) / 0.2
    rpm = 1000 + on * (20 * p_f_bar * np.cos(2 * np.pi * freq_hz * fine)
                       + 0.2 * np.exp(growth * (fine - 0.6))
                       * np.cos(np.pi * freq_hz * fine))
    omega = rpm * np.pi / 30
    angle = np.concatenate([[0.0], np.cumsum((omega[1:] + omega[:-1]) / 2)
                            * 2e-5])
    t_up, n_up = pickup_samples(fine, angle, 41, 0.5, rng)
    t_dn, n_dn = pickup_samples(fine, 20.0 * fine, 41, 0.5, rng)
    f = freq_hz + rng.normal(0.0, 1e-3)
    pressure = np.clip((t_up - 0.1) / 0.5, 0, 1) * (
        10 + p_f_bar * np.cos(2 * np.pi * f * t_up))
    name = f"run{index:03d}.csv"
    write_csv(folder / name, t_up,
              {"n_upstream": n_up, "n_downstream": np.interp(t_up, t_dn, n_dn),
               "p_even": pressure},
              {"n_upstream": "rpm", "n_downstream": "rpm", "p_even": "bar"},
              {})
    return name


def bench_chart():
    """``judder chart`` of 248 acquisitions without dither settings (the
    frequency and amplitude estimated from the pressure): 2 workers
    against 1, and one boundary row per set point."""
    import tempfile
    from judder import api
    rng = np.random.default_rng(19)
    with tempfile.TemporaryDirectory() as text:
        folder = Path(text)
        files = [folder / _acquisition(folder, k, f, p, rng)
                 for k, (f, p) in enumerate(
                     (f, p) for f in CHART_FREQ for p in CHART_PF)]
        serial, baseline_seconds = _timed(api.chart, files, workers=1)
        chart, seconds = _timed(api.chart, files, workers=2)
    rows = chart.as_dict()["boundary"]
    yield {"name": "chart-248-acquisitions", "points": len(files),
           "seconds": seconds, "baseline_seconds": baseline_seconds,
           "speedup": baseline_seconds / seconds,
           "boundary_rows": len(rows), "set_points": len(CHART_FREQ),
           "same_verdicts": bool(
               [r["judder"] for r in serial.as_dict()["runs"]]
               == [r["judder"] for r in chart.as_dict()["runs"]]),
           "target_seconds": 60.0,
           "note": "baseline: the same chart on 1 worker; CSV files of "
                   "tooth-passage speeds, no dither metadata"}


def _checked_boundaries():
    """A stand-in for :func:`stability.tongues.tongue_boundaries` in the
    fit's evaluator that checks every boundary point against the
    monodromy, as the fit did before issue 32 (the baseline)."""
    def checked(*args, **kwargs):
        return tongue_boundaries(*args, **{**kwargs, "check": True})
    return checked


def bench_fit():
    """``judder fit`` as it runs (one process, boundaries unchecked)
    against the same fit with every boundary point checked against the
    monodromy, as it ran before issue 32, in the same run, on two noisy
    boundaries made from known parameters: mu_g and k24 from 15
    frequencies, and c12, mu_g and k24 from the example boundary."""
    import os
    from unittest import mock
    sys.path.insert(0, str(Path(__file__).parent))
    from fit_coverage import noisy_boundary
    from studies.inputs import read_boundary
    from stability.fit import _common, fit_boundary
    truth = get_preset("paper-4dof-fitted")
    freq15 = np.linspace(60.0, 200.0, 15)
    problems = [
        ("fit-2-parameters-15-points", ("mu_g", "k24"), freq15,
         noisy_boundary(truth, freq15, 1.5 * BAR, 0.03,
                        np.random.default_rng(0), 0.0),
         truth.replace(mu_g=0.02, k24=33000.0), 0.0, 2.0),
        ("fit-3-parameters-example", ("c12", "mu_g", "k24"),
         *read_boundary(Path(__file__).parents[1] / "examples"
                        / "measured_boundary.csv"),
         truth.replace(c12=5.0, mu_g=0.02, k24=33000.0), 1.0, 5.0)]
    for name, names, freq, measured, start, growth, target in problems:
        def run():
            return fit_boundary(start, freq, measured, 1.5 * BAR,
                                names=names, min_growth=growth)
        cpu = time.process_time()
        with mock.patch.object(_common, "tongue_boundaries",
                               _checked_boundaries()):
            baseline, baseline_seconds = _timed(run)
        baseline_cpu, cpu = time.process_time() - cpu, time.process_time()
        fit, seconds = _timed(run)
        cpu = time.process_time() - cpu
        inside = [bool(lo <= truth[n] <= hi) for n, lo, hi in
                  zip(fit.names, fit.ci_low, fit.ci_high)]
        same = all(np.array_equal(getattr(fit, n), getattr(baseline, n),
                                  equal_nan=True)
                   for n in ("values", "std", "ci_low", "ci_high"))
        yield {"name": name, "points": len(freq),
               "onsets": int(np.sum(np.isfinite(measured))),
               "seconds": seconds, "baseline_seconds": baseline_seconds,
               "speedup": baseline_seconds / seconds,
               "cpu_seconds": cpu, "baseline_cpu_seconds": baseline_cpu,
               "max_error": float(np.max(np.abs(fit.values - np.array(
                   [truth[n] for n in names])) / fit.std)),
               "error_unit": "standard uncertainties from the truth",
               "truth_inside_95": inside,
               "same_values_and_intervals": same,
               "evaluations": fit.evaluations,
               "baseline_evaluations": baseline.evaluations,
               "target_seconds": target,
               "within_target": seconds <= target,
               "load_average": os.getloadavg()[0],
               "note": "baseline: the same fit with every boundary point "
                       "checked against the monodromy (tongue_boundaries' "
                       "check=True), as judder fit ran before issue 32; "
                       "one process, so cpu_seconds is what a quiet "
                       "machine takes; the targets are for a quiet "
                       "machine"}


#: MSL's first example, a driveline of Modelica.Mechanics.Rotational.
MSL_CLASS = "Modelica.Mechanics.Rotational.Examples.First"


def _msl_folder():
    """The Modelica Standard Library: ../shared/msl beside the repository
    or a folder of MODELICAPATH holding Modelica/package.mo; or None."""
    import os
    root = Path(__file__).resolve().parents[1]
    for folder in [root.parent / "shared" / "msl"] + [
            Path(p) for p in os.environ.get("MODELICAPATH", "").split(
                os.pathsep) if p]:
        if (folder / "Modelica" / "package.mo").is_file():
            return folder
    return None


def bench_msl_compile():
    """python -m fmu of MSL's Rotational.Examples.First (FMI 2.0): rumoca
    flattening the model anew (the flat-model cache off; rumoca's own
    cache of parsed files may be warm), against the same build from the
    flat-model cache (fmu/cache.py); both FMUs simulated by fmpy.

    The cold build's CPU time (this process and its children) is
    compared with the issue's 10 s, and split into rumoca's flattening
    alone (:func:`fmu.rumoca_child.flatten_isolated`, timed apart) and
    the rest (source check, back end, C code, gcc)."""
    import os
    import tempfile
    from fmu.build import build_fmu
    from fmu.frontend import find_class
    from fmu.rumoca_child import flatten_isolated
    from fmu.store import simulate
    msl = _msl_folder()
    if msl is None:
        print("msl-compile: no MSL in ../shared/msl nor on MODELICAPATH; "
              "skipped", file=sys.stderr)
        return
    library = Path(__file__).resolve().parents[1] / "modelica"
    roots = [msl, library]
    source, _ = find_class(MSL_CLASS, roots)
    runs, cpu = {}, {}
    with tempfile.TemporaryDirectory() as tmp:
        saved = os.environ.get("JUDDER_FMU_CACHE")
        folder = str(Path(tmp) / "cache")
        try:
            for label, cache in (("cold", "off"), ("fill", folder),
                                 ("cached", folder)):
                os.environ["JUDDER_FMU_CACHE"] = cache
                target = Path(tmp) / f"{label}.fmu"
                started = _cpu_seconds()
                _, runs[label] = _timed(build_fmu, source, MSL_CLASS, target,
                                        roots=roots)
                cpu[label] = _cpu_seconds() - started
        finally:
            if saved is None:
                os.environ.pop("JUDDER_FMU_CACHE")
            else:
                os.environ["JUDDER_FMU_CACHE"] = saved
        speeds = [simulate(Path(tmp) / f"{label}.fmu", stop_time=1,
                           output=["inertia3.w"])["inertia3.w"]
                  for label in ("cold", "cached")]
    started = _cpu_seconds()
    flatten_isolated(source, MSL_CLASS, roots)
    rumoca_cpu = _cpu_seconds() - started
    yield {"name": "msl-first-compile", "points": 1,
           "seconds": runs["cached"], "baseline_seconds": runs["cold"],
           "speedup": runs["cold"] / runs["cached"],
           "max_error": float(np.abs(speeds[0] - speeds[1]).max()),
           "target_seconds": 30.0,
           "cold_cpu_seconds": cpu["cold"],
           "cached_cpu_seconds": cpu["cached"],
           "rumoca_flatten_cpu_seconds": rumoca_cpu,
           "target_cold_cpu_seconds": 10.0,
           "within_target": cpu["cold"] <= 10.0,
           "note": f"{MSL_CLASS} from {msl}: baseline rumoca flattening "
                   "anew, fast path the flat-model cache; max_error: "
                   "inertia3.w of the two FMUs (fmpy CS); CPU of this "
                   "process and its children; rumoca_flatten_cpu_seconds: "
                   "rumoca's child alone, which the project cannot make "
                   "faster (docs/benchmarks.md)"}


#: Whole-process start-up: the command, its target wall time (s, issue 22).
STARTUP = ((("--help",), 0.2), (("--version",), 0.2), (("eig",), 0.6))
STARTUP_RUNS = 7


def _wall(argv):
    start = time.perf_counter()
    subprocess.run(argv, check=True, stdout=subprocess.DEVNULL,
                   stderr=subprocess.DEVNULL)
    return time.perf_counter() - start


def bench_startup():
    """``judder --help``, ``--version`` and ``eig`` as whole processes
    (the installed console script), against a bare Python start in the
    same run, taken in turn: medians of :data:`STARTUP_RUNS` runs after
    one warm-up."""
    script = Path(sys.executable).with_name("judder")
    judder = [str(script)] if script.exists() else [sys.executable, "-m",
                                                    "judder"]
    bare = [sys.executable, "-c", "pass"]
    for args, target in STARTUP:
        _wall(judder + list(args))
        _wall(bare)
        times, bare_times = [], []
        for _ in range(STARTUP_RUNS):
            times.append(_wall(judder + list(args)))
            bare_times.append(_wall(bare))
        seconds, baseline = float(np.median(times)), float(np.median(
            bare_times))
        yield {"name": f"startup judder {' '.join(args)}", "points": 1,
               "seconds": seconds, "baseline_seconds": baseline,
               "speedup": baseline / seconds, "max_error": 0.0,
               "ratio_to_bare_python": seconds / baseline,
               "target_seconds": target, "within_target": seconds <= target,
               "note": f"median wall time of {STARTUP_RUNS} whole-process "
                       "runs; baseline: python -c pass"}


BENCHMARKS = {"startup": bench_startup,
              "floquet-maps": bench_floquet_maps,
              "modelica-map": bench_modelica_map,
              "fmu-map": bench_fmu_map,
              "tongue-boundaries": bench_tongue_boundaries,
              "tongue-solvers": bench_tongue_solvers,
              "engagement": bench_engagement,
              "chart": bench_chart,
              "fit": bench_fit,
              "envelope": bench_envelope,
              "msl-compile": bench_msl_compile}


def main(names):
    unknown = sorted(set(names) - set(BENCHMARKS))
    if unknown:
        sys.exit(f"bench: unknown benchmark {unknown[0]!r}; allowed: "
                 f"{', '.join(BENCHMARKS)}")
    for name in names or BENCHMARKS:
        for record in BENCHMARKS[name]():
            print(json.dumps(record), flush=True)


if __name__ == "__main__":
    with threadpool_limits(limits=1):   # as the judder command runs
        main(sys.argv[1:])
