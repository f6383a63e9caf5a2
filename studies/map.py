"""``judder map``: stability map over frequency x amplitude."""

import dataclasses
from dataclasses import dataclass
import json

import numpy as np

from infra.errors import JudderError
from infra.files import keeps_foreign_files, save_npz, write_text
from infra.units import PA_PER_BAR, RPM_PER_RAD_S
from sources.dither_modes import check_modes_up_to, linearised_mode
from stability.kinds import KINDS
from stability.maps import stability_map as map_kernel
from stability.monodromy import DEFAULT_METHOD

from ._common import (checked_values, dithered, frequency_dependent,
                      per_frequency, timed)
from ._preflight import check_map, check_map_memory
from stability.bench import driveline_view

#: Largest grid a map accepts, in points.
MAX_MAP_POINTS = 2_000_000


def check_map_grid(values, freqs, amplitudes, options, method, tongues):
    """Refuse a map grid above :data:`MAX_MAP_POINTS`, or beyond the
    memory or the time limit, before any work."""
    if len(freqs) * len(amplitudes) > MAX_MAP_POINTS:
        raise JudderError(f"{options} has {len(freqs) * len(amplitudes)} "
                          f"points; allowed: at most {MAX_MAP_POINTS}")
    check_map_memory(values, freqs, amplitudes)
    check_map(values, freqs, amplitudes, method, tongues=tongues)


def stability_map(freq_hz, p_f_bar, parameters=None, changes=None,
                  method=DEFAULT_METHOD, progress=None, min_growth=None,
                  exact=False, waveform=None, driveline=None,
                  judder_limit_rpm=None):
    """``judder map``: leading multiplier on a frequency x amplitude grid
    (Fig. 12, Fig. 14).

    Parameters
    ----------
    freq_hz : array_like
        Dither frequencies, Hz.
    p_f_bar : array_like
        Dither amplitudes, bar.

    exact : bool
        Also compute the exact tongue boundaries and tips on the map's
        frequencies up to its largest amplitude
        (:func:`stability.tongues.tongue_boundaries`), which
        ``figure()`` draws over the grid with the tongue numbers.
    waveform : object, optional
        Dither shape (:mod:`stability.waveforms`); default the cosine.
    driveline : {'chain', 'bench'}, optional
        The driveline mapped (:func:`stability.bench.driveline_view`);
        default the bench where the preset has one.
    judder_limit_rpm : float, optional
        NVH limit of the upstream speed's oscillation, rpm (default
        :data:`infra.criteria.DEFAULT_JUDDER_LIMIT_RPM`): for a preset's
        driveline the map also holds its linear forced response at the
        dither frequency, judder where it exceeds the limit (forced).

    Returns
    -------
    MapResult
        ``save(path)`` writes NPZ, ``figure()`` draws it.
    min_growth : float, optional
        1/s: the figure shades unstable points growing slower than this
        (not judder, :mod:`stability.decisions.relevance`) and the JSON
        counts the faster ones.
    """
    given = checked_values(parameters, changes, followed=True,
                           freq_hz=freq_hz, p_f_bar=p_f_bar)
    values, view = driveline_view(given, driveline)
    from infra.criteria import DEFAULT_JUDDER_LIMIT_RPM
    judder_limit_rpm = (DEFAULT_JUDDER_LIMIT_RPM if judder_limit_rpm is None
                        else judder_limit_rpm)
    check_modes_up_to(values, freq_hz, p_f_bar)
    driveline = dithered(values, waveform)
    amplitudes = np.asarray(p_f_bar, dtype=float) * PA_PER_BAR
    p_top = float(np.max(p_f_bar)) * PA_PER_BAR
    exact = exact and np.size(freq_hz) > 1 and p_top > 0
    boundaries = found = exact_seconds = None
    if frequency_dependent(values) and np.unique(freq_hz).size > 1:
        # the Jacobian depends on the dither frequency: each column of
        # the map, and of its boundaries, on the model linearised at its
        # own frequency (once for both)
        result, seconds, boundaries, exact_seconds = _followed(
            values, waveform, freq_hz, amplitudes, p_top if exact else None,
            method, progress)
    else:
        result, seconds = timed(map_kernel, driveline, freq_hz, amplitudes,
                                method=method, callback=progress)
        if exact:
            from stability.tongues import tongue_boundaries
            boundaries, exact_seconds = timed(
                tongue_boundaries, driveline, result.freq_hz, p_top, method)
    judder = None
    if boundaries is not None:
        from stability.tongues import find_tongues
        found = find_tongues(driveline, boundaries)
        if min_growth and not frequency_dependent(values):
            # the exact boundaries of judder too: the figure's judder
            # line and its grey follow them, not the grid (issue 46)
            from stability.tongues import tongue_boundaries
            judder_boundaries, spent = timed(
                tongue_boundaries, driveline, result.freq_hz, p_top, method,
                min_growth=min_growth, check=False)
            exact_seconds += spent
            judder = (judder_boundaries,
                      find_tongues(driveline, judder_boundaries))
    forced = slip = linear_slip = None
    if values.source_kind.is_chain and waveform is None:
        from stability.friction import (forced_slip_amplitude,
                                        forced_upstream_amplitude)
        forced = np.array([forced_upstream_amplitude(
            driveline, f, PA_PER_BAR) for f in result.freq_hz]) \
            * RPM_PER_RAD_S
        slip = np.array([forced_slip_amplitude(driveline, f, PA_PER_BAR)
                         for f in result.freq_hz])
        if view == "bench":
            from stability.bench import operating_friction
            linear_slip = operating_friction(given)[1]
    return MapResult(params=values, map=result, seconds=seconds,
                     boundaries=boundaries, tongues=found,
                     min_growth=min_growth, boundaries_seconds=exact_seconds,
                     driveline=view, forced_rpm_per_bar=forced,
                     judder_limit_rpm=judder_limit_rpm,
                     forced_slip_per_bar=slip, linear_slip=linear_slip,
                     judder=judder)


