"""``judder check``: is a dither setting safe, and by how much."""

import dataclasses
from dataclasses import dataclass
import time

import numpy as np

from infra.errors import JudderError
from infra.files import keeps_foreign_files, write_text
from infra.units import PA_PER_BAR
from sources.dither_modes import (check_modes, check_modes_up_to,
                                  linearised_mode, mode_words)
from stability.kinds import KINDS
from stability.maps import stability_map as map_kernel
from stability.source import build_driveline

from ._common import (check_names, checked_values, frequency_dependent,
                      structural_names)
from ._records import finite_or_none, rows_to_csv
from ._words import growth_words, margin_words, response_words

#: Parameters whose effect on the margins ``check`` reports by default
#: (4-DOF model; other models: see :func:`structural_names`).
DEFAULT_CHECK_PARAMETERS = ("J2", "J4", "k12", "k24", "c12", "mu_g")


def check(freq_hz, p_f_bar, parameters=None, changes=None, min_growth=None,
          p_max_bar=None, sensitivity=None, background=False,
          progress=None, driveline=None, judder_limit_rpm=None):
    """``judder check``: is each dither setting safe, and by how much.

    Parameters
    ----------
    freq_hz, p_f_bar : array_like, shape (n,)
        The settings, Hz and bar (pairs: a dither table).
    min_growth : float, optional
        Judder-relevant growth rate, 1/s (default
        :data:`infra.criteria.DEFAULT_MIN_GROWTH_PER_S`).
    p_max_bar : float, optional
        Largest boundary amplitude searched (default the larger of 1.5
        bar and twice the largest setting).
    sensitivity : sequence of str, optional
        Parameters whose effect on the margins is reported (empty: none;
        default :data:`DEFAULT_CHECK_PARAMETERS`, or the model's
        inertias, stiffnesses, coupling dampings and mu_g; for a Modelica
        class or an FMU those of :data:`DEFAULT_CHECK_PARAMETERS` it has,
        and JudderError if none).
    background : bool
        Also compute the map ``figure()`` marks the settings on.
    driveline : {'chain', 'bench'}, optional
        The driveline judged (:data:`stability.bench.DRIVELINES`): the
        preset's chain, or the same on its test bench (what ``simulate``
        runs); default the bench where the preset has one
        (:func:`stability.bench.default_driveline`).
    judder_limit_rpm : float, optional
        NVH limit of the upstream speed's oscillation, rpm (default
        :data:`infra.criteria.DEFAULT_JUDDER_LIMIT_RPM`): a settled
        oscillation above it is judder, forced or parametric.

    Returns
    -------
    CheckResult
        Each setting's verdict is the bench engineer's: JUDDER where the
        settled oscillation at the dither-related frequencies reaches the
        limit (the bench's periodic orbit; for the chain its linear
        harmonic response) or the response grows at ``min_growth`` or
        faster, with its mechanism.
    """
    from infra.criteria import DEFAULT_MIN_GROWTH_PER_S, ENGAGEMENT_DURATION_S
    from stability.decisions.margins import check_settings
    freq_hz = np.atleast_1d(np.asarray(freq_hz, dtype=float))
    p_f_bar = np.atleast_1d(np.asarray(p_f_bar, dtype=float))
    if freq_hz.shape != p_f_bar.shape or freq_hz.ndim != 1 or not len(freq_hz):
        raise JudderError(f"freq and p_f have {freq_hz.size} and "
                          f"{p_f_bar.size} values; allowed: as many of each")
    from infra.criteria import DEFAULT_JUDDER_LIMIT_RPM

    from stability.bench import driveline_view
    judder_limit_rpm = (DEFAULT_JUDDER_LIMIT_RPM if judder_limit_rpm is None
                        else judder_limit_rpm)
    given = checked_values(parameters, changes, freq_hz=freq_hz,
                           p_f_bar=p_f_bar, min_growth=min_growth,
                           p_max_bar=p_max_bar,
                           judder_limit_rpm=judder_limit_rpm)
    values, driveline = driveline_view(given, driveline)
    min_growth = DEFAULT_MIN_GROWTH_PER_S if min_growth is None else min_growth
    if p_max_bar is None:
        p_max_bar = max(1.5, 2 * float(p_f_bar.max()))
    elif not p_max_bar > p_f_bar.max():
        raise JudderError(f"`p_max_bar` {p_max_bar:g} bar is not allowed; "
                          "allowed: above the largest setting, "
                          f"{p_f_bar.max():g} bar")
    if sensitivity is None:
        sensitivity = structural_names(values, DEFAULT_CHECK_PARAMETERS,
                                        ("mu_g",), "sensitivity")
    check_names(values, sensitivity, "`sensitivity`")
    check_modes(values, freq_hz, p_f_bar * PA_PER_BAR)
    if getattr(values, "check_mode", None) is not None:
        # a Modelica class: the margins are searched up to p_max_bar, on
        # the linearisation in its mode (presets need not import casadi)
        from sources.modelica import ModelicaError
        try:
            check_modes_up_to(values, freq_hz, p_max_bar)
        except ModelicaError as error:
            left = str(error).split("; allowed:")[0]
            raise JudderError(
                f"{left}: the margins are searched up to `p_max_bar` = "
                f"{p_max_bar:g} bar on the linearisation in one mode; "
                "allowed: a smaller `p_max_bar`, below the amplitude where "
                "the mode is left") from None
    if frequency_dependent(values):
        from infra.contract import warn
        warn(f"{values.model} is linearised at {freq_hz[0]:g} Hz (its "
             f"Jacobian depends on {values.frequency}): the Hz margin is "
             "searched on that linearisation, not on one at each "
             "neighbouring frequency")
    started = time.perf_counter()
    checks = check_settings(values, freq_hz, p_f_bar * PA_PER_BAR, min_growth,
                            p_max_bar * PA_PER_BAR, tuple(sensitivity),
                            callback=progress)
    responses = settled_responses(given, values, driveline, freq_hz,
                                  p_f_bar * PA_PER_BAR, judder_limit_rpm,
                                  min_growth,
                                  [c.floquet.growth_rate for c in checks],
                                  p_max_bar * PA_PER_BAR,
                                  parametric_bands(checks, freq_hz))
    seconds = time.perf_counter() - started
    result = CheckResult(params=values, checks=checks, min_growth=min_growth,
                         engagement_s=ENGAGEMENT_DURATION_S,
                         p_max=p_max_bar * PA_PER_BAR, seconds=seconds,
                         responses=responses, driveline=driveline,
                         judder_limit_rpm=judder_limit_rpm)
    if background:
        low, high = freq_hz.min(), freq_hz.max()
        grid = np.linspace(max(low - 0.5 * (high - low) - 20, 1.0),
                           high + 0.5 * (high - low) + 20, 200)
        system = build_driveline(values)
        p_top = max(2 * p_f_bar.max(), 0.5) * PA_PER_BAR
        under = map_kernel(system, grid, np.linspace(0, p_top, 100))
        exact = {}
        if not frequency_dependent(values):
            # the fills clipped to the exact boundaries, as the map draws
            # them: not the grid's cells (issue 46)
            from stability.tongues import find_tongues, tongue_boundaries
            boundaries = tongue_boundaries(system, grid, p_top)
            exact = {"background_boundaries": boundaries,
                     "background_tongues": find_tongues(system, boundaries)}
            if min_growth:
                # the judder line and its grey from the exact boundaries
                # of growth at min_growth, not the grid
                judder = tongue_boundaries(system, grid, p_top,
                                           min_growth=min_growth,
                                           check=False)
                exact["background_judder"] = (judder,
                                              find_tongues(system, judder))
        result = dataclasses.replace(result, background=under, **exact)
    return result


