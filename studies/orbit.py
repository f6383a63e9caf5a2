"""``judder orbit``: the periodic orbit of a dithered engagement, its
stability, its continuation, and the predicted judder chart."""

from dataclasses import dataclass
import time

import numpy as np

from infra.criteria import (DEFAULT_JUDDER_LIMIT_RPM, DEFAULT_MIN_GROWTH_PER_S,
                            MECHANISMS, NO_JUDDER)
from infra.errors import JudderError
from infra.files import keeps_foreign_files, save_npz, write_text
from infra.units import PA_PER_BAR, RAD_S_PER_RPM, RPM_PER_RAD_S

from ._common import checked_values


def orbit(freq_hz, p_f_bar, parameters=None, changes=None, bench=None,
          judder_limit_rpm=DEFAULT_JUDDER_LIMIT_RPM,
          min_growth=DEFAULT_MIN_GROWTH_PER_S, progress=None):
    """``judder orbit``: periodic orbits of the held-slip bench run.

    Parameters
    ----------
    freq_hz : float or sequence of float
        Dither frequencies, Hz.
    p_f_bar : float or sequence of float
        Dither amplitudes, bar.
    bench : dict, optional
        Bench parameters (SI), as ``simulate`` takes them.
    judder_limit_rpm : float
        NVH limit of the upstream speed's oscillation, rpm.
    min_growth : float
        Growth rate from which an instability is judder, 1/s.

    Returns
    -------
    OrbitResult
        ``mode`` ``'point'``, ``'amplitude'`` (continued in p_f),
        ``'frequency'`` (over f) or ``'chart'``.
    """
    from stability.orbit import continue_orbit, periodic_orbit
    from stability.orbit_chart import held_slip_motion, orbit_chart

    from stability.bench import check_bench, engagement_model
    freqs = [float(f) for f in np.atleast_1d(freq_hz)]
    amplitudes = sorted(float(p) for p in np.atleast_1d(p_f_bar))
    values = checked_values(parameters, changes, freq_hz=freqs,
                            p_f_bar=amplitudes,
                            judder_limit_rpm=judder_limit_rpm,
                            min_growth=min_growth)
    model, linear = engagement_model(values, check_bench(values, bench))
    limit = judder_limit_rpm * RAD_S_PER_RPM
    started = time.perf_counter()
    orbits, doubled, chart, folds = [], [], None, []
    if len(freqs) > 1 and len(amplitudes) > 1:
        mode = "chart"
        chart = orbit_chart(model, freqs,
                            np.array(amplitudes) * PA_PER_BAR, limit,
                            min_growth, callback=progress)
    elif len(amplitudes) > 1:
        mode = "amplitude"
        start = [0.0] if amplitudes[0] > 0 else []
        branch = continue_orbit(model, freqs[0], [p * PA_PER_BAR for p in
                                                  start + amplitudes])
        # the requested amplitudes in order; the folds between them apart
        orbits = [o for k, o in enumerate(branch.orbits)
                  if k not in branch.folds][len(start):]
        folds = [branch.orbits[k] for k in branch.folds]
        if not branch.complete:
            raise JudderError(
                f"the orbit at {freqs[0]:g} Hz could not be continued "
                f"beyond {orbits[-1].p_f / PA_PER_BAR:.3g} bar (the "
                "harmonic balance did not converge); allowed: a smaller "
                "`p_f_bar` range")
    else:
        mode = "point" if len(freqs) == 1 else "frequency"
        orbits = [periodic_orbit(model, f, amplitudes[0] * PA_PER_BAR)
                  for f in freqs]
    quasi = settled_motions(model, orbits)
    # what the held-slip run shows at its end: the slip drifted
    motions = [held_slip_motion(model, found) for found in orbits]
    orbits = [found for found, _ in motions]
    doubled = [grown for _, grown in motions]
    seconds = time.perf_counter() - started
    return OrbitResult(params=values, mode=mode, orbits=orbits,
                       doubled=doubled, quasi=quasi, folds=folds,
                       chart=chart,
                       limit_rpm=float(judder_limit_rpm),
                       min_growth=float(min_growth), seconds=seconds,
                       model=model, linear=linear)


def settled_motions(model, orbits):
    """The settled motion (:func:`stability.settle.settle`, one batch) of
    each orbit unstable through a complex pair, else None."""
    from stability.settle import settle_orbits
    return [None if m is None else {
        "amplitude_at_combination_rpm": m["combination"] * RPM_PER_RAD_S,
        "combination_freq_hz": m["combination_hz"],
        "amplitude_at_dither_rpm": m["at_dither"] * RPM_PER_RAD_S,
        "integrated_s": m["duration"], "settled": m["settled"]}
        for m in settle_orbits(model, orbits)]


