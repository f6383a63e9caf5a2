"""``judder simulate``: a held-slip bench run or a full engagement with
dither (Fig. 7, 8), run through the FMU.
"""

import math

from infra.errors import JudderError
from studies._common import resolve
from studies._words import nonlinear_words, orbit_words
from studies.simulate import ENGAGEMENTS, simulate

from ._arguments import (force_option, limit_option, method_option,
                         min_growth_option, model_options)
from ._model import model_title, parameters_of, parse_bench
from ._output import emit, make_parents, write_outputs, written
from ._values import DURATION, FREQ_RANGE_HZ, PF, OrNone, QuantityList

#: The command's --help text.
DESCRIPTION = (
    "Held-slip bench run of the EVEN clutch at 1000 rpm on the test-bench "
    "model (TestBenchEngagement FMU, built if needed: the start of an "
    "engagement held at its slip, which never engages), run with fmpy; "
    "its friction law is the bounded curve whose value and slope at the "
    "slip w_op are mu0 and mu_g. Writes "
    "the time histories (SI units) and reports the spectrum peaks of "
    "the upstream speed and of the pressure, the judder verdict as "
    "judder chart reads it (the dither-related oscillation above --limit "
    "or growing at --min-growth or faster) with its mechanism (forced, "
    "parametric or both), and the Floquet verdict of "
    "the bench's linearisation (c1 + d_control, the friction curve's "
    "value and slope at the slip), and whether the dither's forced slip "
    "swing stays within the curve's linear range (else the run need not "
    "follow that verdict). With --modelica CLASS: the class's FMU "
    "(built by the project's compiler) from its start values, a steady "
    "slip, with the dither, and the Floquet verdict of its "
    "linearisation; --fmu is refused (its Jacobian is all the FMU path "
    "reads). With --engagement full: an engagement that engages, the "
    "gearbox side from rest until the EVEN clutch locks up "
    "(TestBenchCurveLockUp, the same friction curve as the held-slip "
    "run), with the lock-up time and the judder verdict while it slips; "
    "--engagement full-linear-law: the same engagement with the straight "
    "line of Eq. 5, another friction law (TestBenchLockUp). With "
    "--friction FILE.csv the held-slip run reads the clutch's own "
    "characteristic (TestBenchTable). With --bench load_share below 1 "
    "the slip falls: the run is followed through the map (the Floquet "
    "exponent of the bench linearised at each mean slip, the spans "
    "inside a tongue and the amplitude gain they predict) and judged by "
    "the envelope of its upstream speed, so a burst through a tongue is "
    "judder with its time and slip. Each output names its kind of run "
    "and its friction law.")


OUTPUTS = (("out", "--out", ("csv", "mf4")), ("plot", "--plot", None))


AMPLITUDE = "pf"


def check_outputs(args, seen):
    """--out holds the time histories of one run: several --freq with one
    file are refused before any work (it would keep the first run only,
    without a word)."""
    if args.out and len(args.freq) > 1:
        raise JudderError(
            f"--out {args.out} holds the time histories of one run; --freq "
            f"gives {len(args.freq)} runs ("
            + ", ".join(f"{f:g}" for f in args.freq) + " Hz); allowed: one "
            "--freq with --out (one simulate per frequency to write each), "
            "or several --freq without --out (--plot shows them all)")


#: What each kind of run is called in text and figures.
RUN_NAMES = {"held_slip": "held-slip bench run",
             "falling_slip": "bench run with a falling slip (--bench "
                             "load_share below 1)",
             "engagement": "full engagement to lock-up",
             "class": "time-domain run with dither"}


