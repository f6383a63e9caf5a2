"""The ``judder`` commands: parse the options, call :mod:`judder.api`,
write ``--out``/``--plot``, and format the result as text or JSON.

No computation lives here: each handler is the options of one command
turned into the arguments of its API function, and the result turned
into lines an engineer reads (Hz, bar, rpm).
"""

import math

import numpy as np

from infra.errors import JudderError, check_number
from infra.files import save_figure
from infra.units import PA_PER_BAR

from .. import api
from ..inputs import (read_boundary, read_boundary_min_growth,
                      read_chart_below, read_chart_boundary,
                      read_chart_min_growth)
from .values import (FREQ_RANGE_HZ, check_advise_grid, check_amplitudes,
                     check_campaign_disk, check_map_memory, check_work,
                     option_value)
from . import estimates
from .options import (emit, make_parents, model_title,
                      parameter_file, parameters_of, parse_grid, parse_list,
                      parse_waveform, Progress)

__all__ = ["cmd_params", "cmd_eig", "cmd_floquet", "cmd_map", "cmd_tongues",
           "cmd_sensitivity", "cmd_threshold", "cmd_fit", "cmd_simulate",
           "cmd_crosscheck", "cmd_campaign", "cmd_chart", "cmd_check",
           "cmd_advise", "cmd_report", "cmd_envelope"]

#: Multipliers of the nominal value in sensitivity without --factors.
DEFAULT_FACTORS = "0.5,2"
#: Fewest dither periods of a crosscheck run (the multipliers are fitted
#: to one sample per period).
MIN_CROSSCHECK_PERIODS = 20
#: Largest grid a map accepts, in points.
MAX_MAP_POINTS = 2_000_000


def _written(*paths):
    return "".join(f"\nwrote {p}" for p in paths if p)


def _files(**paths):
    return {name: (None if path is None else str(path))
            for name, path in paths.items()}


def _write_outputs(args, result, save=None, figure=None):
    """Write --out (``result.save``) and --plot (``result.figure``),
    atomically; keyword arguments for each; returns their paths."""
    if args.out:
        result.save(args.out, force=args.force, **(save or {}))
    if args.plot:
        _save_plot(args.plot, result.figure(**(figure or {})))
    return _files(out=args.out, plot=args.plot)


def _save_plot(path, figure):
    """Save a figure the command drew, then free it (``main`` may run
    many commands in one process)."""
    import matplotlib.pyplot as plt
    try:
        save_figure(path, figure)
    finally:
        plt.close(figure)


def _pf_max(args):
    return check_number("--pf-max", args.pf_max, "bar")


def cmd_params(args):
    """Show (and optionally save) the parameter set."""
    params, changes = parameters_of(args)
    result = api.params(params, changes)
    if args.save:
        make_parents(args.save)
        result.save(args.save, overwrite=args.force)
    specs = result.params.specs
    rows = [f"{'name':22s} {'value':14s} {'unit':10s} {'allowed':24s} "
            "meaning"]
    rows += [f"{name:22s} {result.params[name]:<14.6g} {spec.unit:10s} "
            f"{spec.allowed():24s} {spec.description}"
            for name, spec in specs.items()]
    emit(args, {**result.as_dict(), "saved": args.save},
         f"model {result.params.model}\n" + "\n".join(rows)
         + (f"\nsaved to {args.save}" if args.save else ""))


def cmd_eig(args):
    """Natural frequencies and the clutch-damper damping factor."""
    result = api.eig(*parameters_of(args))
    zeta = result.damping_factor_12
    lines = [f"model {result.params.model}",
             "undamped natural frequencies (Eq. 15): "
             + ", ".join(f"{f:.3f} Hz" for f in result.natural_frequencies_hz),
             "clutch-damper damping factor (Eq. 16): "
             + ("not defined (a formula of the paper's chains)"
                if zeta is None else f"{100 * zeta:.2f} %"),
             "damped modes without dither, rigid-body angles removed: "
             + ", ".join(f"{f:.3f} Hz ({100 * r:.2f} %)" for f, r in
                         zip(result.damped_frequencies_hz,
                             result.damping_ratio))]
    emit(args, result.as_dict(), "\n".join(lines))


def cmd_floquet(args):
    """Floquet multipliers at one dither frequency and amplitude."""
    check_number("--pf", args.pf, "bar", strict=False)
    params, changes = parameters_of(args)
    estimates.check_floquet(params.replace(**changes), args.freq, args.method)
    make_parents(args.plot)
    point = api.floquet(args.freq, args.pf, params, changes,
                        method=args.method,
                        waveform=parse_waveform(args.dither_wave))
    if args.plot:
        _save_plot(args.plot, point.figure(
            title=f"Floquet multipliers (Fig. 15), "
                  f"{model_title(args, params)}"))
    result = point.result
    lam = result.leading
    text = (f"f = {args.freq:g} Hz, p_f = {args.pf:g} bar: {result.kind}\n"
            f"leading multiplier {lam.real:.6f}{lam.imag:+.6f}i "
            f"(|lambda| = {result.leading_abs:.6f}), growth rate "
            f"{result.growth_rate:.4g} 1/s\nall multipliers (|lambda|): "
            + ", ".join(f"{abs(m):.6f}" for m in result.multipliers)
            + _written(args.plot))
    emit(args, {**point.as_dict(), **_files(plot=args.plot)}, text)


