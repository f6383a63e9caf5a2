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
from infra.files import keeps_foreign_files, save_npz, write_text
from infra.numbers import format_interval, format_uncertain
from infra.units import PA_PER_BAR
from stability.kinds import KINDS

__all__ = ["ParamsResult", "EigResult", "FloquetPoint", "MapResult",
           "TonguesResult", "SensitivityResult", "ThresholdResult",
           "FitReport", "SimulationResult", "CrosscheckResult",
           "CampaignResult", "ChartResult", "CheckResult", "AdviceResult",
           "EnvelopeResult"]


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
    fractions. ``closed_form_frequencies_hz`` and ``damping_factor_12``
    are None for a Modelica class or an FMU (they are the paper's
    formulas for its chains).
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
                "damping_factor_12_percent": (
                    None if self.damping_factor_12 is None
                    else 100 * self.damping_factor_12),
                "damped_modes": [{"frequency_hz": f, "damping_ratio": r}
                                 for f, r in zip(self.damped_frequencies_hz,
                                                 self.damping_ratio)]}


def complex_record(value):
    """A complex number as JSON fields a script reads without knowing a
    convention: ``re``, ``im``, ``abs`` and ``arg`` (rad, in (-pi, pi])."""
    value = complex(value)
    return {"re": value.real, "im": value.imag, "abs": abs(value),
            "arg": math.atan2(value.imag, value.real)}


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
                "multipliers": [complex_record(z) for z in r.multipliers],
                "leading": complex_record(r.leading),
                "leading_abs": r.leading_abs, "kind": r.kind,
                "growth_rate_per_s": r.growth_rate,
                "exponents_per_s": [complex_record(z) for z in r.exponents]}

    def figure(self, title=None):
        """The multipliers on the complex plane (Fig. 15)."""
        from stability.plots import multipliers_figure
        return multipliers_figure([self.result], title=title)


