"""``judder advise``: safe dither windows and the design change that clears
the dither range.
"""

from dataclasses import dataclass
import time

import numpy as np

from infra.errors import JudderError
from infra.files import keeps_foreign_files, write_text
from infra.units import PA_PER_BAR
from sources.dither_modes import check_modes_up_to
from stability.decisions.advice import DEFAULT_BOUNDS, PRUNE_BELOW

from ._common import (at_dither_frequency, check_names, checked_values,
                      structural_names)
from ._records import rows_to_csv


def _bounds_of(names, given):
    """``(len(names), 2)`` factors: ``given[name]`` where given, else
    :data:`DEFAULT_BOUNDS`; a bound on a name that is not a design
    parameter is refused."""
    for name, (low, high) in given.items():
        if name not in names:
            raise JudderError(f"`bounds` {name}={low:g}:{high:g}: {name} is "
                              "not a design parameter; allowed: one of "
                              f"`names` ({','.join(names)})")
    return [given.get(n, DEFAULT_BOUNDS) for n in names]


def advise(parameters=None, changes=None, extra_sets=(), freq_range=(60.0, 200.0),
           valve_max_bar=0.7, margin_bar=0.1, margin_hz=5.0, min_growth=None,
           names=None, weights=None, design=True, progress=None,
           bounds=None, background=False, driveline=None):
    """``judder advise``: safe dither windows, the ranking of the design
    parameters, and the smallest weighted change that clears the window.

    Parameters
    ----------
    extra_sets : sequence of drivelines.Parameters
        More parameter sets (an uncertainty envelope): the windows are
        those safe for every set, and the design must clear the window for
        every set (each gets the same relative change).
    freq_range : (float, float)
        Dither operating frequencies, Hz (default the paper's 60-200).
    valve_max_bar : float
        The valve's highest dither amplitude, the top of the operating
        range, bar (default 0.7).
    margin_bar, margin_hz : float
        Margins kept from every judder-relevant tongue, bar and Hz.
    min_growth : float, optional
        1/s, default :data:`infra.criteria.DEFAULT_MIN_GROWTH_PER_S`.
    names : sequence of str, optional
        Design parameters (default J2, J4, k12, k24, c12; for another
        model its inertias, stiffnesses and coupling dampings; for a
        Modelica class or an FMU those of the five it has, and
        JudderError if none).
    weights : sequence of float, optional
        Cost of a unit change of ln(value) of each (default 1).
    design : bool
        Also search the design change and recompute its map.
    bounds : dict, optional
        ``{name: (low, high)}``: factors of the nominal value a design
        parameter may take (default
        :data:`stability.decisions.advice.DEFAULT_BOUNDS` for each).
    background : bool
        Also compute what ``figure()`` draws beyond the operating range:
        the advised design's map over a wider range and both designs'
        stability boundaries.

    Returns
    -------
    AdviceResult
    """
    from infra.criteria import DEFAULT_MIN_GROWTH_PER_S
    from stability.decisions import advice as kernel
    values = checked_values(parameters, changes, valve_max_bar=valve_max_bar,
                            margin_bar=margin_bar, margin_hz=margin_hz,
                            min_growth=min_growth)
    values = at_dither_frequency(values, freq_range, argument="freq_range")
    from stability.bench import driveline_view
    given = values
    values, driveline = driveline_view(values, driveline)
    sets = [values, *(driveline_view(s, driveline)[0] for s in extra_sets)]
    models = {p.model for p in sets}
    if len(models) > 1:
        raise JudderError(f"parameter sets of models {sorted(models)}; "
                          "allowed: one model")
    low, high = (float(v) for v in freq_range)
    if not (np.isfinite(low) and np.isfinite(high) and 0 < low < high):
        raise JudderError(f"freq range = {low:g}:{high:g} Hz is not allowed; "
                          "allowed: 0 < LOW < HIGH")
    if margin_hz >= low:
        raise JudderError(f"margin_hz = {margin_hz:g} Hz is not allowed; "
                          f"allowed: below the lowest frequency {low:g} Hz")
    min_growth = DEFAULT_MIN_GROWTH_PER_S if min_growth is None else min_growth
    names = tuple(structural_names(values, kernel.DEFAULT_DESIGN_PARAMETERS)
                  if names is None else names)
    if not names:
        raise JudderError("`names` is empty; allowed: design parameters "
                          "such as J2,J4,k24")
    for p in sets:
        check_names(p, names, "`names`")
    weights = np.ones(len(names)) if weights is None else \
        np.asarray(weights, dtype=float)
    if weights.shape != (len(names),):
        raise JudderError(f"{len(weights)} weights for {len(names)} "
                          "parameters; allowed: one weight per parameter")
    kernel.check_weights(names, weights)
    bounds = kernel.check_bounds(names, _bounds_of(names, bounds or {}))
    operating = kernel.OperatingRange(
        freq_hz=(low, high), p_max=valve_max_bar * PA_PER_BAR,
        margin_p_f=margin_bar * PA_PER_BAR, margin_hz=margin_hz)
    p_search = max(1.5e5, 2 * operating.required_p_f)
    started = time.perf_counter()
    # the grid on which the search decides that a design clears the window
    grid = kernel.window_grid(operating)

    def windows_of(param_sets):
        # each set is linearised in one mode: held on the grid up to the
        # amplitude searched (a hybrid class; nothing for others)
        for p in param_sets:
            check_modes_up_to(p, grid, p_search / PA_PER_BAR)
        boundary = kernel.window_boundary(param_sets, grid, min_growth,
                                          p_search)
        return kernel.safe_windows(grid, boundary, operating)
    safe, windows = windows_of(sets)
    order = kernel.ranking(values, names, operating, min_growth, p_search)
    found = advised_windows = verification = judder_points = None
    unstable = view = None
    if design:
        found = kernel.advise_design(sets, names, weights, operating,
                                     min_growth, p_search, callback=progress,
                                     bounds=bounds)
        if found.success:
            factors = dict(zip(found.names, found.factors))
            advised = [p.replace(**{n: p[n] * factors[n] for n in names})
                       for p in sets]
            _, advised_windows = windows_of(advised)
            verification, judder_points = kernel.verify_design(
                advised[0], operating, min_growth)
            unstable = kernel.unstable_regions(advised, operating)
            if background:
                view = _wide_view(values, advised[0], operating)
    return AdviceResult(
        params=values, operating=operating, min_growth=min_growth,
        sets=len(sets), freq_hz=grid, safe_p_f=safe, windows=windows,
        ranking=order, advice=found, advised_windows=advised_windows or [],
        verification=verification, judder_points=judder_points,
        seconds=time.perf_counter() - started, unstable=unstable,
        view=view, given=given, driveline=driveline)