def _check_map_grid(values, freqs, amplitudes, options, method, tongues):
    """Refuse a map grid above :data:`MAX_MAP_POINTS`, or beyond the
    memory or the time limit, before any work."""
    if len(freqs) * len(amplitudes) > MAX_MAP_POINTS:
        raise JudderError(f"{options} has {len(freqs) * len(amplitudes)} "
                          f"points; allowed: at most {MAX_MAP_POINTS}")
    check_map_memory(values, freqs, amplitudes)
    estimates.check_map(values, freqs, amplitudes, method, tongues=tongues)


def cmd_map(args):
    """Stability map over a frequency x amplitude grid."""
    freqs = parse_grid(args.freq, "--freq", "Hz")
    amplitudes = parse_grid(args.pf, "--pf", "bar")
    params, changes = parameters_of(args)
    waveform = parse_waveform(args.dither_wave)
    # the exact boundaries are drawn on --plot and stored in --out
    exact = args.plot is not None or args.out is not None
    _check_map_grid(params.replace(**changes), freqs, amplitudes,
                    "--freq x --pf", args.method, exact)
    make_parents(args.out, args.plot)
    with Progress(len(freqs), "stability map") as progress:
        result = api.stability_map(
            freqs, amplitudes, params, changes, method=args.method,
            progress=progress,
            min_growth=check_number("--min-growth", args.min_growth, "1/s",
                                    strict=False),
            exact=exact, waveform=waveform)
    paper = {"3dof": "Fig. 12", "4dof": "Fig. 14"}.get(params.model)
    title = (f"stability map{f' ({paper})' if paper else ''}, "
             f"{model_title(args, params)}")
    files = _write_outputs(args, result,
                           save={"meta": {"preset": args.preset,
                                          "set": args.set,
                                          "dither_wave": args.dither_wave}},
                           figure={"title": title})
    counts = result.map.counts()
    text = (f"{result.map.kind.size} points in {result.seconds:.2f} s: "
            + ", ".join(f"{k} {v}" for k, v in counts.items())
            + _written(args.out, args.plot))
    emit(args, {**result.as_dict(), **files}, text)


def cmd_tongues(args):
    """Tongue boundaries, labels and tips."""
    freqs = parse_grid(args.freq, "--freq", "Hz")
    params, changes = parameters_of(args)
    waveform = parse_waveform(args.dither_wave)
    estimates.check_tongues(params.replace(**changes), freqs,
                            background=args.plot is not None)
    make_parents(args.out, args.plot)
    with Progress(len(freqs), "tongue boundaries") as progress:
        result = api.tongues(freqs, _pf_max(args), params, changes,
                             method=args.method, waveform=waveform,
                             background=args.plot is not None,
                             progress=progress,
                             min_growth=check_number("--min-growth",
                                                     args.min_growth, "1/s",
                                                     low=-math.inf),
                             solver=args.solver)
    data = {**result.as_dict(), **_write_outputs(args, result, figure={
        "title": f"tongue boundaries over the map, "
                 f"{model_title(args, params)}"})}
    rows = [f"{'#':>3} {'kind':14s} {'resonance':>10s} {'tip f [Hz]':>11s} "
            f"{'tip p_f [bar]':>14s} {'offset':>8s}"]
    for r in data["tongues"]:
        offset = ("" if r["tip_offset_percent"] is None
                  else f"{r['tip_offset_percent']:+.2f} %")
        rows.append(f"{r['number'] or '-':>3} {r['kind']:14s} "
                    f"{(r['resonance'] or '-'):>10s} {r['tip_freq_hz']:11.3f} "
                    f"{r['tip_p_f_bar']:14.4f} {offset:>8s}"
                    + ("  (tip at grid edge)" if r["tip_at_edge"] else ""))
    missing = _missing_tongues(result, freqs, _pf_max(args))
    if missing:
        rows.append(missing)
    rows.append(f"{len(freqs)} frequencies in {result.seconds:.2f} s; "
                "boundary points within "
                f"{result.boundaries.max_multiplier_error:.1e} of the unit "
                "circle")
    emit(args, data, "\n".join(rows) + _written(args.out, args.plot))


def _missing_tongues(result, freqs, p_max_bar):
    """A line naming the numbers no tongue got (numbers follow the
    resonances, Fig. 14's scheme for every mode), or ''."""
    from stability.tongues import resonances
    found = {t.number for t in result.tongues}
    gone = [f"{number} ({label}, {hz:.3g} Hz)" for number, label, hz, _
            in resonances(result.boundaries.natural_frequencies_hz)
            if number not in found]
    return ("" if not gone else
            "numbered by resonance; no tongue in "
            f"{freqs[0]:g}-{freqs[-1]:g} Hz up to {p_max_bar:g} bar for "
            + ", ".join(gone))