@dataclass(frozen=True)
class MapResult:
    """``judder map``: the stability map (Fig. 12, 14) and its timing.

    ``map`` is the :class:`stability.maps.StabilityMap`; ``seconds`` the
    computing time.
    """

    params: object
    map: object
    seconds: float
    boundaries: object = None
    tongues: list = None
    min_growth: object = None

    def judder_relevant_points(self):
        """Points growing faster than ``min_growth`` (all unstable ones if
        it is None)."""
        from stability.decisions.relevance import is_judder_relevant
        return int(np.count_nonzero(
            (self.map.kind > 0)
            & is_judder_relevant(self.map.growth_rate, self.min_growth or 0)))

    def as_dict(self):
        m = self.map
        bar = m.p_f / PA_PER_BAR
        return {"model": self.params.model, "method": m.method,
                "points": int(m.kind.size), "seconds": self.seconds,
                "freq_hz": [m.freq_hz[0], m.freq_hz[-1], len(m.freq_hz)],
                "p_f_bar": [bar[0], bar[-1], len(bar)],
                "counts": m.counts(),
                "min_growth_per_s": self.min_growth,
                "judder_relevant_points": self.judder_relevant_points(),
                "max_leading_abs": float(m.leading_abs.max()),
                "natural_frequencies_hz": m.natural_frequencies_hz}

    @keeps_foreign_files
    def save(self, path, meta=None):
        """Save the map as NPZ.

        Arrays: ``freq_hz`` (nf,), ``p_f_pa`` and ``p_f_bar`` (np,),
        ``leading_re``/``leading_im``/``leading_abs``/``growth_rate_per_s``
        (nf, np), ``kind`` (nf, np, int8), ``kind_names``,
        ``natural_frequencies_hz``, ``min_growth_per_s`` (the
        judder-relevant rate, 0 when none was given: every instability);
        with the exact boundaries, ``boundary_freq_hz`` (nb,),
        ``boundary_p_f_bar`` (nb, 3; NaN: none up to ``boundary_p_max_bar``)
        whose columns ``boundary_kinds`` names, and per tongue
        ``tongue_number`` (0: unnumbered), ``tongue_kind``,
        ``tongue_resonance``, ``tongue_tip_freq_hz``,
        ``tongue_tip_p_f_bar``; ``parameters`` holds a JSON string of the
        model, the parameter values (SI), the method and ``meta``.
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
            "min_growth_per_s": np.array(float(self.min_growth or 0.0)),
            "parameters": np.array(json.dumps(info)),
        }
        if self.boundaries is not None:
            b, found = self.boundaries, self.tongues or []
            arrays.update({
                "boundary_freq_hz": b.freq_hz,
                "boundary_p_f_bar": b.amplitude / PA_PER_BAR,
                "boundary_kinds": np.array(KINDS[1:]),
                "boundary_p_max_bar": np.array(b.p_max / PA_PER_BAR),
                "tongue_number": np.array([t.number or 0 for t in found],
                                          dtype=int),
                "tongue_kind": np.array([t.kind for t in found], dtype=str),
                "tongue_resonance": np.array([t.resonance or ""
                                              for t in found], dtype=str),
                "tongue_tip_freq_hz": np.array([t.tip_freq_hz
                                                for t in found]),
                "tongue_tip_p_f_bar": np.array([t.tip_p_f / PA_PER_BAR
                                                for t in found])})
        save_npz(path, arrays)

    def figure(self, title=None, stacked=False):
        from stability.plots import map_figure
        return map_figure(self.map, title=title, tongues=self.tongues,
                          boundaries=self.boundaries,
                          min_growth=self.min_growth, stacked=stacked)


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
        then the lowest boundary of each kind, bar; a first comment gives
        the growth rate they are the boundaries of (``judder fit
        --boundary`` compares with the model's boundary of that rate)."""
        b = self.boundaries
        lines = [f"# min_growth_per_s: {b.min_growth:g}",
                 "freq_hz,p_f_bar,single_period_bar,double_period_bar,"
                 "combination_bar"]

        def cell(value):
            return "" if not math.isfinite(value) \
                else f"{value / PA_PER_BAR:.9g}"
        for f, lowest, row in zip(b.freq_hz, b.stability_boundary,
                                  b.amplitude):
            lines.append(",".join([f"{f:.9g}", cell(lowest)]
                                  + [cell(v) for v in row]))
        return "\n".join(lines) + "\n"

    @keeps_foreign_files
    def save(self, path):
        write_text(path, self.csv_text())

    def figure(self, title=None):
        from infra.criteria import DEFAULT_MIN_GROWTH_PER_S
        from stability.plots import tongues_figure
        # the map's shading as `judder map` draws it: slower growth than
        # the judder-relevant rate grey
        return tongues_figure(
            self.boundaries, self.tongues, self.background,
            title=title or f"{self.params.model}: tongue boundaries over "
                           "the map",
            min_growth=self.boundaries.min_growth or DEFAULT_MIN_GROWTH_PER_S)


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

    @keeps_foreign_files
    def save(self, path):
        write_text(path, _csv_text(self.tip_shifts))

    def figure(self, title=None):
        return self.study.plot(
            title=title or f"{self.params.model}: sensitivity of the "
                           "stability boundary", params=self.params)


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

    @keeps_foreign_files
    def save(self, path):
        s = self.study
        lines = ["c_ext,mu_g_threshold,mu_g_threshold_closed_form"] + [
            f"{c:.9g},{m:.9g},{k:.9g}" for c, m, k in
            zip(s.external_damping, s.thresholds, s.closed_form)]
        write_text(path, "\n".join(lines) + "\n")

    def figure(self, title=None):
        import matplotlib.pyplot as plt
        from stability import build_driveline
        from infra.plotstyle import figure_title
        from stability.plots import plot_threshold
        fig, axes = plt.subplots(1, 2, figsize=(11, 4.4),
                                 layout="constrained")
        driveline = build_driveline(self.params)
        plot_threshold(self.study, axes=axes,
                       own=(float(np.mean(driveline.external_damping)),
                            float(self.params["mu_g"])))
        figure_title(fig, f"Fig. 19 without dither, "
                     f"{title or self.params.model + ' driveline'}: the "
                     "mean pressure's damping in the slip damping (the maps "
                     "keep only the dither's part)", fontsize=10)
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
                "min_growth_per_s": r.min_growth, "added": dict(r.added),
                "determined": r.determined, "held": list(r.held),
                "error_model": r.error_model,
                "scatter": _finite_or_none(r.scatter),
                "scatter_unit": ("share of the amplitude"
                                 if r.error_model == "relative" else "bar"),
                "scatter_given": r.scatter_given,
                "threshold_spread_per_s": r.threshold_spread,
                "threshold_shifts": None if r.threshold_shifts is None else {
                    n: {"lower_threshold": float(a),
                        "higher_threshold": float(b)}
                    for n, (a, b) in zip(r.names, r.threshold_shifts)},
                "covariance": None if r.covariance is None else {
                    "names": list(r.names),
                    "matrix": [[_finite_or_none(v) for v in row]
                               for row in r.covariance]},
                "correlation": None if r.covariance is None else {
                    "names": list(r.names),
                    "matrix": [[_finite_or_none(v) for v in row]
                               for row in r.correlation]}}

    def text(self):
        """The fit as ``judder fit`` prints it: each value with the digits
        its interval supports and its unit, the correlations, the scatter
        of the onsets, the starts, then notes and problems."""
        r = self.fit
        specs = r.params.specs
        rows = []
        for n, v, s, lo, hi, s0 in zip(r.names, r.values, r.std, r.ci_low,
                                       r.ci_high, r.start):
            unit = specs[n].unit if n in specs else ""
            if n in r.held:
                rows.append(f"{n:>8} = {v:.6g} {unit}: held at its start "
                            "value (it does not move the measured boundary)")
            elif n in r.undetermined:
                rows.append(f"{n:>8} = {v:.6g} {unit}: not determined by "
                            "the measured boundary (see the problems)")
            else:
                rows.append(f"{n:>8} = {format_uncertain(v, s, unit)}, 95 % "
                            f"interval {format_interval(lo, hi, s)}  (start "
                            f"{s0:.6g})")
        pairs = [(a, b, r.correlation[i, j])
                 for i, a in enumerate(r.names)
                 for j, b in enumerate(r.names) if j > i]
        pairs = [(a, b, c) for a, b, c in pairs if np.isfinite(c)]
        if pairs:
            rows.append("correlation of the fitted values: " + ", ".join(
                f"{a}-{b} {c:+.2f}" for a, b, c in pairs))
        scatter = (f"{100 * r.scatter:.2g} % of the amplitude"
                   if r.error_model == "relative"
                   else f"{r.scatter:.2g} bar")
        rows.append(f"scatter of the onsets: {scatter} ("
                    + ("given" if r.scatter_given else
                       "estimated from the residuals") + f"; {r.error_model} "
                    f"error model); residual rms {r.residual_rms_bar:.3g} "
                    f"bar over {len(r.freq_hz)} points, "
                    f"{int(np.sum(np.isfinite(r.measured_bar)))} with judder")
        if r.threshold_shifts is not None:
            low = max(r.min_growth - r.threshold_spread, 0.0)
            high = r.min_growth + r.threshold_spread
            rows.append(
                f"growth threshold {low:g} and {high:g} 1/s instead of "
                f"{r.min_growth:g}: " + ", ".join(
                    f"{n} {a:+.2g}/{b:+.2g}" for n, (a, b) in zip(
                        r.names, r.threshold_shifts))
                + " (the intervals cover these shifts)")
        rows.append(f"{_starts_text(r)}; intervals by {r.uncertainty}; "
                    f"{r.evaluations} model boundaries in {self.seconds:.1f} s")
        return rows

    def save_params(self, path, overwrite=False):
        """Write the fitted parameter set as TOML."""
        write_text(path, dumps_toml(self.fit.params), overwrite=overwrite)

    def figure(self):
        return self.fit.plot()[0].figure


