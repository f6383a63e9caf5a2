"""Command line ``judder``: a thin layer over one facade function a command.

Units on the command line are those engineers read: dither frequency in
Hz, dither amplitude in bar. Parameters (``--set``) and files are SI.
Every command can print JSON (``--json``) for scripts. Errors in the input
give ``judder: error: ...`` and exit status 2; Ctrl-C exits with 130 and
leaves no partial output file.
"""

import argparse
import math
import sys
import time
from pathlib import Path

import numpy as np

from .errors import JudderError

__all__ = ["main", "build_parser", "parse_grid"]

PA_PER_BAR = 1e5
DEFAULT_FREQ = "5:250:300"
DEFAULT_PF = "0:1.5:150"
#: Largest grid a map accepts, in points.
MAX_MAP_POINTS = 2_000_000


def parse_grid(text, option, unit, allow_negative=False):
    """Parse ``START:STOP:N`` (or a single value) into a linspace.

    Raises
    ------
    JudderError
        Naming ``option`` and saying what is allowed.
    """
    parts = text.split(":")
    lowest = "" if allow_negative else "0 <= "
    allowed = (f"allowed: START:STOP:N with {lowest}START <= STOP in {unit} "
               f"and N a whole number >= 1, or one value "
               f"(e.g. {option} 10:220:300)")
    try:
        if len(parts) == 1:
            start = stop = float(parts[0])
            count = 1
        elif len(parts) == 3:
            start, stop = float(parts[0]), float(parts[1])
            count = int(parts[2])
        else:
            raise ValueError
    except ValueError:
        raise JudderError(f"{option} {text!r} is not a grid; {allowed}") \
            from None
    if not (np.isfinite(start) and np.isfinite(stop)) or start > stop \
            or (start < 0 and not allow_negative) or count < 1 \
            or (count == 1 and start != stop):
        raise JudderError(f"{option} {text!r} is not allowed; {allowed}")
    return np.linspace(start, stop, count)


def _resolve_parameters(args):
    """Parameters from --params/--preset/--model and --set."""
    from . import parameters as par
    if args.param_file is not None:
        if args.preset is not None:
            raise JudderError("give either --param-file FILE or --preset "
                              "NAME, not both")
        path = Path(args.param_file)
        try:
            text = path.read_text()
        except OSError as exc:
            raise JudderError(f"--param-file {path}: cannot read it "
                              f"({exc.strerror})") from None
        params = par.load_toml(text, source=str(path))
    else:
        name = args.preset or par.default_preset(args.model or "4dof")
        params = par.get_preset(name)
    if args.model is not None and args.model != params.model:
        raise JudderError(f"--model {args.model} does not match the "
                          f"{params.model} parameter set given")
    return params.with_overrides(args.set)


def _emit(args, data, text):
    from .output import to_json
    print(to_json(data) if args.json else text)


def cmd_params(args):
    """Show (and optionally save) the parameter set."""
    from .output import write_text
    from .parameters import SPECS, dumps_toml
    params = _resolve_parameters(args)
    if args.save:
        write_text(args.save, dumps_toml(params), overwrite=args.force)
    specs = SPECS[params.model]
    rows = [f"{name:22s} {params[name]:<14.6g} {spec.unit:10s} "
            f"{spec.description}" for name, spec in specs.items()]
    data = {"model": params.model,
            "parameters": {name: {"value": params[name], "unit": spec.unit,
                                  "description": spec.description}
                           for name, spec in specs.items()},
            "saved": args.save}
    _emit(args, data, f"model {params.model}\n" + "\n".join(rows)
          + (f"\nsaved to {args.save}" if args.save else ""))


def cmd_eig(args):
    """Natural frequencies and the clutch-damper damping factor."""
    from . import modal
    from .model import build_driveline
    params = _resolve_parameters(args)
    driveline = build_driveline(params)
    freqs = modal.natural_frequencies(driveline)
    zeta = modal.clutch_damper_damping_factor(params)
    damped_hz, ratio = modal.damped_modes(driveline)
    data = {"model": params.model,
            "natural_frequencies_hz": freqs,
            "closed_form_frequencies_hz": modal.closed_form_frequencies(params),
            "damping_factor_12": zeta,
            "damping_factor_12_percent": 100 * zeta,
            "damped_modes": [{"frequency_hz": f, "damping_ratio": r}
                             for f, r in zip(damped_hz, ratio)]}
    lines = [f"model {params.model}",
             "undamped natural frequencies (Eq. 15): "
             + ", ".join(f"{f:.3f} Hz" for f in freqs),
             f"clutch-damper damping factor (Eq. 16): {100 * zeta:.2f} %",
             "damped modes without dither: "
             + ", ".join(f"{f:.3f} Hz ({100 * r:.2f} %)"
                         for f, r in zip(damped_hz, ratio))]
    _emit(args, data, "\n".join(lines))


def cmd_floquet(args):
    """Floquet multipliers at one dither frequency and amplitude."""
    from .floquet import floquet
    from .model import build_driveline
    _check("--pf", args.pf, "bar", strict=False)
    params = _resolve_parameters(args)
    result = floquet(build_driveline(params), args.freq,
                     args.pf * PA_PER_BAR, method=args.method)
    data = {"model": params.model, "freq_hz": result.freq_hz,
            "p_f_bar": args.pf, "p_f_pa": result.p_f,
            "period_s": result.period, "method": args.method,
            "multipliers": result.multipliers, "leading": result.leading,
            "leading_abs": result.leading_abs, "kind": result.kind,
            "growth_rate_per_s": result.growth_rate,
            "exponents_per_s": result.exponents}
    lam = result.leading
    text = (f"f = {args.freq:g} Hz, p_f = {args.pf:g} bar: {result.kind}\n"
            f"leading multiplier {lam.real:.6f}{lam.imag:+.6f}i "
            f"(|lambda| = {result.leading_abs:.6f}), growth rate "
            f"{result.growth_rate:.4g} 1/s\nall multipliers (|lambda|): "
            + ", ".join(f"{abs(m):.6f}" for m in result.multipliers))
    _emit(args, data, text)


