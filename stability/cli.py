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

from .errors import JudderError

__all__ = ["main", "build_parser", "parse_grid"]

PA_PER_BAR = 1e5
DEFAULT_FREQ = "5:250:300"
DEFAULT_PF = "0:1.5:150"
#: Largest grid a map accepts, in points.
MAX_MAP_POINTS = 2_000_000


def parse_grid(text, option, unit):
    """Parse ``START:STOP:N`` (or a single value) into a linspace.

    Raises
    ------
    JudderError
        Naming ``option`` and saying what is allowed.
    """
    import numpy as np
    parts = text.split(":")
    allowed = (f"allowed: START:STOP:N with 0 <= START <= STOP in {unit} "
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
            or start < 0 or count < 1 or (count == 1 and start != stop):
        raise JudderError(f"{option} {text!r} is not allowed; {allowed}")
    return np.linspace(start, stop, count)


def _resolve_parameters(args):
    """Parameters from --params/--preset/--model and --set."""
    from . import parameters as par
    if args.params is not None:
        if args.preset is not None:
            raise JudderError("give either --params FILE or --preset NAME, "
                              "not both")
        path = Path(args.params)
        try:
            text = path.read_text()
        except OSError as exc:
            raise JudderError(f"--params {path}: cannot read it "
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
    if not math.isfinite(args.pf) or args.pf < 0:
        raise JudderError(f"--pf {args.pf:g} bar is not allowed; allowed: "
                          "a finite dither amplitude >= 0 bar")
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
                 f"{args.preset or args.params or 'default parameters'}")
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
    group.add_argument("--params", metavar="FILE.toml",
                       help="parameter file (see `judder params --save`)")
    group.add_argument("--set", action="append", default=[],
                       metavar="NAME=VALUE",
                       help="override one parameter, SI units; repeatable "
                            "(e.g. --set c12=10 --set "
                            "mean_pressure_damping=1)")
    parser.add_argument("--json", action="store_true",
                        help="print the result as JSON")


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
                                   "with --params.")
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
    return parser


def main(argv=None):
    """Run ``judder``; returns the exit status."""
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        args.handler(args)
    except JudderError as exc:
        print(f"judder: error: {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("judder: interrupted; no partial output was written",
              file=sys.stderr)
        return 130
    return 0
