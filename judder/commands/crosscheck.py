"""``judder crosscheck``: FMU growth rates against Floquet exponents."""

from infra.errors import JudderError
from studies._preflight import check_crosscheck, check_work
from studies.crosscheck import crosscheck

from ._arguments import (force_option, method_option, model_options,
                         workers_option)
from ._model import model_title, parameters_of
from ._output import Progress, emit, make_parents, write_outputs, written
from ._values import DURATION, Grid

#: The command's --help text.
DESCRIPTION = (
    "Run the paper's driveline FMU (Eq. 1) on a grid, twice per point "
    "with initial speeds 1 rad/s apart; the difference is the free "
    "response, whose Floquet multipliers are fitted (Prony/Hankel DMD "
    "on samples once per dither period) and compared with the stability "
    "layer's. With --modelica CLASS: the class's FMU and its "
    "linearisation; --fmu is refused (the FMU path reads only its "
    "Jacobian, it has no time-domain run here).")


OUTPUTS = (("out", "--out", ("csv",)), ("plot", "--plot", None))


AMPLITUDE = "pf"


#: Fewest dither periods of a crosscheck run (the multipliers are fitted
#: to one sample per period).
MIN_CROSSCHECK_PERIODS = 20


def add_arguments(p):
    """The options of ``judder crosscheck``."""
    p.add_argument("--freq", type=Grid("--freq", "Hz"),
                   default="75:130:23", metavar="START:STOP:N",
                   help="dither frequencies, Hz (default 75:130:23: tongues "
                        "5, 2 and 6)")
    p.add_argument("--pf", type=Grid("--pf", "bar"),
                   default="0.1:0.7:4", metavar="START:STOP:N",
                   help="dither amplitudes, bar (default 0.1:0.7:4)")
    p.add_argument("--duration", type=DURATION, default=3.0, metavar="S",
                   help="length of each run, s (default 3)")
    workers_option(p)
    p.add_argument("--out", metavar="FILE.csv", help="table of all points")
    p.add_argument("--plot", metavar="FILE.png",
                   help="fitted against Floquet rates, and the verdicts")
    method_option(p)
    model_options(p, fmu=False)
    p.add_argument("--perturb", default="w_in", metavar="NAME",
                   help="start-speed parameter raised by 1 rad/s in the "
                        "second run of each point (default w_in)")
    force_option(p)


def run(args):
    """FMU growth rates against Floquet exponents on a grid."""
    freqs = args.freq
    amplitudes = args.pf
    if freqs[0] <= 0:
        raise JudderError("--freq: allowed: frequencies > 0 Hz")
    if args.duration * freqs[0] < MIN_CROSSCHECK_PERIODS:
        raise JudderError(
            f"--duration {args.duration:g} s holds "
            f"{args.duration * freqs[0]:.3g} periods at {freqs[0]:g} Hz; "
            f"allowed: at least {MIN_CROSSCHECK_PERIODS} periods of the "
            f"lowest frequency (>= {MIN_CROSSCHECK_PERIODS / freqs[0]:.3g} s)"
            ", for the multipliers to be fitted")
    check_work("--freq x --pf", 2 * len(freqs) * len(amplitudes),
               "FMU runs")
    check_crosscheck(2 * len(freqs) * len(amplitudes),
                     args.duration, args.workers)
    params, changes = parameters_of(args)
    make_parents(args.out, args.plot)
    with Progress(len(freqs) * len(amplitudes), "FMU runs") as progress:
        result = crosscheck(freqs, amplitudes, duration=args.duration,
                            parameters=params, changes=changes,
                            method=args.method, workers=args.workers,
                            progress=progress, perturb=args.perturb)
    data = {**result.as_dict(), **write_outputs(
        args, result, figure={"title": model_title(args, params)})}
    worst = data["max_rate_error_above_1_per_s"]
    text = (f"{data['points']} points in {result.seconds:.1f} s: verdicts "
            f"agree on {100 * data['agreement']:.1f} %; largest rate "
            "difference where the exponent > 1/s: "
            + ("none" if worst is None else f"{100 * worst:.2g} %")
            + "".join(f"\n  disagree at {r['freq_hz']:g} Hz, "
                      f"{r['p_f_bar']:g} bar: {r['reason']}"
                      for r in data["disagreements"])
            + written(args.out, args.plot))
    emit(args, data, text)
