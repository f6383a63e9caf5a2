"""Result objects of the :mod:`judder.api` functions, one per command.

Each holds the kernel results it was made from, and gives

* ``as_dict()``: the fields ``judder COMMAND --json`` prints (SI inside,
  Hz and bar where the name says so; complex numbers as ``[re, im]``);
* ``save(path)``: the command's ``--out`` file, written atomically;
* ``figure()``: the command's ``--plot`` figure (matplotlib, imported
  only then).

The command line only formats these; a Python user gets the same numbers
and files from the same objects.
"""

from dataclasses import dataclass, field
import csv
import io
import json
import math
from pathlib import Path

import numpy as np

from drivelines import dumps_toml
from infra.files import atomic_write, write_text
from infra.units import PA_PER_BAR
from stability.kinds import KINDS

__all__ = ["ParamsResult", "EigResult", "FloquetPoint", "MapResult",
           "TonguesResult", "SensitivityResult", "ThresholdResult",
           "FitReport", "SimulationResult", "CrosscheckResult",
           "CampaignResult", "ChartResult", "EnvelopeResult"]


def _finite_or_none(value):
    """A float for JSON, None where it is NaN or infinite (undetermined,
    censored)."""
    value = float(value)
    return value if math.isfinite(value) else None


def _csv_text(rows, columns=None):
    """CSV of a list of dicts; None becomes an empty cell."""
    columns = list(columns or (rows[0] if rows else []))
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow(columns)
    for row in rows:
        writer.writerow(["" if row[c] is None else row[c] for c in columns])
    return buffer.getvalue()


@dataclass(frozen=True)
class ParamsResult:
    """``judder params``: a parameter set with units and meanings."""

    params: object

    def as_dict(self):
        specs = self.params.specs
        return {"model": self.params.model,
                "parameters": {name: {"value": self.params[name],
                                      "unit": spec.unit,
                                      "allowed": spec.allowed(),
                                      "description": spec.description}
                               for name, spec in specs.items()}}

    def save(self, path, overwrite=False):
        """Write the set as TOML (refuses to replace a file by default)."""
        write_text(path, dumps_toml(self.params), overwrite=overwrite)


@dataclass(frozen=True)
class EigResult:
    """``judder eig``: natural frequencies (Eq. 15) and damping (Eq. 16).

    Frequencies in Hz; ``damping_factor_12`` and ``damping_ratio`` as
    fractions.
    """

    params: object
    natural_frequencies_hz: np.ndarray
    closed_form_frequencies_hz: np.ndarray
    damping_factor_12: float
    damped_frequencies_hz: np.ndarray
    damping_ratio: np.ndarray

    def as_dict(self):
        return {"model": self.params.model,
                "natural_frequencies_hz": self.natural_frequencies_hz,
                "closed_form_frequencies_hz": self.closed_form_frequencies_hz,
                "damping_factor_12": self.damping_factor_12,
                "damping_factor_12_percent": 100 * self.damping_factor_12,
                "damped_modes": [{"frequency_hz": f, "damping_ratio": r}
                                 for f, r in zip(self.damped_frequencies_hz,
                                                 self.damping_ratio)]}


@dataclass(frozen=True)
class FloquetPoint:
    """``judder floquet``: the multipliers at one dither setting.

    ``result`` is the :class:`stability.floquet.FloquetResult`.
    """

    params: object
    method: str
    result: object

    @property
    def p_f_bar(self):
        return self.result.p_f / PA_PER_BAR

    def as_dict(self):
        r = self.result
        return {"model": self.params.model, "freq_hz": r.freq_hz,
                "p_f_bar": self.p_f_bar, "p_f_pa": r.p_f,
                "period_s": r.period, "method": self.method,
                "multipliers": r.multipliers, "leading": r.leading,
                "leading_abs": r.leading_abs, "kind": r.kind,
                "growth_rate_per_s": r.growth_rate,
                "exponents_per_s": r.exponents}