#: Where a setting's settled amplitude comes from, by driveline.
AMPLITUDE_SOURCES = {
    "bench": "the bench's periodic orbit (harmonic balance of its "
             "friction curve and motor torque limit; the 2T orbit past "
             "period doubling; in a combination tongue the motion "
             "integrated until settled, stability.settle)",
    "chain": "the chain's linear harmonic response at the dither "
             "frequency (Eq. 6 driven by the column D of Eq. 9)"}


def parametric_bands(checks, freq_hz):
    """Per setting the band of frequencies around it free of parametric
    judder at its amplitude, ``(low, high)`` Hz, each end the nearest
    crossing of the judder-relevant boundary or else the end of the range
    searched (:func:`stability.decisions.margins.search_grid`); None for
    a setting inside a tongue of judder."""
    from stability.decisions.margins import search_grid
    grid = search_grid(freq_hz)
    out = []
    for c in checks:
        m = c.margin
        out.append(None if m.inside else (
            grid[0] if m.band_low_hz is None else m.band_low_hz,
            grid[-1] if m.band_high_hz is None else m.band_high_hz))
    return out


def settled_responses(given, values, driveline, freq_hz, p_f, limit_rpm,
                      min_growth, growth_rates, p_max, bands=None):
    """The settled oscillation at each setting (Hz, Pa) and the verdict it
    gives (:func:`stability.orbit_chart.orbit_verdict`): for the bench,
    its periodic orbit; for a chain, its linear forced response with the
    linearisation's growth (``growth_rates``, 1/s). With it, the amplitude
    at which the forced oscillation reaches the limit at the setting's
    frequency, up to ``p_max`` (Pa;
    :func:`stability.orbit_chart.forced_limit_amplitude`, in proportion
    for the chain's linear response), and, within each setting's band
    free of parametric judder (``bands``, :func:`parametric_bands`), the
    nearest frequencies at which the forced oscillation at the setting's
    amplitude reaches the limit
    (:func:`stability.orbit_chart.forced_limit_frequencies`). Returns one
    dict per setting; None for a Modelica class or an FMU (its verdict
    is the growth's)."""
    from infra.criteria import MECHANISMS, mechanism_code
    from infra.units import RAD_S_PER_RPM, RPM_PER_RAD_S
    from stability.friction import forced_upstream_amplitude
    from stability.orbit import periodic_orbit
    from stability.orbit_chart import (forced_limit_amplitude,
                                       forced_limit_frequencies,
                                       held_slip_forced_amplitude,
                                       held_slip_motion, orbit_verdict)
    bands = bands or [None] * len(freq_hz)
    limit = limit_rpm * RAD_S_PER_RPM
    rows = []
    if not given.source_kind.is_chain:
        return None     # a class's or an FMU's forced response: not here
    if driveline == "bench":
        from stability.settle import settle_orbits

        from stability.bench import engagement_model
        model = engagement_model(given)[0]
        orbits = [periodic_orbit(model, f, p) for f, p in zip(freq_hz, p_f)]
        motions = settle_orbits(model, orbits)
    else:
        system = build_driveline(values)
    for k, (f, p, rate) in enumerate(zip(freq_hz, p_f, growth_rates)):
        if driveline == "bench":
            orbit, doubled = held_slip_motion(model, orbits[k])
            motion = motions[k]
            verdict = orbit_verdict(
                orbit, doubled, limit, min_growth,
                0.0 if motion is None else motion["combination"])
            forced, settled, growth = (verdict.forced, verdict.settled,
                                       verdict.growth_rate)
            judder, mechanism = verdict.judder, verdict.mechanism
            converged, quasi = orbit.success, verdict.quasi_periodic
            settled_s = None if motion is None else motion["duration"]
            forced_limit = forced_limit_amplitude(model, f, p, forced, limit,
                                                  p_max)
        else:
            forced = settled = forced_upstream_amplitude(system, f, p)
            growth = rate
            parametric, is_forced = growth >= min_growth, forced > limit
            judder = parametric or is_forced
            mechanism = mechanism_code(is_forced, parametric)
            converged, quasi, settled_s = True, False, None
            forced_limit = p * limit / forced if forced > 0 else np.inf
            forced_limit = forced_limit if forced_limit <= p_max else np.inf
        forced_band = None
        if bands[k] is not None and not judder:
            amplitude = (held_slip_forced_amplitude(model, p)
                         if driveline == "bench" else
                         lambda at, p=p: forced_upstream_amplitude(system,
                                                                   at, p))
            forced_band = forced_limit_frequencies(amplitude, f, limit,
                                                   *bands[k])
        rows.append({
            "forced_amplitude_rpm": forced * RPM_PER_RAD_S,
            "settled_amplitude_rpm": settled * RPM_PER_RAD_S,
            "amplitude_from": AMPLITUDE_SOURCES[driveline],
            "response_growth_per_s": growth,
            "quasi_periodic": bool(quasi), "converged": bool(converged),
            "integrated_s": settled_s,
            "judder": bool(judder) and bool(converged),
            "mechanism": MECHANISMS[int(mechanism)] if judder else None,
            "judder_limit_rpm": limit_rpm,
            # None: below the limit up to the largest amplitude searched;
            # NaN (JSON null with forced_limit_found False): orbit lost
            "forced_limit_p_f_bar": (None if not np.isfinite(forced_limit)
                                     else forced_limit / PA_PER_BAR),
            "forced_limit_found": not np.isnan(forced_limit),
            # around the setting, at its amplitude, within the band free
            # of parametric judder: [(Hz, 'forced'|'end'|'unknown')] * 2
            "forced_band": forced_band})
    return rows