def cmd_sensitivity(args):
    """Tongue tips and boundaries with parameters varied (Fig. 17, 18)."""
    names = parse_list(args.params, "--params", str)
    freqs = parse_grid(args.freq, "--freq", "Hz")
    p_max_bar = _pf_max(args)
    params, changes = parameters_of(args)
    if args.values is not None and args.factors is not None:
        raise JudderError(f"--values {args.values} and --factors "
                          f"{args.factors} given; allowed: one of them")
    factors = parse_list(args.factors or DEFAULT_FACTORS, "--factors")
    values = parse_list(args.values, "--values") if args.values else None
    if values is None:
        for factor in factors:
            check_number("--factors", factor, "(factor)")
        values_now = params.replace(**changes)
        zero = [n for n in names if n in values_now.specs and
                values_now[n] == 0]
        if zero:
            raise JudderError(
                f"--params {zero[0]} is 0 in this parameter set, so "
                "--factors cannot vary it; allowed: --values for it, or a "
                "parameter with a non-zero value")
    make_parents(args.out, args.plot)
    cases = 1 + len(names) * len(values or factors)
    check_work("--params x --values/--factors", cases, "cases")
    estimates.check_sensitivity(params.replace(**changes), freqs, cases,
                                args.workers)
    with Progress(cases, "sensitivity cases") as progress:
        result = api.sensitivity(names, freqs, p_max_bar, factors=factors,
                                 values=values, parameters=params,
                                 changes=changes, method=args.method,
                                 workers=args.workers, progress=progress)
    files = _write_outputs(args, result, figure={
        "title": "sensitivity of the stability boundary (Fig. 17, 18), "
                 + model_title(args, params)})
    rows = [f"{'param':>8} {'factor':>7} {'value':>10} {'#':>2} "
            f"{'tip f [Hz]':>11} {'df [Hz]':>8} {'tip p_f':>8} {'dp_f':>8}"]
    for r in result.tip_shifts:
        if r["present"]:
            rows.append(f"{r['parameter']:>8} {r['factor']:7.3g} "
                        f"{r['value']:10.4g} {r['tongue']:>2} "
                        f"{r['tip_freq_hz']:11.3f} {r['d_freq_hz']:+8.2f} "
                        f"{r['tip_p_f_bar']:8.4f} {r['d_p_f_bar']:+8.4f}")
        else:
            rows.append(f"{r['parameter']:>8} {r['factor']:7.3g} "
                        f"{r['value']:10.4g} {r['tongue']:>2}   above "
                        f"{p_max_bar:g} bar (gone)")
    rows += [f"[{'holds' if c['holds'] else 'does NOT hold'}] "
             f"{c['statement']}: {c['evidence']}" for c in result.conclusions]
    rows.append(f"{result.cases} cases in {result.seconds:.1f} s")
    emit(args, {**result.as_dict(), **files},
         "\n".join(rows) + _written(args.out, args.plot))


def cmd_threshold(args):
    """Friction-gradient threshold without dither (Fig. 19)."""
    mu_g = parse_grid(args.mu_g, "--mu-g", "s/rad", allow_negative=True)
    damping = parse_grid(args.c_ext, "--c-ext", "N m s/rad")
    params, changes = parameters_of(args)
    make_parents(args.out, args.plot)
    with Progress(len(damping), "threshold") as progress:
        result = api.threshold(mu_g, damping, params, changes,
                               progress=progress)
    files = _write_outputs(args, result,
                           figure={"title": model_title(args, params)})
    study = result.study
    text = (f"threshold mu_g* = {study.threshold:.6g} s/rad for this set "
            f"(unstable without dither below it)")
    if result.slope is not None:
        text += (f"\nthreshold against c_i: slope {result.slope:.4g} s/rad "
                 f"per N m s/rad over c_i = {damping[0]:g}..{damping[-1]:g}")
    emit(args, {**result.as_dict(), **files},
         text + _written(args.out, args.plot))


def _bounds(items, params, names):
    """``NAME=LOW:HIGH`` strings of --bounds as ``{name: (low, high)}``,
    each a fitted parameter with LOW < HIGH both allowed for it (SI, or
    with units)."""
    from infra.quantities import parse_quantity
    bounds = {}
    for item in items:
        name, _, rng = item.partition("=")
        name = name.strip()
        parts = rng.split(":")
        if name not in names or len(parts) != 2:
            raise JudderError(f"--bounds {item!r} is not allowed; allowed: "
                              "NAME=LOW:HIGH with NAME one of --fit ("
                              f"{', '.join(names)})")
        spec = params.specs[name]
        low, high = (spec.check(parse_quantity(part, spec.unit,
                                               f"--bounds {name}"))
                     for part in parts)
        if not low < high:
            raise JudderError(f"--bounds {item!r} is not allowed; allowed: "
                              f"LOW < HIGH, each {spec.allowed()} "
                              f"[{spec.unit}]")
        bounds[name] = (low, high)
    return bounds


def _fit_names(text, params):
    names = parse_list(text, "--fit", str)
    unknown = [n for n in names if n not in params.specs]
    if unknown or len(set(names)) != len(names):
        raise JudderError(f"--fit {text!r} is not allowed; allowed: "
                          "distinct parameter names of the "
                          f"{params.model} model: {', '.join(params.specs)}")
    return names