def cmd_map(args):
    """Stability map over a frequency x amplitude grid."""
    from .maps import stability_map
    from .model import build_driveline
    freqs = parse_grid(args.freq, "--freq", "Hz")
    amplitudes = parse_grid(args.pf, "--pf", "bar")
    if len(freqs) * len(amplitudes) > MAX_MAP_POINTS:
        raise JudderError(f"--freq x --pf has {len(freqs) * len(amplitudes)}"
                          f" points; allowed: at most {MAX_MAP_POINTS}")
    params = _resolve_parameters(args)
    for path in (args.out, args.plot):
        if path is not None and not Path(path).parent.is_dir():
            Path(path).parent.mkdir(parents=True, exist_ok=True)
    started = time.perf_counter()
    with _progress(len(freqs), "stability map") as callback:
        result = stability_map(build_driveline(params), freqs,
                               amplitudes * PA_PER_BAR, method=args.method,
                               callback=callback)
    seconds = time.perf_counter() - started
    meta = {"seconds": seconds, "preset": args.preset, "set": args.set}
    if args.out:
        from .output import save_map
        save_map(args.out, result, params, meta)
    if args.plot:
        from .output import save_figure
        from .plotting import map_figure
        title = (f"{params.model} stability map, "
                 f"{args.preset or args.param_file or 'default parameters'}")
        save_figure(args.plot, map_figure(result, title=title))
    counts = result.counts()
    data = {"model": params.model, "method": args.method,
            "points": int(result.kind.size), "seconds": seconds,
            "freq_hz": [freqs[0], freqs[-1], len(freqs)],
            "p_f_bar": [amplitudes[0], amplitudes[-1], len(amplitudes)],
            "counts": counts,
            "max_leading_abs": float(result.leading_abs.max()),
            "natural_frequencies_hz": result.natural_frequencies_hz,
            "out": args.out, "plot": args.plot}
    text = (f"{result.kind.size} points in {seconds:.2f} s: "
            + ", ".join(f"{k} {v}" for k, v in counts.items())
            + "".join(f"\nwrote {p}" for p in (args.out, args.plot) if p))
    _emit(args, data, text)


def _parse_list(text, option, convert=float):
    """Comma-separated values of ``option``."""
    items = [item.strip() for item in text.split(",") if item.strip()]
    try:
        values = [convert(item) for item in items]
    except ValueError:
        raise JudderError(f"{option} {text!r} is not a comma-separated list "
                          "of numbers") from None
    if not values:
        raise JudderError(f"{option} is empty")
    return values


def _check(option, value, unit, strict=True):
    """Raise JudderError unless ``value`` is finite and > 0 (>= 0)."""
    if value is None:
        return value
    ok = math.isfinite(value) and (value > 0 if strict else value >= 0)
    if not ok:
        raise JudderError(f"{option} {value:g} {unit} is not allowed; "
                          f"allowed: a finite value {'>' if strict else '>='}"
                          f" 0 {unit}")
    return value


def _positive_bar(value, option):
    return _check(option, value, "bar") * PA_PER_BAR


def _make_parents(*paths):
    for path in paths:
        if path is not None:
            Path(path).parent.mkdir(parents=True, exist_ok=True)


def _tongue_record(tongue):
    return {"number": tongue.number, "kind": tongue.kind,
            "resonance": tongue.resonance,
            "resonance_hz": tongue.resonance_hz,
            "tip_freq_hz": tongue.tip_freq_hz,
            "tip_p_f_bar": tongue.tip_p_f / PA_PER_BAR,
            "tip_offset_percent": None if tongue.resonance_hz is None else
            100 * (tongue.tip_freq_hz / tongue.resonance_hz - 1),
            "tip_multiplier_error": tongue.tip_multiplier_error,
            "freq_range_hz": list(tongue.freq_range_hz),
            "tip_at_edge": tongue.tip_at_edge}


def _boundaries_csv(boundaries):
    lines = ["freq_hz,p_f_bar,single_period_bar,double_period_bar,"
             "combination_bar"]
    cell = (lambda v: "" if not math.isfinite(v) else f"{v / PA_PER_BAR:.9g}")
    for f, lowest, row in zip(boundaries.freq_hz,
                              boundaries.stability_boundary,
                              boundaries.amplitude):
        lines.append(",".join([f"{f:.9g}", cell(lowest)]
                              + [cell(v) for v in row]))
    return "\n".join(lines) + "\n"