def _starts_text(r):
    """What the starts of a fit did, in words."""
    origins = list(r.start_origins)
    sampled = origins.count("sampled")
    rematched = origins.count("rematched")
    continued = origins.count("continued")
    where = ["the given values"]
    if sampled:
        where.append(f"{sampled} sampled within a factor 3 of them")
    if rematched:
        where.append(f"{rematched} with ambiguous points matched to the "
                     "other kind of tongue")
    if continued:
        where.append("the best one continued after its budget")
    text = (f"{r.starts_tried} local fit{'s' if r.starts_tried > 1 else ''} "
            f"(from {', '.join(where)})")
    if r.starts_tried == 1:
        return text
    others = r.starts_tried - r.starts_agreeing
    return (text + f": {r.starts_agreeing} reached this minimum"
            + (f", {others} stopped at a worse one" if others else ""))


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

    @keeps_foreign_files
    def save(self, path):
        """Time histories of the first run as CSV or MF4 (by suffix)."""
        from pysim.export import write_run
        run = self.runs[0][1]
        write_run(path, run.time, run.signals, self.signals,
                  {"model": self.model_class, "freq_hz": run.freq_hz,
                   "p_f_bar": run.p_f / PA_PER_BAR,
                   "start_values": run.start_values})

    def figure(self, title=None):
        from pysim.engagement import verdict_line
        from pysim.plotting import run_figure
        return run_figure(self.runs, start=self.start, title=title,
                          verdicts=[verdict_line(s) for s in self.summaries])


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

    @keeps_foreign_files
    def save(self, path):
        write_text(path, _csv_text(self.rows()))

    def figure(self, title=None):
        from .figures.crosscheck import crosscheck_figure
        return crosscheck_figure(self.check, title=title)


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
                "reused": sum(bool(r.get("reused")) for r in self.rows),
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
                "speed_kind": run.speed_kind,
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
        :meth:`pysim.charts.Chart.arrays` and, per group, the boundary
        (``boundary_group``, ``boundary_freq_hz``, ``boundary_p_f_bar``
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
                  "min_growth_per_s": np.array(chart.min_growth)}
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
        from pysim.plotting import chart_figure
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