def _followed(values, waveform, freq_hz, amplitudes, p_top, method,
              progress):
    """The map of a frequency-dependent model (and its exact boundaries up
    to ``p_top``, unless None), column by column on the model linearised
    at each frequency (:func:`per_frequency`): the map, its seconds, the
    boundaries and theirs."""
    seconds = {"map": 0.0, "exact": 0.0}

    def column(driveline, f):
        leading, spent = timed(map_kernel, driveline, f, amplitudes,
                               method=method)
        seconds["map"] += spent
        if p_top is None:
            return leading, None
        from stability.tongues import tongue_boundaries
        edges, spent = timed(tongue_boundaries, driveline, f, p_top, method)
        seconds["exact"] += spent
        return leading, edges

    maps, edges = zip(*per_frequency(values, waveform, freq_hz, column,
                                     progress))
    result = _stacked(maps, ("freq_hz", "leading", "kind"))
    if p_top is None:
        return result, seconds["map"], None, None
    return (result, seconds["map"],
            _stacked(edges, ("freq_hz", "amplitude", "multiplier_error")),
            seconds["exact"])


def _stacked(parts, fields):
    """One result of the per-frequency ``parts`` (of one frequency each):
    their ``fields`` joined along the frequency axis, the rest the
    first's."""
    return dataclasses.replace(parts[0], **{
        name: np.concatenate([getattr(part, name) for part in parts])
        for name in fields})


