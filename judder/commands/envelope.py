"""``judder envelope``: broadest unstable region over uncertain parameters
(Fig. 16).
"""

from pathlib import Path

import numpy as np

from infra.errors import JudderError
from infra.files import all_or_none
from infra.units import PA_PER_BAR
from studies._preflight import check_envelope
from studies.envelope import checkpoint_path, envelope

from ._arguments import (driveline_option, force_option, method_option,
                         min_growth_option, model_options, pf_max_option,
                         workers_option)
from ._model import model_title, parameters_of
from ._output import (Progress, emit, make_parents, output_files, save_plot,
                      written)
from ._values import SEED, Grid

#: The command's --help text.
DESCRIPTION = (
    "Exact tongue boundaries for every vertex of the parameter ranges "
    "and a space-filling sample of them (section 4.2): the broadest "
    "unstable region (their union, refined between the samples), the "
    "probability of instability over frequency x amplitude, and how "
    "converged the union is. Resumes from FILE.checkpoint.npz beside "
    "the first output when interrupted. See docs/envelope.md.")


OUTPUTS = (("out", "--out", ("npz",)),
           ("csv", "--csv", ("csv",)),
           ("plot", "--plot", None))


def check_outputs(args, seen):
    """The envelope's checkpoint (given, or beside the first output) on
    none of its outputs: it is written during the work and removed at the
    end, so the output would be lost (or refused only after the work)."""
    given = args.checkpoint
    path = given or checkpoint_path(args.out, args.csv, args.plot)
    if path is None:
        return
    other = seen.get(Path(path).resolve())
    if other is not None:
        what = f"--checkpoint {given}" if given else \
            f"the checkpoint {path} (beside the first output)"
        raise JudderError(f"{what} is also given as {other}; allowed: a "
                          "different file for the checkpoint and each "
                          "output")


def add_arguments(p):
    """The options of ``judder envelope``."""
    p.add_argument("--ranges", required=True, metavar="FILE.toml",
                   help="uncertain parameters: intervals, uniform or normal "
                        "distributions, a judder fit's covariance (see "
                        "examples/ranges.toml)")
    p.add_argument("--freq", type=Grid("--freq", "Hz"),
                   default="10:220:106", metavar="START:STOP:N",
                   help="dither frequencies, Hz (default 10:220:106)")
    pf_max_option(p, "largest amplitude searched")
    p.add_argument("--samples", type=int, default=256, metavar="N",
                   help="space-filling samples after the 2**d vertices "
                        "(default 256)")
    p.add_argument("--sampler", default="sobol", metavar="{sobol,lhs}",
                   help="scrambled Sobol (default) or Latin hypercube (lhs)")
    p.add_argument("--seed", type=SEED, default=0,
                   help="seed of the sample (default 0)")
    p.add_argument("--no-vertices", action="store_true",
                   help="leave out the vertices of the ranges")
    p.add_argument("--refine", type=int, default=20, metavar="N",
                   help="boundary evaluations per uncertain parameter spent "
                        "at each frequency searching the lowest boundary "
                        "between the samples (default 20; 0: the union of "
                        "the samples only)")
    min_growth_option(p)
    p.add_argument("--out", metavar="FILE.npz",
                   help="every sample's boundaries, the broadest edge and "
                        "the probability grid (NPZ, see docs/envelope.md)")
    p.add_argument("--csv", metavar="FILE.csv",
                   help="per frequency: nominal and broadest boundary and "
                        "where 10/50/90 %% of the samples are unstable, bar")
    p.add_argument("--plot", metavar="FILE.png",
                   help="Fig. 16 style plot: probability shading, broadest "
                        "and nominal boundary (PNG, SVG or PDF)")
    p.add_argument("--checkpoint", metavar="FILE.npz",
                   help="checkpoint file (default beside the first of --out, "
                        "--csv, --plot; none without outputs)")
    method_option(p)
    workers_option(p)
    model_options(p)
    driveline_option(p)
    force_option(p)


def run(args):
    """Broadest unstable region over uncertain parameters (section 4.2)."""
    from studies.envelope import checkpoint_path, read_ranges
    freqs = args.freq
    p_max_bar = args.pf_max
    growth = args.min_growth
    for option, value in (("--samples", args.samples),
                          ("--refine", args.refine)):
        if value < 0:
            raise JudderError(f"{option} {value} is not allowed; allowed: a "
                              "whole number >= 0")
    params, changes = parameters_of(args)
    ranges = read_ranges(args.ranges, params.replace(**changes))
    check_envelope(params.replace(**changes), freqs, ranges,
                   args.samples, not args.no_vertices, args.refine,
                   args.workers)
    make_parents(args.out, args.csv, args.plot, args.checkpoint)
    checkpoint = args.checkpoint or checkpoint_path(args.out, args.csv,
                                                    args.plot)
    with Progress(None, "envelope samples") as progress:
        result = envelope(ranges, freqs, p_max_bar, samples=args.samples,
                          seed=args.seed, sampler=args.sampler,
                          vertices=not args.no_vertices,
                          min_growth=growth, refine=args.refine,
                          parameters=params, changes=changes,
                          method=args.method, workers=args.workers,
                          checkpoint=checkpoint, progress=progress,
                          driveline=args.driveline)
    with all_or_none():
        if args.out:
            result.save(args.out, force=args.force)
        if args.csv:
            result.save_csv(args.csv, force=args.force)
        if args.plot:
            save_plot(args.plot, result.figure(
                title=f"envelope, {model_title(args, params)}"))
    result.discard_checkpoint()
    e, c = result.envelope, result.envelope.convergence
    lowest = e.broadest
    tip = (f"lowest point {np.nanmin(lowest) / PA_PER_BAR:.4f} bar at "
           f"{e.freq_hz[np.nanargmin(lowest)]:g} Hz"
           if np.isfinite(lowest).any() else
           f"stable up to {p_max_bar:g} bar at every frequency")
    text = (f"{int(e.ok.sum())} of {len(e.ok)} samples ({int(e.is_vertex.sum())}"
            f" vertices) over {', '.join(e.names)} in {result.seconds:.1f} s"
            + (f" ({result.resumed} from the checkpoint)" if result.resumed
               else "")
            + f"\nbroadest region: {tip}; area {c['refined_area_bar_hz']:.4g}"
            f" bar Hz\nconvergence: the last {c['last']} samples added "
            f"{100 * c['added_share']:.2g} % of the union's area (edge "
            f"lowered by up to {c['max_drop_bar']:.2g} bar); the refinement "
            f"between samples added {100 * c['refinement_added_share']:.2g} %"
            + written(args.out, args.csv, args.plot))
    emit(args, {**result.as_dict(), **output_files(out=args.out, csv=args.csv,
                                             plot=args.plot)}, text)
    if result.failures:
        raise JudderError(
            f"{len(result.failures)} samples failed and are left out (run "
            "again to retry them): " + "; ".join(
                str(f) for f in result.failures[:5]))
