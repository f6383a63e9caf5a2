"""``judder floquet``: Floquet multipliers at one point."""

from dataclasses import dataclass
import math

from infra.criteria import SLOW_GROWTH, STABLE
from infra.units import PA_PER_BAR
from stability import floquet as floquet_kernel
from stability.monodromy import DEFAULT_METHOD

from ._arguments import (driveline_option, force_option, method_option,
                         min_growth_option,
                         model_options, waveform_option)
from ._common import (check_modes, checked_values, dithered,
                      linearised_mode, mode_words)
from ._model import model_title, parameters_of
from ._output import emit, make_parents, output_files, save_plot, written
from ._preflight import check_floquet
from ._values import FREQ, MIN_GROWTH, PF, parse_waveform

#: The command's --help text.
DESCRIPTION = (
    "Monodromy matrix over one dither period and its Floquet "
    "multipliers (Eq. 10-13), rigid-body angles removed; the leading "
    "multiplier is classified as in Fig. 15.")
OUTPUTS = (("plot", "--plot", None),)
AMPLITUDE = "pf"


def add_arguments(p):
    """The options of ``judder floquet``."""
    p.add_argument("--freq", type=FREQ, required=True, metavar="HZ",
                   help="dither frequency, Hz")
    p.add_argument("--pf", type=PF, required=True, metavar="BAR",
                   help="dither amplitude p_f, bar (1 bar = 1e5 Pa)")
    p.add_argument("--plot", metavar="FILE.png",
                   help="the multipliers on the complex plane with the "
                        "unit circle, and near the leading one (Fig. 15)")
    min_growth_option(p, "; the verdict line says which the point is")
    method_option(p)
    model_options(p)
    driveline_option(p)
    waveform_option(p)
    force_option(p)


def run(args):
    """Floquet multipliers at one dither frequency and amplitude."""
    params, changes = parameters_of(args)
    check_floquet(params.replace(**changes), args.freq, args.method)
    make_parents(args.plot)
    point = floquet(args.freq, args.pf, params, changes,
                    method=args.method,
                    waveform=parse_waveform(args.dither_wave),
                    min_growth=args.min_growth, driveline=args.driveline)
    if args.plot:
        save_plot(args.plot, point.figure(
            title=f"Floquet multipliers (Fig. 15), "
                  f"{model_title(args, params)}"
                  + (" on its test bench" if point.driveline == "bench"
                     else "")))
    result = point.result
    lam = result.leading
    from ..bench import driveline_words
    words = mode_words(linearised_mode(point.params))
    text = (f"driveline: {driveline_words(point.params, point.driveline)}\n"
            + (words + "\n" if words else "")
            + f"f = {args.freq:g} Hz, p_f = {args.pf:g} bar: {result.kind}\n"
            f"leading multiplier {lam.real:.6f}{lam.imag:+.6f}i "
            f"(|lambda| = {result.leading_abs:.6f}), growth rate "
            f"{result.growth_rate:.4g} 1/s\nall multipliers (|lambda|): "
            + ", ".join(f"{abs(m):.6f}" for m in result.multipliers)
            + "\n" + point.verdict_words() + written(args.plot))
    emit(args, {**point.as_dict(), **output_files(plot=args.plot)}, text)


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
        The driveline linearised (:func:`judder.bench.driveline_view`);
        default the bench where the preset has one.

    Returns
    -------
    FloquetPoint
    """
    from infra.criteria import DEFAULT_MIN_GROWTH_PER_S
    min_growth = DEFAULT_MIN_GROWTH_PER_S if min_growth is None else min_growth
    values = checked_values(parameters, changes, freq_hz=freq_hz,
                            p_f_bar=p_f_bar, min_growth=min_growth)
    from ..bench import driveline_view
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
        """One of :data:`stability.decisions.relevance.VERDICTS`."""
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
        from ..bench import driveline_words
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
