"""``judder check``: is a dither setting safe, and by how much."""

import math

from infra.errors import JudderError
from infra.units import PA_PER_BAR
from studies._preflight import check_settings_time, check_work
from studies.check import DEFAULT_CHECK_PARAMETERS, check
from studies.rules import FREQ_RANGE_HZ, check_amplitudes, refuse_decimal

from ._arguments import (decimal_option, driveline_option, force_option,
                         limit_option, min_growth_option, model_options)
from ._model import model_title, parameters_of
from ._output import Progress, emit, make_parents, write_outputs, written
from ._values import PF_MAX, NameList, Settings

#: The command's --help text.
DESCRIPTION = (
    "Verdict of each dither setting, of a preset's driveline on its test "
    "bench unless --driveline chain (judder if its settled oscillation "
    "exceeds --limit, from the bench's periodic orbit or the chain's "
    "linear forced response, or if it grows faster than --min-growth; "
    "with the mechanism), its growth rate and e-folding time against the "
    "engagement, the highest safe amplitude at its frequency (the lower of "
    "the parametric boundary and the amplitude whose settled forced "
    "oscillation reaches --limit, and which it is), the safe band of "
    "frequencies around it at its amplitude (from where to where neither "
    "parametric judder nor a forced oscillation over --limit occurs, and "
    "what ends each side), the margin to the "
    "nearest judder-relevant tongue "
    "boundary in bar (at the same frequency) and in Hz (at the same "
    "amplitude), exact from the boundary curves, which tongue that is, "
    "and how much each parameter moves those margins. Settings: --freq "
    "x --pf (every pair), or --table.")


OUTPUTS = (("out", "--out", ("csv",)), ("plot", "--plot", None))
#: This command's options for the study's arguments
#: (:func:`judder.commands._flags.in_flags`).
FLAGS = {"sensitivity": "--params"}


def add_arguments(p):
    """The options of ``judder check``."""
    p.add_argument("--freq", type=Settings("--freq", "Hz"),
                   metavar="HZ[,HZ...]",
                   help="dither frequencies, Hz: a list or START:STOP:N")
    p.add_argument("--pf", type=Settings("--pf", "bar"),
                   metavar="BAR[,BAR...]",
                   help="dither amplitudes, bar: a list or START:STOP:N")
    p.add_argument("--table", metavar="FILE.csv",
                   help="a dither table instead: columns freq_hz,p_f_bar, "
                        "one setting a row (e.g. a controller's table)")
    decimal_option(p, "the --table file")
    min_growth_option(p)
    limit_option(p)
    driveline_option(p)
    p.add_argument("--pf-max", type=PF_MAX, default=None, metavar="BAR",
                   help="largest boundary amplitude searched, bar (default "
                        "the larger of 1.5 and twice the largest setting)")
    p.add_argument("--params", type=NameList("--params"), default=None,
                   metavar="NAMES",
                   help="parameters whose effect on the margins is reported "
                        "(d margin / d ln value; default J2,J4,k12,k24,c12,"
                        "mu_g, for the 3-DOF model its inertias, stiffnesses, "
                        "dampings and mu_g; for --modelica/--fmu those of "
                        "J2,J4,k12,k24,c12,mu_g it has, and NAMES is "
                        "required if it has none; 'none' for none)")
    p.add_argument("--out", metavar="FILE.csv",
                   help="one row per setting (the scalar JSON fields)")
    p.add_argument("--plot", metavar="FILE.png",
                   help="the settings marked on the map")
    model_options(p)
    force_option(p)


def run(args):
    """Verdict, growth and margins of dither settings."""
    names = args.params
    params, changes = parameters_of(args)
    from stability.bench import default_driveline
    bench = (args.driveline or default_driveline(params)) == "bench"
    freqs, amplitudes = _settings(args, len(
        DEFAULT_CHECK_PARAMETERS if names is None else names), bench)
    make_parents(args.out, args.plot)
    with Progress(len(freqs), "check") as progress:
        result = check(freqs, amplitudes, params, changes,
                       min_growth=args.min_growth, p_max_bar=args.pf_max,
                       sensitivity=names, background=bool(args.plot),
                       progress=progress, driveline=args.driveline,
                       judder_limit_rpm=args.limit)
    data = {**result.as_dict(), **write_outputs(
        args, result, figure={"title": model_title(args, params)})}
    emit(args, data, result.summary() + written(args.out, args.plot))


def _settings(args, parameters, bench=False):
    """Frequencies (Hz) and amplitudes (bar) of ``judder check``; the
    time of ``parameters`` sensitivity parameters per setting (on a test
    bench with ``bench``) is estimated before the settings are made (a
    grid x grid of 1e10 would fill the memory first)."""
    from studies.inputs import empty_cell, read_boundary_table, read_input
    if args.table:
        if args.freq or args.pf:
            raise JudderError("--table and --freq/--pf: allowed: one of them")
        # every message of the table names it as the option gave it
        source = f"--table {args.table}"
        table = read_boundary_table(read_input(args.table, "--table"),
                                    source, args.decimal)
        freqs, p_f, lines = table["freq_hz"], table["p_f"], table["lines"]
        empty = [line for line, p in zip(lines, p_f) if not math.isfinite(p)]
        if empty:
            raise empty_cell(source, empty[0], "p_f_bar", "a dither "
                             "amplitude >= 0 bar (every row is a setting "
                             "to check)")
        amplitudes = [p / PA_PER_BAR for p in p_f]
        check_amplitudes(amplitudes, f"{source}: p_f_bar")
        check_settings_time(len(freqs), parameters, source, bench)
        check_work(source, len(freqs), "settings")
        low, high = FREQ_RANGE_HZ
        for line, f in zip(lines, freqs):
            if not low <= f <= high:
                raise JudderError(
                    f"{source}, line {line}: column 'freq_hz' = {f:g} Hz is "
                    f"not allowed; allowed: {low:g} to {high:g} Hz")
        return list(freqs), amplitudes
    refuse_decimal(args.decimal, "a --table file", "with --freq and --pf")
    if not (args.freq and args.pf):
        raise JudderError("--freq and --pf are required (or --table)")
    freqs, amplitudes = args.freq, args.pf
    # the time first (it says what to change); then, with the time limit
    # raised, the count (the pairs of 1e10 settings would not fit)
    check_settings_time(len(freqs) * len(amplitudes), parameters,
                        bench=bench)
    check_work("--freq x --pf", len(freqs) * len(amplitudes), "settings")
    pairs = [(f, p) for f in freqs for p in amplitudes]
    return [f for f, _ in pairs], [p for _, p in pairs]