def setting_record(check, min_growth, engagement_s, p_max, search_hz=None):
    """One :class:`stability.margins.SettingCheck` as JSON fields.

    ``verdict`` is one of :data:`stability.relevance.VERDICTS`;
    ``search_hz`` the (low, high) frequencies the Hz margin was searched
    over (``frequency_search_hz``).
    """
    from stability.decisions.relevance import verdict
    m, point = check.margin, check.floquet
    rate = point.growth_rate
    unstable = point.kind != KINDS[0]

    def tongue(t):
        return None if t is None else {"number": t.number, "kind": t.kind,
                                       "resonance": t.resonance,
                                       "tip_freq_hz": t.tip_freq_hz,
                                       "tip_p_f_bar": t.tip_p_f / PA_PER_BAR}
    sensitivity = sorted(
        ({"parameter": name,
          "margin_bar_per_unit_log": _finite_or_none(bar / PA_PER_BAR),
          "margin_hz_per_unit_log": _finite_or_none(hz)}
         for name, (bar, hz) in check.sensitivity.items()
         if np.isfinite(bar) or np.isfinite(hz)),
        key=lambda r: -abs(r["margin_hz_per_unit_log"] or 0.0)
        - abs(r["margin_bar_per_unit_log"] or 0.0) * 1e-6)
    return {"freq_hz": m.freq_hz, "p_f_bar": m.p_f / PA_PER_BAR,
            "verdict": verdict(unstable, rate, min_growth),
            "kind": point.kind,
            "inside_stability_tongue": bool(unstable),
            "judder_relevant": bool(check.judder),
            "tongue": tongue(check.tongue),
            "growth_rate_per_s": rate,
            "e_folding_time_s": 1.0 / rate if rate > 0 else None,
            "efolds_per_engagement": rate * engagement_s,
            "min_growth_per_s": min_growth,
            "boundary_p_f_bar": _finite_or_none(m.boundary_p_f / PA_PER_BAR),
            "margin_bar": _finite_or_none(m.margin_p_f / PA_PER_BAR),
            "margin_bar_at_least": (None if np.isfinite(m.margin_p_f)
                                    else (p_max - m.p_f) / PA_PER_BAR),
            "margin_bar_tongue": (tongue(check.bar_tongue)
                                  if np.isfinite(m.margin_p_f) else None),
            "crossing_hz": m.crossing_hz,
            "crossing_tolerance_hz": m.crossing_tolerance_hz,
            "margin_hz": _finite_or_none(m.margin_hz),
            "margin_hz_tongue": tongue(check.hz_tongue),
            "frequency_search_hz": (None if search_hz is None else
                                    [float(f) for f in search_hz]),
            "sensitivity": sensitivity}


def _named(tongue):
    """`` (tongue N)`` of a record's tongue, or nothing."""
    return "" if tongue is None else f" (tongue {tongue['number'] or '?'})"


def growth_words(record, engagement_s):
    """The growth of a record in words: rate, e-folding time against an
    engagement of ``engagement_s`` seconds."""
    rate = record["growth_rate_per_s"]
    if record["e_folding_time_s"] is None:
        return f"decays at {-rate:.3g} 1/s"
    efold = record["e_folding_time_s"]
    return (f"grows at {rate:.3g} 1/s, one e-fold in {efold:.3g} s ("
            + ("longer than" if efold > engagement_s else "within")
            + f" a {engagement_s:g} s engagement)")