def _wide_view(given, advised, operating):
    """What the figure shows beyond the operating range: the advised
    design's map from half the lowest to 1.5 times the highest frequency
    and up to twice the valve's highest amplitude, with the stability
    boundaries (|lambda| = 1) of both designs and the advised one's
    tongues."""
    from stability.maps import stability_map as map_kernel
    from stability.source import build_driveline
    from stability.tongues import find_tongues, tongue_boundaries
    low, high = operating.freq_hz
    freqs = np.linspace(max(0.5 * low, 1.0), 1.5 * high, 160)
    p_top = max(2 * operating.p_max, 1.2 * operating.required_p_f)
    for p in (advised, given):
        check_modes_up_to(p, freqs, p_top / PA_PER_BAR)
    driveline = build_driveline(advised)
    view = map_kernel(driveline, freqs, np.linspace(0, p_top, 50))
    mine = tongue_boundaries(driveline, freqs, p_top, check=False)
    theirs = tongue_boundaries(build_driveline(given), freqs, p_top,
                               check=False)
    return {"map": view, "boundaries": mine,
            "tongues": find_tongues(driveline, mine),
            "given_boundaries": theirs}


def _window_records(windows):
    return [{"freq_hz": list(w.freq_hz), "max_p_f_bar": w.max_p_f / PA_PER_BAR,
             "full_range": w.full_range} for w in windows]


