"""``judder sensitivity``: tongue shifts per parameter (Fig. 17, 18)."""

from infra.errors import JudderError
from studies._preflight import check_sensitivity, check_work
from studies.sensitivity import sensitivity

from ._arguments import (driveline_option, force_option, method_option,
                         model_options, pf_max_option, workers_option)
from ._model import model_title, parameters_of
from ._output import Progress, emit, make_parents, write_outputs, written
from ._values import Grid, Listed, Quantity

#: The command's --help text.
DESCRIPTION = (
    "Vary each parameter (by --factors, or to --values), recompute the "
    "boundaries and report how each tongue tip moves in frequency (Hz) "
    "and amplitude (bar); checks the paper's conclusions of section "
    "4.3. The tips are where each tongue becomes unstable (|lambda| = 1, "
    "Fig. 17, 18), not where it becomes judder (growth >= 1 1/s, see "
    "judder tongues). Clutch-damper study: --params c12 --values 0.5,10.")


OUTPUTS = (("out", "--out", ("csv",)), ("plot", "--plot", None))
#: This command's options for the study's arguments
#: (:func:`judder.commands._flags.in_flags`).
FLAGS = {"names": "--params"}


AMPLITUDE = "pf_max"


#: Multipliers of the nominal value in sensitivity without --factors.
DEFAULT_FACTORS = (0.5, 2.0)


def add_arguments(p):
    """The options of ``judder sensitivity``."""
    p.add_argument("--params", type=Listed("--params", str),
                   required=True, metavar="NAMES",
                   help="comma-separated parameters, e.g. "
                        "k12,k24,J1,J2,J3,J4,mu_g,c12")
    p.add_argument("--factors", metavar="F1,F2",
                   type=Listed("--factors", Quantity("--factors", "1", 0.0,
                                                     low_open=True)),
                   help="multipliers of the nominal value (default 0.5,2)")
    p.add_argument("--values", metavar="V1,V2", type=Listed("--values"),
                   help="absolute values (SI) instead of --factors")
    p.add_argument("--freq", type=Grid("--freq", "Hz"),
                   default="10:220:200", metavar="START:STOP:N",
                   help="dither frequencies, Hz (default 10:220:200)")
    pf_max_option(p, "largest amplitude searched")
    workers_option(p)
    p.add_argument("--out", metavar="FILE.csv", help="tip-shift table as CSV")
    p.add_argument("--plot", metavar="FILE.png",
                   help="one panel per parameter: nominal and varied "
                        "boundaries")
    method_option(p)
    model_options(p)
    driveline_option(p)
    force_option(p)


def run(args):
    """Tongue tips and boundaries with parameters varied (Fig. 17, 18)."""
    names = args.params
    freqs = args.freq
    p_max_bar = args.pf_max
    params, changes = parameters_of(args)
    if args.values is not None and args.factors is not None:
        raise JudderError("--values and --factors given; allowed: one of "
                          "them")
    factors = args.factors or DEFAULT_FACTORS
    values = args.values
    if values is None:
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
    check_sensitivity(params.replace(**changes), freqs, cases,
                      args.workers)
    with Progress(cases, "sensitivity cases") as progress:
        result = sensitivity(names, freqs, p_max_bar, factors=factors,
                             values=values, parameters=params,
                             changes=changes, method=args.method,
                             workers=args.workers, progress=progress,
                             driveline=args.driveline)
    files = write_outputs(args, result, figure={
        "title": "sensitivity of the unstable boundary "
                 r"($|\lambda| = 1$; "
                 "Fig. 17, 18), " + model_title(args, params)})
    rows = ["tips where each tongue becomes unstable (|lambda| = 1, "
            "growth 0), not where it becomes judder (growth >= 1 1/s; "
            "judder tongues gives both)",
            f"{'param':>8} {'factor':>7} {'value':>10} {'#':>2} "
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
    if result.conclusions:
        rows.append("the paper's conclusions of section 4.3, checked on "
                    "this driveline ([does NOT hold]: this driveline "
                    "behaves otherwise, not an error of the tool):")
    rows += [f"[{'holds' if c['holds'] else 'does NOT hold'}] "
             f"{c['statement']}: {c['evidence']}" for c in result.conclusions]
    rows.append(f"{result.cases} cases in {result.seconds:.1f} s")
    emit(args, {**result.as_dict(), **files},
         "\n".join(rows) + written(args.out, args.plot))