def cmd_fit(args):
    """Fit parameters to a measured boundary (section 4.2, Fig. 16a)."""
    from infra.criteria import DEFAULT_MIN_GROWTH_PER_S
    from stability.decisions.relevance import CHART_THRESHOLD_SPREAD_PER_S
    params, changes = parameters_of(args)
    names = _fit_names(args.fit, params)
    bounds = _bounds(args.bounds, params, names)
    default_p_max = 1.5
    default_growth = DEFAULT_MIN_GROWTH_PER_S
    default_spread = CHART_THRESHOLD_SPREAD_PER_S if args.chart else 0.0
    if args.chart:
        freqs, measured, default_p_max = read_chart_boundary(args.chart,
                                                             args.group)
        default_growth = read_chart_min_growth(args.chart)
        below = read_chart_below(args.chart, args.group)
    else:
        freqs, measured = read_boundary(args.boundary)
        below = None
        stated = read_boundary_min_growth(args.boundary)
        default_growth = default_growth if stated is None else stated
    min_growth = check_number("--min-growth", default_growth
                              if args.min_growth is None else args.min_growth,
                              "1/s", strict=False)
    if args.bench and not args.bench_linearisation:
        raise JudderError("--bench is for --bench-linearisation; give both")
    bench = _bench_values(args.bench) if args.bench_linearisation else None
    p_max_bar = check_number("--pf-max", default_p_max if args.pf_max is None
                             else args.pf_max, "bar")
    scatter = _scatter(args.scatter, args.error_model)
    spread = check_number("--threshold-spread", default_spread
                          if args.threshold_spread is None
                          else args.threshold_spread, "1/s", strict=False)
    make_parents(args.plot, args.save_params)
    with Progress(None, "fit") as progress:
        report = api.fit(freqs, measured / PA_PER_BAR, p_max_bar,
                         names=names, bounds=bounds, parameters=params,
                         changes=changes, method=args.method,
                         starts=args.starts, uncertainty=args.uncertainty,
                         error_model=args.error_model, seed=args.seed,
                         workers=args.workers, progress=progress,
                         min_growth=min_growth, bench=bench,
                         scatter=scatter, below_bar=None if below is None
                         else below / PA_PER_BAR, threshold_spread=spread)
    result = report.fit
    if args.save_params:
        report.save_params(args.save_params, overwrite=args.force)
    if args.plot:
        _save_plot(args.plot, report.figure())
    rows = report.text()
    rows.append("compared with: " + _compared_with(result))
    rows += [f"note: {n}" for n in result.notes]
    rows += [f"problem: {p}" for p in result.problems]
    emit(args, {**report.as_dict(),
                **_files(saved_params=args.save_params, plot=args.plot)},
         "\n".join(rows) + _written(args.save_params, args.plot))
    if not result.success:
        raise JudderError("the fit cannot be trusted: "
                          + "; ".join(result.problems or [result.message]))


def _scatter(text, error_model):
    """``--scatter``: a share of the amplitude (relative error model) or
    Pa (absolute), or None."""
    from infra.quantities import parse_quantity
    if text is None:
        return None
    if error_model == "relative":
        share = parse_quantity(text, "1", "--scatter")
        if not 0 < share <= 1:
            raise JudderError(
                f"--scatter {text} is not allowed with the relative error "
                "model; allowed: a share of the amplitude above 0 and up to "
                "100 %, such as 3% or 0.03 (or --error-model absolute and "
                "a scatter in bar, such as 20mbar)")
        return share
    return check_number("--scatter", parse_quantity(
        text, "bar", "--scatter"), "bar") * PA_PER_BAR


def _compared_with(result):
    """Which model boundary the fit compared with, in words."""
    what = ("the stability boundary" if result.min_growth == 0 else
            f"the boundary of judder growing at {result.min_growth:g} 1/s "
            "or faster")
    model = (f"the {result.params.model} driveline" if not result.added else
             "the bench's linearisation (the driveline with "
             + ", ".join(f"{n} + {v:g}" for n, v in result.added) + ")")
    return f"{what} of {model}; fitted: {', '.join(result.names)}"


#: Bench parameters of ``simulate --bench``: unit and allowed range
#: (low, high, low_open, integer).
BENCH_PARAMETERS = {
    "w_motor": ("rad/s", 0.0, 2e3, True, False),
    "w_gearbox": ("rad/s", 0.0, 2e3, False, False),
    "w_op": ("rad/s", 0.0, 2e3, False, False),
    "delta_mu": ("1", 0.0, 1.0, True, False),
    "t_engage": ("s", 0.0, 3600.0, False, False),
    "t_ramp": ("s", 0.0, 3600.0, True, False),
    "p_load": ("Pa", 0.0, 1e8, False, False),
    "load_share": ("1", 0.0, 10.0, False, False),
    "N_c_load": ("1", 1.0, 100.0, False, True),
    "d_control": ("N m s/rad", 0.0, 1e7, False, False),
}


def _bench_values(assignments):
    """``NAME=VALUE`` strings of --bench, checked against
    :data:`BENCH_PARAMETERS` (SI, or with a unit: w_motor=1000rpm)."""
    from .values import option_value
    values = {}
    for text in assignments:
        name, sep, value = text.partition("=")
        name = name.strip()
        if not sep or name not in BENCH_PARAMETERS:
            raise JudderError(f"--bench {text!r} is not allowed; allowed: "
                              "NAME=VALUE with NAME one of "
                              f"{', '.join(BENCH_PARAMETERS)}")
        unit, low, high, low_open, integer = BENCH_PARAMETERS[name]
        number = option_value(value, f"--bench {name}", unit, low, high,
                              low_open)
        if integer and number != int(number):
            raise JudderError(f"--bench {text!r} is not allowed; allowed: a "
                              f"whole number from {low:g} to {high:g}")
        values[name] = number
    return values


