"""``judder chart``: experimental stability chart from bench acquisitions
(Fig. 10, 11).
"""

from dataclasses import dataclass
import time

import numpy as np

from infra.contract import warn
from infra.criteria import DEFAULT_JUDDER_LIMIT_RPM
from infra.errors import JudderError
from infra.files import (all_or_none, keeps_foreign_files, save_npz,
                         write_text)
from infra.units import PA_PER_BAR
from stability.monodromy import DEFAULT_METHOD

from ._arguments import (decimal_option, driveline_option, force_option,
                         limit_option,
                         method_option, model_options, refuse_decimal,
                         workers_option)
from ._flags import in_flags
from ._model import parameters_of
from ._output import Progress, emit, make_parents, write_outputs, written
from ._preflight import check_acquisitions
from ._values import MIN_GROWTH, Quantity
from .tongues import tongues

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
    p.add_argument("--bench-linearisation", action="store_true",
                   help="the same as --driveline bench (kept for one "
                        "release)")
    driveline_option(p)
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
                       bench_linearisation=args.bench_linearisation,
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
        judder = sum(r.analysis.judder for r in runs)
        estimated = sum(r.analysis.estimated for r in runs)
        mechanisms = ", ".join(
            f"{n} {m}" for m in ("forced", "parametric", "both")
            if (n := sum(r.analysis.mechanism == m for r in runs)))
        rows.append(f"{label}: {len(runs)} run{'s' * (len(runs) != 1)}, "
                    f"{judder} with judder"
                    + (f" ({mechanisms})" if mechanisms else "")
                    + (f" ({estimated} with the dither estimated from the "
                       "pressure)" if estimated else ""))
        for f, p, top in result.chart.boundary(group):
            rows.append(f"  {f:8.2f} Hz: " + (
                f"judder from {p:.3g} bar" if p is not None else
                f"no judder up to {top:.3g} bar"))
        rows += [f"  {run.path.name}: on no boundary and in no contour: "
                 f"its dither frequency, estimated at "
                 f"{run.analysis.freq_hz:.4g} Hz, may be an alias (see its "
                 "warning); give freq_hz in the index"
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


def chart(sources, index=None, channels=None, group_by=None, decimal=None,
          min_growth=None, min_amplitude_rpm=None,
          judder_limit_rpm=DEFAULT_JUDDER_LIMIT_RPM, model=False,
          parameters=None, changes=None, method=DEFAULT_METHOD,
          workers=None, progress=None, bench_linearisation=False,
          driveline=None):
    """``judder chart``: experimental stability charts from bench
    acquisitions (section 3.2, Fig. 10 and 11).

    Parameters
    ----------
    sources : sequence of path
        Campaign folders (``index.csv``) and acquisition files (MF4, CSV,
        TDMS, MAT).
    index : path, optional
        CSV with a ``file`` column and the runs' settings.
    channels : dict, optional
        Role (``upstream_speed``, ``pressure``, ``downstream_speed``) ->
        :class:`pysim.bench_data.acquisition.ChannelSpec`; default the names
        ``judder campaign`` writes.
    group_by : sequence of str, optional
        Columns making the panels (default: oil temperature and engine
        speed where they vary).
    decimal : {'.', ','}, optional
        Decimal separator of CSV acquisitions and of ``index`` (default:
        decided per file from its cells).
    min_growth : float, optional
        Growth rate (1/s) from which a run counts as judder (default
        :data:`infra.criteria.DEFAULT_MIN_GROWTH_PER_S`).
    min_amplitude_rpm : float, optional
    judder_limit_rpm : float
        NVH limit of the dither-related oscillation, rpm.
    model : bool
        Also compute the model's tongue boundaries (``parameters`` and
        ``changes``) over the chart's frequencies, drawn by ``figure()``.
    bench_linearisation : bool
        The same as ``driveline='bench'`` (kept for one release).
    driveline : {'chain', 'bench'}, optional
        Whose tongues ``model`` draws (:func:`judder.bench.driveline_view`;
        default the bench where the preset has one, as a chart of ``judder
        campaign`` runs has them: tongues 5, 6 at 86.4 and 119.4 Hz with
        the Appendix values, not 84 and 122).

    Returns
    -------
    ChartResult
    """
    from infra.criteria import DEFAULT_MIN_GROWTH_PER_S
    from pysim.bench.charts import build_chart, gather_sources
    from pysim.bench.readers import TEXT_SUFFIXES
    from pysim.bench.verdict import MIN_AMPLITUDE_RPM
    started = time.perf_counter()
    runs = gather_sources(sources, index, decimal)
    if index is None and not any(run.path.suffix.lower() in TEXT_SUFFIXES
                                 for run in runs):
        refuse_decimal(decimal, "CSV acquisitions and a --index file",
                       "where every acquisition is binary (MF4, TDMS, "
                       "MAT) and no --index is given")
    run_bytes = check_acquisitions([run.path for run in runs], workers)
    result = build_chart(
        runs, channels=channels, run_bytes=run_bytes,
        group_by=group_by, decimal=decimal,
        min_growth=DEFAULT_MIN_GROWTH_PER_S if min_growth is None else min_growth,
        min_amplitude_rpm=(MIN_AMPLITUDE_RPM if min_amplitude_rpm is None
                           else min_amplitude_rpm),
        judder_limit_rpm=judder_limit_rpm,
        workers=workers, callback=progress)
    seconds = time.perf_counter() - started
    overlay = None
    if model and result.read:
        freqs = [r.analysis.freq_hz for r in result.read]
        top = max(r.analysis.p_f_bar for r in result.read)
        overlay = tongues(np.linspace(min(freqs), max(freqs), 200),
                          max(1.5 * top, 0.1), parameters, changes,
                          method=method,
                          driveline="bench" if bench_linearisation
                          else driveline)
    return ChartResult(chart=result, seconds=seconds, model=overlay)


@dataclass(frozen=True)
class ChartResult:
    """``judder chart``: an experimental stability chart (Fig. 10, 11).

    ``chart`` is the :class:`pysim.bench_data.charts.Chart`; ``model`` the
    :class:`TonguesResult` of the model drawn over it (None unless asked
    for).
    """

    chart: object
    seconds: float
    model: object = None

    def _boundaries(self):
        return {"/".join(group): self.chart.boundary(group)
                for group in self.chart.groups()}

    def as_dict(self):
        from pysim.bench.verdict import dither_estimate_dict
        chart = self.chart
        runs = []
        for run in chart.read:
            a = run.analysis
            estimate = dither_estimate_dict(a.dither, a.given)
            if estimate is not None:
                # the warnings as the command prints them: the file and
                # the pressure channel named
                estimate["warnings"] = list(run.warnings)
            runs.append({"file": str(run.path), **{
                c: run.settings.get(c) for c in chart.group_by},
                "freq_hz": a.freq_hz, "p_f_bar": a.p_f_bar,
                "dither_estimated": a.estimated,
                "dither_estimate": estimate,
                "speed_kind": run.speed_kind,
                "amplitude_rpm": a.amplitude_rpm,
                "growth_per_s": a.growth_per_s, "judder": a.judder,
                "verdict": a.verdict,
                "kind": a.kind, "mechanism": a.mechanism,
                "oscillation_rpm": a.oscillation_rpm,
                "forced_rpm": a.forced_rpm})
        boundaries = self._boundaries()
        single = next(iter(boundaries.values())) if len(boundaries) == 1 \
            else None
        return {"runs": runs, "group_by": list(chart.group_by),
                "min_growth_per_s": chart.min_growth,
                "judder_limit_rpm": chart.judder_limit_rpm,
                "boundary": None if single is None else
                [[f, p] for f, p, _ in single],
                "boundaries": {g: [[f, p] for f, p, _ in b]
                               for g, b in boundaries.items()},
                "set_points": {"/".join(group): [
                    {"freq_hz": f, "spread_hz": spread, "runs": len(runs)}
                    for f, spread, runs in chart.set_points(group)]
                    for group in chart.groups()},
                "failed": [{"file": str(r.path), "message": r.error}
                           for r in chart.failed],
                "seconds": self.seconds}

    @keeps_foreign_files
    def save(self, path):
        """Save the chart as NPZ: the per-run arrays of
        :meth:`pysim.bench_data.charts.Chart.arrays` and, per group, the
        boundary (``boundary_group``, ``boundary_freq_hz``, ``boundary_p_f_bar``
        with NaN where censored, ``boundary_tried_bar``, and
        ``boundary_below_bar``: the highest amplitude without judder below
        each onset, NaN where none)."""
        chart = self.chart
        rows = [("/".join(g), f, np.nan if p is None else p, top,
                 np.nan if q is None else q)
                for g in chart.groups()
                for (f, p, top), q in zip(chart.boundary(g),
                                          chart.quiet_below(g))]
        arrays = {**chart.arrays(),
                  "boundary_group": np.array([r[0] for r in rows]),
                  "boundary_freq_hz": np.array([r[1] for r in rows]),
                  "boundary_p_f_bar": np.array([r[2] for r in rows]),
                  "boundary_tried_bar": np.array([r[3] for r in rows]),
                  "boundary_below_bar": np.array([r[4] for r in rows]),
                  "group_by": np.array(chart.group_by),
                  "min_growth_per_s": np.array(chart.min_growth),
                  "judder_limit_rpm": np.array(chart.judder_limit_rpm)}
        save_npz(path, arrays)

    def save_boundary(self, path, force=False):
        """Write the experimental boundary as ``judder fit --boundary``
        reads it; with several groups, one file per group
        (``STEM_GROUP.csv``, a number as 1000, not 1000.0). Returns the
        paths written.

        Without ``force``, refuses (before writing any) to replace a file
        judder did not write (:func:`infra.files.check_output`).
        """
        from pathlib import Path

        from infra.files import check_output
        path = Path(path)
        groups = list(self.chart.groups())
        targets = [path if len(groups) == 1 else path.with_name(
            f"{path.stem}_{'_'.join(_file_word(v) for v in group)}"
            f"{path.suffix}")
            for group in groups]
        for target in targets:
            check_output(target, "--boundary", ("csv",), force)
        for group, target in zip(groups, targets):
            write_text(target, self.chart.boundary_csv(group))
        return [str(target) for target in targets]

    def figure(self, title=None):
        from pysim.bench.plots import chart_figure
        fig, panels = chart_figure(self.chart, title=title)
        if self.model is not None:
            from stability.plots import plot_boundaries
            for ax in panels.values():
                limits = ax.get_xlim(), ax.get_ylim()
                plot_boundaries(self.model.boundaries, ax=ax,
                                label=f"model ({self.model.params.model})")
                ax.set_xlim(*limits[0])
                ax.set_ylim(*limits[1])
        return fig


def _file_word(value):
    """A group value as it reads in a file name: a number without a
    trailing ``.0`` (1000, not 1000.0), text as it is."""
    try:
        return f"{float(value):g}"
    except ValueError:
        return str(value)
