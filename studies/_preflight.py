"""Time of a command's work, estimated before it starts (issue 9).

The estimate adds up per-unit costs measured once on the development
machine with ``benchmarks/time_calibration.py`` (CPU seconds of one
thread, paper's 4-DOF set, 6 states; the script prints the constants
below). A request estimated above :data:`ANNOUNCE_S` says so on stderr
(on a terminal, like the progress bars);
one above the time limit is refused before any work, naming the estimate,
what drives it and what to change. The limit is :data:`MAX_HOURS` hours,
or the hours in the environment variable ``JUDDER_MAX_HOURS`` (to allow a
longer study on purpose: ``JUDDER_MAX_HOURS=100 judder map ...``).

The estimate is a lower bound of the wall time: it counts the
sub-intervals the fastest eigenvalue asks for (a strong modulation may
add more), one thread at full speed (a loaded machine, or several BLAS
threads fighting for the cores, is slower) and sizes other than 6 states
by ``(m / 6)^2``.

The memory and disk a request would take are checked here too
(:func:`infra.memory.available_memory` follows ``ulimit -v`` and the
cgroup).
"""

import sys

import numpy as np

from infra.environment import positive_setting
from infra.errors import JudderError
from infra.memory import available_memory

from ._common import BACKGROUND_AMPLITUDES
from .rules import MAX_GRID_VALUES

#: Longest work allowed without ``JUDDER_MAX_HOURS``, hours.
MAX_HOURS = 24.0


#: Estimates above this (s) are printed on stderr before the work.
ANNOUNCE_S = 10.0


#: Environment variable raising (or lowering) the time limit, hours.
LIMIT_VARIABLE = "JUDDER_MAX_HOURS"


# Per-unit costs, CPU seconds of one thread on the development machine
# (2 shared cores), measured by benchmarks/time_calibration.py:
# {"frequency_s": 0.00110, "subinterval_s": 0.000224,
#  "product_s": 1.78e-06}, and in a second run (the test suite running
# beside it) {"frequency_s": 0.00133, "subinterval_s": 0.000225,
#  "product_s": 1.26e-06, "tongue_frequency_s": 0.000498,
#  "tongue_fixed_s": 0.0815}; the tongues once more by hand, 0.00071 and
# 0.13 (0.17 s for 50 frequencies, 0.49 s for 500).
#: Fixed cost of one frequency of a Dyson map.
FREQUENCY_S = 1.1e-3


#: Building the Dyson series on one sub-interval.
SUBINTERVAL_S = 2.24e-4


#: One amplitude on one sub-interval (Horner evaluation, matrix product).
PRODUCT_S = 1.78e-6


#: One frequency of ``tongues`` (default solver), and its fixed cost.
TONGUE_FREQUENCY_S = 6.0e-4


TONGUE_FIXED_S = 0.1


#: One simulated second of one FMU run of ``crosscheck`` (4-DOF), and of
#: one ``campaign`` run at 1000 rpm (its tooth signals), CPU seconds:
#: from ``judder crosscheck --freq 40:60:3 --pf 0.5 --duration 3`` (6
#: runs of 3 s, 5.8 s user time with the start-up) and ``judder campaign
#: --freq 40:60:3 --pf 0.5 --duration 2`` (3 runs of 2 s, 5.6 s).
FMU_SECOND_S = 0.25


CAMPAIGN_SECOND_S = 0.5


#: One setting of ``check`` (Floquet point and margins), and one
#: parameter of its margin sensitivity per setting, CPU seconds: from
#: ``judder check --freq 60:200:10 --pf 0:0.7:10`` with ``--params none``
#: (6.1 s for 100 settings with the 1.5 s start-up) and with the 6
#: default parameters (14.4 s).
CHECK_SETTING_S = 0.045

#: One setting of ``check`` on a preset's test bench (its periodic orbit,
#: the forced limit in amplitude and the safe band's walk in frequency
#: added), CPU seconds: ``judder check --freq 60:200:10 --pf 0:0.7:10
#: --params none`` on the paper preset, 22.4 s user for 100 settings with
#: the 1.5 s start-up (5.4 s with ``--driveline chain``), 2026-12-08.
CHECK_BENCH_SETTING_S = 0.21


CHECK_PARAMETER_S = 0.014


#: One point of ``threshold``'s Fig. 19a (the eigenvalues at one mu_g)
#: and one of its Fig. 19b (a root of the largest real part in mu_g),
#: CPU seconds: from ``judder threshold`` with 2002 mu_g (0.52 s more
#: than with 2) and with 402 c_i (1.76 s more).
THRESHOLD_MU_S = 2.6e-4


THRESHOLD_DAMPING_S = 4.4e-3


