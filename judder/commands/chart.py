"""``judder chart``: experimental stability chart from bench acquisitions
(Fig. 10, 11).
"""

from infra.contract import warn
from infra.criteria import CANNOT_TELL
from infra.errors import JudderError
from infra.files import all_or_none
from infra.units import PA_PER_BAR
from studies.chart import chart

from ._arguments import (decimal_option, driveline_option, force_option,
                         limit_option, method_option, model_options,
                         renamed_option, workers_option)
from ._flags import in_flags
from ._model import parameters_of
from ._output import Progress, emit, make_parents, write_outputs, written
from ._values import MIN_GROWTH, Quantity

#: The command's --help text.
DESCRIPTION = (
    "Read engagement acquisitions (a campaign folder, or MF4, CSV, TDMS "
    "and MAT files), find in each run the engagement window, the dither "
    "setting (given, from the file's metadata, or estimated from the "
    "pressure), the amplitude and growth of the upstream speed at f, "
    "f/2 and other peaks, and the judder verdict as a bench engineer "
    "reads it: the dither-related oscillation exceeds --limit (rpm) or "
    "an instability grows at >= --min-growth, with its mechanism: "
    "forced (the dither drives a resonance), parametric (an instability: "
    "growth, f/2 or a combination frequency) or both. Draws the "
    "amplitude contour per oil temperature or engine speed, and writes "
    "the experimental boundary for `judder fit --boundary`. Give "
    "--model, --preset, --param-file or --set to draw the model's "
    "tongue boundaries over it: those of the driveline on its test "
    "bench where the preset has one (c1 + d_control, what a `judder "
    "campaign` chart shows), else of the chain; --driveline chooses.")


OUTPUTS = (("out", "--out", ("npz",)),
           ("plot", "--plot", None),
           ("boundary", "--boundary", ("csv",)))


def read_too(args):
    """The acquisitions the --index file lists, by the index's line ->
    path: the input digest covers their bytes, not the
    index's alone (two data sets that differ in one acquisition differ in
    their digest; a campaign folder given as SOURCE is hashed whole)."""
    if args.index is None:
        return {}
    from pysim.bench.charts import sources_from_index
    return {source.origin.rsplit(",", 1)[-1].strip(): source.path
            for source in sources_from_index(args.index, args.decimal)}


def add_arguments(p):
    """The options of ``judder chart``."""
    p.add_argument("sources", nargs="*", metavar="SOURCE",
                   help="campaign folder (with index.csv) or acquisition "
                        "file (.mf4, .csv, .tdms, .mat)")
    p.add_argument("--index", metavar="FILE.csv",
                   help="CSV with a 'file' column (relative to it) and "
                        "optional freq_hz, p_f_bar, oil_temperature, "
                        "engine_rpm and further columns")
    p.add_argument("--channel", action="append", default=[],
                   metavar="ROLE=NAME[:UNIT[:KIND]]",
                   help="channel of ROLE (upstream_speed, required; "
                        "pressure; downstream_speed; time, the files' time "
                        "column when it is not called time, t, Zeit or "
                        "timestamp, e.g. 'time=Zeit  1 - "
                        "Standardmessrate:s') in the files, with its "
                        "unit if the file has none (rpm, rad/s, bar, Pa, "
                        "...; an angle unit, rad, deg, rev or counts/N "
                        "(N a revolution), for an encoder) or a sensor's "
                        "linear scale LOW..HIGH UNIT=LOW..HIGH UNIT (e.g. "
                        "pressure=Ch3:4..20mA=0..25bar: 4-20 mA recorded "
                        "for 0-25 bar); for a speed, "
                        "KIND says what its samples "
                        "are: passage (a pick-up's tooth passages), "
                        "sampled (a DAQ's rate), angle (an encoder), "
                        "default told from the data; repeatable. Without "
                        "any, the names judder campaign writes")
    decimal_option(p, "the CSV acquisitions and the --index file")
    p.add_argument("--group-by", action="append", metavar="COLUMN",
                   help="panel per value of COLUMN; repeatable (default: "
                        "oil_temperature and engine_rpm where they vary)")
    p.add_argument("--min-growth", type=MIN_GROWTH,
                   default=None, metavar="1/S",
                   help="growth rate of the non-periodic part from which "
                        "a run is judder, 1/s (default 1)")
    p.add_argument("--min-amplitude",
                   type=Quantity("--min-amplitude", "rpm", 0.0), default=None,
                   metavar="RPM", help="smallest judder amplitude, rpm "
                                       "(default 2)")
    limit_option(p)
    driveline_option(p)
    renamed_option(p, "--bench-linearisation", "--driveline bench",
                   "driveline", const="bench")
    p.add_argument("--out", metavar="FILE.npz",
                   help="per-run arrays and boundaries (NPZ)")
    p.add_argument("--boundary", metavar="FILE.csv",
                   help="experimental boundary (freq_hz,p_f_bar; empty = "
                        "no judder); with several groups one file each, "
                        "named by the group (b.csv: b_1000.csv, "
                        "b_1500.csv, ...), each named on its 'wrote' line")
    p.add_argument("--plot", metavar="FILE.png",
                   help="the chart, one panel per group")
    workers_option(p)
    method_option(p)
    model_options(p, modelica=False)
    force_option(p)