@dataclass(frozen=True)
class MapResult:
    """``judder map``: the stability map (Fig. 12, 14) and its timing.

    ``map`` is the :class:`stability.maps.StabilityMap`; ``seconds`` the
    time of the Floquet map, ``boundaries_seconds`` that of the exact
    boundaries (None without them).
    """

    params: object
    map: object
    seconds: float
    boundaries: object = None
    tongues: list = None
    min_growth: object = None
    boundaries_seconds: object = None
    driveline: str = "chain"
    forced_rpm_per_bar: object = None
    judder_limit_rpm: float = 30.0
    forced_slip_per_bar: object = None
    linear_slip: float = None
    #: (Boundaries, tongues) of growth at ``min_growth``, exact (None:
    #: not computed; the figure then contours the map's growth rate)
    judder: object = None

    def beyond_linear_range(self):
        """Points where the dither's forced slip swing exceeds the bench
        friction curve's linear range (rad/s; bool grid, or None for a
        view without the curve): there the motion need not follow the
        linear view (``judder orbit`` gives it)."""
        if self.forced_slip_per_bar is None or self.linear_slip is None:
            return None
        return np.outer(self.forced_slip_per_bar,
                        self.map.p_f / PA_PER_BAR) > self.linear_slip

    def verdicts(self):
        """The verdict at each point as ``check`` gives it from the
        linear view: ``judder`` (bool grid) and ``mechanism`` (index into
        :data:`infra.criteria.MECHANISMS`: growth at ``min_growth`` or
        faster is parametric, a forced oscillation above the limit
        forced). Without ``min_growth`` the judder rate is ``check``'s
        default (:data:`infra.criteria.DEFAULT_MIN_GROWTH_PER_S`), not
        every instability as the map's shading takes it."""
        from infra.criteria import DEFAULT_MIN_GROWTH_PER_S, mechanism_code
        from stability.decisions.relevance import is_judder_relevant
        rate = (DEFAULT_MIN_GROWTH_PER_S if self.min_growth is None
                else self.min_growth)
        parametric = (self.map.kind > 0) & is_judder_relevant(
            self.map.growth_rate, rate)
        forced = self.forced_amplitude_rpm()
        forced = np.zeros_like(parametric) if forced is None else \
            forced > self.judder_limit_rpm
        mechanism = mechanism_code(forced, parametric).astype(np.int8)
        return parametric | forced, mechanism

    def forced_amplitude_rpm(self):
        """The linear forced oscillation of the upstream speed at the
        dither frequency, rpm, shape (nf, np) (None: not computed, a
        class, an FMU or another waveform)."""
        if self.forced_rpm_per_bar is None:
            return None
        return np.outer(self.forced_rpm_per_bar,
                        self.map.p_f / PA_PER_BAR)

    def judder_points(self):
        """Points that judder by growth or by the forced oscillation."""
        return self.verdicts()[0]

    def judder_relevant_points(self):
        """Points growing faster than ``min_growth`` (all unstable ones if
        it is None)."""
        return int(np.count_nonzero(self._judder()))

    def as_dict(self):
        m = self.map
        bar = m.p_f / PA_PER_BAR
        mode = linearised_mode(self.params)
        from stability.bench import driveline_words
        return {"model": self.params.model, "driveline": self.driveline,
                "driveline_description": driveline_words(self.params,
                                                         self.driveline),
                **({"mode": mode, "mode_checked_at_p_f_bar":
                    float(bar.max())} if mode else {}), "method": m.method,
                "points": int(m.kind.size), "seconds": self.seconds,
                "freq_hz": [m.freq_hz[0], m.freq_hz[-1], len(m.freq_hz)],
                "p_f_bar": [bar[0], bar[-1], len(bar)],
                "counts": m.counts(),
                "min_growth_per_s": self.min_growth,
                "judder_relevant_points": self.judder_relevant_points(),
                **self.forced_counts(),
                "max_leading_abs": float(m.leading_abs.max()),
                "natural_frequencies_hz": m.natural_frequencies_hz}

    def forced_counts(self):
        """The JSON fields of the forced response: the limit, the points
        above it, the judder points in all and those beyond the linear
        range ({} where the map has no forced response)."""
        forced = self.forced_amplitude_rpm()
        if forced is None:
            return {}
        beyond = self.beyond_linear_range()
        return {"judder_limit_rpm": self.judder_limit_rpm,
                "forced_response": "linear harmonic response of the "
                                   "upstream speed at the dither frequency",
                "forced_judder_points": int(np.count_nonzero(
                    forced > self.judder_limit_rpm)),
                "judder_points": int(np.count_nonzero(
                    self.judder_points())),
                "friction_linear_range_rad_s": self.linear_slip,
                "beyond_linear_range_points": (
                    None if beyond is None else
                    int(np.count_nonzero(beyond)))}

    def csv_text(self, meta=None):
        """The map as a long table, one row per grid point: ``freq_hz``,
        ``p_f_bar``, ``leading_abs`` (|lambda|), ``growth_rate_per_s``
        (ln|lambda|/T), ``kind`` (its name), ``judder`` (1: unstable and
        growing at ``min_growth`` or faster; 0 else), ``leading_re``,
        ``leading_im``; after the rows, ``# key: value`` comments (the
        model, the method, the rate, the natural frequencies, the
        parameter values in SI units and ``meta``)."""
        m = self.map
        bar = m.p_f / PA_PER_BAR
        judder = self._judder()
        lines = ["freq_hz,p_f_bar,leading_abs,growth_rate_per_s,kind,"
                 "judder,leading_re,leading_im"]
        for i, freq in enumerate(m.freq_hz):
            for j, amplitude in enumerate(bar):
                z = m.leading[i, j]
                lines.append(
                    f"{freq:.9g},{amplitude:.9g},{abs(z):.12g},"
                    f"{m.growth_rate[i, j]:.9g},{KINDS[m.kind[i, j]]},"
                    f"{int(judder[i, j])},{z.real:.12g},{z.imag:.12g}")
        info = {"model": self.params.model, "method": m.method,
                "min_growth_per_s": float(self.min_growth or 0.0),
                "natural_frequencies_hz": list(m.natural_frequencies_hz),
                **(meta or {}), "parameters": self.params.as_dict()}
        lines += [f"# {key}: {json.dumps(value)}"
                  for key, value in info.items()]
        return "\n".join(lines) + "\n"

    def _judder(self):
        from stability.decisions.relevance import is_judder_relevant
        return (self.map.kind > 0) & is_judder_relevant(
            self.map.growth_rate, self.min_growth or 0)

    @keeps_foreign_files
    def save(self, path, meta=None):
        """Save the map as CSV (:meth:`csv_text`) by a ``.csv`` suffix,
        else as NPZ.

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
        if str(path).lower().endswith(".csv"):
            write_text(path, self.csv_text(meta))
            return
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
        if self.forced_rpm_per_bar is not None:
            arrays.update({
                "forced_amplitude_rpm": self.forced_amplitude_rpm(),
                "judder_limit_rpm": np.array(self.judder_limit_rpm)})
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
        forced = None if self.forced_rpm_per_bar is None else \
            (self.map.freq_hz, self.judder_limit_rpm
             / np.maximum(self.forced_rpm_per_bar, 1e-300),
             self.judder_limit_rpm)
        return map_figure(self.map, title=title, tongues=self.tongues,
                          boundaries=self.boundaries,
                          min_growth=self.min_growth, stacked=stacked,
                          forced=forced, judder=self.judder)
