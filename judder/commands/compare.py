"""``judder compare``: two parameter sets side by side."""

from infra.errors import JudderError
from studies.compare import compare

from ._arguments import (driveline_option, force_option, min_growth_option,
                         window_options)
from ._output import Progress, emit, make_parents, save_plot, written
from ._values import PF_MAX, Grid, Settings

#: The command's --help text.
DESCRIPTION = (
    "Two parameter sets (files of `judder params --save`, e.g. before and "
    "after a design change) side by side: natural frequencies, each "
    "tongue's tip where it becomes unstable (|lambda| = 1) and where it "
    "becomes judder (growth >= --min-growth), the safe dither windows of "
    "the operating range (as judder advise gives them) and, with --freq "
    "and --pf, the verdict of each setting (as judder check gives it); "
    "--plot draws both maps on one figure, each with the other's "
    "boundaries dashed.")


OUTPUTS = (("plot", "--plot", None),)


#: Tongue and map frequencies of the comparison.
DEFAULT_FREQ = "10:220:500"


def add_arguments(p):
    """The options of ``judder compare``."""
    p.add_argument("files", nargs=2, metavar="FILE.toml",
                   help="the two parameter sets (`judder params --save`)")
    p.add_argument("--freq", type=Settings("--freq", "Hz"),
                   metavar="HZ[,HZ...]",
                   help="dither settings whose verdicts are compared, Hz "
                        "(with --pf: every pair)")
    p.add_argument("--pf", type=Settings("--pf", "bar"),
                   metavar="BAR[,BAR...]",
                   help="dither amplitudes of those settings, bar")
    p.add_argument("--grid", type=Grid("--grid", "Hz"), default=DEFAULT_FREQ,
                   metavar="START:STOP:N",
                   help="frequencies of the tongue boundaries and of the "
                        f"maps, Hz (default {DEFAULT_FREQ})")
    p.add_argument("--pf-max", type=PF_MAX, default=1.5, metavar="BAR",
                   help="largest amplitude of the tongues and maps, bar "
                        "(default %(default)g)")
    window_options(p, subject=" of the safe windows",
                   freq_note=", as judder advise",
                   valve_note=", as judder advise --pf-max",
                   margin_words=("of the safe windows",) * 2)
    min_growth_option(p)
    driveline_option(p)
    p.add_argument("--plot", metavar="FILE.png",
                   help="both maps on one figure")
    p.add_argument("--json", action="store_true",
                   help="print the result as JSON")
    force_option(p)


def run(args):
    """Two parameter sets side by side."""
    from studies._preflight import (check_advise_grid, check_settings_time,
                                    check_tongues)
    from studies.inputs import load_parameters
    if bool(args.freq) != bool(args.pf):
        raise JudderError("--freq and --pf: allowed: both (every pair is a "
                          "setting) or neither")
    low, high = args.freq_range
    check_advise_grid(low, high, args.margin_hz)
    if args.margin_bar >= args.valve_max:
        raise JudderError(f"--margin-bar {args.margin_bar:g} bar is not "
                          "allowed; allowed: below --valve-max "
                          f"({args.valve_max:g} bar)")
    sets = [load_parameters(param_file=path) for path in args.files]
    settings = ([(f, p) for f in args.freq for p in args.pf]
                if args.freq else [])
    if settings:
        check_settings_time(2 * len(settings), 0)
        if args.pf_max <= max(p for _, p in settings):
            raise JudderError(f"--pf-max {args.pf_max:g} bar is not "
                              "allowed; allowed: above the largest --pf, "
                              f"{max(p for _, p in settings):g} bar")
    for params in sets:
        check_tongues(params, args.grid, background=args.plot is not None)
    make_parents(args.plot)
    with Progress(2, "compare") as progress:
        result = compare(sets[0], sets[1], labels=tuple(args.files),
                         freq_hz=args.grid, p_max_bar=args.pf_max,
                         settings=settings, freq_range=(low, high),
                         valve_max_bar=args.valve_max,
                         margin_bar=args.margin_bar,
                         margin_hz=args.margin_hz,
                         min_growth=args.min_growth,
                         maps=args.plot is not None, progress=progress,
                         driveline=args.driveline)
    if args.plot:
        save_plot(args.plot, result.figure())
    emit(args, {**result.as_dict(), "plot": args.plot},
         result.summary() + written(args.plot))