def quasi_words(quasi):
    """The settled quasi-periodic motion of a row, in words."""
    return (f"; quasi-periodic motion "
            f"{quasi['amplitude_at_combination_rpm']:.3g} rpm at "
            f"{quasi['combination_freq_hz']:.1f} Hz, "
            + ("settled" if quasi["settled"] else "not settled")
            + f" after {quasi['integrated_s']:.1f} s of integration")


def orbit_row(found, doubled, limit_rpm, min_growth, quasi=None):
    """One orbit as a JSON row (Hz, bar, rpm, 1/s, N m), with the
    verdict of :mod:`stability.orbit_chart` (``verdict`` in the words of
    :data:`pysim.bench.verdict.RUN_VERDICTS`); ``quasi``: the settled
    quasi-periodic motion of an orbit unstable through a complex pair
    (:func:`settled_motions`), its component at the combination frequency
    taken as the settled amplitude."""
    from pysim.bench.verdict import run_verdict
    from stability.orbit_chart import orbit_verdict
    combination = 0.0 if quasi is None else \
        quasi["amplitude_at_combination_rpm"] * RAD_S_PER_RPM
    verdict = orbit_verdict(found, doubled, limit_rpm * RAD_S_PER_RPM,
                            min_growth, combination)
    forced = verdict.forced * RPM_PER_RAD_S
    half = verdict.half * RPM_PER_RAD_S
    settled = verdict.settled * RPM_PER_RAD_S
    # where the balance did not converge its numbers are an iterate's:
    # no kind, no verdict, no mechanism (``converged`` False)
    converged = bool(found.success)
    judder = bool(verdict.judder) if converged else None
    mechanism = None if not judder else MECHANISMS[verdict.mechanism]
    lead = found.multipliers[0] if len(found.multipliers) else 1.0
    return {"freq_hz": found.freq_hz, "p_f_bar": found.p_f / PA_PER_BAR,
            "success": found.success, "converged": converged,
            "message": found.message,
            "amplitude_at_dither_rpm": forced,
            "upstream_swing_rpm": found.upstream_amplitude * RPM_PER_RAD_S,
            "slip_range_rad_s": list(found.slip_range),
            "drift_torque_nm": found.drift_torque,
            "kind": found.kind if converged else None,
            "growth_per_s": found.growth_rate,
            "leading_multiplier": {"re": float(np.real(lead)),
                                   "im": float(np.imag(lead)),
                                   "abs": float(abs(lead))},
            "double_period": None if doubled is None else {
                "amplitude_at_half_rpm": half,
                "growth_per_s": doubled.growth_rate,
                "stable": doubled.stable},
            "quasi_periodic": quasi,
            "settled_rpm": settled, "judder": judder,
            "verdict": run_verdict(judder),
            "mechanism": mechanism, "judder_limit_rpm": limit_rpm}