def setting_record(check, min_growth, engagement_s, p_max, search_hz=None,
                   response=None):
    """One :class:`stability.decisions.margins.SettingCheck` as JSON fields.

    ``verdict`` is one of :data:`infra.criteria.VERDICTS`;
    ``search_hz`` the (low, high) frequencies the Hz margin was searched
    over (``frequency_search_hz``).
    """
    from stability.decisions.relevance import verdict
    from infra.criteria import JUDDER
    m, point = check.margin, check.floquet
    rate = point.growth_rate
    unstable = point.kind != KINDS[0]
    word = verdict(unstable, rate, min_growth)
    if response is not None:
        # the settled oscillation decides with the growth (the bench's
        # orbit is the motion, so its growth replaces the steady slip's)
        word = JUDDER if response["judder"] else verdict(
            response["response_growth_per_s"] > 0,
            response["response_growth_per_s"], min_growth)

    def tongue(t):
        # the tongue of judder (growth min_growth): its tip is where it
        # judders, named as `judder tongues` names it (``tip_*`` there is
        # where a tongue becomes unstable)
        return None if t is None else {
            "number": t.number, "kind": t.kind, "resonance": t.resonance,
            "judder_tip_freq_hz": t.tip_freq_hz,
            "judder_tip_p_f_bar": t.tip_p_f / PA_PER_BAR}
    sensitivity = sorted(
        ({"parameter": name,
          "margin_bar_per_unit_log": finite_or_none(bar / PA_PER_BAR),
          "margin_hz_per_unit_log": finite_or_none(hz)}
         for name, (bar, hz) in check.sensitivity.items()
         if np.isfinite(bar) or np.isfinite(hz)),
        key=lambda r: -abs(r["margin_hz_per_unit_log"] or 0.0)
        - abs(r["margin_bar_per_unit_log"] or 0.0) * 1e-6)
    response = dict(response or {})
    forced_band = response.pop("forced_band", None)
    return {"freq_hz": m.freq_hz, "p_f_bar": m.p_f / PA_PER_BAR,
            "verdict": word,
            **response,
            "kind": point.kind,
            "inside_stability_tongue": bool(unstable),
            "judder_relevant": bool(check.judder),
            "tongue": tongue(check.tongue),
            "growth_rate_per_s": rate,
            "e_folding_time_s": 1.0 / rate if rate > 0 else None,
            "efolds_per_engagement": rate * engagement_s,
            "min_growth_per_s": min_growth,
            "boundary_p_f_bar": finite_or_none(m.boundary_p_f / PA_PER_BAR),
            "unstable_boundary_p_f_bar": finite_or_none(
                check.unstable_p_f / PA_PER_BAR),
            "margin_bar": finite_or_none(m.margin_p_f / PA_PER_BAR),
            "margin_bar_at_least": (None if np.isfinite(m.margin_p_f)
                                    else (p_max - m.p_f) / PA_PER_BAR),
            "margin_bar_tongue": (tongue(check.bar_tongue)
                                  if np.isfinite(m.margin_p_f) else None),
            "crossing_hz": m.crossing_hz,
            "crossing_tolerance_hz": m.crossing_tolerance_hz,
            "margin_hz": finite_or_none(m.margin_hz),
            "margin_hz_tongue": tongue(check.hz_tongue),
            "frequency_search_hz": (None if search_hz is None else
                                    [float(f) for f in search_hz]),
            **highest_safe(m.boundary_p_f, response or None, p_max),
            **safe_band(check, response or None, forced_band, search_hz),
            "sensitivity": sensitivity}