def cmd_tongues(args):
    """Tongue boundaries, labels and tips."""
    from .maps import stability_map
    from .model import build_driveline
    from .tongues import find_tongues, tongue_boundaries
    freqs = parse_grid(args.freq, "--freq", "Hz")
    p_max = _positive_bar(args.pf_max, "--pf-max")
    params = _resolve_parameters(args)
    driveline = build_driveline(params)
    _make_parents(args.out, args.plot)
    started = time.perf_counter()
    with _progress(len(freqs), "tongue boundaries") as callback:
        boundaries = tongue_boundaries(driveline, freqs, p_max,
                                       callback=callback)
    tongues = find_tongues(driveline, boundaries)
    seconds = time.perf_counter() - started
    if args.out:
        from .output import write_text
        write_text(args.out, _boundaries_csv(boundaries))
    if args.plot:
        from .output import save_figure
        from .plotting import tongues_figure
        background = stability_map(driveline, freqs,
                                   np.linspace(0, p_max, 150))
        save_figure(args.plot, tongues_figure(
            boundaries, tongues, background,
            title=f"{params.model}: tongue boundaries over the map"))
    records = [_tongue_record(t) for t in tongues]
    data = {"model": params.model, "seconds": seconds,
            "freq_hz": [freqs[0], freqs[-1], len(freqs)],
            "p_max_bar": args.pf_max,
            "max_boundary_multiplier_error": boundaries.max_multiplier_error,
            "natural_frequencies_hz": boundaries.natural_frequencies_hz,
            "tongues": records, "out": args.out, "plot": args.plot}
    rows = [f"{'#':>3} {'kind':14s} {'resonance':>10s} {'tip f [Hz]':>11s} "
            f"{'tip p_f [bar]':>14s} {'offset':>8s}"]
    for r in records:
        offset = ("" if r["tip_offset_percent"] is None
                  else f"{r['tip_offset_percent']:+.2f} %")
        rows.append(f"{r['number'] or '-':>3} {r['kind']:14s} "
                    f"{(r['resonance'] or '-'):>10s} {r['tip_freq_hz']:11.3f} "
                    f"{r['tip_p_f_bar']:14.4f} {offset:>8s}"
                    + ("  (tip at grid edge)" if r["tip_at_edge"] else ""))
    rows.append(f"{len(freqs)} frequencies in {seconds:.2f} s; boundary "
                f"points within {boundaries.max_multiplier_error:.1e} of the "
                "unit circle")
    rows += [f"wrote {p}" for p in (args.out, args.plot) if p]
    _emit(args, data, "\n".join(rows))


def cmd_sensitivity(args):
    """Tongue tips and boundaries with parameters varied (Fig. 17, 18)."""
    from .parameters import SPECS
    from .sensitivity import paper_conclusions, sensitivity_study, tip_shifts
    names = _parse_list(args.params, "--params", str)
    freqs = parse_grid(args.freq, "--freq", "Hz")
    p_max = _positive_bar(args.pf_max, "--pf-max")
    params = _resolve_parameters(args)
    for name in names:
        if name not in SPECS[params.model]:
            raise JudderError(f"--params: unknown parameter {name!r} for the "
                              f"{params.model} model; allowed names: "
                              f"{', '.join(SPECS[params.model])}")
    factors = _parse_list(args.factors, "--factors")
    values = _parse_list(args.values, "--values") if args.values else None
    if values is None:
        for factor in factors:
            _check("--factors", factor, "(factor)")
    _make_parents(args.out, args.plot)
    started = time.perf_counter()
    cases = 1 + len(names) * len(values or factors)
    with _progress(cases, "sensitivity cases") as callback:
        study = sensitivity_study(params, names, freqs, p_max,
                                  factors=factors, values=values,
                                  workers=args.workers, callback=callback)
    seconds = time.perf_counter() - started
    table = tip_shifts(study)
    conclusions = paper_conclusions(study) if params.model == "4dof" else []
    if args.out:
        from .output import write_text
        columns = list(table[0]) if table else []
        lines = [",".join(columns)] + [
            ",".join("" if row[c] is None else str(row[c]) for c in columns)
            for row in table]
        write_text(args.out, "\n".join(lines) + "\n")
    if args.plot:
        from .output import save_figure
        save_figure(args.plot, study.plot(
            title=f"{params.model}: sensitivity of the stability boundary"))
    data = {"model": params.model, "seconds": seconds, "cases": cases,
            "nominal_tongues": [_tongue_record(t)
                                for t in study.nominal.tongues],
            "tip_shifts": table, "paper_conclusions": conclusions,
            "out": args.out, "plot": args.plot}
    rows = [f"{'param':>8} {'factor':>7} {'value':>10} {'#':>2} "
            f"{'tip f [Hz]':>11} {'df [Hz]':>8} {'tip p_f':>8} {'dp_f':>8}"]
    for r in table:
        if r["present"]:
            rows.append(f"{r['parameter']:>8} {r['factor']:7.3g} "
                        f"{r['value']:10.4g} {r['tongue']:>2} "
                        f"{r['tip_freq_hz']:11.3f} {r['d_freq_hz']:+8.2f} "
                        f"{r['tip_p_f_bar']:8.4f} {r['d_p_f_bar']:+8.4f}")
        else:
            rows.append(f"{r['parameter']:>8} {r['factor']:7.3g} "
                        f"{r['value']:10.4g} {r['tongue']:>2}   above "
                        f"{args.pf_max:g} bar (gone)")
    rows += [f"[{'holds' if c['holds'] else 'does NOT hold'}] "
             f"{c['statement']}: {c['evidence']}" for c in conclusions]
    rows.append(f"{cases} cases in {seconds:.1f} s")
    rows += [f"wrote {p}" for p in (args.out, args.plot) if p]
    _emit(args, data, "\n".join(rows))


def cmd_threshold(args):
    """Friction-gradient threshold without dither (Fig. 19)."""
    from .threshold import threshold_study
    mu_g = parse_grid(args.mu_g, "--mu-g", "s/rad", allow_negative=True)
    damping = parse_grid(args.c_ext, "--c-ext", "N m s/rad")
    params = _resolve_parameters(args)
    explicit = any(a.split("=")[0].strip() == "mean_pressure_damping"
                   for a in args.set)
    if not explicit:
        params = params.replace(mean_pressure_damping=1.0)
    _make_parents(args.out, args.plot)
    with _progress(len(damping), "threshold") as callback:
        study = threshold_study(params, mu_g, damping, callback=callback)
    if args.out:
        from .output import write_text
        lines = ["c_ext,mu_g_threshold,mu_g_threshold_closed_form"] + [
            f"{c:.9g},{m:.9g},{k:.9g}" for c, m, k in
            zip(study.external_damping, study.thresholds, study.closed_form)]
        write_text(args.out, "\n".join(lines) + "\n")
    if args.plot:
        import matplotlib.pyplot as plt
        from .output import save_figure
        fig, axes = plt.subplots(1, 2, figsize=(11, 4), layout="constrained")
        study.plot(axes=axes)
        save_figure(args.plot, fig)
    data = {"model": params.model,
            "mean_pressure_damping": params["mean_pressure_damping"],
            "mu_g": study.mu_g, "max_real_part_per_s": study.max_real_part,
            "mu_g_threshold": study.threshold,
            "external_damping": study.external_damping,
            "mu_g_thresholds": study.thresholds,
            "mu_g_thresholds_closed_form": study.closed_form,
            "out": args.out, "plot": args.plot}
    slope = np.polyfit(study.external_damping, study.thresholds, 1)[0] \
        if len(damping) > 1 else float("nan")
    text = (f"threshold mu_g* = {study.threshold:.6g} s/rad for this set "
            f"(unstable without dither below it)\n"
            f"threshold against c_i: slope {slope:.4g} s/rad per N m s/rad "
            f"over c_i = {damping[0]:g}..{damping[-1]:g}"
            + "".join(f"\nwrote {p}" for p in (args.out, args.plot) if p))
    _emit(args, data, text)