def add_arguments(p):
    """The options of ``judder simulate``."""
    p.add_argument("--freq", type=QuantityList("--freq", "Hz", *FREQ_RANGE_HZ),
                   required=True, metavar="HZ[,HZ...]",
                   help="dither frequency, Hz; several (e.g. 86,206) give "
                        "one engagement each, side by side, with their "
                        "spectra overlaid (Fig. 1, Fig. 8)")
    p.add_argument("--pf", type=PF, required=True, metavar="BAR",
                   help="dither amplitude, bar")
    p.add_argument("--duration", type=DURATION, metavar="S",
                   help="simulated time, s (default: the model's "
                        "StopTime, 4 s for the bench)")
    p.add_argument("--compare", nargs="?", const="none", metavar="HZ|none",
                   type=OrNone("--compare", "Hz", *FREQ_RANGE_HZ),
                   help="also run the same kind of run without dither "
                        "(--compare or --compare none), or with dither at "
                        "HZ; plotted side by side (Fig. 7)")
    p.add_argument("--bench", action="append", default=[],
                   metavar="NAME=VALUE",
                   help="bench parameter of the model (SI, or with a "
                        "unit: w_motor=1500rpm): w_motor, w_gearbox (the "
                        "steady slip is w_motor - w_gearbox), w_op and "
                        "delta_mu (the EVEN friction curve: mu0 and mu_g "
                        "are its value and slope at the slip w_op, mu stays "
                        "within mu0 +- delta_mu), t_engage, t_ramp, "
                        "p_load, load_share (REV torque over the EVEN "
                        "mean torque: 1 keeps the slip steady, below 1 it "
                        "falls), N_c_load, d_control, tau_max (the motor's "
                        "torque limit); repeatable (not with --modelica: set "
                        "the class's parameters with --set)")
    p.add_argument("--engagement", choices=tuple(ENGAGEMENTS),
                   default="steady",
                   help="steady: the held-slip bench run, the EVEN clutch "
                        "held at a steady slip, never engaging (default; "
                        "TestBenchEngagement, the friction curve whose "
                        "value and slope at w_op are mu0 and mu_g); full: "
                        "an engagement, the gearbox side from rest, the "
                        "pressure ramped in 0.05 s, until the EVEN clutch "
                        "locks up, with the same friction curve "
                        "(TestBenchCurveLockUp); full-linear-law: that "
                        "engagement with the straight line of Eq. 5 over "
                        "the whole slip, another friction law than the "
                        "bench's curve (TestBenchLockUp); an engagement's "
                        "verdict is that of its slipping part")
    p.add_argument("--out", metavar="run.csv|run.mf4",
                   help="time histories as CSV or ASAM MDF4")
    p.add_argument("--plot", metavar="FILE.png",
                   help="time histories and spectra; with a bench, "
                        "each run's path through the map (Floquet exponent "
                        "and mean slip against time)")
    limit_option(p)
    min_growth_option(p)
    method_option(p)
    model_options(p, fmu=False)
    force_option(p)


def run(args):
    """A held-slip bench run or a full engagement of the test-bench model
    with dither (Fig. 7, Fig. 8)."""
    freqs = args.freq
    params, changes = parameters_of(args)
    bench = parse_bench(args.bench, resolve(params, changes))
    compare = args.compare
    make_parents(args.out, args.plot)
    result = simulate(freqs if len(freqs) > 1 else freqs[0], args.pf,
                      duration=args.duration, engagement=args.engagement,
                      compare=compare, bench=bench, parameters=params,
                      changes=changes, method=args.method,
                      min_growth=args.min_growth,
                      judder_limit_rpm=args.limit)
    files = write_outputs(
        args, result,
        figure={"title": _run_title(result)
                + f", {result.model_class.rsplit('.', 1)[-1]} FMU with the "
                  f"parameters of {model_title(args, params)}"})
    emit(args, {**result.as_dict(), **files},
         "\n".join([_run_title(result)
                    + f" ({result.model_class.rsplit('.', 1)[-1]} FMU)"]
                   + [_engagement_line(s, params.source_kind.is_chain)
                      for s in result.summaries])
         + written(args.out and f"{args.out} (the run "
                   f"{result.summaries[0]['label']})", args.plot))