@dataclass(frozen=True)
class MapResult:
    """``judder map``: the stability map (Fig. 12, 14) and its timing.

    ``map`` is the :class:`stability.maps.StabilityMap`; ``seconds`` the
    computing time.
    """

    params: object
    map: object
    seconds: float

    def as_dict(self):
        m = self.map
        bar = m.p_f / PA_PER_BAR
        return {"model": self.params.model, "method": m.method,
                "points": int(m.kind.size), "seconds": self.seconds,
                "freq_hz": [m.freq_hz[0], m.freq_hz[-1], len(m.freq_hz)],
                "p_f_bar": [bar[0], bar[-1], len(bar)],
                "counts": m.counts(),
                "max_leading_abs": float(m.leading_abs.max()),
                "natural_frequencies_hz": m.natural_frequencies_hz}

    def save(self, path, meta=None):
        """Save the map as NPZ.

        Arrays: ``freq_hz`` (nf,), ``p_f_pa`` and ``p_f_bar`` (np,),
        ``leading_re``/``leading_im``/``leading_abs``/``growth_rate_per_s``
        (nf, np), ``kind`` (nf, np, int8), ``kind_names``,
        ``natural_frequencies_hz``; ``parameters`` holds a JSON string of
        the model, the parameter values (SI), the method and ``meta``.
        """
        m = self.map
        info = {"model": self.params.model,
                "parameters": self.params.as_dict(), "method": m.method,
                "seconds": self.seconds, **(meta or {})}
        arrays = {
            "freq_hz": m.freq_hz, "p_f_pa": m.p_f,
            "p_f_bar": m.p_f / PA_PER_BAR,
            "leading_re": m.leading.real, "leading_im": m.leading.imag,
            "leading_abs": m.leading_abs,
            "growth_rate_per_s": m.growth_rate, "kind": m.kind,
            "kind_names": np.array(KINDS),
            "natural_frequencies_hz": m.natural_frequencies_hz,
            "parameters": np.array(json.dumps(info)),
        }
        atomic_write(path,
                     lambda stream: np.savez_compressed(stream, **arrays))

    def figure(self, title=None):
        from stability.plotting import map_figure
        return map_figure(self.map, title=title)


def tongue_record(tongue):
    """A :class:`stability.tongues.Tongue` as JSON fields (bar, Hz)."""
    return {"number": tongue.number, "kind": tongue.kind,
            "resonance": tongue.resonance,
            "resonance_hz": tongue.resonance_hz,
            "tip_freq_hz": tongue.tip_freq_hz,
            "tip_p_f_bar": tongue.tip_p_f / PA_PER_BAR,
            "tip_offset_percent": None if tongue.resonance_hz is None else
            100 * (tongue.tip_freq_hz / tongue.resonance_hz - 1),
            "tip_multiplier_error": tongue.tip_multiplier_error,
            "freq_range_hz": list(tongue.freq_range_hz),
            "tip_at_edge": tongue.tip_at_edge}


@dataclass(frozen=True)
class TonguesResult:
    """``judder tongues``: exact boundaries, labelled tongues and tips.

    ``boundaries`` is a :class:`stability.tongues.Boundaries`, ``tongues``
    a list of :class:`stability.tongues.Tongue`; ``background`` the map
    drawn under them (None unless asked for).
    """

    params: object
    boundaries: object
    tongues: list
    seconds: float
    background: object = None

    def as_dict(self):
        b = self.boundaries
        return {"model": self.params.model, "method": b.method,
                "min_growth_per_s": b.min_growth, "seconds": self.seconds,
                "freq_hz": [b.freq_hz[0], b.freq_hz[-1], len(b.freq_hz)],
                "p_max_bar": b.p_max / PA_PER_BAR,
                "max_boundary_multiplier_error": b.max_multiplier_error,
                "natural_frequencies_hz": b.natural_frequencies_hz,
                "tongues": [tongue_record(t) for t in self.tongues]}

    def csv_text(self):
        """Boundaries as CSV: freq_hz, p_f_bar (lowest, empty if none),
        then the lowest boundary of each kind, bar."""
        lines = ["freq_hz,p_f_bar,single_period_bar,double_period_bar,"
                 "combination_bar"]
        b = self.boundaries

        def cell(value):
            return "" if not math.isfinite(value) \
                else f"{value / PA_PER_BAR:.9g}"
        for f, lowest, row in zip(b.freq_hz, b.stability_boundary,
                                  b.amplitude):
            lines.append(",".join([f"{f:.9g}", cell(lowest)]
                                  + [cell(v) for v in row]))
        return "\n".join(lines) + "\n"

    def save(self, path):
        write_text(path, self.csv_text())

    def figure(self, title=None):
        from stability.plotting import tongues_figure
        return tongues_figure(
            self.boundaries, self.tongues, self.background,
            title=title or f"{self.params.model}: tongue boundaries over "
                           "the map")