def safe_band(check, response, forced_band, search_hz):
    """The band of dither frequencies around a setting, at its amplitude,
    with neither parametric judder (growth >= min_growth) nor a forced
    oscillation over the limit: ``safe_band_hz`` [low, high] Hz (None
    where the setting judders) and what ends it on each side,
    ``safe_band_low_limited_by`` and ``safe_band_high_limited_by``:
    ``parametric`` (the judder-relevant boundary, its tongue in
    ``safe_band_*_tongue``), ``forced`` (the settled oscillation at the
    dither frequency reaches the limit), ``unknown`` (the orbit was lost
    there) or None (the end of the range searched, ``search_hz``: the
    band reaches at least that far). Where the setting judders, both
    name its mechanism. ``forced_band``: the forced crossings
    (:func:`stability.orbit_chart.forced_limit_frequencies`) within the
    band free of parametric judder; None for a Modelica class or an FMU
    (the band is the parametric one)."""
    m = check.margin
    if m.inside or (response is not None and response["judder"]):
        # the verdict's mechanism where the settled oscillation judders
        # (the bench at 103 Hz, 0.3 bar: forced, though its steady
        # slip's linearisation grows), else the linearisation's
        judders = response is not None and response["judder"]
        why = response["mechanism"] if judders else "parametric"
        return {"safe_band_hz": None, "safe_band_low_limited_by": why,
                "safe_band_high_limited_by": why,
                "safe_band_low_tongue": None, "safe_band_high_tongue": None}
    out, edges = {}, []
    parametric = ((m.band_low_hz, check.band_low_tongue),
                  (m.band_high_hz, check.band_high_tongue))
    for side, (at, tongue), end in zip(("low", "high"), parametric,
                                       search_hz or (None, None)):
        by = None if at is None else "parametric"
        edge = end if at is None else at
        if forced_band is not None and forced_band[len(edges)][1] != "end":
            edge, by = forced_band[len(edges)]
            tongue = None
        edges.append(None if edge is None else float(edge))
        out[f"safe_band_{side}_limited_by"] = by
        out[f"safe_band_{side}_tongue"] = (None if by != "parametric" or
                                           tongue is None else tongue.number)
    return {"safe_band_hz": edges, **out}