def _run_title(result):
    """What ran, in words: ``held-slip bench run of the EVEN clutch
    (Fig. 1, 7, 8), friction law: curve (...)``, or a full engagement to
    lock-up, or a class's time-domain run."""
    if result.run_kind == "class":
        return RUN_NAMES["class"]
    return (f"{RUN_NAMES[result.run_kind]} of the EVEN clutch"
            + (" (Fig. 1, 7, 8)" if result.run_kind == "held_slip" else "")
            + f", friction law: {result.friction_law}")


def _engagement_line(s, bench=True):
    """One run's line; ``bench``: it ran on the bench model, whose
    linearisation (its speed control's damping, its friction curve at the
    slip) is not the driveline's that ``judder check`` judges."""
    from pysim.bench.engagement import judder_words, lock_words
    return (f"{s['label']}: f = {s['freq_hz']:g} Hz, p_f = "
            f"{s['p_f_bar']:g} bar; "
            + ("" if "lock_up_time_s" not in s else
               f"slip {s['slip_at_ramp_end_rad_s']:.4g} rad/s at the ramp's "
               f"end, {lock_words(s)}; while slipping: ")
            + f"upstream speed peak "
            f"{s['speed_peak_amplitude_rpm']:.3g} rpm at "
            f"{s['speed_peak_freq_hz']:.2f} Hz"
            + (" (the dither frequency)"
               if s["peak_at_dither_frequency"] else "")
            + f"; pressure peak at {s['pressure_peak_freq_hz']:.2f} Hz"
            + ("" if s["judder"] is None else "; " + (
                burst_words(s) if s.get("judder_in_burst") else
                judder_words(s)))
            + ("; Floquet of the bench's linearisation (judder check's "
               "view of the bench): " if bench else
               "; Floquet of the class's linearisation: ")
            + f"{s['floquet_kind']} "
              f"({s['floquet_exponent_per_s']:+.2f} 1/s)"
            + ("" if s.get("orbit_kind") is None else
               "; settled motion (quasi-periodic, integrated): "
               if s["orbit_kind"] == "combination" else "; periodic orbit: ")
            + orbit_words(s)
            + ("" if s.get("linearisation_holds") is not False else
               "; nonlinear: " + nonlinear_words(s))
            + path_words(s))


def burst_words(s):
    """A run judged by its envelope: judder in a burst the whole run's
    spectrum averages below the limit, when and where."""
    return (f"judder in a burst, {s['mechanism']} ({s['judder_kind']}): "
            f"{s['envelope_peak_rpm']:.3g} rpm at {s['envelope_peak_hz']:.2f}"
            f" Hz, {s['envelope_peak_s']:.2f} s, slip "
            f"{s['envelope_peak_slip_rad_s']:.1f} rad/s; above "
            f"{s['judder_limit_rpm']:.3g} rpm from {s['judder_from_s']:.2f} "
            f"to {s['judder_to_s']:.2f} s (the whole run's spectrum: "
            f"{s['spectrum_oscillation_rpm']:.3g} rpm)")


def path_words(s):
    """The run's path through the map, where its slip moved: the mean
    slip from the ramp's end to the run's end, each span inside a tongue
    (exponent over --min-growth) with its times, slips, kind and the
    amplitude gain it predicts, and the gain over the whole run."""
    if s.get("path_efolds") is None or abs(
            s["path_slip_start_rad_s"] - s["path_slip_end_rad_s"]) < 0.5:
        return ""
    spans = "; ".join(
        f"inside a {span['kind']} tongue {span['start_s']:.2f}-"
        f"{span['stop_s']:.2f} s at {span['slip_start_rad_s']:.1f}-"
        f"{span['slip_stop_rad_s']:.1f} rad/s, x{math.exp(span['efolds']):.3g}"
        for span in s["path_spans"]) or "never inside a tongue"
    return (f"; path through the map (quasi-static): mean slip "
            f"{s['path_slip_start_rad_s']:.1f} -> "
            f"{s['path_slip_end_rad_s']:.1f} rad/s, {spans}; amplitude gain "
            f"over the run x{s['path_gain']:.3g}")
