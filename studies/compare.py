"""``judder compare``: two parameter sets side by side."""

from dataclasses import dataclass
import time

import numpy as np

from infra.units import PA_PER_BAR

from ._common import check_arguments

#: Amplitudes of each map (0 to --pf-max).
MAP_AMPLITUDES = 80


def compare(first, second, labels=("A", "B"), freq_hz=None, p_max_bar=1.5,
            settings=(), freq_range=(60.0, 200.0), valve_max_bar=0.7,
            margin_bar=0.1, margin_hz=5.0, min_growth=None, maps=False,
            progress=None, driveline=None):
    """``judder compare``: two parameter sets side by side.

    Parameters
    ----------
    first, second : drivelines.Parameters
    labels : (str, str)
        Their names in the output (the files).
    freq_hz : array_like, optional
        Frequencies of the tongue boundaries and maps, Hz (default 500
        from 10 to 220).
    p_max_bar : float
        Largest amplitude of the tongues and maps, bar.
    settings : sequence of (float, float)
        Dither settings (Hz, bar) whose verdicts are compared.
    freq_range : (float, float)
        Operating frequencies of the safe windows, Hz.
    valve_max_bar : float
        Highest operating dither amplitude, bar.
    margin_bar, margin_hz : float
        Margins of the safe windows (as ``judder advise``).
    min_growth : float, optional
        Judder rate, 1/s (default
        :data:`infra.criteria.DEFAULT_MIN_GROWTH_PER_S`).
    maps : bool
        Also compute both maps with their exact boundaries, for
        ``figure()``.
    driveline : {'chain', 'bench'}, optional
        The driveline both sets are judged as
        (:func:`stability.bench.driveline_view`; default the bench where the
        preset has one).

    Returns
    -------
    CompareResult
    """
    from infra.criteria import DEFAULT_MIN_GROWTH_PER_S
    from stability.decisions.advice import (OperatingRange, safe_windows,
                                            window_boundary, window_grid)

    from .check import check
    from .eig import eig
    from .map import stability_map
    from .tongues import tongues
    freq_hz = (np.linspace(10.0, 220.0, 500) if freq_hz is None
               else np.asarray(freq_hz, dtype=float))
    check_arguments(min_growth=min_growth, valve_max_bar=valve_max_bar,
                    margin_bar=margin_bar, margin_hz=margin_hz)
    min_growth = DEFAULT_MIN_GROWTH_PER_S if min_growth is None else min_growth
    low, high = (float(v) for v in freq_range)
    operating = OperatingRange(
        freq_hz=(low, high), p_max=valve_max_bar * PA_PER_BAR,
        margin_p_f=margin_bar * PA_PER_BAR, margin_hz=margin_hz)
    grid = window_grid(operating)
    started = time.perf_counter()
    sides = []
    from stability.bench import driveline_view
    for index, params in enumerate((first, second)):
        viewed, view = driveline_view(params, driveline)
        found = tongues(freq_hz, p_max_bar, params, judder_growth=min_growth,
                        driveline=view)
        boundary = window_boundary([viewed], grid, min_growth,
                                   max(1.5e5, 2 * operating.required_p_f))
        safe, windows = safe_windows(grid, boundary, operating)
        checked = (check([f for f, _ in settings], [p for _, p in settings],
                         params, min_growth=min_growth,
                         p_max_bar=p_max_bar, sensitivity=(),
                         driveline=view)
                   if settings else None)
        shown = (stability_map(freq_hz, np.linspace(0, p_max_bar,
                                                    MAP_AMPLITUDES),
                               params, min_growth=min_growth, exact=True,
                               driveline=view)
                 if maps else None)
        sides.append(Side(label=labels[index], params=params,
                          modes=eig(params, driveline=view), tongues=found,
                          windows=windows, safe_p_f=safe, check=checked,
                          map=shown))
        if progress is not None:
            progress(index + 1, 2)
    return CompareResult(sides=sides, operating=operating,
                         min_growth=min_growth, window_freq_hz=grid,
                         seconds=time.perf_counter() - started)


@dataclass(frozen=True)
class Side:
    """One parameter set of ``judder compare`` and what was computed for
    it: ``modes`` (:class:`studies.eig.EigResult`), ``tongues``
    (:class:`studies.tongues.TonguesResult`), the safe
    ``windows`` and amplitudes ``safe_p_f`` (Pa) of
    :func:`stability.decisions.advice.safe_windows`, ``check`` (a
    :class:`studies.check.CheckResult` or None) and ``map`` (a
    :class:`studies.map.MapResult` or None)."""

    label: str
    params: object
    modes: object
    tongues: object
    windows: list
    safe_p_f: np.ndarray
    check: object
    map: object