def _engagement_line(s):
    growth = s["judder_growth_per_s"]
    return (f"{s['label']}: f = {s['freq_hz']:g} Hz, p_f = "
            f"{s['p_f_bar']:g} bar; upstream speed peak "
            f"{s['speed_peak_amplitude_rpm']:.3g} rpm at "
            f"{s['speed_peak_freq_hz']:.2f} Hz"
            + (" (the dither frequency)"
               if s["peak_at_dither_frequency"] else "")
            + f"; pressure peak at {s['pressure_peak_freq_hz']:.2f} Hz"
            + ("" if s["judder"] is None else
               "; judder: " + (s["judder_kind"] if s["judder"] else "none")
               + ("" if growth is None else
                  f" (non-periodic part grows at {growth:+.2f} 1/s)"))
            + f"; Floquet at this point: {s['floquet_kind']} "
              f"({s['floquet_exponent_per_s']:+.2f} 1/s)"
            + ("" if s.get("linearisation_holds") is not False else
               f"; nonlinear: the dither's forced slip swing "
               f"(+-{s['forced_slip_amplitude_rad_s']:.2g} rad/s) exceeds "
               f"the friction curve's linear range "
               f"(+-{s['friction_linear_range_rad_s']:.2g} rad/s), so the "
               "run need not follow the Floquet verdict"))


def cmd_simulate(args):
    """Engagement of the test-bench model with dither (Fig. 7, Fig. 8)."""
    freqs = [check_number("--freq", f, "Hz") for f in args.freq]
    check_number("--pf", args.pf, "bar", strict=False)
    check_number("--duration", args.duration, "s")
    params, changes = parameters_of(args)
    bench = _bench_values(args.bench)
    compare = None if args.compare is None else (
        "none" if args.compare == "none" else
        check_number("--compare", _float(args.compare, "--compare"), "Hz"))
    make_parents(args.out, args.plot)
    result = api.simulate(freqs if len(freqs) > 1 else freqs[0], args.pf,
                          duration=args.duration,
                          compare=compare, bench=bench, parameters=params,
                          changes=changes, method=args.method)
    files = _write_outputs(
        args, result,
        figure={"title": ("bench engagement of the EVEN clutch (Fig. 1, 7, "
                          "8)" if params.driveline is not None else
                          "time-domain run with dither")
                + f": {result.model_class.rsplit('.', 1)[-1]} FMU with the "
                  f"parameters of {model_title(args, params)}"})
    emit(args, {**result.as_dict(), **files},
         "\n".join(_engagement_line(s) for s in result.summaries)
         + _written(args.out, args.plot))


def _float(text, option):
    try:
        return float(text)
    except ValueError:
        raise JudderError(f"{option} {text!r} is not a number; allowed: a "
                          "frequency in Hz, or nothing for no dither") \
            from None


def cmd_crosscheck(args):
    """FMU growth rates against Floquet exponents on a grid."""
    freqs = parse_grid(args.freq, "--freq", "Hz")
    amplitudes = parse_grid(args.pf, "--pf", "bar")
    if freqs[0] <= 0:
        raise JudderError("--freq: allowed: frequencies > 0 Hz")
    check_number("--duration", args.duration, "s")
    if args.duration * freqs[0] < MIN_CROSSCHECK_PERIODS:
        raise JudderError(
            f"--duration {args.duration:g} s holds "
            f"{args.duration * freqs[0]:.3g} periods at {freqs[0]:g} Hz; "
            f"allowed: at least {MIN_CROSSCHECK_PERIODS} periods of the "
            f"lowest frequency (>= {MIN_CROSSCHECK_PERIODS / freqs[0]:.3g} s)"
            ", for the multipliers to be fitted")
    check_work("--freq x --pf", 2 * len(freqs) * len(amplitudes),
               "FMU runs")
    estimates.check_crosscheck(2 * len(freqs) * len(amplitudes),
                               args.duration, args.workers)
    params, changes = parameters_of(args)
    make_parents(args.out, args.plot)
    with Progress(len(freqs) * len(amplitudes), "FMU runs") as progress:
        result = api.crosscheck(freqs, amplitudes, duration=args.duration,
                                parameters=params, changes=changes,
                                method=args.method, workers=args.workers,
                                progress=progress, perturb=args.perturb)
    data = {**result.as_dict(), **_write_outputs(
        args, result, figure={"title": model_title(args, params)})}
    worst = data["max_rate_error_above_1_per_s"]
    text = (f"{data['points']} points in {result.seconds:.1f} s: verdicts "
            f"agree on {100 * data['agreement']:.1f} %; largest rate "
            "difference where the exponent > 1/s: "
            + ("none" if worst is None else f"{100 * worst:.2g} %")
            + "".join(f"\n  disagree at {r['freq_hz']:g} Hz, "
                      f"{r['p_f_bar']:g} bar: {r['reason']}"
                      for r in data["disagreements"])
            + _written(args.out, args.plot))
    emit(args, data, text)


