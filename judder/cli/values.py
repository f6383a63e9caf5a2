"""Values of the command-line options: numbers with or without a unit,
checked against what is allowed and plausible before any work.

A plain number is in the option's unit (frequencies Hz, amplitudes bar,
times s, speeds rpm, parameters SI); a number may carry a unit instead
(``--freq 1.2kHz``, ``--pf 300mbar``, ``--duration 50ms``), read by
:func:`infra.quantities.parse_quantity`. A plain number far outside what
its unit makes plausible is refused with the likely slip
(``--pf 30000``: Pa given for bar; ``--set p_m=10``: bar given for Pa).
"""

import math
import os
import sys

import numpy as np

from infra.errors import JudderError
from infra.quantities import has_unit, parse_quantity
from infra.units import PA_PER_BAR

__all__ = ["normalise_options", "option_value", "check_pressures",
           "check_amplitudes", "check_plain_pressure", "check_file_pressure",
           "check_plausible", "check_advise_grid",
           "FREQ_RANGE_HZ", "MAX_PLAIN_PF_BAR", "MIN_PLAIN_P_M_PA",
           "MAX_WORKERS", "warn"]

#: Dither frequencies allowed, Hz: below, the period needs more
#: sub-intervals than any engine takes; above, no hydraulic valve
#: dithers and the multipliers round to 1.
FREQ_RANGE_HZ = (1e-3, 1e5)
#: A plain --pf above this (bar) is taken for a slip of unit (Pa for bar).
MAX_PLAIN_PF_BAR = 100.0
#: A plain p_m below this (Pa, i.e. 1 bar) is taken for bar given as Pa.
MIN_PLAIN_P_M_PA = 1e5
#: Most worker processes (a request for more is a typo).
MAX_WORKERS = 256
#: Longest simulated time of one run, s.
MAX_DURATION_S = 3600.0

#: Options holding one number: attribute -> (option, unit, low, high,
#: low_open). ``freq`` and ``pf`` are single values only in these
#: commands (elsewhere they are grids).
_SINGLE = {"freq": ("--freq", "Hz", *FREQ_RANGE_HZ, False),
           "pf": ("--pf", "bar", 0.0, math.inf, False),
           "pf_max": ("--pf-max", "bar", 0.0, math.inf, True),
           "duration": ("--duration", "s", 0.0, MAX_DURATION_S, True),
           "min_growth": ("--min-growth", "1/s", 0.0, math.inf, False),
           "noise_rpm": ("--noise-rpm", "rpm", 0.0, math.inf, False),
           "min_amplitude": ("--min-amplitude", "rpm", 0.0, math.inf,
                             False)}
_SINGLE_FREQ_COMMANDS = ("floquet", "simulate", "report")


def warn(text):
    """A warning line on stderr (the command goes on)."""
    print(f"judder: warning: {text}", file=sys.stderr)


def option_value(text, option, unit, low=-math.inf, high=math.inf,
                 low_open=False):
    """A number of an option, in ``unit`` (plain, or with a unit).

    Raises
    ------
    JudderError
        Naming the option, the value and the allowed range.
    """
    value = parse_quantity(text, unit, option)
    allowed = _allowed(unit, low, high, low_open)
    if not math.isfinite(value) or value > high or (
            value <= low if low_open else value < low):
        raise JudderError(f"{option} {text} is not allowed; allowed: "
                          f"{allowed}")
    if unit == "bar" and not has_unit(text):
        check_amplitudes([value], option, f": write {text}Pa, or give the "
                                          "unit")
    return value


def check_amplitudes(values_bar, option, fix=""):
    """Refuse a dither amplitude above :data:`MAX_PLAIN_PF_BAR`: Pa given
    where bar is meant (an option, a list, a grid or a table column);
    ``fix`` says how to write it."""
    for value in values_bar:
        if value is not None and value > MAX_PLAIN_PF_BAR:
            raise JudderError(
                f"{option} {value:g} bar is not plausible for a dither "
                f"amplitude (a plain number is in bar); did you give Pa? "
                f"{value:g} Pa = {value / PA_PER_BAR:g} bar{fix} (allowed: "
                f"at most {MAX_PLAIN_PF_BAR:g} bar)")