def cmd_fit(args):
    """Fit parameters to a measured boundary (section 4.2, Fig. 16a)."""
    from .fitting import fit_boundary, read_boundary_csv
    names = _parse_list(args.fit, "--fit", str)
    p_max = _positive_bar(args.pf_max, "--pf-max")
    params = _resolve_parameters(args)
    path = Path(args.boundary)
    try:
        text = path.read_text()
    except OSError as exc:
        raise JudderError(f"--boundary {path}: cannot read it "
                          f"({exc.strerror})") from None
    freqs, measured = read_boundary_csv(text, source=str(path))
    bounds = {}
    for item in args.bounds:
        name, sep, rng = item.partition("=")
        parts = rng.split(":")
        try:
            low, high = float(parts[0]), float(parts[1])
        except (ValueError, IndexError):
            raise JudderError(f"--bounds {item!r} is not NAME=LOW:HIGH") \
                from None
        bounds[name.strip()] = (low, high)
    _make_parents(args.plot, args.save_params)
    started = time.perf_counter()
    result = fit_boundary(params, freqs, measured, p_max, names=names,
                          bounds=bounds)
    seconds = time.perf_counter() - started
    if args.save_params:
        from .output import write_text
        from .parameters import dumps_toml
        write_text(args.save_params, dumps_toml(result.params),
                   overwrite=args.force)
    if args.plot:
        from .output import save_figure
        save_figure(args.plot, result.plot()[0].figure)
    data = {"model": params.model, "seconds": seconds,
            "success": result.success, "message": result.message,
            "fitted": {n: {"value": v, "std": s, "start": s0}
                       for n, v, s, s0 in zip(result.names, result.values,
                                              result.std, result.start)},
            "residual_rms_bar": result.residual_rms_bar,
            "evaluations": result.evaluations,
            "freq_hz": result.freq_hz, "measured_bar": result.measured_bar,
            "model_bar": result.model_bar,
            "saved_params": args.save_params, "plot": args.plot}
    rows = [f"{n:>8} = {v:.6g} ± {s:.2g}  (start {s0:.6g})"
            for n, v, s, s0 in zip(result.names, result.values, result.std,
                                   result.start)]
    rows.append(f"residual rms {result.residual_rms_bar:.4g} bar over "
                f"{len(freqs)} points; {result.evaluations} model boundaries "
                f"in {seconds:.1f} s; {result.message}")
    rows += [f"wrote {p}" for p in (args.save_params, args.plot) if p]
    _emit(args, data, "\n".join(rows))
    if not result.success:
        raise JudderError("the fit did not converge: " + result.message)


def _bench_values(assignments):
    values = {}
    for text in assignments:
        name, sep, value = text.partition("=")
        try:
            values[name.strip()] = float(value)
        except ValueError:
            raise JudderError(f"--bench {text!r} is not NAME=VALUE with a "
                              "number") from None
        if not sep or not math.isfinite(values[name.strip()]):
            raise JudderError(f"--bench {text!r} is not NAME=VALUE with a "
                              "finite number")
    return values


def _run_summary(run, start):
    from pysim.signals import amplitude_spectrum, dither_envelope
    keep = run.time >= start
    if run.p_f > 0:
        envelope, growth = dither_envelope(run.time, run["w_upstream"],
                                           run.freq_hz, start)
    else:
        envelope, growth = np.zeros(1), float("nan")
    speed = amplitude_spectrum(run.time[keep], run["w_upstream"][keep])
    pressure = amplitude_spectrum(run.time[keep],
                                  run["actuation_pressure"][keep])
    resolution = 1.0 / max(run.time[keep][-1] - run.time[keep][0], 1e-9)
    line = int(np.argmin(np.abs(speed.freq_hz - run.freq_hz)))
    return {"freq_hz": run.freq_hz, "p_f_bar": run.p_f / PA_PER_BAR,
            "speed_peak_freq_hz": speed.peak_freq_hz,
            "speed_peak_amplitude_rpm": speed.peak_amplitude * 60 / (2 * np.pi),
            "speed_amplitude_at_dither_rpm":
                float(speed.amplitude[line]) * 60 / (2 * np.pi),
            "pressure_peak_freq_hz": pressure.peak_freq_hz,
            "pressure_peak_amplitude_bar":
                pressure.peak_amplitude / PA_PER_BAR,
            "peak_at_dither_frequency":
                bool(abs(speed.peak_freq_hz - run.freq_hz) <= 2 * resolution),
            "judder_growth_per_s": growth,
            "dither_envelope_max_rpm": float(envelope.max()) * 60 / (2 * np.pi),
            "final_slip_rad_s": float(run["slip"][-1])}