def cmd_campaign(args):
    """Bench emulator: a campaign of engagement acquisitions."""
    from pysim.bench import TEMPERATURES
    freqs = parse_grid(args.freq, "--freq", "Hz")
    amplitudes = parse_grid(args.pf, "--pf", "bar")
    if freqs[0] <= 0:
        raise JudderError("--freq: allowed: frequencies > 0 Hz")
    rpm = [check_number("--rpm", n, "rpm")
           for n in parse_list(args.rpm, "--rpm")]
    temperatures = (list(TEMPERATURES) if args.temperatures == "all"
                    else [t.strip() for t in args.temperatures.split(",")])
    for option, values in (("--rpm", [f"{n:g}" for n in rpm]),
                           ("--temperatures", temperatures)):
        twice = next((v for i, v in enumerate(values) if v in values[:i]),
                     None)
        if twice is not None:
            raise JudderError(f"{option}: {twice} is given twice; allowed: "
                              "each value once (one run per setting)")
    formats = tuple(f.strip() for f in args.format.split(","))
    if not set(formats) <= {"csv", "mf4"} or not formats:
        raise JudderError(f"--format {args.format!r}: allowed: csv, mf4 or "
                          "csv,mf4")
    check_number("--duration", args.duration, "s")
    check_number("--noise-rpm", args.noise_rpm, "rpm", strict=False)
    params, changes = parameters_of(args)
    runs = (len(freqs) * len(amplitudes) * len(rpm) * len(temperatures))
    check_work("--freq x --pf x --rpm x --temperatures", runs, "runs")
    check_campaign_disk(args.out, runs, args.duration, max(rpm), formats)
    estimates.check_campaign(runs, args.duration, max(rpm), args.workers)
    with Progress(runs, "bench runs") as progress:
        result = api.campaign(args.out, freqs, amplitudes, engine_rpm=rpm,
                              temperatures=temperatures,
                              duration=args.duration,
                              noise_rpm=args.noise_rpm, seed=args.seed,
                              formats=formats, parameters=params,
                              changes=changes, workers=args.workers,
                              progress=progress)
    data = result.as_dict()
    text = (f"{data['runs']} runs ({data['ok']} ok"
            + (f"; {data['reused']} already in the folder with the same "
               "settings, kept" if data["reused"] else "")
            + f") in {result.seconds:.1f} s; index {result.index}"
            + "".join(f"\n  failed {r['run_id']}: {r['message']}"
                      for r in result.failed))
    emit(args, data, text)
    if result.failed:
        raise JudderError(f"{len(result.failed)} runs failed; the others "
                          "were written (run the same command again to "
                          "retry)")


def _channels(items):
    """``ROLE=NAME[:UNIT]`` strings as ``{role: ChannelSpec}`` (None if
    none given: the names judder campaign writes)."""
    from pysim.acquisitions import parse_channel_option
    if not items:
        return None
    channels = dict(parse_channel_option(item) for item in items)
    if "upstream_speed" not in channels:
        raise JudderError("--channel upstream_speed=NAME is required when "
                          "--channel is given")
    return channels


def cmd_chart(args):
    """Experimental stability chart from bench acquisitions."""
    channels = _channels(args.channel)
    check_number("--min-growth", args.min_growth, "1/s", strict=False)
    check_number("--min-amplitude", args.min_amplitude, "rpm", strict=False)
    overlay = bool(args.model or args.preset or args.param_file or args.set)
    params, changes = parameters_of(args)
    make_parents(args.out, args.plot, args.boundary)
    with Progress(None, "runs") as progress:
        result = api.chart(args.sources, index=args.index, channels=channels,
                           group_by=args.group_by,
                           min_growth=args.min_growth,
                           min_amplitude_rpm=args.min_amplitude,
                           model=overlay, parameters=params,
                           changes=changes, method=args.method,
                           workers=args.workers, progress=progress)
    files = _write_outputs(args, result, figure={
        "title": "experimental stability chart"
                 + (f" with the {params.model} model's boundaries"
                    if overlay else "")})
    boundaries = (result.save_boundary(args.boundary, force=args.force)
                  if args.boundary
                  and result.chart.read else [])
    data = {**result.as_dict(), **files, "boundary_files": boundaries}
    rows = []
    for group, runs in result.chart.groups().items():
        label = ", ".join(f"{c} {v}" for c, v in
                          zip(result.chart.group_by, group)) or "all runs"
        judder = sum(r.analysis.judder for r in runs)
        estimated = sum(r.analysis.estimated for r in runs)
        rows.append(f"{label}: {len(runs)} runs, {judder} with judder"
                    + (f" ({estimated} with the dither estimated from the "
                       "pressure)" if estimated else ""))
        for f, p, top in result.chart.boundary(group):
            rows.append(f"  {f:8.2f} Hz: " + (
                f"judder from {p:.3g} bar" if p is not None else
                f"no judder up to {top:.3g} bar"))
    rows += [f"could not read {r.path}: {r.error}"
             for r in result.chart.failed]
    rows.append(f"{len(result.chart.runs)} runs in {result.seconds:.1f} s"
                + _written(args.out, args.plot, *boundaries))
    emit(args, data, "\n".join(rows))
    if not result.chart.read:
        raise JudderError("no run could be read")



def _values(text, option, unit):
    """A comma-separated list or a START:STOP:N grid, each value plain
    (in ``unit``) or with a unit, in its documented range."""
    if ":" in text:
        return list(parse_grid(text, option, unit))
    low, high = FREQ_RANGE_HZ if unit == "Hz" else (0.0, math.inf)
    return parse_list(text, option, lambda item: option_value(
        item, option, unit, low, high))