def run(args):
    """Experimental stability chart from bench acquisitions."""
    channels = _channels(args.channel)
    overlay = bool(args.model or args.preset or args.param_file or args.set)
    params, changes = parameters_of(args)
    make_parents(args.out, args.plot, args.boundary)
    with Progress(None, "runs") as progress:
        result = chart(args.sources, index=args.index, channels=channels,
                       group_by=args.group_by, decimal=args.decimal,
                       min_growth=args.min_growth,
                       min_amplitude_rpm=args.min_amplitude,
                       judder_limit_rpm=args.limit,
                       model=overlay, parameters=params,
                       driveline=args.driveline,
                       changes=changes, method=args.method,
                       workers=args.workers, progress=progress)
    if not result.chart.read:
        # before any output is written: a chart of no run is none
        raise JudderError(_unread(result.chart.failed))
    for text in (t for run in result.chart.read for t in run.warnings):
        warn(text)
    with all_or_none():     # --out, --plot and --boundary, or none
        files = write_outputs(args, result, figure={
            "title": "experimental stability chart"
                     + (f" with the {params.model} model's boundaries"
                        if overlay else "")})
        boundaries = (result.save_boundary(args.boundary, force=args.force)
                      if args.boundary else [])
    data = {**result.as_dict(), **files, "boundary_files": boundaries}
    data["failed"] = [{**failed, "message": in_flags(failed["message"])}
                      for failed in data["failed"]]
    rows = []
    for group, runs in result.chart.groups().items():
        label = ", ".join(f"{c} {v}" for c, v in
                          zip(result.chart.group_by, group)) or "all runs"
        # a run that cannot be told is counted as no verdict
        told = result.chart.told(group)
        judder = sum(r.analysis.judder for r in told)
        estimated = sum(r.analysis.estimated for r in runs)
        mechanisms = ", ".join(
            f"{n} {m}" for m in ("forced", "parametric", "both")
            if (n := sum(r.analysis.mechanism == m for r in told)))
        untold = len(runs) - len(told)
        rows.append(f"{label}: {len(runs)} run{'s' * (len(runs) != 1)}, "
                    f"{judder} with judder"
                    + (f" ({mechanisms})" if mechanisms else "")
                    + (f", {len(told) - judder} without, {untold} cannot "
                       "tell (no verdict)" if untold else "")
                    + (f" ({estimated} with the dither estimated from the "
                       "pressure)" if estimated else ""))
        for f, p, top in result.chart.boundary(group):
            rows.append(f"  {f:8.2f} Hz: " + (
                f"judder from {p:.3g} bar" if p is not None else
                f"no judder up to {top:.3g} bar"))
        rows += [f"  {run.path.name}: {CANNOT_TELL}, on no boundary and "
                 f"in no contour: {run.analysis.cannot_tell}"
                 + ("" if args.index else "; or list the runs in an "
                    "--index with a freq_hz column")
                 for run in result.chart.aliased(group)]
        rows += [_estimate_line(run) for run in runs
                 if run.analysis.dither is not None]
    rows += [f"could not read {in_flags(r.reason)}"
             for r in result.chart.failed]
    rows.append(f"{len(result.chart.runs)} runs in {result.seconds:.1f} s"
                + written(args.out, args.plot, *boundaries))
    emit(args, data, "\n".join(rows))


def _estimate_line(run):
    """A run's dither as estimated from its pressure, with the standard
    uncertainties, and the values that were given instead."""
    fit, given = run.analysis.dither, run.analysis.given
    freq = (f"{fit.freq_hz:.4g} Hz (given)" if "freq_hz" in given else
            f"{fit.freq_hz:.4g} ± {fit.freq_std_hz:.2g} Hz")
    amplitude = (f"{fit.amplitude / PA_PER_BAR:.3g} ± "
                 f"{fit.amplitude_std / PA_PER_BAR:.2g} bar")
    if "p_f_bar" in given:
        amplitude = (f"{run.analysis.p_f_bar:.4g} bar (given; the "
                     f"pressure's {amplitude})")
    return (f"  {run.path.name}: dither estimated {freq}, {amplitude}, "
            f"phase {fit.phase_rad:.3f} ± {fit.phase_std_rad:.2g} rad at "
            f"{fit.reference_s:.4g} s (standard uncertainties)")


#: Unreadable runs named in the error when none could be read.
_LISTED_FAILURES = 3


def _unread(failed):
    """The error line when no run could be read: each file's reason."""
    listed = "; ".join(r.reason for r in failed[:_LISTED_FAILURES])
    more = len(failed) - _LISTED_FAILURES
    return ("no run could be read: " if len(failed) == 1 else
            f"none of the {len(failed)} runs could be read: ") + listed \
        + (f"; and {more} more" if more > 0 else "")


def _channels(items):
    """``ROLE=NAME[:UNIT]`` strings as ``{role: ChannelSpec}`` (None if
    none given: the names judder campaign writes)."""
    from pysim.bench.channels import parse_channel_option
    if not items:
        return None
    channels, given = {}, {}
    for item in items:
        role, spec = parse_channel_option(item)
        if role in channels:
            raise JudderError(
                f"--channel {given[role]} and --channel {item} both give "
                f"{role}; allowed: one channel per role")
        channels[role], given[role] = spec, item
    if "upstream_speed" not in channels:
        raise JudderError("--channel upstream_speed=NAME is required when "
                          "--channel is given")
    return channels