def cmd_simulate(args):
    """Engagement of the test-bench model with dither (Fig. 7, Fig. 8)."""
    from pysim.export import write_run
    from pysim.fmus import ensure_fmu
    from pysim.runs import SIGNALS, run_fmu
    _check("--freq", args.freq, "Hz")
    _check("--pf", args.pf, "bar", strict=False)
    _check("--duration", args.duration, "s")
    params = _resolve_parameters(args)
    if params.model != "4dof":
        raise JudderError("the bench engagement model is 4-DOF; give a "
                          "4-DOF preset or parameter file")
    bench = _bench_values(args.bench)
    fmu = ensure_fmu("TestBenchEngagement")
    interval = min(1e-3, 1.0 / (20 * args.freq))
    settings = [("with dither", args.freq, args.pf * PA_PER_BAR)]
    if args.compare is not None:
        settings.append(("without dither", args.freq, 0.0)
                        if args.compare == "none" else
                        (f"dither at {float(args.compare):g} Hz",
                         float(args.compare), args.pf * PA_PER_BAR))
    _make_parents(args.out, args.plot)
    runs = []
    for label, freq, p_f in settings:
        runs.append((label, run_fmu(fmu, freq, p_f, params=params,
                                    extra=bench, duration=args.duration,
                                    output_interval=interval)))
    start = (bench.get("t_engage", _fmu_default(fmu, "t_engage"))
             + bench.get("t_ramp", _fmu_default(fmu, "t_ramp")))
    from .floquet import floquet
    from .model import build_driveline
    driveline = build_driveline(params)
    summaries = []
    for label, run in runs:
        linear = floquet(driveline, run.freq_hz, run.p_f)
        summaries.append({"label": label, **_run_summary(run, start),
                          "floquet_kind": linear.kind,
                          "floquet_exponent_per_s": linear.growth_rate})
    if args.out:
        run = runs[0][1]
        write_run(args.out, run.time, run.signals, SIGNALS,
                  {"model": "Judder.Examples.TestBenchEngagement",
                   "freq_hz": run.freq_hz, "p_f_bar": run.p_f / PA_PER_BAR,
                   "start_values": run.start_values})
    if args.plot:
        from pysim.plotting import run_figure
        from .output import save_figure
        save_figure(args.plot, run_figure(
            runs, start=start, title="bench engagement, EVEN clutch at "
                                     "1000 rpm"))
    data = {"model": "TestBenchEngagement", "fmu": str(fmu),
            "runs": summaries, "out": args.out, "plot": args.plot}
    rows = []
    for s in summaries:
        rows.append(f"{s['label']}: f = {s['freq_hz']:g} Hz, p_f = "
                    f"{s['p_f_bar']:g} bar; upstream speed peak "
                    f"{s['speed_peak_amplitude_rpm']:.3g} rpm at "
                    f"{s['speed_peak_freq_hz']:.2f} Hz"
                    + (" (the dither frequency)"
                       if s["peak_at_dither_frequency"] else "")
                    + f"; pressure peak at {s['pressure_peak_freq_hz']:.2f} Hz"
                    + ("" if math.isnan(s["judder_growth_per_s"]) else
                       f"; oscillation at the dither frequency "
                       f"{'grows' if s['judder_growth_per_s'] > 0 else 'decays'}"
                       f" at {s['judder_growth_per_s']:+.2f} 1/s after the "
                       "ramp")
                    + f"; Floquet at this point: {s['floquet_kind']} "
                      f"({s['floquet_exponent_per_s']:+.2f} 1/s)")
    rows += [f"wrote {p}" for p in (args.out, args.plot) if p]
    _emit(args, data, "\n".join(rows))


def _fmu_default(fmu, name):
    from fmpy import read_model_description
    return float(next(v.start for v in read_model_description(
        str(fmu)).modelVariables if v.name == name))


def cmd_crosscheck(args):
    """FMU growth rates against Floquet exponents on a grid."""
    from pysim.crosscheck import crosscheck
    freqs = parse_grid(args.freq, "--freq", "Hz")
    amplitudes = parse_grid(args.pf, "--pf", "bar")
    if freqs[0] <= 0:
        raise JudderError("--freq: allowed: frequencies > 0 Hz")
    _check("--duration", args.duration, "s")
    params = _resolve_parameters(args)
    _make_parents(args.out, args.plot)
    started = time.perf_counter()
    with _progress(len(freqs) * len(amplitudes), "FMU runs") as callback:
        check = crosscheck(params, freqs, amplitudes * PA_PER_BAR,
                           duration=args.duration, workers=args.workers,
                           callback=callback)
    seconds = time.perf_counter() - started
    rows = [{"freq_hz": p.freq_hz, "p_f_bar": p.p_f / PA_PER_BAR,
             "floquet_kind": p.floquet_kind,
             "floquet_rate_per_s": p.floquet_rate,
             "fitted_rate_per_s": p.fitted_rate,
             "floquet_unstable": p.floquet_unstable,
             "time_unstable": p.time_unstable, "agree": p.agree,
             "reason": p.reason} for p in check.points]
    if args.out:
        from .output import write_text
        columns = list(rows[0])
        lines = [",".join(columns)] + [",".join(
            f'"{r[c]}"' if c == "reason" else str(r[c]) for c in columns)
            for r in rows]
        write_text(args.out, "\n".join(lines) + "\n")
    if args.plot:
        from pysim.plotting import crosscheck_figure
        from .output import save_figure
        save_figure(args.plot, crosscheck_figure(check))
    worst = check.max_rate_error(above=1.0)
    data = {"model": params.model, "points": len(rows), "seconds": seconds,
            "duration_s": args.duration, "agreement": check.agreement,
            "max_rate_error_above_1_per_s": worst,
            "disagreements": [r for r in rows if not r["agree"]],
            "out": args.out, "plot": args.plot}
    text = (f"{len(rows)} points in {seconds:.1f} s: verdicts agree on "
            f"{100 * check.agreement:.1f} %; largest rate difference where "
            f"the exponent > 1/s: "
            + ("none" if worst is None else f"{100 * worst:.2g} %")
            + "".join(f"\n  disagree at {r['freq_hz']:g} Hz, "
                      f"{r['p_f_bar']:g} bar: {r['reason']}"
                      for r in rows if not r["agree"])
            + "".join(f"\nwrote {p}" for p in (args.out, args.plot) if p))
    _emit(args, data, text)