def _settings(args, parameters):
    """Frequencies (Hz) and amplitudes (bar) of ``judder check``; the
    time of ``parameters`` sensitivity parameters per setting is estimated
    before the settings are made (a grid x grid of 1e10 would fill the
    memory first)."""
    from ..inputs import read_boundary
    if args.table:
        if args.freq or args.pf:
            raise JudderError("--table and --freq/--pf: allowed: one of them")
        freqs, p_f = read_boundary(args.table, "--table")
        if not len(freqs) or not all(math.isfinite(p) for p in p_f):
            raise JudderError(f"--table {args.table}: every row needs "
                              "freq_hz and p_f_bar; allowed: no empty cells")
        amplitudes = [p / PA_PER_BAR for p in p_f]
        check_amplitudes(amplitudes, f"--table {args.table}: p_f_bar")
        estimates.check_settings(len(freqs), parameters)
        check_work(f"--table {args.table}", len(freqs), "settings")
        low, high = FREQ_RANGE_HZ
        for row, f in enumerate(freqs, start=2):
            if not low <= f <= high:
                raise JudderError(
                    f"--table {args.table}: freq_hz {f:g} Hz (row {row}) is "
                    f"not allowed; allowed: {low:g} to {high:g} Hz")
        return list(freqs), amplitudes
    if not (args.freq and args.pf):
        raise JudderError("--freq and --pf are required (or --table)")
    freqs = _values(args.freq, "--freq", "Hz")
    amplitudes = _values(args.pf, "--pf", "bar")
    check_amplitudes(amplitudes, "--pf")
    # the time first (it says what to change); then, with the time limit
    # raised, the count (the pairs of 1e10 settings would not fit)
    estimates.check_settings(len(freqs) * len(amplitudes), parameters)
    check_work("--freq x --pf", len(freqs) * len(amplitudes), "settings")
    pairs = [(f, p) for f in freqs for p in amplitudes]
    return [f for f, _ in pairs], [p for _, p in pairs]


def cmd_check(args):
    """Verdict, growth and margins of dither settings."""
    if args.params is None:
        names = None
    elif args.params.strip().lower() == "none":
        names = []
    else:
        names = parse_list(args.params, "--params", str)
    freqs, amplitudes = _settings(args, len(
        api.DEFAULT_CHECK_PARAMETERS if names is None else names))
    check_amplitudes([args.pf_max], "--pf-max")
    if args.pf_max is not None and not args.pf_max > max(amplitudes):
        raise JudderError(f"--pf-max {args.pf_max:g} bar is not allowed; "
                          "allowed: above the largest setting, "
                          f"{max(amplitudes):g} bar")
    params, changes = parameters_of(args)
    make_parents(args.out, args.plot)
    with Progress(len(freqs), "check") as progress:
        result = api.check(freqs, amplitudes, params, changes,
                           min_growth=args.min_growth, p_max_bar=args.pf_max,
                           sensitivity=names, background=bool(args.plot),
                           progress=progress)
    data = {**result.as_dict(), **_write_outputs(
        args, result, figure={"title": model_title(args, params)})}
    emit(args, data, result.summary() + _written(args.out, args.plot))


def cmd_advise(args):
    """Safe dither windows, parameter ranking and design change."""
    low_high = args.freq_range.split(":")
    if len(low_high) != 2:
        raise JudderError(f"--freq-range {args.freq_range!r} is not "
                          "LOW:HIGH in Hz (e.g. 60:200, 90Hz:120Hz)")
    low, high = (option_value(v.strip(), "--freq-range", "Hz",
                              *FREQ_RANGE_HZ) for v in low_high)
    if not low < high:
        raise JudderError(f"--freq-range {args.freq_range} is not allowed; "
                          "allowed: LOW < HIGH")
    names = None if args.params is None else \
        parse_list(args.params, "--params", str)
    weights = None if args.weights is None else \
        parse_list(args.weights, "--weights")
    check_number("--pf-max", args.pf_max, "bar")
    check_number("--margin-bar", args.margin_bar, "bar", strict=False)
    check_number("--margin-hz", args.margin_hz, "Hz", strict=False)
    check_number("--min-growth", args.min_growth, "1/s", strict=False)
    check_amplitudes([args.pf_max], "--pf-max")
    check_advise_grid(args.freq_range, low, high, args.margin_hz)
    if math.isfinite(args.margin_bar) and math.isfinite(args.pf_max) and \
            args.margin_bar >= args.pf_max:
        raise JudderError(f"--margin-bar {args.margin_bar:g} bar is not "
                          "allowed; allowed: below --pf-max "
                          f"({args.pf_max:g} bar), the top of the operating "
                          "range")
    params, changes = parameters_of(args)
    extra = [parameter_file(args, path, "--also") for path in args.also]
    make_parents(args.out, args.plot)
    with Progress(8, "advise") as progress:
        result = api.advise(params, changes, extra_sets=extra,
                            freq_range=(low, high), p_max_bar=args.pf_max,
                            margin_bar=args.margin_bar,
                            margin_hz=args.margin_hz,
                            min_growth=args.min_growth, names=names,
                            weights=weights, design=not args.no_design,
                            progress=progress)
    data = {**result.as_dict(), **_write_outputs(
        args, result, figure={"title": model_title(args, params)})}
    emit(args, data, result.summary() + _written(args.out, args.plot))


