"""``judder envelope``: broadest unstable region over uncertain parameters
(Fig. 16).
"""

from dataclasses import dataclass
import json
import math
from pathlib import Path
import time

import numpy as np

from infra.errors import JudderError
from infra.files import (all_or_none, keeps_foreign_files, save_npz,
                         write_text)
from infra.units import PA_PER_BAR
from stability.kinds import KINDS
from stability.monodromy import DEFAULT_METHOD

from ..envelope import checkpoint_path
from ._arguments import (driveline_option, force_option, method_option,
                         min_growth_option, model_options, pf_max_option,
                         workers_option)
from ._common import (BACKGROUND_AMPLITUDES, checked_values,
                      linearised_mode, mode_words)
from ._model import model_title, parameters_of
from ._output import (Progress, emit, make_parents, output_files, save_plot,
                      written)
from ._preflight import check_envelope
from ._records import finite_or_none, rows_to_csv
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
    from ..envelope import checkpoint_path, read_ranges
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


def envelope(ranges, freq_hz, p_max_bar=1.5, samples=256, seed=0,
             sampler="sobol", vertices=True, min_growth=None, refine=20,
             parameters=None, changes=None, method=DEFAULT_METHOD,
             workers=None, checkpoint=None, progress=None, driveline=None):
    """``judder envelope``: the broadest unstable region over uncertain
    parameters and the probability of instability (section 4.2, Fig. 16).

    Parameters
    ----------
    ranges : path or stability.uncertainty.ranges.Ranges
        A ranges file (:func:`judder.envelope.read_ranges`) or the ranges.
    freq_hz : array_like
        Dither frequencies, Hz.
    p_max_bar : float
        Largest amplitude searched, bar.
    samples, seed, sampler, vertices
        Space-filling samples after the vertices, as
        :func:`stability.uncertainty.ranges.design_points` takes them.
    min_growth : float, optional
        1/s: count only judder growing at least this fast (default
        :data:`infra.criteria.DEFAULT_MIN_GROWTH_PER_S`; 0: every
        instability).
    refine : int
        Boundary evaluations per uncertain parameter spent at each
        frequency searching the lowest boundary between the samples
        (:func:`stability.uncertainty.envelope.refine_at`); 0: the union of the
        samples only.
    workers : int, optional
        Local Dask worker processes (see :mod:`infra.parallel`).
    checkpoint : path, optional
        Resume from / save to this NPZ (see
        :func:`judder.envelope.run_envelope`).

    Returns
    -------
    EnvelopeResult
        ``failures`` lists the samples that failed (left out).
    """
    from infra.criteria import DEFAULT_MIN_GROWTH_PER_S
    from stability.uncertainty.ranges import Ranges

    from ..envelope import read_ranges, run_envelope
    from ..bench import driveline_view
    values, driveline = driveline_view(
        checked_values(parameters, changes, freq_hz=freq_hz,
                       p_max_bar=p_max_bar, min_growth=min_growth),
        driveline)
    _refuse_modes(values)
    if not isinstance(ranges, Ranges):
        ranges = read_ranges(ranges, values)
    growth = DEFAULT_MIN_GROWTH_PER_S if min_growth is None else min_growth
    started = time.perf_counter()
    result, failures, resumed = run_envelope(
        values, ranges, freq_hz, p_max_bar * PA_PER_BAR, samples=samples,
        seed=seed, sampler=sampler, vertices=vertices, method=method,
        min_growth=growth, amplitudes=BACKGROUND_AMPLITUDES, refine=refine,
        workers=workers, checkpoint=checkpoint, progress=progress)
    return EnvelopeResult(params=values, ranges=ranges, envelope=result,
                          failures=failures, resumed=resumed,
                          seconds=time.perf_counter() - started,
                          checkpoint=checkpoint, driveline=driveline)


def _refuse_modes(values):
    """Refuse a hybrid Modelica class (:func:`linearised_mode`): its
    linearisation holds in one mode, which would have to be checked at
    each of the envelope's parameter sets (its samples, the corners of
    the ranges, the refinement's) and each frequency (about 6 ms a
    setting checked in batches: 256 samples over 100 frequencies take
    2.5 minutes), and was
    checked at the nominal set only."""
    mode = linearised_mode(values)
    if mode:
        raise JudderError(
            f"{values.model} is {mode_words(mode)}, checked at the "
            "nominal parameters only: each of the envelope's parameter "
            "sets (its samples, the corners of the ranges and those the "
            "refinement searches) would need it checked at every "
            "frequency, about 6 ms a setting, so the envelope is not run "
            "on a class with modes; allowed: judder sensitivity, which "
            "checks the mode at each parameter set it uses, or a class "
            "without Integer and Boolean modes")


