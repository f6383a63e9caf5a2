"""``judder tongues``: tongue boundaries, labels and tips."""

from sources.dither_modes import linearised_mode, mode_words
from studies._preflight import check_tongues
from studies.tongues import tongues

from ._arguments import (driveline_option, force_option, method_option,
                         min_growth_option, model_options, pf_max_option,
                         waveform_option)
from ._model import model_title, parameters_of
from ._output import Progress, emit, make_parents, write_outputs, written
from ._values import Grid, parse_waveform

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
    waveform = parse_waveform(args.dither_wave, args.decimal)
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