def cmd_campaign(args):
    """Bench emulator: a campaign of engagement acquisitions."""
    from pysim.bench import TEMPERATURES, Campaign, run_campaign
    freqs = parse_grid(args.freq, "--freq", "Hz")
    amplitudes = parse_grid(args.pf, "--pf", "bar")
    if freqs[0] <= 0:
        raise JudderError("--freq: allowed: frequencies > 0 Hz")
    rpm = [_check("--rpm", n, "rpm") for n in _parse_list(args.rpm, "--rpm")]
    temperatures = (list(TEMPERATURES) if args.temperatures == "all"
                    else [t.strip() for t in args.temperatures.split(",")])
    formats = tuple(f.strip() for f in args.format.split(","))
    if not set(formats) <= {"csv", "mf4"} or not formats:
        raise JudderError(f"--format {args.format!r}: allowed: csv, mf4 or "
                          "csv,mf4")
    _check("--duration", args.duration, "s")
    _check("--noise-rpm", args.noise_rpm, "rpm", strict=False)
    params = _resolve_parameters(args)
    campaign = Campaign(freq_hz=tuple(freqs), p_f_bar=tuple(amplitudes),
                        engine_rpm=tuple(rpm), temperatures=tuple(temperatures),
                        duration=args.duration, noise_rpm=args.noise_rpm,
                        formats=formats, seed=args.seed)
    started = time.perf_counter()
    with _progress(len(campaign.runs()), "bench runs") as callback:
        rows = run_campaign(campaign, params, args.out, workers=args.workers,
                            callback=callback)
    seconds = time.perf_counter() - started
    failed = [r for r in rows if r["status"] != "ok"]
    data = {"runs": len(rows), "ok": len(rows) - len(failed),
            "failed": failed, "index": str(Path(args.out) / "index.csv"),
            "seconds": seconds}
    text = (f"{len(rows)} runs ({len(rows) - len(failed)} ok) in "
            f"{seconds:.1f} s; index {data['index']}"
            + "".join(f"\n  failed {r['run_id']}: {r['message']}"
                      for r in failed))
    _emit(args, data, text)
    if failed:
        raise JudderError(f"{len(failed)} runs failed; the others were "
                          "written (run the same command again to retry)")


class _progress:
    """tqdm bar on stderr (shown on a terminal only) as a map callback."""

    def __init__(self, total, description):
        from tqdm import tqdm
        self._bar = tqdm(total=total, desc=description, unit="freq",
                         disable=None, file=sys.stderr)

    def __enter__(self):
        return self._update

    def _update(self, done, total):
        self._bar.update(done - self._bar.n)

    def __exit__(self, *exc):
        self._bar.close()
        return False


def _model_options(parser):
    group = parser.add_argument_group(
        "model", "Parameter set: a preset or a TOML file, then --set "
        "overrides. Values in SI units (see `judder params`).")
    group.add_argument("--model", choices=("4dof", "3dof"),
                       help="model; picks the paper's preset for it "
                            "(default 4dof)")
    group.add_argument("--preset",
                       help="paper-4dof (Appendix A), paper-4dof-fitted "
                            "(section 4.2) or paper-3dof")
    group.add_argument("--param-file", metavar="FILE.toml",
                       help="parameter file (see `judder params --save`)")
    group.add_argument("--set", action="append", default=[],
                       metavar="NAME=VALUE",
                       help="override one parameter, SI units; repeatable "
                            "(e.g. --set c12=10 --set "
                            "mean_pressure_damping=1)")
    parser.add_argument("--json", action="store_true",
                        help="print the result as JSON")


def _pf_max_option(parser, meaning):
    parser.add_argument("--pf-max", type=float, default=1.5, metavar="BAR",
                        help=f"{meaning}, bar (default 1.5)")


def _workers_option(parser):
    parser.add_argument("--workers", type=int, default=None,
                        help="processes (default: all cores)")


def _method_option(parser):
    parser.add_argument("--method", default="dyson",
                        choices=("dyson", "solve_ivp"),
                        help="monodromy engine: dyson (fast, default) or "
                             "solve_ivp (per-point reference)")