#: One measured point of ``fit`` per local fit (start), and the fixed
#: cost, CPU seconds: ``judder fit --boundary`` with the example's 26
#: points and the same repeated 4 times (104 points, 3 starts): 0.29 s per
#: point fitting mu_g,k24 and 0.23 s fitting mu_g (8.1 and 30.9 s).
FIT_POINT_START_S = 0.1


FIT_FIXED_S = 0.5


#: One periodic orbit of ``orbit`` (harmonic balance and its multipliers),
#: CPU seconds: ``judder orbit`` over 60-200 Hz x 14 amplitudes took 2.35
#: s more with 282 frequencies than with 141 (1974 orbits more).
ORBIT_S = 1.2e-3


#: States of the calibration set (paper's 4-DOF).
REFERENCE_SIZE = 6




def subintervals(params, freq_hz):
    """Sub-intervals per period the Dyson engine needs at least, per
    frequency (:func:`stability.monodromy.least_subintervals`), and the
    number of states."""
    from stability import build_driveline
    from stability.monodromy import least_subintervals
    system = build_driveline(params).periodic_system()
    return least_subintervals(system.A0, freq_hz), len(system.A0)


def _scale(size):
    return (size / REFERENCE_SIZE) ** 2


def map_seconds(params, freq_hz, amplitudes, tongues=False):
    """Estimated seconds of ``map``: per frequency, a fixed cost, the
    series on each sub-interval and each amplitude on each sub-interval
    (plus the exact boundaries when ``tongues``)."""
    steps, size = subintervals(params, freq_hz)
    seconds = (len(steps) * FREQUENCY_S + _scale(size) * float(
        np.sum(steps * (SUBINTERVAL_S + len(amplitudes) * PRODUCT_S))))
    return seconds + (tongues_seconds(params, freq_hz) if tongues else 0.0)


def tongues_seconds(params, freq_hz):
    """Estimated seconds of ``tongues`` over these frequencies."""
    _, size = subintervals(params, freq_hz[:1])
    return ((TONGUE_FIXED_S + len(freq_hz) * TONGUE_FREQUENCY_S)
            * _scale(size))


def time_limit():
    """The time limit, s (``JUDDER_MAX_HOURS`` or :data:`MAX_HOURS`)."""
    return positive_setting(LIMIT_VARIABLE, MAX_HOURS, "a number of hours") \
        * 3600.0


def _duration(seconds):
    if seconds < 120:
        return f"{seconds:.3g} s"
    if seconds < 7200:
        return f"{seconds / 60:.3g} min"
    return f"{seconds / 3600:.3g} h"


def check_time(seconds, drivers, change, workers=1):
    """Refuse work estimated above the time limit; announce work above
    :data:`ANNOUNCE_S` on stderr when it is a terminal.

    Parameters
    ----------
    seconds : float
        Estimated CPU seconds of the whole work.
    drivers : str
        What the estimate is made of (``'2000 frequencies x 11200
        sub-intervals'``).
    change : str
        What to change to make it shorter.
    workers : int
        Processes sharing the work (the estimate is divided by them).

    Returns
    -------
    float
        The estimated wall seconds.
    """
    wall = seconds / max(1, workers or 1)
    limit = time_limit()
    if wall > limit:
        raise JudderError(
            f"the work is estimated at {_duration(wall)} ({drivers}), "
            f"above the limit of {_duration(limit)}; allowed: {change}, or "
            f"raise the limit with {LIMIT_VARIABLE}=HOURS")
    if wall > ANNOUNCE_S and _terminal():
        print(f"judder: estimated time {_duration(wall)} ({drivers})",
              file=sys.stderr)
    return wall


def _dyson(method):
    return method == "dyson"


def check_map(params, freq_hz, amplitudes, method, tongues=False):
    """``map``: frequencies x sub-intervals (x amplitudes)."""
    if not _dyson(method):
        return None
    steps, _ = subintervals(params, freq_hz)
    return check_time(
        map_seconds(params, freq_hz, amplitudes, tongues),
        f"{len(freq_hz)} frequencies x {steps.mean():.4g} sub-intervals per "
        f"period on average (from {steps.max():.4g} at {np.min(freq_hz):g} "
        f"Hz) x {len(amplitudes)} amplitudes",
        "fewer or higher frequencies (`freq_hz`), or fewer amplitudes (`p_f_bar`)")


def check_floquet(params, freq_hz, method):
    """``floquet``: the sub-intervals of one period."""
    if not _dyson(method):
        return None
    steps, _ = subintervals(params, [freq_hz])
    return check_time(map_seconds(params, [freq_hz], [0.0]),
                      f"{steps[0]:.4g} sub-intervals per period at "
                      f"{freq_hz:g} Hz", "higher `freq_hz`")