def margin_words(record):
    """Both margins of a record in plain words (amplitude, frequency)."""
    bar = record["margin_bar"]
    if bar is None:
        amplitude = ("no judder at this frequency up to "
                     f"{record['p_f_bar'] + record['margin_bar_at_least']:.3g}"
                     " bar")
    elif bar >= 0:
        amplitude = f"{bar:.3f} bar below judder" + _named(
            record["margin_bar_tongue"])
    else:
        amplitude = f"{-bar:.3f} bar above the judder boundary" + _named(
            record["margin_bar_tongue"])
    hz = record["margin_hz"]
    if hz is None:
        search = record["frequency_search_hz"]
        frequency = (f"no dither frequency judders at {record['p_f_bar']:g} "
                     "bar" + ("" if search is None else
                              f" from {search[0]:.3g} to {search[1]:.3g} Hz"))
    elif hz > 0:
        frequency = (f"nearest judder {hz:.2f} Hz away, at "
                     f"{record['crossing_hz']:.2f} Hz"
                     + _named(record["margin_hz_tongue"]))
    else:
        frequency = (f"judder up to {-hz:.2f} Hz away, to "
                     f"{record['crossing_hz']:.2f} Hz"
                     + _named(record["margin_hz_tongue"]))
    return amplitude, frequency


def sensitivity_words(record, count=3):
    """The ``count`` parameters that move the margin most, per +10 %
    (Hz where the frequency margin exists, else bar); "" if none."""
    parts = []
    for entry in record["sensitivity"][:count]:
        hz, bar = (entry["margin_hz_per_unit_log"],
                   entry["margin_bar_per_unit_log"])
        if hz is not None:
            parts.append(f"{entry['parameter']} {0.1 * hz:+.2f} Hz")
        elif bar is not None:
            parts.append(f"{entry['parameter']} {0.1 * bar:+.3f} bar")
    return "" if not parts else \
        "margin per +10 %: " + ", ".join(parts)


def setting_summary(record, engagement_s=1.0):
    """One line: verdict, growth against an engagement, both margins, the
    parameters that move the margin most."""
    head = f"{record['freq_hz']:g} Hz, {record['p_f_bar']:g} bar: " \
        f"{record['verdict']}"
    if record["inside_stability_tongue"]:
        tongue = record["tongue"]
        head += (f" ({record['kind']})" if tongue is None else
                 f" in tongue {tongue['number'] or '?'} ({record['kind']})")
    parts = [head, growth_words(record, engagement_s),
             *margin_words(record)]
    sensitive = sensitivity_words(record)
    if sensitive:
        parts.append(sensitive)
    return "; ".join(parts)


@dataclass(frozen=True)
class CheckResult:
    """``judder check``: verdict and margins of each dither setting.

    ``checks`` are :class:`stability.margins.SettingCheck` objects;
    ``min_growth`` the judder-relevant rate (1/s), ``engagement_s`` the
    engagement duration the e-folds are counted over.
    """

    params: object
    checks: list
    min_growth: float
    engagement_s: float
    p_max: float
    seconds: float
    background: object = None

    def records(self):
        from stability.decisions.margins import search_grid
        grid = search_grid([c.margin.freq_hz for c in self.checks]) \
            if self.checks else None
        search = None if grid is None else (grid[0], grid[-1])
        return [setting_record(c, self.min_growth, self.engagement_s,
                               self.p_max, search)
                for c in self.checks]

    def as_dict(self):
        return {"model": self.params.model,
                "min_growth_per_s": self.min_growth,
                "engagement_s": self.engagement_s,
                "p_max_bar": self.p_max / PA_PER_BAR,
                "seconds": self.seconds, "settings": self.records()}

    def summary(self):
        return "\n".join(setting_summary(r, self.engagement_s)
                         for r in self.records())

    @keeps_foreign_files
    def save(self, path):
        """CSV: one row per setting (the scalar fields; tongues by
        number)."""
        rows = []
        for r in self.records():
            row = {k: v for k, v in r.items()
                   if not isinstance(v, (dict, list)) and k not in
                   ("tongue", "margin_bar_tongue", "margin_hz_tongue")}
            for key in ("tongue", "margin_bar_tongue", "margin_hz_tongue"):
                row[key] = None if r[key] is None else r[key]["number"]
            rows.append(row)
        write_text(path, _csv_text(rows))

    def figure(self, title=None):
        from .figures.check import check_figure
        return check_figure(self.records(), self.background,
                            min_growth=self.min_growth, title=title)


def _window_records(windows):
    return [{"freq_hz": list(w.freq_hz), "max_p_f_bar": w.max_p_f / PA_PER_BAR,
             "full_range": w.full_range} for w in windows]