@dataclass(frozen=True)
class AdviceResult:
    """``judder advise``: safe dither windows, parameter ranking, design.

    ``windows`` are :class:`stability.decisions.advice.SafeWindow` of the given
    design (over every parameter set), ``ranking`` the list of
    :func:`stability.decisions.advice.ranking`, ``advice`` the
    :class:`stability.decisions.advice.Advice` (None if not asked for), and
    ``verification`` the recomputed map of the advised design with its
    count of judder-relevant points, ``unstable`` the
    :class:`stability.decisions.advice.UnstableRegion` of the advised
    design (unstable but slower than judder), ``view`` what the figure
    draws beyond the operating range (None unless asked for).
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
    unstable: list = None
    view: dict = None
    given: object = None
    driveline: str = "chain"

    def advised_params(self):
        """The advised parameter set (None if there is none): the given
        driveline's, without what its bench adds."""
        a = self.advice
        if a is None or not a.success:
            return None
        given = self.given if self.given is not None else self.params
        return given.replace(**{n: given[n] * f
                                for n, f in zip(a.names, a.factors)})

    def _max_growth(self):
        """Fastest growth of an unstable point of the recomputed map of
        the advised design, 1/s (None: no map, or nothing unstable)."""
        v = self.verification
        if v is None or not np.any(v.kind > 0):
            return None
        return float(v.growth_rate[v.kind > 0].max())

    def as_dict(self):
        op = self.operating
        from stability.bench import driveline_words
        out = {"model": self.params.model, "driveline": self.driveline,
               "driveline_description": driveline_words(self.params,
                                                        self.driveline),
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
                "bounds": {n: list(b) for n, b in
                           zip(a.names, a.bounds.tolist())},
                "dropped_as_unnecessary": dict(a.dropped),
                "drop_below_relative_change": PRUNE_BELOW,
                "units": {n: self.params.specs[n].unit for n in a.names},
                "unstable_regions": (None if self.unstable is None else [
                    {"freq_hz": list(r.freq_hz),
                     "lowest_p_f_bar": r.lowest_p_f / PA_PER_BAR,
                     "lowest_at_hz": r.lowest_at_hz}
                    for r in self.unstable]),
                "max_growth_per_s_in_range": self._max_growth(),
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
            lines.append("  share: the part of its way out of the window "
                         "(up, down or up in amplitude, the easiest) that "
                         "a change of ln(value) by 1, x2.72, moves the "
                         "tongue that needs most; 1 = all the way")
        a = self.advice
        if a is not None:
            lines += self._design_lines(a)
        return "\n".join(lines)

    def _design_lines(self, a):
        """The design in the parameters' units, its check, and the
        instability it still has."""
        from infra.numbers import readable_number
        from stability.decisions.advice import bounds_words
        bounds = f"bounds {bounds_words(a.names, a.bounds)}"
        if not a.success:
            return [f"design: none: {a.message}",
                    "  to find one: widen `bounds`, add `names`, or "
                    "narrow the operating range (`freq_range`, `valve_max_bar`)"]
        advised = self.advised_params()
        changed = [(n, f) for n, f in zip(a.names, a.factors)
                   if abs(f - 1) > 5e-4]
        # a drop of a change too small to print (x1.000) is no news
        dropped = {n: f for n, f in a.dropped.items() if abs(f - 1) > 5e-4}
        kept = [n for n, f in zip(a.names, a.factors)
                if abs(f - 1) <= 5e-4 and n not in dropped]
        design = ", ".join(
            f"{n} {readable_number(self.params[n])} -> "
            f"{readable_number(advised[n])} "
            f"{self.params.specs[n].unit} (x{f:.3f})" for n, f in changed)
        lines = [("design: " + design if changed else
                  "design: none needed: the window is already clear")
                 + (f"; unchanged: {', '.join(kept)}" if kept else ""),
            *([f"  dropped as unnecessary (under {PRUNE_BELOW:.0%}, the "
               "window stays clear without "
               + ("it" if len(dropped) == 1 else "them") + "): " + ", ".join(
                   f"{n} x{f:.3f}" for n, f in dropped.items())]
              if dropped else []),
            f"  weighted change {a.weighted_change:.3f}; {bounds}; "
            f"recomputed map: {self.judder_points} judder points "
            f"(>= {self.min_growth:g} 1/s) of {self.verification.kind.size}"
            f" in the operating range"]
        lines.append("  " + self._unstable_words())
        return lines

    def _unstable_words(self):
        """What instability the advised design still has, in words."""
        low, high = self.operating.freq_hz
        top = self.operating.p_max / PA_PER_BAR
        if not self.unstable:
            return (f"the advised design is stable (|lambda| < 1) in "
                    f"{low:g}-{high:g} Hz up to {top:g} bar")
        where = ", ".join(
            f"{r.freq_hz[0]:.1f}-{r.freq_hz[1]:.1f} Hz from "
            f"{r.lowest_p_f / PA_PER_BAR:.3f} bar (at "
            f"{r.lowest_at_hz:.1f} Hz)" for r in self.unstable)
        fastest = self._max_growth()
        rate = ("" if fastest is None else
                f", growing at most {fastest:.2g} 1/s there (one e-fold in "
                f"{1 / fastest:.2g} s)" if fastest > 0 else "")
        return (f"still unstable (|lambda| > 1) but not judder (growth < "
                f"{self.min_growth:g} 1/s) at {where}{rate}")

    @keeps_foreign_files
    def save(self, path):
        """CSV: freq_hz, safe_p_f_bar of the given design (operating
        frequencies only)."""
        low, high = self.operating.freq_hz
        write_text(path, rows_to_csv(
            [{"freq_hz": f, "safe_p_f_bar": p / PA_PER_BAR}
             for f, p in zip(self.freq_hz, self.safe_p_f)
             if low <= f <= high]))

    def figure(self, title=None, stacked=False):
        from .figures.advice import advice_figure
        return advice_figure(self, title=title, stacked=stacked)
