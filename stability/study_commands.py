"""``judder tongues``, ``sensitivity``, ``threshold`` and ``fit``: the
paper's stability studies (sections 4.2-4.3)."""

import math
import time

import numpy as np

from .cli_support import (PA_PER_BAR, Progress, bar_to_pa, check_number,
                          emit, make_parents, parse_grid, parse_list,
                          read_input, resolve_parameters)
from .errors import JudderError

__all__ = ["cmd_tongues", "cmd_sensitivity", "cmd_threshold", "cmd_fit"]


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
    p_max = bar_to_pa(args.pf_max, "--pf-max")
    params = resolve_parameters(args)
    driveline = build_driveline(params)
    make_parents(args.out, args.plot)
    started = time.perf_counter()
    with Progress(len(freqs), "tongue boundaries") as callback:
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
    emit(args, data, "\n".join(rows))


def cmd_sensitivity(args):
    """Tongue tips and boundaries with parameters varied (Fig. 17, 18)."""
    from .parameters import SPECS
    from .sensitivity import paper_conclusions, sensitivity_study, tip_shifts
    names = parse_list(args.params, "--params", str)
    freqs = parse_grid(args.freq, "--freq", "Hz")
    p_max = bar_to_pa(args.pf_max, "--pf-max")
    params = resolve_parameters(args)
    for name in names:
        if name not in SPECS[params.model]:
            raise JudderError(f"--params: unknown parameter {name!r} for the "
                              f"{params.model} model; allowed names: "
                              f"{', '.join(SPECS[params.model])}")
    factors = parse_list(args.factors, "--factors")
    values = parse_list(args.values, "--values") if args.values else None
    if values is None:
        for factor in factors:
            check_number("--factors", factor, "(factor)")
    make_parents(args.out, args.plot)
    started = time.perf_counter()
    cases = 1 + len(names) * len(values or factors)
    with Progress(cases, "sensitivity cases") as callback:
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
    emit(args, data, "\n".join(rows))


def cmd_threshold(args):
    """Friction-gradient threshold without dither (Fig. 19)."""
    from .threshold import threshold_study
    mu_g = parse_grid(args.mu_g, "--mu-g", "s/rad", allow_negative=True)
    damping = parse_grid(args.c_ext, "--c-ext", "N m s/rad")
    params = resolve_parameters(args)
    explicit = any(a.split("=")[0].strip() == "mean_pressure_damping"
                   for a in args.set)
    if not explicit:
        params = params.replace(mean_pressure_damping=1.0)
    make_parents(args.out, args.plot)
    with Progress(len(damping), "threshold") as callback:
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
    text = (f"threshold mu_g* = {study.threshold:.6g} s/rad for this set "
            f"(unstable without dither below it)")
    if len(damping) > 1:
        slope = np.polyfit(study.external_damping, study.thresholds, 1)[0]
        text += (f"\nthreshold against c_i: slope {slope:.4g} s/rad per "
                 f"N m s/rad over c_i = {damping[0]:g}..{damping[-1]:g}")
    text += "".join(f"\nwrote {p}" for p in (args.out, args.plot) if p)
    emit(args, data, text)


def cmd_fit(args):
    """Fit parameters to a measured boundary (section 4.2, Fig. 16a)."""
    from .fitting import fit_boundary, read_boundary_csv
    names = parse_list(args.fit, "--fit", str)
    p_max = bar_to_pa(args.pf_max, "--pf-max")
    params = resolve_parameters(args)
    freqs, measured = read_boundary_csv(
        read_input(args.boundary, "--boundary"), source=str(args.boundary))
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
    make_parents(args.plot, args.save_params)
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
    emit(args, data, "\n".join(rows))
    if not result.success:
        raise JudderError("the fit did not converge: " + result.message)