def check_tongues(params, freq_hz, background=False):
    """``tongues``: frequencies (and the background map of --plot)."""
    seconds = tongues_seconds(params, freq_hz) + (
        map_seconds(params, freq_hz, range(BACKGROUND_AMPLITUDES))
        if background else 0.0)
    return check_time(seconds, f"{len(freq_hz)} frequencies",
                      "fewer or higher frequencies (`freq_hz`)")


def check_sensitivity(params, freq_hz, cases, workers):
    """``sensitivity``: cases x the tongues of one case."""
    return check_time(cases * tongues_seconds(params, freq_hz),
                      f"{cases} cases x {len(freq_hz)} frequencies",
                      "fewer `names`, `factors` or `freq_hz`",
                      _workers(workers, cases))


def check_settings_time(settings, parameters, source=None, bench=False):
    """``check``: settings x (one point + the sensitivity parameters);
    ``source``: the table the settings came from (named as what to
    shorten), else the grid of ``freq_hz`` x ``p_f_bar``; ``bench``: the
    settings are judged on a test bench (its orbits cost more)."""
    one = CHECK_BENCH_SETTING_S if bench else CHECK_SETTING_S
    return check_time(
        settings * (one + parameters * CHECK_PARAMETER_S),
        f"{settings} settings x {parameters} sensitivity parameters",
        ("fewer `freq_hz` x `p_f_bar` settings" if source is None else
         f"fewer rows in {source}") + ", or `sensitivity` none")


def check_threshold(mu_g, damping):
    """``threshold``: the mu_g of Fig. 19a and the c_i of Fig. 19b."""
    return check_time(mu_g * THRESHOLD_MU_S + damping * THRESHOLD_DAMPING_S,
                      f"{mu_g} mu_g x {damping} c_i values",
                      "fewer `mu_g` or `c_ext` values")


def check_fit(points, fits, option, starts=True):
    """``fit``: measured points x local fits (the starts, the bootstrap's
    refits, the fits at the threshold's spread); ``starts`` False where
    their number is no argument (the report fits from one start)."""
    return check_time(FIT_FIXED_S + points * fits * FIT_POINT_START_S,
                      f"{points} measured points x {fits} local fits",
                      f"fewer points in {option}"
                      + (", or fewer `starts`" if starts else ""))


def check_orbit(frequencies, amplitudes):
    """``orbit``: frequencies x amplitudes, one orbit each."""
    return check_time(frequencies * amplitudes * ORBIT_S,
                      f"{frequencies} frequencies x {amplitudes} amplitudes",
                      "fewer `freq_hz` or `p_f_bar` values")


def check_crosscheck(runs, duration, workers):
    """``crosscheck``: FMU runs x simulated seconds."""
    return check_time(runs * duration * FMU_SECOND_S,
                      f"{runs} FMU runs x {duration:g} s simulated",
                      "fewer `freq_hz` x `p_f_bar` points or a shorter `duration`",
                      _workers(workers, runs))


def check_campaign(runs, duration, rpm_max, workers):
    """``campaign``: runs x simulated seconds x speed (tooth signals)."""
    return check_time(
        runs * duration * max(rpm_max, 1000.0) / 1000.0 * CAMPAIGN_SECOND_S,
        f"{runs} runs x {duration:g} s simulated up to {rpm_max:g} rpm",
        "fewer `freq_hz` x `p_f_bar` x `engine_rpm` x `temperatures` runs "
        "or a shorter `duration`", _workers(workers, runs))


def check_envelope(params, freq_hz, ranges, samples, vertices, refine,
                   workers):
    """``envelope``: samples (and vertices) x the tongues and background
    map of one sample, and the refining boundary evaluations."""
    names = len(ranges.names)
    jobs = samples + (2 ** names if vertices else 0)
    per_job = (tongues_seconds(params, freq_hz)
               + map_seconds(params, freq_hz, range(BACKGROUND_AMPLITUDES)))
    refining = refine * names * len(freq_hz) * TONGUE_FREQUENCY_S
    seconds = jobs * per_job + refining
    return check_time(seconds, f"{jobs} samples x {len(freq_hz)} "
                      f"frequencies, and `refine` {refine} x {names} "
                      f"parameters x {len(freq_hz)} frequencies",
                      "fewer `samples`, "
                      "uncertain parameters or `freq_hz`, or a smaller `refine`",
                      _workers(workers, jobs))


def _terminal():
    """Whether stderr is a terminal (where the progress bars show too)."""
    return sys.stderr.isatty()


def _workers(workers, jobs):
    """The worker processes the jobs will run on
    (:func:`infra.parallel.worker_count`)."""
    from infra.parallel import worker_count
    return worker_count(workers, jobs)[0]


#: Bytes ``advise`` holds per frequency of its 0.5 Hz grid (peak resident
#: memory of ``judder advise --no-design --freq-range=60:LOW`` grows by
#: 12.2 kB per frequency from 60:200 to 60:20000, 117 to 599 MB).
ADVISE_BYTES_PER_FREQUENCY = 12_500


