"""``judder chart``: experimental stability chart from bench acquisitions
(Fig. 10, 11).
"""

from dataclasses import dataclass
import time

import numpy as np

from infra.criteria import DEFAULT_JUDDER_LIMIT_RPM
from infra.files import keeps_foreign_files, save_npz, write_text
from stability.monodromy import DEFAULT_METHOD

from ._preflight import check_acquisitions
from .rules import refuse_decimal
from .tongues import tongues


def chart(sources, index=None, channels=None, group_by=None, decimal=None,
          min_growth=None, min_amplitude_rpm=None,
          judder_limit_rpm=DEFAULT_JUDDER_LIMIT_RPM, model=False,
          parameters=None, changes=None, method=DEFAULT_METHOD,
          workers=None, progress=None, driveline=None):
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
        :class:`pysim.bench.acquisition.ChannelSpec`; default the names
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
    driveline : {'chain', 'bench'}, optional
        Whose tongues ``model`` draws (:func:`stability.bench.driveline_view`;
        default the bench where the preset has one, as a chart of ``judder
        campaign`` runs has them: tongues 5, 6 at 86.4 and 119.4 Hz with
        the Appendix values, not 84 and 122).

    Returns
    -------
    ChartResult
    """
    from infra.criteria import DEFAULT_MIN_GROWTH_PER_S
    from pysim.bench.verdict import MIN_AMPLITUDE_RPM
    from pysim.bench.charts import build_chart, gather_sources
    from pysim.bench.readers import TEXT_SUFFIXES
    started = time.perf_counter()
    runs = gather_sources(sources, index, decimal)
    if index is None and not any(run.path.suffix.lower() in TEXT_SUFFIXES
                                 for run in runs):
        refuse_decimal(decimal, "CSV acquisitions and an `index` file",
                       "where every acquisition is binary (MF4, TDMS, "
                       "MAT) and no `index` is given")
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
                          driveline=driveline)
    return ChartResult(chart=result, seconds=seconds, model=overlay)


@dataclass(frozen=True)
class ChartResult:
    """``judder chart``: an experimental stability chart (Fig. 10, 11).

    ``chart`` is the :class:`pysim.bench.charts.Chart`; ``model`` the
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
            # a run that cannot be told is no verdict: no judder, kind or
            # mechanism, and why (``cannot_tell``)
            told = a.cannot_tell is None
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
                "growth_per_s": a.growth_per_s,
                "growth_std_per_s": a.growth_std_per_s,
                "judder": a.judder if told else None,
                "verdict": a.verdict, "cannot_tell": a.cannot_tell,
                "kind": a.kind if told else None,
                "mechanism": a.mechanism if told else None,
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
        :meth:`pysim.bench.charts.Chart.arrays` and, per group, the
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
            check_output(target, "`boundary`", ("csv",), force)
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
