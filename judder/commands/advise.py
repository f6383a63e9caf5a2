"""``judder advise``: safe dither windows and the design change that clears
the dither range.
"""

import math

from infra.errors import JudderError
from stability.decisions.advice import DEFAULT_BOUNDS
from studies._preflight import check_advise_grid
from studies.advise import advise

from ._arguments import (driveline_option, force_option, min_growth_option,
                         model_options, renamed_option, window_options)
from ._model import model_title, parameter_file, parameters_of
from ._output import Progress, emit, make_parents, write_outputs, written
from ._values import BOUNDS_FORM, VALVE_MAX, Listed, parse_bounds

#: The command's --help text.
DESCRIPTION = (
    "(a) The safe (frequency, amplitude) windows inside the valve's "
    "operating range, keeping --margin-bar and --margin-hz from every "
    "judder-relevant tongue (over every --also parameter set: the "
    "broadest region); (b) the ranking of the design parameters by the "
    "share of the way out of the window per relative change, and the "
    "smallest weighted relative change of them that clears the window "
    "of judder, each parameter inside its --bounds, checked by "
    "recomputing the Floquet map of the advised design (section 4.3, 5). "
    "'Judder' is growth at --min-growth (1 1/s) or faster; the advice "
    "also says where its design is still unstable (|lambda| > 1) but "
    "growing slower.")


OUTPUTS = (("out", "--out", ("csv",)), ("plot", "--plot", None))
#: This command's options for the study's arguments
#: (:func:`judder.commands._flags.in_flags`).
FLAGS = {"names": "--params"}


def add_arguments(p):
    """The options of ``judder advise``."""
    window_options(p, freq_note=", the paper's valve")
    renamed_option(p, "--pf-max", "--valve-max", "valve_max", type=VALVE_MAX,
                   metavar="BAR")
    min_growth_option(p)
    p.add_argument("--params", type=Listed("--params", str),
                   default=None, metavar="NAMES",
                   help="design parameters that may change (default "
                        "J2,J4,k12,k24,c12; for the 3-DOF model its "
                        "inertias, stiffnesses and dampings; for --modelica"
                        "/--fmu those of J2,J4,k12,k24,c12 it has, and "
                        "NAMES is required if it has none: its tunable "
                        "parameters by their names, e.g. k24,J4,k35)")
    p.add_argument("--weights", type=Listed("--weights"),
                   default=None, metavar="W[,W...]",
                   help="cost of a unit change of ln(value) of each design "
                        "parameter, in the order of --params (default 1 "
                        "each)")
    p.add_argument("--bounds", action="append", default=[],
                   metavar="NAME=LOW:HIGH",
                   help="range a design parameter may take, around its "
                        "nominal value: " + BOUNDS_FORM + "; repeatable; "
                        "default %gx:%gx for each, halved to doubled, the "
                        "range of the paper's sensitivity study (Fig. 17, "
                        "18); a plain number is still read as a factor "
                        "for this release" % DEFAULT_BOUNDS)
    p.add_argument("--also", action="append", default=[],
                   metavar="FILE.toml",
                   help="another parameter set the advice must hold for "
                        "(an uncertainty envelope), a file of `judder params "
                        "--save` for the same model (with --modelica or "
                        "--fmu: of `judder params --modelica CLASS --save`)"
                        "; repeatable")
    p.add_argument("--no-design", action="store_true",
                   help="only the windows and the ranking")
    p.add_argument("--out", metavar="FILE.csv",
                   help="safe amplitude per frequency: freq_hz,safe_p_f_bar")
    p.add_argument("--plot", metavar="FILE.png",
                   help="safe amplitude per frequency and the map of the "
                        "advised design")
    model_options(p)
    driveline_option(p)
    force_option(p)


def run(args):
    """Safe dither windows, parameter ranking and design change."""
    low, high = args.freq_range
    names, weights = args.params, args.weights
    check_advise_grid(low, high, args.margin_hz)
    if math.isfinite(args.margin_bar) and math.isfinite(args.valve_max) \
            and args.margin_bar >= args.valve_max:
        raise JudderError(f"--margin-bar {args.margin_bar:g} bar is not "
                          "allowed; allowed: below --valve-max "
                          f"({args.valve_max:g} bar), the top of the "
                          "operating range")
    params, changes = parameters_of(args)
    bounds = _factors(args.bounds, params.replace(**changes))
    extra = [parameter_file(args, path, "--also") for path in args.also]
    make_parents(args.out, args.plot)
    with Progress(8, "advise") as progress:
        result = advise(params, changes, extra_sets=extra,
                        freq_range=(low, high), valve_max_bar=args.valve_max,
                        margin_bar=args.margin_bar,
                        margin_hz=args.margin_hz,
                        min_growth=args.min_growth, names=names,
                        weights=weights, design=not args.no_design,
                        progress=progress, bounds=bounds,
                        background=args.plot is not None,
                        driveline=args.driveline)
    data = {**result.as_dict(), **write_outputs(
        args, result, figure={"title": model_title(args, params)})}
    emit(args, data, result.summary() + written(args.out, args.plot))


def _factors(items, values):
    """``--bounds`` as factors of the nominal values ``{name: (low,
    high)}``, each range around its nominal value (the design starts
    there)."""
    factors = {}
    for name, (low, high) in parse_bounds(items, values, None, "--params",
                                          plain_factors=True).items():
        low, high = low / values[name], high / values[name]
        if not low <= 1 <= high:
            raise JudderError(
                f"--bounds {name}: {low:g}x:{high:g}x of its nominal value "
                f"{values[name]:g} is not allowed; allowed: a range "
                "around the nominal value (LOW <= 1x <= HIGH)")
        factors[name] = (low, high)
    return factors