#: Most runs of one campaign, FMU runs of one crosscheck, cases of one
#: sensitivity study: beyond, a request is a typo or a week of work.
MAX_RUNS = 100_000


#: Bytes one campaign run writes per format, second of engagement and
#: 1000 rpm (41 teeth; measured 29.6 kB CSV and 31.3 kB MF4 for 1 s).
BYTES_PER_RUN_SECOND = 32_000


#: Share of the memory available a request may take.
MEMORY_SHARE = 0.8


def check_memory(needed, what, drivers, change, bound="about"):
    """Refuse work whose memory (bytes) is above :data:`MEMORY_SHARE` of
    the memory available (:func:`infra.memory.available_memory`), naming
    ``what`` needs it, what the estimate is made of (``drivers``) and what
    to change; returns ``needed``."""
    free = available_memory()
    if needed > MEMORY_SHARE * free:
        raise JudderError(
            f"{what} needs {bound} {needed / 2**30:.3g} GiB ({drivers}), "
            f"and {free / 2**30:.3g} GiB are available; allowed: {change}")
    return needed


def check_acquisitions(paths, workers):
    """``chart``: each acquisition's memory, and the time of reading and
    analysing all of them, from their sizes
    (:func:`pysim.bench.readers.read_cost`), before any is read.

    Returns
    -------
    int
        The largest memory one run takes (bytes), for the worker count.
    """
    from pysim.bench.readers import MEMORY_PER_BYTE, read_cost
    costs = [read_cost(path) for path in paths]
    largest = max(range(len(paths)), key=lambda i: costs[i][0])
    memory = costs[largest][0]
    check_memory(memory, f"{paths[largest]}",
                 f"{memory / MEMORY_PER_BYTE / 2**20:.4g} MB of file x "
                 f"{MEMORY_PER_BYTE} to read and analyse it",
                 "a shorter acquisition (split it into engagements, or "
                 "keep only the channels needed)")
    total = sum(seconds for _, seconds in costs)
    size = sum(m for m, _ in costs) / MEMORY_PER_BYTE
    check_time(total, f"{len(paths)} acquisitions, {size / 2**20:.4g} MB",
               "fewer or shorter acquisitions",
               _workers(workers, len(paths)))
    return memory


def check_map_memory(params, freq_hz, p_f_bar):
    """Refuse a map whose Dyson series would not fit in memory.

    At each frequency the engine holds, for every amplitude, one matrix
    per sub-interval of the period (:class:`stability.monodromy.
    DysonPropagator`); the sub-intervals at the lowest frequency follow
    from the spectral radius of ``A0`` (the modulation only adds more).
    """
    f = float(np.min(freq_hz))
    steps, size = subintervals(params, [f])
    steps = int(steps[0])
    needed = 3 * len(p_f_bar) * steps * size * size * 8 \
        + 64 * len(freq_hz) * len(p_f_bar)
    return check_memory(
        needed, "`freq_hz` x `p_f_bar`", f"{len(p_f_bar)} amplitudes x {steps} "
        f"sub-intervals at {f:g} Hz", "fewer amplitudes per frequency, or "
        "higher frequencies", bound="at least")


def check_advise_grid(low, high, margin_hz):
    """Refuse an ``advise`` frequency range whose 0.5 Hz grid has more
    than :data:`studies.rules.MAX_GRID_VALUES` frequencies or would
    not fit in memory, naming ``--freq-range``; returns the number of
    frequencies."""
    text = f"{low:g}:{high:g}"
    points = int(round(2 * (high - low + 2 * margin_hz))) + 1
    widest = (MAX_GRID_VALUES - 1) / 2 - 2 * margin_hz
    if points > MAX_GRID_VALUES:
        raise JudderError(
            f"`freq_range` {text} makes {points} frequencies (0.5 Hz "
            f"apart); allowed: at most {MAX_GRID_VALUES}, i.e. a range of "
            f"at most {widest:g} Hz (`margin_hz` {margin_hz:g})")
    check_memory(points * ADVISE_BYTES_PER_FREQUENCY, f"`freq_range` {text}",
                 f"{points} frequencies 0.5 Hz apart", "a narrower range")
    return points


def check_work(option, count, what):
    """Refuse more than :data:`MAX_RUNS` pieces of work."""
    if count > MAX_RUNS:
        raise JudderError(f"{option} asks for {count:.4g} {what}; allowed: "
                          f"at most {MAX_RUNS} (split the study)")


def check_campaign_disk(folder, runs, duration, rpm_max, formats):
    """Refuse a campaign whose files would not fit on the disk."""
    from pathlib import Path
    import shutil
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
