"""``judder floquet``: Floquet multipliers at one point."""

from sources.dither_modes import linearised_mode, mode_words
from studies._preflight import check_floquet
from studies.floquet import floquet

from ._arguments import (driveline_option, force_option, method_option,
                         min_growth_option, model_options, waveform_option)
from ._model import model_title, parameters_of
from ._output import emit, make_parents, output_files, save_plot, written
from ._values import FREQ, PF, parse_waveform

#: The command's --help text.
DESCRIPTION = (
    "Monodromy matrix over one dither period and its Floquet "
    "multipliers (Eq. 10-13), rigid-body angles removed; the leading "
    "multiplier is classified as in Fig. 15.")


OUTPUTS = (("plot", "--plot", None),)


AMPLITUDE = "pf"


def add_arguments(p):
    """The options of ``judder floquet``."""
    p.add_argument("--freq", type=FREQ, required=True, metavar="HZ",
                   help="dither frequency, Hz")
    p.add_argument("--pf", type=PF, required=True, metavar="BAR",
                   help="dither amplitude p_f, bar (1 bar = 1e5 Pa)")
    p.add_argument("--plot", metavar="FILE.png",
                   help="the multipliers on the complex plane with the "
                        "unit circle, and near the leading one (Fig. 15)")
    min_growth_option(p, "; the verdict line says which the point is")
    method_option(p)
    model_options(p)
    driveline_option(p)
    waveform_option(p)
    force_option(p)


def run(args):
    """Floquet multipliers at one dither frequency and amplitude."""
    params, changes = parameters_of(args)
    check_floquet(params.replace(**changes), args.freq, args.method)
    make_parents(args.plot)
    point = floquet(args.freq, args.pf, params, changes,
                    method=args.method,
                    waveform=parse_waveform(args.dither_wave, args.decimal),
                    min_growth=args.min_growth, driveline=args.driveline)
    if args.plot:
        save_plot(args.plot, point.figure(
            title=f"Floquet multipliers (Fig. 15), "
                  f"{model_title(args, params)}"
                  + (" on its test bench" if point.driveline == "bench"
                     else "")))
    result = point.result
    lam = result.leading
    from stability.bench import driveline_words
    words = mode_words(linearised_mode(point.params))
    text = (f"driveline: {driveline_words(point.params, point.driveline)}\n"
            + (words + "\n" if words else "")
            + f"f = {args.freq:g} Hz, p_f = {args.pf:g} bar: {result.kind}\n"
            f"leading multiplier {lam.real:.6f}{lam.imag:+.6f}i "
            f"(|lambda| = {result.leading_abs:.6f}), growth rate "
            f"{result.growth_rate:.4g} 1/s\nall multipliers (|lambda|): "
            + ", ".join(f"{abs(m):.6f}" for m in result.multipliers)
            + "\n" + point.verdict_words() + written(args.plot))
    emit(args, {**point.as_dict(), **output_files(plot=args.plot)}, text)