@dataclass(frozen=True)
class SensitivityResult:
    """``judder sensitivity``: tip shifts per varied parameter.

    ``study`` is the :class:`stability.sensitivity.SensitivityStudy`;
    ``tip_shifts`` and ``conclusions`` as
    :func:`stability.sensitivity.tip_shifts` and
    :func:`stability.sensitivity.paper_conclusions` give them.
    """

    params: object
    study: object
    tip_shifts: list
    conclusions: list
    seconds: float
    method: str

    @property
    def cases(self):
        return 1 + len(self.study.cases)

    def as_dict(self):
        return {"model": self.params.model, "method": self.method,
                "seconds": self.seconds, "cases": self.cases,
                "nominal_tongues": [tongue_record(t)
                                    for t in self.study.nominal.tongues],
                "tip_shifts": self.tip_shifts,
                "paper_conclusions": self.conclusions}

    def save(self, path):
        write_text(path, _csv_text(self.tip_shifts))

    def figure(self, title=None):
        return self.study.plot(
            title=title or f"{self.params.model}: sensitivity of the "
                           "stability boundary")


@dataclass(frozen=True)
class ThresholdResult:
    """``judder threshold``: Fig. 19 (a :class:`stability.threshold.ThresholdStudy`)."""

    params: object
    study: object

    @property
    def slope(self):
        """Slope of the threshold against c_i, s/rad per N m s/rad (None
        with one c_i)."""
        s = self.study
        if len(s.external_damping) < 2:
            return None
        return float(np.polyfit(s.external_damping, s.thresholds, 1)[0])

    def as_dict(self):
        s = self.study
        return {"model": self.params.model,
                "mean_pressure_damping":
                    self.params["mean_pressure_damping"],
                "mu_g": s.mu_g, "max_real_part_per_s": s.max_real_part,
                "mu_g_threshold": s.threshold,
                "external_damping": s.external_damping,
                "mu_g_thresholds": s.thresholds,
                "mu_g_thresholds_closed_form": s.closed_form,
                "slope": self.slope}

    def save(self, path):
        s = self.study
        lines = ["c_ext,mu_g_threshold,mu_g_threshold_closed_form"] + [
            f"{c:.9g},{m:.9g},{k:.9g}" for c, m, k in
            zip(s.external_damping, s.thresholds, s.closed_form)]
        write_text(path, "\n".join(lines) + "\n")

    def figure(self):
        import matplotlib.pyplot as plt
        fig, axes = plt.subplots(1, 2, figsize=(11, 4), layout="constrained")
        self.study.plot(axes=axes)
        return fig


@dataclass(frozen=True)
class FitReport:
    """``judder fit``: a :class:`stability.fitting.FitResult` and timing."""

    fit: object
    seconds: float
    method: str

    def as_dict(self):
        r = self.fit
        return {"model": r.params.model, "method": self.method,
                "seconds": self.seconds, "success": r.success,
                "message": r.message,
                "fitted": {n: {"value": v, "std": _finite_or_none(s),
                               "ci95": [_finite_or_none(lo),
                                        _finite_or_none(hi)], "start": s0}
                           for n, v, s, lo, hi, s0 in zip(
                               r.names, r.values, r.std, r.ci_low,
                               r.ci_high, r.start)},
                "uncertainty": r.uncertainty, "problems": list(r.problems),
                "notes": list(r.notes), "at_bound": list(r.at_bound),
                "undetermined": list(r.undetermined),
                "starts_tried": r.starts_tried,
                "starts_agreeing": r.starts_agreeing,
                "kinds": list(r.kinds),
                "residual_rms_bar": r.residual_rms_bar,
                "evaluations": r.evaluations, "freq_hz": r.freq_hz,
                "measured_bar": [_finite_or_none(v) for v in r.measured_bar],
                "model_bar": [_finite_or_none(v) for v in r.model_bar],
                "covariance": None if r.covariance is None else {
                    "names": list(r.names),
                    "matrix": [[_finite_or_none(v) for v in row]
                               for row in r.covariance]}}

    def save_params(self, path, overwrite=False):
        """Write the fitted parameter set as TOML."""
        write_text(path, dumps_toml(self.fit.params), overwrite=overwrite)

    def figure(self):
        return self.fit.plot()[0].figure


