"""``judder tongues``: tongue boundaries, labels and tips."""

from dataclasses import dataclass
import math
import time

import numpy as np

from infra.files import keeps_foreign_files, write_text
from infra.units import PA_PER_BAR
from stability.maps import stability_map as map_kernel
from stability.monodromy import DEFAULT_METHOD

from ..bench import driveline_view
from ._arguments import (driveline_option, force_option, method_option,
                         min_growth_option, model_options, pf_max_option,
                         waveform_option)
from ._common import (BACKGROUND_AMPLITUDES, check_modes_up_to,
                      checked_values, dithered, linearised_mode,
                      mode_words)
from ._model import model_title, parameters_of
from ._output import Progress, emit, make_parents, write_outputs, written
from ._preflight import check_tongues
from ._values import MIN_GROWTH, Grid, parse_waveform

#: The command's --help text.
DESCRIPTION = (
    "Exact tongue boundaries by Hill's method (--solver hill: every "
    "kind, all frequencies at once; scan: combination by Brent's method "
    "on the monodromy); each point checked against the monodromy. "
    "Tongues numbered as in Fig. 14, with two tips each: where it "
    "becomes unstable (a Floquet multiplier outside the unit circle, "
    "|lambda| > 1) and where it becomes judder (growing at --min-growth, "
    "1 1/s by default, or faster). The boundaries drawn and written are "
    "the unstable ones (Fig. 14, 16).")
OUTPUTS = (("out", "--out", ("csv",)), ("plot", "--plot", None))
AMPLITUDE = "pf_max"


def add_arguments(p):
    """The options of ``judder tongues``."""
    p.add_argument("--freq", type=Grid("--freq", "Hz"),
                   default="10:220:500", metavar="START:STOP:N",
                   help="dither frequencies, Hz (default 10:220:500)")
    pf_max_option(p, "largest amplitude searched")
    min_growth_option(p, "; the 'judder from' tips are where the growth "
                         "reaches it, the 'unstable from' tips where "
                         "|lambda| = 1 (growth 0)")
    p.add_argument("--solver", default="hill", choices=("hill", "scan"),
                   help="boundary solver: hill (default, fast) or scan "
                        "(per frequency, Brent on the monodromy)")
    p.add_argument("--out", metavar="FILE.csv",
                   help="the unstable boundaries (|lambda| = 1) as CSV: "
                        "freq_hz, p_f_bar (lowest, empty if none), then "
                        "per kind, bar")
    p.add_argument("--plot", metavar="FILE.png",
                   help="boundaries drawn over the map (Fig. 16)")
    method_option(p)
    model_options(p)
    driveline_option(p)
    waveform_option(p)
    force_option(p)


def run(args):
    """Tongue boundaries, labels and tips."""
    freqs = args.freq
    params, changes = parameters_of(args)
    waveform = parse_waveform(args.dither_wave)
    check_tongues(params.replace(**changes), freqs,
                  background=args.plot is not None)
    make_parents(args.out, args.plot)
    with Progress(len(freqs), "tongue boundaries") as progress:
        result = tongues(freqs, args.pf_max, params, changes,
                         method=args.method, waveform=waveform,
                         background=args.plot is not None,
                         progress=progress,
                         judder_growth=args.min_growth,
                         solver=args.solver, driveline=args.driveline)
    data = {**result.as_dict(), **write_outputs(args, result, figure={
        "title": f"tongue boundaries over the map, "
                 f"{model_title(args, params)}"
                 + (" on its test bench" if result.driveline == "bench"
                    else "")})}
    rows = tip_table(data)
    words = mode_words(linearised_mode(result.params), args.pf_max)
    if words:
        rows.insert(0, words)
    rows.insert(0, f"driveline: {data['driveline_description']}")
    if result.driveline == "bench":
        rows.append("the resonances f1, f2 are the undamped natural "
                    "frequencies of the chain; on the bench, whose speed "
                    "control damps body 1, the damped modes are " + ", ".join(
                        f"{f:.3f} Hz" for f in data["damped_frequencies_hz"])
                    + " (judder eig --driveline bench)")
    missing = _missing_tongues(result, freqs, args.pf_max)
    if missing:
        rows.append(missing)
    rows.append(f"{len(freqs)} frequencies in {result.seconds:.2f} s; "
                "boundary points within "
                f"{result.boundaries.max_multiplier_error:.1e} of the unit "
                "circle")
    emit(args, data, "\n".join(rows) + written(args.out, args.plot))


