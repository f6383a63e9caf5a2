"""``judder simulate``, ``crosscheck`` and ``campaign``: the time-domain
commands, running the FMUs with fmpy."""

import math
import time
from pathlib import Path

import numpy as np

from stability.cli_support import (PA_PER_BAR, Progress, check_number, emit,
                                   make_parents, parse_grid, parse_list,
                                   resolve_parameters)
from stability.errors import JudderError

__all__ = ["cmd_simulate", "cmd_crosscheck", "cmd_campaign"]


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
    from pysim.runs import SIGNALS, parameter_default, run_fmu
    check_number("--freq", args.freq, "Hz")
    check_number("--pf", args.pf, "bar", strict=False)
    check_number("--duration", args.duration, "s")
    params = resolve_parameters(args)
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
    make_parents(args.out, args.plot)
    runs = []
    for label, freq, p_f in settings:
        runs.append((label, run_fmu(fmu, freq, p_f, params=params,
                                    extra=bench, duration=args.duration,
                                    output_interval=interval)))
    start = (bench.get("t_engage", parameter_default(fmu, "t_engage"))
             + bench.get("t_ramp", parameter_default(fmu, "t_ramp")))
    from stability.floquet import floquet
    from stability.model import build_driveline
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
        from stability.output import save_figure
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
    emit(args, data, "\n".join(rows))


def cmd_crosscheck(args):
    """FMU growth rates against Floquet exponents on a grid."""
    from pysim.crosscheck import crosscheck
    freqs = parse_grid(args.freq, "--freq", "Hz")
    amplitudes = parse_grid(args.pf, "--pf", "bar")
    if freqs[0] <= 0:
        raise JudderError("--freq: allowed: frequencies > 0 Hz")
    check_number("--duration", args.duration, "s")
    params = resolve_parameters(args)
    make_parents(args.out, args.plot)
    started = time.perf_counter()
    with Progress(len(freqs) * len(amplitudes), "FMU runs") as callback:
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
        from stability.output import write_text
        columns = list(rows[0])
        lines = [",".join(columns)] + [",".join(
            f'"{r[c]}"' if c == "reason" else str(r[c]) for c in columns)
            for r in rows]
        write_text(args.out, "\n".join(lines) + "\n")
    if args.plot:
        from pysim.plotting import crosscheck_figure
        from stability.output import save_figure
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
    emit(args, data, text)


def cmd_campaign(args):
    """Bench emulator: a campaign of engagement acquisitions."""
    from pysim.bench import TEMPERATURES, Campaign, run_campaign
    freqs = parse_grid(args.freq, "--freq", "Hz")
    amplitudes = parse_grid(args.pf, "--pf", "bar")
    if freqs[0] <= 0:
        raise JudderError("--freq: allowed: frequencies > 0 Hz")
    rpm = [check_number("--rpm", n, "rpm") for n in parse_list(args.rpm, "--rpm")]
    temperatures = (list(TEMPERATURES) if args.temperatures == "all"
                    else [t.strip() for t in args.temperatures.split(",")])
    formats = tuple(f.strip() for f in args.format.split(","))
    if not set(formats) <= {"csv", "mf4"} or not formats:
        raise JudderError(f"--format {args.format!r}: allowed: csv, mf4 or "
                          "csv,mf4")
    check_number("--duration", args.duration, "s")
    check_number("--noise-rpm", args.noise_rpm, "rpm", strict=False)
    params = resolve_parameters(args)
    campaign = Campaign(freq_hz=tuple(freqs), p_f_bar=tuple(amplitudes),
                        engine_rpm=tuple(rpm), temperatures=tuple(temperatures),
                        duration=args.duration, noise_rpm=args.noise_rpm,
                        formats=formats, seed=args.seed)
    started = time.perf_counter()
    with Progress(len(campaign.runs()), "bench runs") as callback:
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
    emit(args, data, text)
    if failed:
        raise JudderError(f"{len(failed)} runs failed; the others were "
                          "written (run the same command again to retry)")
