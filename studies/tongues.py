"""``judder tongues``: tongue boundaries, labels and tips."""

from dataclasses import dataclass
import math
import time

import numpy as np

from infra.files import keeps_foreign_files, write_text
from infra.units import PA_PER_BAR
from sources.dither_modes import check_modes_up_to, linearised_mode
from stability.maps import stability_map as map_kernel
from stability.monodromy import DEFAULT_METHOD

from ._common import BACKGROUND_AMPLITUDES, checked_values, dithered
from stability.bench import driveline_view
from .rules import RULES


def tongues(freq_hz, p_max_bar=1.5, parameters=None, changes=None,
            method=DEFAULT_METHOD, background=False, progress=None,
            min_growth=0.0, solver="hill", waveform=None,
            judder_growth=None, driveline=None):
    """``judder tongues``: exact tongue boundaries, tongue numbers (Fig.
    14) and tips.

    Parameters
    ----------
    freq_hz : array_like
        Dither frequencies, Hz.
    p_max_bar : float
        Largest amplitude searched, bar.
    background : bool
        Also compute the map drawn under the boundaries by ``figure()``
        (:data:`BACKGROUND_AMPLITUDES` amplitudes from 0 to ``p_max``).
    min_growth : float
        1/s: the boundaries (``boundaries``, ``tongues``) are those of
        growth at this rate (0: the stability boundaries, where a tongue
        becomes unstable).
    judder_growth : float, optional
        1/s: also the tongues of judder, growing at this rate
        (``judder_tongues``; default
        :data:`infra.criteria.DEFAULT_MIN_GROWTH_PER_S`).
    solver : str
        Boundary solver, a key of :data:`stability.tongues.SOLVERS`.
    waveform : object, optional
        Dither shape (:mod:`stability.waveforms`); default the cosine.
    driveline : {'chain', 'bench'}, optional
        The driveline whose tongues these are
        (:func:`stability.bench.driveline_view`); default the bench where the
        preset has one.

    Returns
    -------
    TonguesResult
    """
    from infra.criteria import DEFAULT_MIN_GROWTH_PER_S
    from stability.tongues import find_tongues, tongue_boundaries
    values = checked_values(parameters, changes, freq_hz=freq_hz,
                            p_max_bar=p_max_bar)
    values, view = driveline_view(values, driveline)
    check_modes_up_to(values, freq_hz, p_max_bar)
    judder_growth = (DEFAULT_MIN_GROWTH_PER_S if judder_growth is None
                     else float(RULES["min_growth"].check(judder_growth,
                                                 "judder_growth")))
    driveline = dithered(values, waveform)
    p_max = p_max_bar * PA_PER_BAR
    started = time.perf_counter()
    boundaries = tongue_boundaries(driveline, freq_hz, p_max, method,
                                   callback=progress, min_growth=min_growth,
                                   solver=solver)
    found = find_tongues(driveline, boundaries)
    if judder_growth == boundaries.min_growth:
        judder, judder_boundaries = found, boundaries
    else:
        judder_boundaries = tongue_boundaries(
            driveline, freq_hz, p_max, method, min_growth=judder_growth,
            solver=solver, check=False)
        judder = find_tongues(driveline, judder_boundaries)
    seconds = time.perf_counter() - started
    under = (map_kernel(driveline, freq_hz,
                        np.linspace(0, p_max, BACKGROUND_AMPLITUDES),
                        method=method) if background else None)
    return TonguesResult(params=values, boundaries=boundaries,
                         tongues=found, seconds=seconds, background=under,
                         judder_tongues=judder, judder_growth=judder_growth,
                         driveline=view, judder_boundaries=judder_boundaries)