@dataclass(frozen=True)
class SimulationResult:
    """``judder simulate``: bench engagements through the FMU.

    Attributes
    ----------
    runs : list of (str, pysim.runs.Run)
        Labelled runs: the setting asked for first, then the comparison.
    summaries : list of dict
        Per run, :func:`pysim.engagement.engagement_summary` plus its
        ``label`` and the Floquet verdict of its dither setting
        (``floquet_kind``, ``floquet_exponent_per_s``).
    fmu : path
    model_class : str
    start : float
        End of the pressure ramp, s.
    """

    runs: list
    summaries: list
    fmu: object
    model_class: str
    start: float
    signals: dict = field(default_factory=dict)

    def as_dict(self):
        return {"model": self.model_class.rsplit(".", 1)[-1],
                "fmu": str(self.fmu), "runs": self.summaries}

    def save(self, path):
        """Time histories of the first run as CSV or MF4 (by suffix)."""
        from pysim.export import write_run
        run = self.runs[0][1]
        write_run(path, run.time, run.signals, self.signals,
                  {"model": self.model_class, "freq_hz": run.freq_hz,
                   "p_f_bar": run.p_f / PA_PER_BAR,
                   "start_values": run.start_values})

    def figure(self, title=None):
        from pysim.plotting import run_figure
        return run_figure(self.runs, start=self.start, title=title)


@dataclass(frozen=True)
class CrosscheckResult:
    """``judder crosscheck``: a :class:`judder.crosscheck.Crosscheck`."""

    params: object
    check: object
    seconds: float
    method: str

    def rows(self):
        """One dict per grid point (Hz, bar, 1/s)."""
        return [{"freq_hz": p.freq_hz, "p_f_bar": p.p_f / PA_PER_BAR,
                 "floquet_kind": p.floquet_kind,
                 "floquet_rate_per_s": p.floquet_rate,
                 "fitted_rate_per_s": p.fitted_rate,
                 "floquet_unstable": p.floquet_unstable,
                 "time_unstable": p.time_unstable, "agree": p.agree,
                 "reason": p.reason} for p in self.check.points]

    def as_dict(self):
        rows = self.rows()
        return {"model": self.params.model, "method": self.method,
                "points": len(rows), "seconds": self.seconds,
                "duration_s": self.check.duration,
                "agreement": self.check.agreement,
                "max_rate_error_above_1_per_s":
                    self.check.max_rate_error(above=1.0),
                "disagreements": [r for r in rows if not r["agree"]]}

    def save(self, path):
        write_text(path, _csv_text(self.rows()))

    def figure(self):
        from pysim.plotting import crosscheck_figure
        return crosscheck_figure(self.check)


@dataclass(frozen=True)
class CampaignResult:
    """``judder campaign``: the index rows of the campaign folder."""

    rows: list
    index: str
    seconds: float

    @property
    def failed(self):
        return [r for r in self.rows if r["status"] != "ok"]

    def as_dict(self):
        return {"runs": len(self.rows),
                "ok": len(self.rows) - len(self.failed),
                "failed": self.failed, "index": self.index,
                "seconds": self.seconds}


