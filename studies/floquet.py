"""``judder floquet``: Floquet multipliers at one point."""

from dataclasses import dataclass
import math

from infra.criteria import SLOW_GROWTH, STABLE
from infra.units import PA_PER_BAR
from sources.dither_modes import check_modes, linearised_mode
from stability import floquet as floquet_kernel
from stability.monodromy import DEFAULT_METHOD

from ._common import checked_values, dithered


def floquet(freq_hz, p_f_bar, parameters=None, changes=None,
            method=DEFAULT_METHOD, waveform=None, min_growth=None,
            driveline=None):
    """``judder floquet``: Floquet multipliers at one dither setting
    (Eq. 10-13), rigid-body angles removed.

    Parameters
    ----------
    freq_hz : float
        Dither frequency, Hz.
    p_f_bar : float
        Dither amplitude, bar.

    waveform : object, optional
        Dither shape (:mod:`stability.waveforms`); default the cosine.
    min_growth : float, optional
        Judder rate, 1/s, of the verdict (default
        :data:`infra.criteria.DEFAULT_MIN_GROWTH_PER_S`).
    driveline : {'chain', 'bench'}, optional
        The driveline linearised (:func:`stability.bench.driveline_view`);
        default the bench where the preset has one.

    Returns
    -------
    FloquetPoint
    """
    from infra.criteria import DEFAULT_MIN_GROWTH_PER_S
    min_growth = DEFAULT_MIN_GROWTH_PER_S if min_growth is None else min_growth
    values = checked_values(parameters, changes, freq_hz=freq_hz,
                            p_f_bar=p_f_bar, min_growth=min_growth)
    from stability.bench import driveline_view
    values, view = driveline_view(values, driveline)
    check_modes(values, freq_hz, p_f_bar * PA_PER_BAR)
    result = floquet_kernel(dithered(values, waveform), freq_hz,
                            p_f_bar * PA_PER_BAR, method=method)
    return FloquetPoint(params=values, method=method, result=result,
                        min_growth=min_growth, driveline=view)


def complex_record(value):
    """A complex number as JSON fields a script reads without knowing a
    convention: ``re``, ``im``, ``abs`` and ``arg`` (rad, in (-pi, pi])."""
    value = complex(value)
    return {"re": value.real, "im": value.imag, "abs": abs(value),
            "arg": math.atan2(value.imag, value.real)}


@dataclass(frozen=True)
class FloquetPoint:
    """``judder floquet``: the multipliers at one dither setting.

    ``result`` is the :class:`stability.multipliers.FloquetResult`;
    ``min_growth`` the judder rate (1/s) of its verdict.
    """

    params: object
    method: str
    result: object
    min_growth: float = 1.0
    driveline: str = "chain"

    def verdict(self):
        """One of :data:`infra.criteria.VERDICTS`."""
        from stability.decisions.relevance import verdict
        from stability.kinds import KINDS
        r = self.result
        return verdict(r.kind != KINDS[0], r.growth_rate, self.min_growth)

    def verdict_words(self):
        """The verdict with both thresholds named."""
        word, rate = self.verdict(), self.result.growth_rate
        judder = f"judder (growth >= {self.min_growth:g} 1/s)"
        if word == STABLE:
            return f"{word}: every multiplier inside the unit circle"
        if word == SLOW_GROWTH:
            return (f"{word}: unstable (|lambda| > 1), growing at "
                    f"{rate:.4g} 1/s, slower than {judder}")
        return f"{word}: unstable (|lambda| > 1) and {judder}"

    @property
    def p_f_bar(self):
        return self.result.p_f / PA_PER_BAR

    def as_dict(self):
        r = self.result
        mode = linearised_mode(self.params)
        from stability.bench import driveline_words
        return {"model": self.params.model, "driveline": self.driveline,
                "driveline_description": driveline_words(self.params,
                                                         self.driveline),
                **({"mode": mode} if mode else {}), "freq_hz": r.freq_hz,
                "p_f_bar": self.p_f_bar, "p_f_pa": r.p_f,
                "period_s": r.period, "method": self.method,
                "multipliers": [complex_record(z) for z in r.multipliers],
                "leading": complex_record(r.leading),
                "leading_abs": r.leading_abs, "kind": r.kind,
                "growth_rate_per_s": r.growth_rate,
                "verdict": self.verdict(),
                "min_growth_per_s": self.min_growth,
                "exponents_per_s": [complex_record(z) for z in r.exponents]}

    def figure(self, title=None):
        """The multipliers on the complex plane (Fig. 15)."""
        from stability.plots import multipliers_figure
        return multipliers_figure([self.result], title=title)