def cmd_report(args):
    """The paper's figures and tables for one driveline, as one HTML
    file."""
    if (args.freq is None) != (args.pf is None):
        raise JudderError("--freq and --pf go together: give both for a "
                          "dither setting, or neither")
    if args.freq is not None:
        check_number("--freq", args.freq, "Hz")
        check_number("--pf", args.pf, "bar", strict=False)
        check_amplitudes([args.pf], "--pf")
    grid = parse_grid(args.grid, "--grid", "Hz")
    map_freq = parse_grid(args.map_freq, "--map-freq", "Hz")
    map_pf = parse_grid(args.map_pf, "--map-pf", "bar")
    if grid[0] <= 0 or map_freq[0] <= 0:
        raise JudderError("--grid, --map-freq: allowed: frequencies > 0 Hz")
    params, changes = parameters_of(args)
    _check_map_grid(params.replace(**changes), map_freq, map_pf,
                    "--map-freq x --map-pf", args.method, True)
    make_parents(args.out)
    with Progress(None, "report") as progress:
        result = api.report(
            params, changes, description=model_title(args, params),
            freq_hz=args.freq, p_f_bar=args.pf, chart=args.chart,
            boundary=args.boundary, group=args.group,
            fit_names=parse_list(args.fit, "--fit", str),
            sensitivity_names=(parse_list(args.sensitivity, "--sensitivity",
                                          str) if args.sensitivity else None),
            grid_freq=grid, map_freq=map_freq, map_pf=map_pf,
            p_max_bar=float(map_pf[-1]) if map_pf[-1] > 0 else 1.5,
            method=args.method, workers=args.workers,
            engagement=args.engagement, min_growth=args.min_growth,
            progress=progress)
    result.save(args.out, force=args.force)
    if args.pdf:
        make_parents(args.pdf)
        result.save_pdf(args.pdf, args.out, force=args.force)
    verdict = result.data.get("verdict")
    text = (f"{len(result.figures)} figures"
            + (f"; dither {args.freq:g} Hz, {args.pf:g} bar: "
               f"{verdict['verdict']}" if verdict else "")
            + (f"\nbench data: {result.data['fit_status']}"
               if "fit_status" in result.data else "")
            + _written(args.out, args.pdf))
    emit(args, {**result.as_dict(), **_files(out=args.out, pdf=args.pdf)},
         text)


def cmd_envelope(args):
    """Broadest unstable region over uncertain parameters (section 4.2)."""
    from ..envelope import checkpoint_path, read_ranges
    freqs = parse_grid(args.freq, "--freq", "Hz")
    p_max_bar = _pf_max(args)
    growth = check_number("--min-growth", args.min_growth, "1/s",
                          strict=False)
    for option, value in (("--samples", args.samples),
                          ("--refine", args.refine)):
        if value < 0:
            raise JudderError(f"{option} {value} is not allowed; allowed: a "
                              "whole number >= 0")
    params, changes = parameters_of(args)
    ranges = read_ranges(args.ranges, params.replace(**changes))
    estimates.check_envelope(params.replace(**changes), freqs, ranges,
                             args.samples, not args.no_vertices, args.refine,
                             args.workers)
    make_parents(args.out, args.csv, args.plot, args.checkpoint)
    checkpoint = args.checkpoint or checkpoint_path(args.out, args.csv,
                                                    args.plot)
    with Progress(None, "envelope samples") as progress:
        result = api.envelope(ranges, freqs, p_max_bar, samples=args.samples,
                              seed=args.seed, sampler=args.sampler,
                              vertices=not args.no_vertices,
                              min_growth=growth, refine=args.refine,
                              parameters=params, changes=changes,
                              method=args.method, workers=args.workers,
                              checkpoint=checkpoint, progress=progress)
    if args.out:
        result.save(args.out, force=args.force)
    if args.csv:
        result.save_csv(args.csv, force=args.force)
    if args.plot:
        _save_plot(args.plot, result.figure(
            title=f"envelope, {model_title(args, params)}"))
    result.discard_checkpoint()
    e, c = result.envelope, result.envelope.convergence
    lowest = e.broadest
    tip = (f"lowest point {np.nanmin(lowest) / PA_PER_BAR:.4f} bar at "
           f"{e.freq_hz[np.nanargmin(lowest)]:g} Hz"
           if np.isfinite(lowest).any() else
           f"stable up to {p_max_bar:g} bar at every frequency")
    text = (f"{int(e.ok.sum())} of {len(e.ok)} samples ({int(e.is_vertex.sum())}"
            f" vertices) over {', '.join(e.names)} in {result.seconds:.1f} s"
            + (f" ({result.resumed} from the checkpoint)" if result.resumed
               else "")
            + f"\nbroadest region: {tip}; area {c['refined_area_bar_hz']:.4g}"
            f" bar Hz\nconvergence: the last {c['last']} samples added "
            f"{100 * c['added_share']:.2g} % of the union's area (edge "
            f"lowered by up to {c['max_drop_bar']:.2g} bar); the refinement "
            f"between samples added {100 * c['refinement_added_share']:.2g} %"
            + _written(args.out, args.csv, args.plot))
    emit(args, {**result.as_dict(), **_files(out=args.out, csv=args.csv,
                                             plot=args.plot)}, text)
    if result.failures:
        raise JudderError(
            f"{len(result.failures)} samples failed and are left out (run "
            "again to retry them): " + "; ".join(
                str(f) for f in result.failures[:5]))