@dataclass(frozen=True)
class AdviceResult:
    """``judder advise``: safe dither windows, parameter ranking, design.

    ``windows`` are :class:`stability.advice.SafeWindow` of the given
    design (over every parameter set), ``ranking`` the list of
    :func:`stability.advice.ranking`, ``advice`` the
    :class:`stability.advice.Advice` (None if not asked for), and
    ``verification`` the recomputed map of the advised design with its
    count of judder-relevant points.
    """

    params: object
    operating: object
    min_growth: float
    sets: int
    freq_hz: np.ndarray
    safe_p_f: np.ndarray
    windows: list
    ranking: list
    advice: object
    advised_windows: list
    verification: object
    judder_points: object
    seconds: float

    def advised_params(self):
        """The advised parameter set (None if there is none)."""
        a = self.advice
        if a is None or not a.success:
            return None
        return self.params.replace(**{n: self.params[n] * f
                                      for n, f in zip(a.names, a.factors)})

    def as_dict(self):
        op = self.operating
        out = {"model": self.params.model,
               "min_growth_per_s": self.min_growth,
               "parameter_sets": self.sets,
               "operating_range": {
                   "freq_hz": list(op.freq_hz),
                   "p_f_max_bar": op.p_max / PA_PER_BAR,
                   "margin_bar": op.margin_p_f / PA_PER_BAR,
                   "margin_hz": op.margin_hz},
               "safe_windows": _window_records(self.windows),
               "best_safe_setting": {
                   "freq_hz": float(self.freq_hz[np.argmax(self.safe_p_f)]),
                   "p_f_bar": float(self.safe_p_f.max() / PA_PER_BAR)},
               "ranking": [{"parameter": name, "share_per_unit_log": share,
                            "tongues": {str(n): {"d_ln_left_edge": d[0],
                                                 "d_ln_right_edge": d[1],
                                                 "d_ln_tip_p_f": d[2]}
                                        for n, d in detail.items()}}
                           for name, share, detail in self.ranking],
               "seconds": self.seconds}
        a = self.advice
        if a is not None:
            out["design"] = {
                "success": a.success, "message": a.message,
                "iterations": a.iterations,
                "tongues_in_the_way": a.history,
                "weighted_change": a.weighted_change,
                "factors": dict(zip(a.names, a.factors.tolist())),
                "values": ({n: self.advised_params()[n] for n in a.names}
                           if a.success else None),
                "nominal": {n: self.params[n] for n in a.names},
                "safe_windows": _window_records(self.advised_windows),
                "recomputed_map_judder_points": self.judder_points,
                "recomputed_map_points": (None if self.verification is None
                                          else int(self.verification.kind.size))}
        return out

    def summary(self):
        lines = []
        op = self.operating
        lo, hi = op.freq_hz
        best = int(np.argmax(self.safe_p_f))
        lines.append(f"safe in {lo:g}-{hi:g} Hz (margins "
                     f"{op.margin_p_f / PA_PER_BAR:g} bar, {op.margin_hz:g} "
                     f"Hz): up to {self.safe_p_f[best] / PA_PER_BAR:.3f} bar "
                     f"at best ({self.freq_hz[best]:.1f} Hz)")
        for level in sorted({w.max_p_f for w in self.windows}, reverse=True):
            lines.append(f"  up to {level / PA_PER_BAR:.3f} bar: " + ", ".join(
                f"{w.freq_hz[0]:.1f}-{w.freq_hz[1]:.1f} Hz"
                for w in self.windows if w.max_p_f == level))
        if self.ranking:
            lines.append("ranking (share of the way out per unit ln change): "
                         + ", ".join(f"{n} {s:.3f}"
                                     for n, s, _ in self.ranking))
        a = self.advice
        if a is not None:
            if a.success:
                lines.append("design: " + ", ".join(
                    f"{n} x{f:.3f}" for n, f in zip(a.names, a.factors))
                    + f" (weighted change {a.weighted_change:.3f}); "
                    f"recomputed map: {self.judder_points} judder points of "
                    f"{self.verification.kind.size}")
            else:
                lines.append(f"design: none found: {a.message}")
        return "\n".join(lines)

    @keeps_foreign_files
    def save(self, path):
        """CSV: freq_hz, safe_p_f_bar of the given design (operating
        frequencies only)."""
        low, high = self.operating.freq_hz
        write_text(path, _csv_text(
            [{"freq_hz": f, "safe_p_f_bar": p / PA_PER_BAR}
             for f, p in zip(self.freq_hz, self.safe_p_f)
             if low <= f <= high]))

    def figure(self, title=None):
        from .figures.advice import advice_figure
        return advice_figure(self, title=title)


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