def _allowed(unit, low, high, low_open):
    parts = []
    if low > -math.inf:
        parts.append(f"{'>' if low_open else '>='} {low:g}")
    if high < math.inf:
        parts.append(f"<= {high:g}")
    return (" and ".join(parts) or "a finite number") + f" {unit}" + (
        " (a plain number; or with a unit, e.g. 1.2kHz)" if unit == "Hz"
        else "")


def normalise_options(args):
    """Turn the number options of ``args`` into floats (in their units)
    and check the whole numbers (--workers, --seed, --starts), before
    any work."""
    for attribute, (option, unit, low, high, low_open) in _SINGLE.items():
        if attribute in ("freq", "pf") and \
                args.command not in _SINGLE_FREQ_COMMANDS:
            continue
        value = getattr(args, attribute, None)
        if attribute == "freq" and args.command == "simulate":
            # one engagement per frequency (Fig. 1, 8): a list
            setattr(args, attribute, [
                option_value(text.strip(), option, unit, low, high, low_open)
                for text in value.split(",")])
        elif isinstance(value, str):
            setattr(args, attribute, option_value(value, option, unit, low,
                                                  high, low_open))
    workers = getattr(args, "workers", None)
    if workers is not None and not 1 <= workers <= MAX_WORKERS:
        raise JudderError(f"--workers {workers} is not allowed; allowed: a "
                          f"whole number from 1 to {MAX_WORKERS}")
    seed = getattr(args, "seed", None)
    if seed is not None and not 0 <= seed < 2 ** 63:
        raise JudderError(f"--seed {seed} is not allowed; allowed: a whole "
                          "number >= 0")
    starts = getattr(args, "starts", None)
    if starts is not None and not 1 <= starts <= 1000:
        raise JudderError(f"--starts {starts} is not allowed; allowed: a "
                          "whole number from 1 to 1000")


def check_pressures(p_f_max_pa, params, option="--pf"):
    """Warn when the dither amplitude reaches the mean pressure: the
    clutch pressure ``p_m + p_f cos`` would go below zero, which a clutch
    cannot do and the linear model does not know."""
    p_m = params["p_m"] if "p_m" in params.specs else None
    if p_m is not None and np.isfinite(p_f_max_pa) and p_f_max_pa >= p_m:
        warn(f"{option}: p_f = {p_f_max_pa / PA_PER_BAR:g} bar reaches the "
             f"mean pressure p_m = {p_m / PA_PER_BAR:g} bar; the clutch "
             "pressure p_m + p_f cos(2 pi f t) would go below zero, which "
             "the linear model does not represent (check the units: --pf "
             "is in bar, p_m in Pa unless a unit is given)")


def check_plain_pressure(assignment):
    """Refuse ``--set p_m=10``: a plain number is in Pa, and a mean clutch
    pressure below 1 bar is bar given as Pa; with a unit it is taken as
    it is (``p_m=10bar``, ``p_m=50000Pa``)."""
    name, _, value = assignment.partition("=")
    if name.strip() != "p_m" or has_unit(value.strip()):
        return
    number = float(value)
    if 0 <= number < MIN_PLAIN_P_M_PA:
        raise JudderError(
            f"--set {assignment.strip()}: p_m = {number:g} Pa (a plain "
            f"number is in Pa, SI) is not plausible for a clutch pressure "
            f"(below 1 bar); did you mean {value.strip()}bar = "
            f"{number * PA_PER_BAR:g} Pa? Give the unit (p_m={value.strip()}"
            f"bar, or p_m={value.strip()}Pa to keep it)")