def tip_table(data):
    """The tips of a :meth:`TonguesResult.as_dict` as text lines: number,
    kind, resonance, where each tongue becomes unstable and where it
    becomes judder, how far its tip lies from its resonance, and a line
    saying what those words mean."""
    rate = data["judder_min_growth_per_s"]
    judder = f"judder (>= {rate:g} 1/s) from"
    rows = [f"{'#':>3} {'kind':14s} {'resonance':>9s} "
            f" {'unstable from':>25s}  {judder:>26s}  {'tip off res.':>12s}"]
    for r in data["tongues"]:
        offset = ("" if r["tip_offset_percent"] is None
                  else f"{r['tip_offset_percent']:+.2f} %")
        unstable = f"{r['tip_p_f_bar']:.4f} bar at {r['tip_freq_hz']:.3f} Hz"
        late = ("above the searched range" if r["judder_tip_p_f_bar"] is None
                else f"{r['judder_tip_p_f_bar']:.4f} bar at "
                     f"{r['judder_tip_freq_hz']:.3f} Hz")
        rows.append(f"{r['number'] or '-':>3} {r['kind']:14s} "
                    f"{(r['resonance'] or '-'):>9s} {unstable:>25s}  "
                    f"{late:>26s}  {offset:>12s}"
                    + ("  (tip at grid edge)" if r["tip_at_edge"] else ""))
    rows.append(f"unstable: a Floquet multiplier outside the unit circle "
                f"(|lambda| > 1), growth > 0; judder: growth >= {rate:g} "
                "1/s (--min-growth), at least one e-fold per "
                f"{1 / rate:.3g} s" if rate > 0 else
                "unstable: a Floquet multiplier outside the unit circle "
                "(|lambda| > 1); judder: the same (--min-growth 0)")
    rows.append("tip off res.: tip frequency of the unstable tongue "
                "relative to the resonance it grows from (f_tip / f_res - 1)")
    return rows


def _missing_tongues(result, freqs, p_max_bar):
    """A line naming the numbers no tongue got (numbers follow the
    resonances, Fig. 14's scheme for every mode), or ''."""
    from stability.tongues import resonances
    found = {t.number for t in result.tongues}
    gone = [f"{number} ({label}, {hz:.3g} Hz)" for number, label, hz, _
            in resonances(result.boundaries.natural_frequencies_hz)
            if number not in found]
    return ("" if not gone else
            "numbered by resonance; no tongue in "
            f"{freqs[0]:g}-{freqs[-1]:g} Hz up to {p_max_bar:g} bar for "
            + ", ".join(gone))


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
        (:func:`judder.bench.driveline_view`); default the bench where the
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
                     else float(MIN_GROWTH.check(judder_growth,
                                                 "judder_growth")))
    driveline = dithered(values, waveform)
    p_max = p_max_bar * PA_PER_BAR
    started = time.perf_counter()
    boundaries = tongue_boundaries(driveline, freq_hz, p_max, method,
                                   callback=progress, min_growth=min_growth,
                                   solver=solver)
    found = find_tongues(driveline, boundaries)
    if judder_growth == boundaries.min_growth:
        judder = found
    else:
        judder = find_tongues(driveline, tongue_boundaries(
            driveline, freq_hz, p_max, method, min_growth=judder_growth,
            solver=solver, check=False))
    seconds = time.perf_counter() - started
    under = (map_kernel(driveline, freq_hz,
                        np.linspace(0, p_max, BACKGROUND_AMPLITUDES),
                        method=method) if background else None)
    return TonguesResult(params=values, boundaries=boundaries,
                         tongues=found, seconds=seconds, background=under,
                         judder_tongues=judder, judder_growth=judder_growth,
                         driveline=view)


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

    def as_dict(self):
        b = self.boundaries
        mode = linearised_mode(self.params)
        from ..bench import driveline_words
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
                        or DEFAULT_MIN_GROWTH_PER_S))