@dataclass(frozen=True)
class OrbitResult:
    """``judder orbit``: periodic orbits of the held-slip bench run.

    ``orbits`` (and ``doubled``: the 2T orbit of each, or None) for a
    point, a continuation in p_f (``folds``: where it turns back) or a
    sweep in f; ``chart`` (:class:`stability.orbit_chart.OrbitChart`) for
    a grid. ``model`` is the :class:`stability.orbit.EngagementModel`,
    ``linear`` the bench's linearisation at its slip (the Floquet view of
    the same bench).
    """

    params: object
    mode: str
    orbits: list
    doubled: list
    quasi: list
    folds: list
    chart: object
    limit_rpm: float
    min_growth: float
    seconds: float
    model: object = None
    linear: object = None

    def rows(self):
        """The orbits as JSON rows."""
        quasi = self.quasi or [None] * len(self.orbits)
        return [orbit_row(o, d, self.limit_rpm, self.min_growth, q)
                for o, d, q in zip(self.orbits, self.doubled, quasi)]

    def as_dict(self):
        out = {"model": self.params.model, "mode": self.mode,
               "slip_rad_s": self.model.slip,
               "judder_limit_rpm": self.limit_rpm,
               "min_growth_per_s": self.min_growth,
               "seconds": self.seconds}
        if self.chart is None:
            out["orbits"] = self.rows()
            out["folds"] = [{"freq_hz": o.freq_hz,
                             "p_f_bar": o.p_f / PA_PER_BAR,
                             "amplitude_at_dither_rpm":
                                 o.dither_amplitude * RPM_PER_RAD_S}
                            for o in self.folds]
            return out
        c = self.chart
        onsets = c.onsets() / PA_PER_BAR
        out.update({
            "freq_hz": [float(c.freq_hz[0]), float(c.freq_hz[-1]),
                        len(c.freq_hz)],
            "p_f_bar": [float(c.p_f[0] / PA_PER_BAR),
                        float(c.p_f[-1] / PA_PER_BAR), len(c.p_f)],
            "counts": c.counts(),
            # no verdict where the balance did not converge
            "not_converged": c.not_converged(),
            "boundary": [[float(f), None if not np.isfinite(p) else
                          float(p)] for f, p in zip(c.freq_hz, onsets)]})
        return out

    def text(self):
        """What the terminal shows."""
        if self.chart is not None:
            counts = self.chart.counts()
            lines = [f"{self.chart.judder.size} settings in "
                     f"{self.seconds:.1f} s: "
                     + ", ".join(f"{counts[m]} {m}" for m in
                                 ("forced", "parametric", "both"))
                     + f" judder, {counts['none']} without"
                     + ("" if not self.chart.not_converged() else
                        f", {self.chart.not_converged()} without a "
                        "verdict (the balance did not converge)")
                     + f" (limit {self.limit_rpm:g} rpm, growth "
                       f"{self.min_growth:g} 1/s)"]
            onsets = self.chart.onsets() / PA_PER_BAR
            runs = _judder_ranges(self.chart.freq_hz, onsets)
            lines += [f"  judder from {p:.3g} bar at {f0:g}-{f1:g} Hz "
                      f"(lowest at {fl:g} Hz)" for f0, f1, fl, p in runs]
            return "\n".join(lines)
        lines = []
        for row in self.rows():
            verdict = ("no verdict" if row["judder"] is None else
                       NO_JUDDER.lower() if not row["judder"] else
                       f"judder ({row['mechanism']})")
            double = row["double_period"]
            lines.append(
                f"f = {row['freq_hz']:g} Hz, p_f = {row['p_f_bar']:.4g} "
                f"bar: T-orbit {row['amplitude_at_dither_rpm']:.3g} rpm at "
                f"f, {row['kind'] or 'not converged'} "
                f"({row['growth_per_s']:+.3g} 1/s)"
                + ("" if double is None else
                   f"; 2T orbit {double['amplitude_at_half_rpm']:.3g} rpm "
                   f"at f/2 ({double['growth_per_s']:+.3g} 1/s)")
                + ("" if row["quasi_periodic"] is None else
                   quasi_words(row["quasi_periodic"]))
                + f"; slip {row['slip_range_rad_s'][0]:.1f}-"
                  f"{row['slip_range_rad_s'][1]:.1f} rad/s, rectified "
                  f"torque {row['drift_torque_nm']:+.2g} N m; {verdict}"
                + ("" if row["success"] else f" [{row['message']}]"))
        lines += [f"fold at {o.p_f / PA_PER_BAR:.4g} bar "
                  f"({o.dither_amplitude * RPM_PER_RAD_S:.3g} rpm): the "
                  "orbit jumps" for o in self.folds]
        return "\n".join(lines)

    @keeps_foreign_files
    def save(self, path):
        """The orbits as CSV (one row each), or the chart as NPZ
        (``freq_hz`` (nf,), ``p_f_bar`` (np,), ``forced_rpm``,
        ``half_rpm``, ``settled_rpm``, ``growth_rate_per_s``, ``kind``,
        ``quasi_periodic``, ``drift_torque_nm``, ``judder``,
        ``mechanism`` (index into ``mechanism_names``), ``converged``
        (False: the balance did not converge, no verdict), all (nf, np);
        ``judder_limit_rpm``, ``min_growth_per_s``)."""
        from pathlib import Path
        if Path(path).suffix.lower() == ".npz":
            c = self._chart_for(path)
            save_npz(path, {
                "freq_hz": c.freq_hz, "p_f_bar": c.p_f / PA_PER_BAR,
                "forced_rpm": c.forced_amplitude * RPM_PER_RAD_S,
                "half_rpm": c.half_amplitude * RPM_PER_RAD_S,
                "settled_rpm": c.settled_amplitude * RPM_PER_RAD_S,
                "growth_rate_per_s": c.growth_rate, "kind": c.kind,
                "quasi_periodic": c.quasi_periodic,
                "drift_torque_nm": c.drift_torque, "judder": c.judder,
                "mechanism": c.mechanism, "converged": c._converged(),
                "mechanism_names": np.array(MECHANISMS),
                "judder_limit_rpm": np.array(self.limit_rpm),
                "min_growth_per_s": np.array(self.min_growth)})
            return
        rows = self.rows() if self.chart is None else self._chart_rows()
        columns = ["freq_hz", "p_f_bar", "amplitude_at_dither_rpm",
                   "settled_rpm", "kind", "growth_per_s", "converged",
                   "judder", "mechanism", "drift_torque_nm"]
        write_text(path, ",".join(columns) + "\n" + "".join(
            ",".join("" if row.get(c) is None else f"{row[c]}"
                     for c in columns) + "\n" for row in rows))

    def _chart_for(self, path):
        if self.chart is None:
            raise JudderError(f"{path}: an NPZ holds a chart (several "
                              "frequencies and amplitudes); allowed: a .csv")
        return self.chart

    def _chart_rows(self):
        from pysim.bench.verdict import run_verdict
        c = self.chart
        converged = c._converged()

        def verdict(i, j, value):
            return value if converged[i, j] else None
        return [{"freq_hz": f, "p_f_bar": p / PA_PER_BAR,
                 "amplitude_at_dither_rpm":
                     c.forced_amplitude[i, j] * RPM_PER_RAD_S,
                 "settled_rpm": c.settled_amplitude[i, j] * RPM_PER_RAD_S,
                 "kind": verdict(i, j, c.kind[i, j]),
                 "growth_per_s": c.growth_rate[i, j],
                 "converged": bool(converged[i, j]),
                 "judder": verdict(i, j, bool(c.judder[i, j])),
                 "verdict": verdict(i, j, run_verdict(bool(c.judder[i, j]))),
                 "mechanism": verdict(i, j, MECHANISMS[c.mechanism[i, j]]),
                 "drift_torque_nm": c.drift_torque[i, j]}
                for i, f in enumerate(c.freq_hz)
                for j, p in enumerate(c.p_f)]

    def figure(self, title=None):
        from infra.plotstyle import setting_text
        from stability.plots.orbit import (orbit_chart_figure,
                                           orbit_curve_figure)
        if self.chart is not None:
            return orbit_chart_figure(self.chart, title=title,
                                      boundaries=self._tongues())
        rows = self.rows()
        if self.mode == "amplitude":
            x = np.array([r["p_f_bar"] for r in rows])
            xlabel = "dither amplitude $p_f$ [bar]"
            setting = setting_text(freq_hz=rows[0]["freq_hz"])
        else:
            x = np.array([r["freq_hz"] for r in rows])
            xlabel = "dither frequency $f$ [Hz]"
            setting = setting_text(p_f_bar=rows[0]["p_f_bar"])
        # the setting held along the branch, in engineering precision
        title = f"{setting}, " + (title or "periodic orbits")
        curves = [(x, np.array([r["amplitude_at_dither_rpm"] for r in rows]),
                   np.array([r["growth_per_s"] < 0 for r in rows]),
                   "T-orbit at f", "black")]
        doubled = [r["double_period"] for r in rows]
        if any(d is not None for d in doubled):
            curves.append((x, np.array([np.nan if d is None else
                                        d["amplitude_at_half_rpm"]
                                        for d in doubled]),
                           np.array([d is not None and d["stable"]
                                     for d in doubled]),
                           "2T orbit at f/2", "#1f77b4"))
        folds = [((o.p_f / PA_PER_BAR) if self.mode == "amplitude"
                  else o.freq_hz, o.dither_amplitude * RPM_PER_RAD_S)
                 for o in self.folds]
        return orbit_curve_figure(curves, self.limit_rpm, xlabel,
                                  title=title, folds=folds)

    def _tongues(self):
        """Floquet tongue boundaries of the bench's linearisation over the
        chart's grid (the stability layer's view of the same bench)."""
        from stability.tongues import tongue_boundaries
        c = self.chart
        return tongue_boundaries(self.linear, np.linspace(c.freq_hz[0],
                                                     c.freq_hz[-1], 200),
                                 float(c.p_f[-1]))


def _judder_ranges(freq_hz, onsets):
    """Contiguous frequency ranges with judder: ``(first Hz, last Hz,
    Hz of the lowest onset, lowest onset in bar)``."""
    ranges, start = [], None
    for i, p in enumerate(np.append(onsets, np.nan)):
        if np.isfinite(p) and start is None:
            start = i
        elif not np.isfinite(p) and start is not None:
            part = onsets[start:i]
            low = start + int(np.argmin(part))
            ranges.append((float(freq_hz[start]), float(freq_hz[i - 1]),
                           float(freq_hz[low]), float(part.min())))
            start = None
    return ranges