def check_file_pressure(params, path):
    """Refuse ``p_m = 10`` in a parameter file: the file is in SI (Pa),
    and a mean clutch pressure below 1 bar is bar written as Pa."""
    if "p_m" not in params.specs:
        return
    p_m = params["p_m"]
    if 0 <= p_m < MIN_PLAIN_P_M_PA:
        raise JudderError(
            f"--param-file {path}: p_m = {p_m:g} Pa (the file is in SI) is "
            "not plausible for a clutch pressure (below 1 bar); did you mean "
            f"{p_m:g} bar = {p_m * PA_PER_BAR:g} Pa? Write p_m = "
            f"{p_m * PA_PER_BAR:g}")


#: Where each command keeps its largest dither amplitude: (attribute,
#: grid or single value).
_AMPLITUDE = {"floquet": ("pf", False), "simulate": ("pf", False),
              "map": ("pf", True), "crosscheck": ("pf", True),
              "campaign": ("pf", True), "tongues": ("pf_max", False),
              "sensitivity": ("pf_max", False), "fit": ("pf_max", False)}


def check_plausible(args):
    """Warn when the command's largest dither amplitude reaches the mean
    pressure of its parameter set (see :func:`check_pressures`)."""
    from .options import parameters_of, parse_grid
    if args.command not in _AMPLITUDE:
        return
    attribute, grid = _AMPLITUDE[args.command]
    value = getattr(args, attribute, None)
    if value is None:
        return
    p_max_bar = parse_grid(value, "--pf", "bar").max() if grid else value
    params, _ = parameters_of(args)
    check_pressures(p_max_bar * PA_PER_BAR, params,
                    "--pf" if attribute == "pf" else "--pf-max")


def available_memory():
    """Bytes of memory this process may still use: the least of the
    memory available now (``MemAvailable`` of /proc/meminfo, else the
    physical memory), what is left of its cgroup's limit (a batch job's
    or a container's, v2 or v1) and what is left of its address-space
    limit (``ulimit -v``)."""
    import resource
    try:
        with open("/proc/meminfo") as stream:
            free = next(int(line.split()[1]) * 1024 for line in stream
                        if line.startswith("MemAvailable:"))
    except (OSError, StopIteration, ValueError):
        free = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
    limits = [free, _cgroup_left()]
    soft, _ = resource.getrlimit(resource.RLIMIT_AS)
    if soft != resource.RLIM_INFINITY:
        limits.append(soft - _status_bytes("VmSize:"))
    return max(0, min(v for v in limits if v is not None))


def _status_bytes(key):
    try:
        with open("/proc/self/status") as stream:
            return next(int(line.split()[1]) * 1024 for line in stream
                        if line.startswith(key))
    except (OSError, StopIteration, ValueError):
        return 0


def _cgroup_left():
    """Limit minus usage of this process's memory cgroup, or None."""
    try:
        with open("/proc/self/cgroup") as stream:
            lines = [line.strip().split(":", 2) for line in stream]
    except OSError:
        return None
    places = []
    for _, controllers, path in lines:
        if controllers == "":                      # v2
            places.append((f"/sys/fs/cgroup{path}", "memory.max",
                           "memory.current"))
        elif "memory" in controllers.split(","):   # v1
            places.append((f"/sys/fs/cgroup/memory{path}",
                           "memory.limit_in_bytes", "memory.usage_in_bytes"))
    for folder, limit, usage in places:
        try:
            with open(os.path.join(folder, limit)) as a, \
                    open(os.path.join(folder, usage)) as b:
                text, used = a.read().strip(), int(b.read())
        except (OSError, ValueError):
            continue
        if text != "max" and int(text) < 2 ** 60:
            return int(text) - used
    return None