@dataclass(frozen=True)
class ChartResult:
    """``judder chart``: an experimental stability chart (Fig. 10, 11).

    ``chart`` is the :class:`pysim.charts.Chart`; ``model`` the
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
        chart = self.chart
        runs = []
        for run in chart.read:
            a = run.analysis
            runs.append({"file": str(run.path), **{
                c: run.settings.get(c) for c in chart.group_by},
                "freq_hz": a.freq_hz, "p_f_bar": a.p_f_bar,
                "dither_estimated": a.estimated,
                "amplitude_rpm": a.amplitude_rpm,
                "growth_per_s": a.growth_per_s, "judder": a.judder,
                "kind": a.kind})
        boundaries = self._boundaries()
        single = next(iter(boundaries.values())) if len(boundaries) == 1 \
            else None
        return {"runs": runs, "group_by": list(chart.group_by),
                "min_growth_per_s": chart.min_growth,
                "boundary": None if single is None else
                [[f, p] for f, p, _ in single],
                "boundaries": {g: [[f, p] for f, p, _ in b]
                               for g, b in boundaries.items()},
                "failed": [{"file": str(r.path), "message": r.error}
                           for r in chart.failed],
                "seconds": self.seconds}

    def save(self, path):
        """Save the chart as NPZ: the per-run arrays of
        :meth:`pysim.charts.Chart.arrays` and, per group, the boundary
        (``boundary_group``, ``boundary_freq_hz``, ``boundary_p_f_bar``
        with NaN where censored, ``boundary_tried_bar``)."""
        rows = [(g, f, np.nan if p is None else p, top)
                for g, b in self._boundaries().items() for f, p, top in b]
        arrays = {**self.chart.arrays(),
                  "boundary_group": np.array([r[0] for r in rows]),
                  "boundary_freq_hz": np.array([r[1] for r in rows]),
                  "boundary_p_f_bar": np.array([r[2] for r in rows]),
                  "boundary_tried_bar": np.array([r[3] for r in rows]),
                  "group_by": np.array(self.chart.group_by),
                  "min_growth_per_s": np.array(self.chart.min_growth)}
        atomic_write(path,
                     lambda stream: np.savez_compressed(stream, **arrays))

    def save_boundary(self, path):
        """Write the experimental boundary as ``judder fit --boundary``
        reads it; with several groups, one file per group
        (``STEM_GROUP.csv``). Returns the paths written."""
        from pathlib import Path
        path = Path(path)
        groups = list(self.chart.groups())
        written = []
        for group in groups:
            target = path if len(groups) == 1 else path.with_name(
                f"{path.stem}_{'_'.join(group)}{path.suffix}")
            write_text(target, self.chart.boundary_csv(group))
            written.append(str(target))
        return written

    def figure(self, title=None):
        from pysim.plotting import chart_figure
        fig, panels = chart_figure(self.chart, title=title)
        if self.model is not None:
            from stability.plotting import plot_boundaries
            for ax in panels.values():
                limits = ax.get_xlim(), ax.get_ylim()
                plot_boundaries(self.model.boundaries, ax=ax,
                                label=f"model ({self.model.params.model})")
                ax.set_xlim(*limits[0])
                ax.set_ylim(*limits[1])
        return fig



def _bar_or_none(values):
    return [_finite_or_none(v / PA_PER_BAR) for v in values]


@dataclass(frozen=True)
class EnvelopeResult:
    """``judder envelope``: a :class:`stability.envelope.Envelope`, the
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

    #: Probabilities whose boundaries the CSV lists.
    LEVELS = (0.1, 0.5, 0.9)

    def as_dict(self):
        e = self.envelope
        return {"model": self.params.model, "method": e.method,
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
                    [_finite_or_none(v) for v in e.probability[:, -1]]}

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
        return _csv_text(rows)

    def save_csv(self, path):
        write_text(path, self.csv_text())

    def save(self, path):
        """NPZ: every sample's values and boundaries, the nominal, the
        broadest edge, the probability grid (bar where named so)."""
        e = self.envelope
        arrays = {"freq_hz": e.freq_hz, "p_f_bar": e.p_f / PA_PER_BAR,
                  "p_max_bar": e.p_max / PA_PER_BAR,
                  "names": np.array(e.names), "values": e.values,
                  "is_vertex": e.is_vertex, "ok": e.ok,
                  "amplitude_bar": e.amplitude / PA_PER_BAR,
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
        buffer = io.BytesIO()
        np.savez_compressed(buffer, **arrays)
        atomic_write(path, lambda stream: stream.write(buffer.getvalue()))

    def discard_checkpoint(self):
        """Delete the checkpoint once the outputs are written (kept while
        samples failed, so a new run retries only those)."""
        if self.checkpoint is not None and not self.failures:
            Path(self.checkpoint).unlink(missing_ok=True)

    def figure(self, title=None):
        from stability.envelope_plotting import envelope_figure
        return envelope_figure(self.envelope, title=title)