def highest_safe(judder_boundary, response, p_max):
    """The highest safe amplitude at a setting's frequency (bar): the
    lower of the judder-relevant boundary (``judder_boundary``, Pa) and
    the amplitude at which the settled forced oscillation of
    ``response`` reaches the limit; what limits it (``parametric``,
    ``forced``; None: safe up to ``p_max``, Pa, the largest amplitude
    searched; ``unknown`` where the orbit was lost before the limit)."""
    limits = {"parametric": judder_boundary}
    if response is not None:
        if not response["forced_limit_found"]:
            return {"highest_safe_p_f_bar": None,
                    "highest_safe_limited_by": "unknown",
                    "highest_safe_searched_to_bar": p_max / PA_PER_BAR}
        if response["forced_limit_p_f_bar"] is not None:
            limits["forced"] = response["forced_limit_p_f_bar"] * PA_PER_BAR
    finite = {k: v for k, v in limits.items() if np.isfinite(v)}
    by = min(finite, key=finite.get) if finite else None
    return {"highest_safe_p_f_bar": (None if by is None
                                     else finite[by] / PA_PER_BAR),
            "highest_safe_limited_by": by,
            "highest_safe_searched_to_bar": p_max / PA_PER_BAR}


def highest_safe_words(record):
    """``highest safe amplitude at F Hz: X bar (why)`` of a record."""
    at = f"highest safe amplitude at {record['freq_hz']:g} Hz"
    by, top = record["highest_safe_limited_by"], record["highest_safe_p_f_bar"]
    if by is None:
        return (f"{at}: above the {record['highest_safe_searched_to_bar']:g}"
                " bar searched")
    if by == "unknown":
        return f"{at}: unknown (the periodic orbit was lost below the limit)"
    why = (f"the forced oscillation reaches the "
           f"{record['judder_limit_rpm']:g} rpm limit" if by == "forced"
           else "parametric judder"
           + _tongue_words(record["margin_bar_tongue"]))
    return f"{at}: {top:.3f} bar ({why})"