def build_parser():
    """The argparse parser of ``judder``."""
    parser = argparse.ArgumentParser(
        prog="judder",
        description="Clutch judder from parametric excitation by hydraulic "
                    "dither: Floquet stability of the 3-DOF and 4-DOF "
                    "driveline. Frequencies in Hz, dither amplitude in bar, "
                    "parameters in SI units.")
    sub = parser.add_subparsers(dest="command", required=True,
                                metavar="COMMAND")

    p = sub.add_parser("params", help="show, or save as TOML, a parameter set",
                       description="Show a parameter set with units, or save "
                                   "it (--save FILE.toml) to edit and load "
                                   "with --param-file.")
    _model_options(p)
    p.add_argument("--save", metavar="FILE.toml",
                   help="write the set as TOML (never overwrites unless "
                        "--force)")
    p.add_argument("--force", action="store_true",
                   help="allow --save to replace an existing file")
    p.set_defaults(handler=cmd_params)

    p = sub.add_parser("eig", help="natural frequencies and damping factor",
                       description="Undamped natural frequencies (Eq. 14-15, "
                                   "Hz), clutch-damper damping factor "
                                   "(Eq. 16) and the damped modes without "
                                   "dither.")
    _model_options(p)
    p.set_defaults(handler=cmd_eig)

    p = sub.add_parser("floquet", help="Floquet multipliers at one point",
                       description="Monodromy matrix over one dither period "
                                   "and its Floquet multipliers (Eq. 10-13), "
                                   "rigid-body angles removed; the leading "
                                   "multiplier is classified as in Fig. 15.")
    p.add_argument("--freq", type=float, required=True, metavar="HZ",
                   help="dither frequency, Hz")
    p.add_argument("--pf", type=float, required=True, metavar="BAR",
                   help="dither amplitude p_f, bar (1 bar = 1e5 Pa)")
    _method_option(p)
    _model_options(p)
    p.set_defaults(handler=cmd_floquet)

    p = sub.add_parser("map", help="stability map over frequency x amplitude",
                       description="Leading Floquet multiplier on a grid of "
                                   "dither frequency (Hz) x amplitude (bar), "
                                   "classified single-period, double-period "
                                   "or combination (Fig. 14). Ctrl-C stops it "
                                   "without writing a partial file.")
    p.add_argument("--freq", default=DEFAULT_FREQ, metavar="START:STOP:N",
                   help=f"dither frequencies, Hz (default {DEFAULT_FREQ})")
    p.add_argument("--pf", default=DEFAULT_PF, metavar="START:STOP:N",
                   help=f"dither amplitudes, bar (default {DEFAULT_PF})")
    p.add_argument("--out", metavar="FILE.npz",
                   help="save the map arrays (NPZ, see README)")
    p.add_argument("--plot", metavar="FILE.png",
                   help="save a plot of the map (PNG, SVG or PDF)")
    _method_option(p)
    _model_options(p)
    p.set_defaults(handler=cmd_map)

    p = sub.add_parser("tongues", help="tongue boundaries, labels and tips",
                       description="Exact tongue boundaries: single- and "
                                   "double-period by Hill's method, "
                                   "combination by Brent's method on the "
                                   "monodromy; each point checked against "
                                   "the monodromy. Tongues numbered as in "
                                   "Fig. 14, with their tips (lowest p_f).")
    p.add_argument("--freq", default="10:220:500", metavar="START:STOP:N",
                   help="dither frequencies, Hz (default 10:220:500)")
    _pf_max_option(p, "largest amplitude searched")
    p.add_argument("--out", metavar="FILE.csv",
                   help="boundaries as CSV: freq_hz, p_f_bar (lowest, empty "
                        "if none), then per kind, bar")
    p.add_argument("--plot", metavar="FILE.png",
                   help="boundaries drawn over the map (Fig. 16)")
    _model_options(p)
    p.set_defaults(handler=cmd_tongues)

    p = sub.add_parser("sensitivity", help="tongue shifts per parameter "
                                           "(Fig. 17, 18)",
                       description="Vary each parameter (by --factors, or to "
                                   "--values), recompute the boundaries and "
                                   "report how each tongue tip moves in "
                                   "frequency (Hz) and amplitude (bar); "
                                   "checks the paper's conclusions of "
                                   "section 4.3. Clutch-damper study: "
                                   "--params c12 --values 0.5,10.")
    p.add_argument("--params", required=True, metavar="NAMES",
                   help="comma-separated parameters, e.g. "
                        "k12,k24,J1,J2,J3,J4,mu_g,c12")
    p.add_argument("--factors", default="0.5,2", metavar="F1,F2",
                   help="multipliers of the nominal value (default 0.5,2)")
    p.add_argument("--values", metavar="V1,V2",
                   help="absolute values (SI) instead of --factors")
    p.add_argument("--freq", default="10:220:200", metavar="START:STOP:N",
                   help="dither frequencies, Hz (default 10:220:200)")
    _pf_max_option(p, "largest amplitude searched")
    _workers_option(p)
    p.add_argument("--out", metavar="FILE.csv", help="tip-shift table as CSV")
    p.add_argument("--plot", metavar="FILE.png",
                   help="one panel per parameter: nominal and varied "
                        "boundaries")
    _model_options(p)
    p.set_defaults(handler=cmd_sensitivity)

    p = sub.add_parser("threshold", help="friction-gradient threshold "
                                         "without dither (Fig. 19)",
                       description="Largest real part of the eigenvalues "
                                   "without dither against mu_g (Fig. 19a), "
                                   "and the threshold mu_g* against the "
                                   "external damping c_i (Fig. 19b; every c_i "
                                   "set to the value). Uses the mean "
                                   "pressure in the damping "
                                   "(mean_pressure_damping = 1) unless "
                                   "--set gives it.")
    p.add_argument("--mu-g", default="-0.001:0.001:81",
                   metavar="START:STOP:N",
                   help="friction gradients for Fig. 19a, s/rad")
    p.add_argument("--c-ext", default="0:2:41", metavar="START:STOP:N",
                   help="external damping values for Fig. 19b, N m s/rad")
    p.add_argument("--out", metavar="FILE.csv",
                   help="threshold against c_i as CSV")
    p.add_argument("--plot", metavar="FILE.png", help="Fig. 19a and 19b")
    _model_options(p)
    p.set_defaults(handler=cmd_threshold)

    p = sub.add_parser("fit", help="fit parameters to a measured boundary "
                                   "(section 4.2)",
                       description="Adjust hard-to-know parameters so the "
                                   "model's stability boundary matches a "
                                   "measured one (CSV: freq_hz,p_f_bar; "
                                   "empty p_f_bar = no judder up to "
                                   "--pf-max). Reports values, standard "
                                   "uncertainties and the residual.")
    p.add_argument("--boundary", required=True, metavar="FILE.csv",
                   help="measured boundary, Hz and bar")
    p.add_argument("--fit", default="c12,mu_g,k24", metavar="NAMES",
                   help="parameters to fit (default c12,mu_g,k24)")
    p.add_argument("--bounds", action="append", default=[],
                   metavar="NAME=LOW:HIGH",
                   help="search range of a fitted parameter, SI; repeatable "
                        "(default a factor 100 either way of the start)")
    _pf_max_option(p, "largest amplitude tried on the bench (and "
                      "searched in the model)")
    p.add_argument("--plot", metavar="FILE.png",
                   help="measured and fitted boundaries (Fig. 16a)")
    p.add_argument("--save-params", metavar="FILE.toml",
                   help="write the fitted set (never overwrites unless "
                        "--force)")
    p.add_argument("--force", action="store_true",
                   help="allow --save-params to replace a file")
    _model_options(p)
    p.set_defaults(handler=cmd_fit)

    p = sub.add_parser("simulate", help="bench engagement with dither "
                                        "(Fig. 7, 8), run through the FMU",
                       description="Engagement of the EVEN clutch at 1000 rpm "
                                   "on the test-bench model "
                                   "(TestBenchEngagement FMU, built if "
                                   "needed), run with fmpy. Writes the time "
                                   "histories (SI units) and reports the "
                                   "spectrum peak of the upstream speed and "
                                   "of the pressure.")
    p.add_argument("--freq", type=float, required=True, metavar="HZ",
                   help="dither frequency, Hz")
    p.add_argument("--pf", type=float, required=True, metavar="BAR",
                   help="dither amplitude, bar")
    p.add_argument("--duration", type=float, metavar="S",
                   help="simulated time, s (default: the model's 4 s)")
    p.add_argument("--compare", nargs="?", const="none", metavar="HZ",
                   help="also run a correct engagement: without dither, or "
                        "with dither at HZ; plotted side by side (Fig. 7)")
    p.add_argument("--bench", action="append", default=[],
                   metavar="NAME=VALUE",
                   help="bench parameter of the model (SI): w_motor, "
                        "t_engage, t_ramp, p_load, S_load, N_c_load, "
                        "d_control; repeatable")
    p.add_argument("--out", metavar="run.csv|run.mf4",
                   help="time histories as CSV or ASAM MDF4")
    p.add_argument("--plot", metavar="FILE.png",
                   help="time histories and spectra")
    _model_options(p)
    p.set_defaults(handler=cmd_simulate)

    p = sub.add_parser("crosscheck", help="FMU growth rates against Floquet "
                                          "exponents",
                       description="Run the paper's driveline FMU (Eq. 1) on "
                                   "a grid, twice per point with initial "
                                   "speeds 1 rad/s apart; the difference is "
                                   "the free response, whose Floquet "
                                   "multipliers are fitted (Prony/Hankel "
                                   "DMD on samples once per dither period) "
                                   "and compared with the stability layer's.")
    p.add_argument("--freq", default="75:130:23", metavar="START:STOP:N",
                   help="dither frequencies, Hz (default 75:130:23: tongues "
                        "5, 2 and 6)")
    p.add_argument("--pf", default="0.1:0.7:4", metavar="START:STOP:N",
                   help="dither amplitudes, bar (default 0.1:0.7:4)")
    p.add_argument("--duration", type=float, default=3.0, metavar="S",
                   help="length of each run, s (default 3)")
    _workers_option(p)
    p.add_argument("--out", metavar="FILE.csv", help="table of all points")
    p.add_argument("--plot", metavar="FILE.png",
                   help="fitted against Floquet rates, and the verdicts")
    _model_options(p)
    p.set_defaults(handler=cmd_crosscheck)

    p = sub.add_parser("campaign", help="bench emulator: engagement "
                                        "acquisitions over a dither grid",
                       description="Emulate a bench campaign (section 3): one "
                                   "engagement per dither frequency x "
                                   "amplitude x engine speed x oil "
                                   "temperature, speeds sampled by a "
                                   "41-tooth pick-up (684 samples/s at "
                                   "1000 rpm) with noise, pressure at 1 kHz; "
                                   "one CSV and/or MF4 per run and "
                                   "OUT/index.csv. Runs in parallel; an "
                                   "interrupted or failed campaign resumes "
                                   "when run again.")
    p.add_argument("--freq", default="60:200:15", metavar="START:STOP:N",
                   help="dither frequencies, Hz (default 60:200:15)")
    p.add_argument("--pf", default="0.02:0.3:8", metavar="START:STOP:N",
                   help="dither amplitudes, bar (default 0.02:0.3:8)")
    p.add_argument("--rpm", default="1000", metavar="N1,N2",
                   help="engine (motor) speeds, rpm (default 1000; the "
                        "paper also used 1500)")
    p.add_argument("--temperatures", default="65-70", metavar="T1,T2|all",
                   help="oil temperature ranges (55-60, 65-70, 75-80, "
                        "85-90, or all), represented by parameter changes")
    p.add_argument("--duration", type=float, default=1.5, metavar="S",
                   help="length of each engagement, s (default 1.5)")
    p.add_argument("--noise-rpm", type=float, default=0.5,
                   help="speed measurement noise, rpm (default 0.5)")
    p.add_argument("--seed", type=int, default=1, help="noise seed")
    p.add_argument("--format", default="csv,mf4", metavar="csv,mf4",
                   help="file formats per run (default both)")
    _workers_option(p)
    p.add_argument("--out", required=True, metavar="DIR",
                   help="campaign folder (created; an existing campaign "
                        "there is resumed)")
    _model_options(p)
    p.set_defaults(handler=cmd_campaign)
    return parser


def main(argv=None):
    """Run ``judder``; returns the exit status."""
    from threadpoolctl import threadpool_limits
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        # the kernels work on many tiny matrices: BLAS threads only contend
        with threadpool_limits(limits=1):
            args.handler(args)
    except JudderError as exc:
        print(f"judder: error: {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("judder: interrupted; no partial output was written",
              file=sys.stderr)
        return 130
    return 0