def _bar_or_none(values):
    return [finite_or_none(v / PA_PER_BAR) for v in values]


@dataclass(frozen=True)
class EnvelopeResult:
    """``judder envelope``: a
    :class:`stability.uncertainty.envelope.Envelope`, the
    ranges it was sampled from, the failed samples (each an
    :class:`infra.parallel.TaskFailure`) and how many samples came from the
    checkpoint."""

    params: object
    ranges: object
    envelope: object
    failures: list
    resumed: int
    seconds: float
    checkpoint: object = None
    driveline: str = "chain"

    #: Probabilities whose boundaries the CSV lists.
    LEVELS = (0.1, 0.5, 0.9)

    def as_dict(self):
        e = self.envelope
        from ..bench import driveline_words
        return {"model": self.params.model, "driveline": self.driveline,
                "driveline_description": driveline_words(self.params,
                                                         self.driveline),
                "method": e.method,
                "min_growth_per_s": e.min_growth, "seconds": self.seconds,
                "ranges": self.ranges.describe(),
                "samples": int(len(e.ok)), "vertices": int(e.is_vertex.sum()),
                "computed": int(e.ok.sum()), "resumed": self.resumed,
                "failures": [{"index": f.index, "inputs": f.inputs,
                              "message": f.message} for f in self.failures],
                "convergence": e.convergence,
                "freq_hz": e.freq_hz, "p_max_bar": e.p_max / PA_PER_BAR,
                "nominal_p_f_bar": _bar_or_none(e.nominal_boundary),
                "broadest_p_f_bar": _bar_or_none(e.broadest),
                "unstable_share_at_p_max":
                    [finite_or_none(v) for v in e.probability[:, -1]]}

    def csv_text(self):
        """Per frequency: nominal and broadest boundary, and the amplitude
        from which 10, 50, 90 % of the samples are unstable (bar; empty:
        none up to p_max)."""
        e = self.envelope
        columns = [e.nominal_boundary, e.broadest] + [
            e.quantile_boundary(q) for q in self.LEVELS]
        rows = [{"freq_hz": f"{f:.9g}", **{
            name: (None if not math.isfinite(c[i]) else
                   f"{c[i] / PA_PER_BAR:.9g}")
            for name, c in zip(["nominal_p_f_bar", "broadest_p_f_bar"] + [
                f"p_f_bar_{round(100 * q)}pct_unstable" for q in self.LEVELS],
                columns)}} for i, f in enumerate(e.freq_hz)]
        return rows_to_csv(rows)

    @keeps_foreign_files
    def save_csv(self, path):
        write_text(path, self.csv_text())

    @keeps_foreign_files
    def save(self, path):
        """NPZ: every sample's values and boundaries, the nominal, the
        broadest edge, the probability grid (bar where named so).

        ``amplitude_bar`` is (samples, frequencies, kinds) and
        ``nominal_bar`` (frequencies, kinds): the lowest boundary of each
        kind, the kinds named by ``amplitude_bar_axes`` and
        ``kind_columns`` (NaN: none up to ``p_max_bar``); ``probability``
        is (frequencies, amplitudes)."""
        e = self.envelope
        arrays = {"freq_hz": e.freq_hz, "p_f_bar": e.p_f / PA_PER_BAR,
                  "p_max_bar": e.p_max / PA_PER_BAR,
                  "names": np.array(e.names), "values": e.values,
                  "is_vertex": e.is_vertex, "ok": e.ok,
                  "amplitude_bar": e.amplitude / PA_PER_BAR,
                  "amplitude_bar_axes": np.array(["sample", "freq_hz",
                                                  "kind"]),
                  "kind_columns": np.array(KINDS[1:]),
                  "nominal_bar": e.nominal / PA_PER_BAR,
                  "broadest_bar": e.broadest / PA_PER_BAR,
                  "probability": e.probability,
                  "area_history_bar_hz": e.area_history / PA_PER_BAR,
                  "min_growth_per_s": e.min_growth,
                  "meta": json.dumps({
                      "model": self.params.model,
                      "ranges": self.ranges.describe(),
                      "convergence": e.convergence, "method": e.method,
                      "failures": [str(f) for f in self.failures]})}
        save_npz(path, arrays)

    def discard_checkpoint(self):
        """Delete the checkpoint once the outputs are written (kept while
        samples failed, so a new run retries only those)."""
        if self.checkpoint is not None and not self.failures:
            Path(self.checkpoint).unlink(missing_ok=True)

    def figure(self, title=None):
        from stability.plots import envelope_figure
        return envelope_figure(self.envelope, title=title)
