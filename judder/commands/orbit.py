"""``judder orbit``: the periodic orbit of a dithered engagement, its
stability, its continuation, and the predicted judder chart."""

from studies._common import resolve
from studies._preflight import check_orbit
from studies.orbit import orbit

from ._arguments import (force_option, limit_option, min_growth_option,
                         model_options)
from ._model import model_title, parameters_of, parse_bench
from ._output import Progress, emit, make_parents, write_outputs, written
from ._values import Settings

#: The command's --help text.
DESCRIPTION = (
    "The steady motion the held-slip bench run settles into under the "
    "dither: the periodic orbit of the bench's equations (those of the "
    "TestBenchEngagement FMU: the driveline with the bench motor's speed "
    "control and its 680 N m torque limit, and the EVEN clutch's friction "
    "curve, at the bench's slip), by harmonic balance, with its own "
    "Floquet multipliers (judder as the physicist defines it: the "
    "instability of the actual forced orbit); in a combination tongue, "
    "where no periodic orbit settles, the same equations integrated until "
    "the motion settles. One --freq and one --pf: the orbit (T-periodic, "
    "and the 2T orbit where it loses stability through -1). One --freq "
    "and several --pf: the orbit continued in p_f (pseudo-arclength, "
    "through folds). Several --freq and one --pf: the orbit over f. "
    "Several of both (the default, 60-200 Hz x 0.05-0.7 bar): the "
    "predicted judder chart, each point judged as `judder chart` judges a "
    "bench run (the oscillation above --limit or growing at --min-growth) "
    "with its mechanism. The torque the dither rectifies (reported) "
    "moves the held slip during the bench's run: the orbit follows that "
    "drift, quasi-statically, to the run's end.")


OUTPUTS = (("out", "--out", ("csv", "npz")), ("plot", "--plot", None))


AMPLITUDE = "pf"


DEFAULT_ORBIT_FREQ = "60:200:141"


DEFAULT_ORBIT_PF = "0.05:0.7:14"


def add_arguments(p):
    """The options of ``judder orbit``."""
    p.add_argument("--freq", type=Settings("--freq", "Hz"),
                   default=DEFAULT_ORBIT_FREQ, metavar="HZ|START:STOP:N",
                   help="dither frequency, Hz: one, a list or a grid "
                        f"(default {DEFAULT_ORBIT_FREQ})")
    p.add_argument("--pf", type=Settings("--pf", "bar"),
                   default=DEFAULT_ORBIT_PF, metavar="BAR|START:STOP:N",
                   help="dither amplitude, bar: one, a list or a grid "
                        f"(default {DEFAULT_ORBIT_PF})")
    p.add_argument("--bench", action="append", default=[],
                   metavar="NAME=VALUE",
                   help="bench parameter (SI, or with a unit: "
                        "w_motor=1500rpm), as for simulate; repeatable")
    limit_option(p)
    min_growth_option(p)
    p.add_argument("--out", metavar="FILE.csv|FILE.npz",
                   help="the orbits as CSV (one or a curve) or the chart's "
                        "arrays as NPZ")
    p.add_argument("--plot", metavar="FILE.png",
                   help="amplitude against p_f or f with stable (solid) "
                        "and unstable (dashed) orbits, or the predicted "
                        "chart with the Floquet tongues of the same bench")
    model_options(p, modelica=False)
    force_option(p)


def run(args):
    """Periodic orbits of the held-slip bench run."""
    params, changes = parameters_of(args)
    freqs, amplitudes = list(args.freq), list(args.pf)
    check_orbit(len(freqs), len(amplitudes))
    make_parents(args.out, args.plot)
    with Progress(len(freqs) if len(freqs) > 1 and len(amplitudes) > 1
                  else None, "orbits") as progress:
        result = orbit(freqs, amplitudes, params, changes,
                       bench=parse_bench(args.bench,
                                          resolve(params, changes)),
                       judder_limit_rpm=args.limit,
                       min_growth=args.min_growth, progress=progress)
    files = write_outputs(args, result, figure={
        "title": f"settled motion of the held-slip bench run, "
                 f"{model_title(args, params)}"})
    emit(args, {**result.as_dict(), **files},
         result.text() + written(args.out, args.plot))