def safe_band_words(record):
    """``at P bar safe from A to B Hz around the setting (below A Hz ...;
    above B Hz ...)``, or why there is no such band."""
    at = f"at {record['p_f_bar']:g} bar"
    band = record["safe_band_hz"]
    if band is None:
        why = record["safe_band_low_limited_by"]
        return (f"{at} no safe dither frequency around the setting: it "
                f"judders ({why})")
    ends, whys = [], []
    for side, edge, beyond in (("low", band[0], "below"),
                               ("high", band[1], "above")):
        by = record[f"safe_band_{side}_limited_by"]
        if edge is None:        # no range known: a record without one
            ends.append("the end searched")
            continue
        if by is None:
            ends.append(f"{edge:.3g} Hz or {'lower' if side == 'low' else 'higher'}")
            whys.append(f"the range searched ends at {edge:.3g} Hz")
            continue
        ends.append(f"{edge:.2f} Hz")
        if by == "forced":
            why = (f"the forced oscillation exceeds the "
                   f"{record['judder_limit_rpm']:g} rpm limit")
        elif by == "unknown":
            why = "the periodic orbit is lost"
        else:
            number = record[f"safe_band_{side}_tongue"]
            why = "parametric judder" + ("" if number is None
                                         else f", tongue {number}")
        whys.append(f"{beyond} {edge:.2f} Hz {why}")
    return (f"{at} safe from {ends[0]} to {ends[1]} around the setting "
            f"({'; '.join(whys)})")


def _tongue_words(tongue):
    return "" if tongue is None else f" in tongue {tongue['number'] or '?'}"


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
    parts = [head]
    if "settled_amplitude_rpm" in record:
        parts.append(response_words(record))
    parts += [growth_words(record, engagement_s), highest_safe_words(record),
              safe_band_words(record), *margin_words(record)]
    sensitive = sensitivity_words(record)
    if sensitive:
        parts.append(sensitive)
    return "; ".join(parts)


@dataclass(frozen=True)
class CheckResult:
    """``judder check``: verdict and margins of each dither setting.

    ``checks`` are :class:`stability.decisions.margins.SettingCheck` objects;
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
    background_boundaries: object = None
    background_tongues: list = None
    responses: list = None
    driveline: str = "chain"
    judder_limit_rpm: float = None
    background_judder: object = None

    def records(self):
        from stability.decisions.margins import search_grid
        grid = search_grid([c.margin.freq_hz for c in self.checks]) \
            if self.checks else None
        search = None if grid is None else (grid[0], grid[-1])
        responses = self.responses or [None] * len(self.checks)
        return [setting_record(c, self.min_growth, self.engagement_s,
                               self.p_max, search, response)
                for c, response in zip(self.checks, responses)]

    def as_dict(self):
        mode = linearised_mode(self.params)
        from stability.bench import driveline_words
        return {"model": self.params.model,
                "driveline": self.driveline,
                "driveline_description": driveline_words(self.params,
                                                         self.driveline),
                **({"mode": mode} if mode else {}),
                "min_growth_per_s": self.min_growth,
                "engagement_s": self.engagement_s,
                "p_max_bar": self.p_max / PA_PER_BAR,
                "seconds": self.seconds, "settings": self.records()}

    def summary(self):
        from stability.bench import driveline_words
        words = mode_words(linearised_mode(self.params))
        return "\n".join([f"driveline: {driveline_words(self.params, self.driveline)}"]
                         + ([words] if words else [])
                         + [setting_summary(r, self.engagement_s)
                            for r in self.records()])

    @keeps_foreign_files
    def save(self, path):
        """CSV: one row per setting (the scalar fields; tongues by
        number; the safe band as ``safe_band_low_hz``,
        ``safe_band_high_hz``)."""
        rows = []
        for r in self.records():
            row = {k: v for k, v in r.items()
                   if not isinstance(v, (dict, list)) and k not in
                   ("tongue", "margin_bar_tongue", "margin_hz_tongue")}
            for key in ("tongue", "margin_bar_tongue", "margin_hz_tongue"):
                row[key] = None if r[key] is None else r[key]["number"]
            band = r.get("safe_band_hz") or (None, None)
            row["safe_band_low_hz"], row["safe_band_high_hz"] = band
            rows.append(row)
        write_text(path, rows_to_csv(rows))

    def figure(self, title=None):
        from .figures.check import check_figure
        return check_figure(self.records(), self.background,
                            min_growth=self.min_growth, title=title,
                            boundaries=self.background_boundaries,
                            tongues=self.background_tongues,
                            judder=self.background_judder)
