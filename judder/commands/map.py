"""``judder map``: stability map over frequency x amplitude."""

import time

import numpy as np

from sources.dither_modes import linearised_mode, mode_words
from stability.kinds import KINDS
from studies.map import check_map_grid, stability_map

from ._arguments import (driveline_option, force_option, limit_option,
                         method_option, min_growth_option, model_options,
                         waveform_option)
from ._model import model_title, parameters_of
from ._output import Progress, emit, make_parents, write_outputs, written
from ._values import Grid, parse_waveform

#: The command's --help text.
DESCRIPTION = (
    "Leading Floquet multiplier on a grid of dither frequency (Hz) x "
    "amplitude (bar), classified single-period, double-period or "
    "combination (Fig. 14): unstable where |lambda| > 1; judder where it "
    "grows at --min-growth (1 1/s) or faster, the rest of the unstable "
    "region shaded grey; a line where the linear forced oscillation at "
    "the dither frequency reaches --limit (forced judder above it), and "
    "a count of the points where the forced slip swing leaves the "
    "friction curve's linear range. A preset's driveline is mapped on its "
    "test bench unless --driveline chain (the paper's Fig. 14). Ctrl-C "
    "stops it without writing a partial file.")


OUTPUTS = (("out", "--out", ("npz", "csv")), ("plot", "--plot", None))


AMPLITUDE = "pf"


DEFAULT_MAP_FREQ = "5:250:300"


DEFAULT_MAP_PF = "0:1.5:150"


def add_arguments(p):
    """The options of ``judder map``."""
    p.add_argument("--freq", type=Grid("--freq", "Hz"),
                   default=DEFAULT_MAP_FREQ, metavar="START:STOP:N",
                   help=f"dither frequencies, Hz (default {DEFAULT_MAP_FREQ})")
    p.add_argument("--pf", type=Grid("--pf", "bar"),
                   default=DEFAULT_MAP_PF, metavar="START:STOP:N",
                   help=f"dither amplitudes, bar (default {DEFAULT_MAP_PF})")
    p.add_argument("--out", metavar="FILE.npz|FILE.csv",
                   help="save the map: NPZ arrays with the exact boundaries "
                        "(see README), or CSV, one row per grid point with "
                        "the header on the first line, for a spreadsheet")
    p.add_argument("--plot", metavar="FILE.png",
                   help="save a plot of the map (PNG, SVG or PDF), with the "
                        "exact tongue boundaries and numbers")
    min_growth_option(p, "; the plot shades slower ones grey")
    limit_option(p)
    method_option(p)
    model_options(p)
    driveline_option(p)
    waveform_option(p)
    force_option(p)


def run(args):
    """Stability map over a frequency x amplitude grid."""
    started = time.perf_counter()
    freqs = args.freq
    amplitudes = args.pf
    params, changes = parameters_of(args)
    waveform = parse_waveform(args.dither_wave, args.decimal)
    # the exact boundaries are drawn on --plot and stored in --out (NPZ)
    exact = args.plot is not None or (
        args.out is not None and not str(args.out).lower().endswith(".csv"))
    check_map_grid(params.replace(**changes), freqs, amplitudes,
                    "--freq x --pf", args.method, exact)
    make_parents(args.out, args.plot)
    with Progress(len(freqs), "stability map") as progress:
        result = stability_map(
            freqs, amplitudes, params, changes, method=args.method,
            progress=progress,
            min_growth=args.min_growth,
            exact=exact, waveform=waveform, driveline=args.driveline,
            judder_limit_rpm=args.limit)
    bench = result.driveline == "bench"
    paper = None if bench else {"3dof": "Fig. 12",
                                "4dof": "Fig. 14"}.get(params.model)
    title = (f"stability map{f' ({paper})' if paper else ''}, "
             f"{model_title(args, params)}"
             + (" on its test bench" if bench else ""))
    files = write_outputs(args, result,
                           save={"meta": {"preset": args.preset,
                                          "set": args.set,
                                          "dither_wave": args.dither_wave}},
                           figure={"title": title})
    words = mode_words(linearised_mode(result.params),
                       float(np.max(amplitudes)))
    text = (f"driveline: {result.as_dict()['driveline_description']}\n"
            + (words + "\n" if words else "") + count_words(result) + "\n"
            + time_words(
        result, time.perf_counter() - started)
            + written(args.out, args.plot))
    emit(args, {**result.as_dict(), **files}, text)


def count_words(result):
    """The points of a map by what they are: stable, unstable
    (|lambda| > 1) by kind, and judder (growth >= min-growth) among
    them."""
    counts = result.map.counts()
    stable = counts.pop(KINDS[0], 0)
    unstable = sum(counts.values())
    rate = result.min_growth or 0.0
    return (f"{result.map.kind.size} points: {stable} stable, {unstable} "
            "unstable (|lambda| > 1: "
            + ", ".join(f"{k} {v}" for k, v in counts.items()) + ")"
            + (f", of which {result.judder_relevant_points()} judder "
               f"(growth >= {rate:g} 1/s)" if rate > 0 else "")
            + forced_words(result))


def forced_words(result):
    """The points whose linear forced oscillation exceeds the limit, and
    the judder points in all; '' where the map has no forced response."""
    counts = result.forced_counts()
    if not counts:
        return ""
    beyond = counts["beyond_linear_range_points"]
    return (f"; forced oscillation above {counts['judder_limit_rpm']:g} rpm "
            f"(linear harmonic response) at {counts['forced_judder_points']}"
            f"; judder in all (grows or forced): {counts['judder_points']}"
            + ("" if not beyond else
               f"\nbeyond the linear view at {beyond} points: the dither's "
               "forced slip swing exceeds the friction curve's linear "
               f"range (+-{counts['friction_linear_range_rad_s']:.2g} "
               "rad/s); there the motion need not follow the map (judder "
               "orbit and judder check give it)"))


def time_words(result, total=None):
    """What the time went on: the Floquet map, the exact boundaries, and
    the whole command (with the figure and the files)."""
    parts = [f"Floquet map {result.seconds:.2f} s"]
    if result.boundaries_seconds is not None:
        parts.append(f"exact boundaries {result.boundaries_seconds:.2f} s")
    return ("time: " + ", ".join(parts)
            + ("" if total is None else
               f"; {total:.2f} s in all after start-up (with the figure and "
               "the files)"))