def check_map_memory(params, freq_hz, p_f_bar):
    """Refuse a map whose Dyson series would not fit in memory.

    At each frequency the engine holds, for every amplitude, one matrix
    per sub-interval of the period (:class:`stability.monodromy.
    DysonPropagator`); the sub-intervals at the lowest frequency follow
    from the spectral radius of ``A0`` (the modulation only adds more).
    """
    from .estimates import subintervals
    f = float(np.min(freq_hz))
    steps, size = subintervals(params, [f])
    steps = int(steps[0])
    needed = 3 * len(p_f_bar) * steps * size * size * 8 \
        + 64 * len(freq_hz) * len(p_f_bar)
    free = available_memory()
    if needed > 0.8 * free:
        raise JudderError(
            f"--freq x --pf needs at least {needed / 2**30:.3g} GiB "
            f"({len(p_f_bar)} amplitudes x {steps} sub-intervals at "
            f"{f:g} Hz), and {free / 2**30:.3g} GiB are available; "
            "allowed: fewer amplitudes per frequency, or higher "
            "frequencies")
    return needed


#: Bytes ``advise`` holds per frequency of its 0.5 Hz grid (peak resident
#: memory of ``judder advise --no-design --freq-range=60:LOW`` grows by
#: 12.2 kB per frequency from 60:200 to 60:20000, 117 to 599 MB).
ADVISE_BYTES_PER_FREQUENCY = 12_500


def check_advise_grid(text, low, high, margin_hz):
    """Refuse an ``advise`` frequency range whose 0.5 Hz grid has more
    than :data:`judder.cli.options.MAX_GRID_VALUES` frequencies or would
    not fit in memory, naming ``--freq-range``; returns the number of
    frequencies."""
    from .options import MAX_GRID_VALUES
    points = int(round(2 * (high - low + 2 * margin_hz))) + 1
    widest = (MAX_GRID_VALUES - 1) / 2 - 2 * margin_hz
    if points > MAX_GRID_VALUES:
        raise JudderError(
            f"--freq-range {text} makes {points} frequencies (0.5 Hz "
            f"apart); allowed: at most {MAX_GRID_VALUES}, i.e. a range of "
            f"at most {widest:g} Hz (--margin-hz {margin_hz:g})")
    needed = points * ADVISE_BYTES_PER_FREQUENCY
    free = available_memory()
    if needed > 0.8 * free:
        raise JudderError(
            f"--freq-range {text} needs about {needed / 2**30:.3g} GiB "
            f"({points} frequencies 0.5 Hz apart), and "
            f"{free / 2**30:.3g} GiB are available; allowed: a narrower "
            "range")
    return points


#: Most runs of one campaign, FMU runs of one crosscheck, cases of one
#: sensitivity study: beyond, a request is a typo or a week of work.
MAX_RUNS = 100_000
#: Bytes one campaign run writes per format, second of engagement and
#: 1000 rpm (41 teeth; measured 29.6 kB CSV and 31.3 kB MF4 for 1 s).
BYTES_PER_RUN_SECOND = 32_000


def check_work(option, count, what):
    """Refuse more than :data:`MAX_RUNS` pieces of work."""
    if count > MAX_RUNS:
        raise JudderError(f"{option} asks for {count:.4g} {what}; allowed: "
                          f"at most {MAX_RUNS} (split the study)")


def check_campaign_disk(folder, runs, duration, rpm_max, formats):
    """Refuse a campaign whose files would not fit on the disk."""
    import shutil
    from pathlib import Path
    needed = (runs * duration * max(rpm_max, 1.0) / 1000.0
              * BYTES_PER_RUN_SECOND * len(formats))
    place = Path(folder)
    while not place.exists():
        place = place.parent
    free = shutil.disk_usage(place).free
    if needed > free:
        raise JudderError(f"the campaign would write about "
                          f"{needed / 2**30:.3g} GiB ({runs} runs) and "
                          f"{free / 2**30:.3g} GiB are free on {place}; "
                          "allowed: fewer runs, or another folder")