def tongue_record(tongue, judder=None):
    """A :class:`stability.tongues.Tongue` as JSON fields (bar, Hz); with
    ``judder`` (the tongues of judder), the tip of the same number there
    (``judder_tip_*``, None where it does not reach judder)."""
    late = None if judder is None or tongue.number is None else next(
        (t for t in judder if t.number == tongue.number), None)
    extra = {} if judder is None else {
        "judder_tip_freq_hz": None if late is None else late.tip_freq_hz,
        "judder_tip_p_f_bar": (None if late is None
                               else late.tip_p_f / PA_PER_BAR)}
    return {"number": tongue.number, "kind": tongue.kind,
            "resonance": tongue.resonance,
            "resonance_hz": tongue.resonance_hz,
            "tip_freq_hz": tongue.tip_freq_hz,
            "tip_p_f_bar": tongue.tip_p_f / PA_PER_BAR,
            "tip_offset_percent": None if tongue.resonance_hz is None else
            100 * (tongue.tip_freq_hz / tongue.resonance_hz - 1),
            "tip_multiplier_error": tongue.tip_multiplier_error,
            "freq_range_hz": list(tongue.freq_range_hz),
            "tip_at_edge": tongue.tip_at_edge, **extra}


@dataclass(frozen=True)
class TonguesResult:
    """``judder tongues``: exact boundaries, labelled tongues and tips.

    ``boundaries`` is a :class:`stability.tongues.Boundaries`, ``tongues``
    a list of :class:`stability.tongues.Tongue` (of growth
    ``boundaries.min_growth``, 0: where each becomes unstable);
    ``judder_tongues`` those of growth ``judder_growth`` (1/s, where each
    becomes judder); ``background`` the map drawn under them (None unless
    asked for).
    """

    params: object
    boundaries: object
    tongues: list
    seconds: float
    background: object = None
    judder_tongues: list = None
    judder_growth: float = None
    driveline: str = "chain"
    judder_boundaries: object = None

    def as_dict(self):
        b = self.boundaries
        mode = linearised_mode(self.params)
        from stability.bench import driveline_words
        return {"model": self.params.model, "driveline": self.driveline,
                "driveline_description": driveline_words(self.params,
                                                         self.driveline),
                **({"mode": mode, "mode_checked_at_p_f_bar":
                    b.p_max / PA_PER_BAR} if mode else {}),
                "method": b.method,
                "min_growth_per_s": b.min_growth, "seconds": self.seconds,
                "freq_hz": [b.freq_hz[0], b.freq_hz[-1], len(b.freq_hz)],
                "p_max_bar": b.p_max / PA_PER_BAR,
                "max_boundary_multiplier_error": b.max_multiplier_error,
                "natural_frequencies_hz": b.natural_frequencies_hz,
                "judder_min_growth_per_s": self.judder_growth,
                "damped_frequencies_hz": self._damped_hz(),
                "tongues": [tongue_record(t, self.judder_tongues or [])
                            for t in self.tongues]}

    def _damped_hz(self):
        """The damped modes of the driveline without dither, Hz (None for
        a class or an FMU, whose modes ``judder eig`` gives)."""
        if not self.params.source_kind.is_chain:
            return None
        from stability.modal import damped_modes
        from stability.source import build_driveline
        return [float(f) for f in
                damped_modes(build_driveline(self.params))[0]]

    def csv_text(self):
        """Boundaries as CSV: freq_hz, p_f_bar (lowest, empty if none),
        then the lowest boundary of each kind and the amplitude searched
        up to (``tried_bar``: a point without a boundary is stable up to
        it), bar; a comment after the rows gives the growth rate they are
        the boundaries of (``judder fit --boundary`` compares with the
        model's boundary of that rate)."""
        b = self.boundaries
        lines = ["freq_hz,p_f_bar,single_period_bar,double_period_bar,"
                 "combination_bar,tried_bar"]

        def cell(value):
            return "" if not math.isfinite(value) \
                else f"{value / PA_PER_BAR:.9g}"
        for f, lowest, row in zip(b.freq_hz, b.stability_boundary,
                                  b.amplitude):
            lines.append(",".join([f"{f:.9g}", cell(lowest)]
                                  + [cell(v) for v in row]
                                  + [cell(b.p_max)]))
        lines.append(f"# min_growth_per_s: {b.min_growth:g}")
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
            min_growth=(self.judder_growth or self.boundaries.min_growth
                        or DEFAULT_MIN_GROWTH_PER_S),
            # the judder line and the grey from the exact boundaries of
            # that growth (issue 46), when the figure's boundaries are
            # the stability boundaries
            judder=(None if self.judder_boundaries is None
                    or self.boundaries.min_growth
                    or not self.judder_growth else
                    (self.judder_boundaries, self.judder_tongues)))