def _window_text(windows, level):
    """``60.0-95.0, 116.0-200.0 Hz`` at one amplitude level, or none."""
    spans = [f"{w.freq_hz[0]:.1f}-{w.freq_hz[1]:.1f}" for w in windows
             if w.max_p_f == level]
    return (", ".join(spans) + " Hz") if spans else "none"


@dataclass(frozen=True)
class CompareResult:
    """``judder compare``: two :class:`Side` objects, the operating range
    of their safe windows and the judder rate (1/s)."""

    sides: list
    operating: object
    min_growth: float
    window_freq_hz: np.ndarray
    seconds: float

    def as_dict(self):
        op = self.operating
        out = []
        for side in self.sides:
            modes = side.modes.as_dict()
            tips = side.tongues.as_dict()
            best = int(np.argmax(side.safe_p_f))
            out.append({
                "file": side.label, "model": side.params.model,
                "natural_frequencies_hz": modes["natural_frequencies_hz"],
                "tongues": tips["tongues"],
                "safe_windows": [
                    {"freq_hz": list(w.freq_hz),
                     "max_p_f_bar": w.max_p_f / PA_PER_BAR,
                     "full_range": w.full_range} for w in side.windows],
                "best_safe_setting": {
                    "freq_hz": float(self.window_freq_hz[best]),
                    "p_f_bar": float(side.safe_p_f[best] / PA_PER_BAR)},
                "settings": ([] if side.check is None else [
                    {k: r[k] for k in (
                        "freq_hz", "p_f_bar", "verdict", "kind",
                        "growth_rate_per_s", "boundary_p_f_bar",
                        "unstable_boundary_p_f_bar", "margin_bar",
                        "margin_hz")}
                    for r in side.check.records()])})
        return {"min_growth_per_s": self.min_growth,
                "operating_range": {
                    "freq_hz": list(op.freq_hz),
                    "p_f_max_bar": op.p_max / PA_PER_BAR,
                    "margin_bar": op.margin_p_f / PA_PER_BAR,
                    "margin_hz": op.margin_hz},
                "sets": out, "seconds": self.seconds}

    def summary(self):
        data = self.as_dict()
        a, b = data["sets"]
        rate = self.min_growth
        width = 34
        rows = [("", a["file"], b["file"]),
                ("model", a["model"], b["model"]),
                ("natural frequencies",
                 *(", ".join(f"{f:.2f}" for f in s["natural_frequencies_hz"])
                   + " Hz" for s in (a, b)))]
        numbers = sorted({t["number"] for s in (a, b) for t in s["tongues"]
                          if t["number"] is not None})
        top = self.sides[0].tongues.boundaries.p_max / PA_PER_BAR
        for number in numbers:
            mine = [next((t for t in s["tongues"] if t["number"] == number),
                         None) for s in (a, b)]
            known = next(t for t in mine if t is not None)
            name = f"tongue {number} ({known['resonance'] or known['kind']})"

            def tip(t, key):
                if t is None or t[f"{key}p_f_bar"] is None:
                    return f"none up to {top:g} bar"
                return (f"{t[f'{key}p_f_bar']:.4f} bar at "
                        f"{t[f'{key}freq_hz']:.2f} Hz")
            rows.append((f"{name} unstable from",
                         *(tip(t, "tip_") for t in mine)))
            rows.append((f"  judder (>= {rate:g} 1/s) from",
                         *(tip(t, "judder_tip_") for t in mine)))
        op = self.operating
        lo, hi = op.freq_hz
        for share in (1.0, 0.5):
            level = share * op.p_max
            rows.append((f"safe up to {level / PA_PER_BAR:.3g} bar "
                         f"({lo:g}-{hi:g} Hz)",
                         *(_window_text(s.windows, level)
                           for s in self.sides)))
        for ra, rb in zip(a["settings"], b["settings"]):
            rows.append((f"{ra['freq_hz']:g} Hz, {ra['p_f_bar']:g} bar",
                         *(f"{r['verdict']} ({r['growth_rate_per_s']:+.3g} "
                           "1/s)" for r in (ra, rb))))
        first = max(len(r[0]) for r in rows) + 2
        lines = [f"{r[0]:<{first}}{r[1]:<{width}}{r[2]}" for r in rows]
        lines.append(
            f"unstable: |lambda| > 1 (growth > 0); judder: growth >= "
            f"{rate:g} 1/s; safe windows keep {op.margin_p_f / PA_PER_BAR:g}"
            f" bar and {op.margin_hz:g} Hz from judder (as judder advise)")
        return "\n".join(lines)

    def figure(self, title=None):
        from .figures.compare import compare_figure
        return compare_figure(self, title=title)
