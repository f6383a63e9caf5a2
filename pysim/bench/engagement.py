"""What a bench run shows: the judder and where it sits.

:func:`engagement_summary` reduces the time histories of one bench run
(Fig. 7: a held-slip bench run, or the slipping part of a full
engagement) to the numbers an engineer reads off it: the spectrum
peaks of the upstream speed and of the pressure (Fig. 8), whether the
speed peak sits at the dither frequency, and the judder verdict of
:func:`pysim.bench.verdict.analyse_run`: how fast the non-periodic part of
the speed grows (whichever the kind: at ``f``, ``f/2`` or a combination
frequency), and which kind it is.
"""

from dataclasses import replace

import numpy as np

from infra.criteria import (DEFAULT_JUDDER_LIMIT_RPM,
                            DEFAULT_MIN_GROWTH_PER_S, JUDDER, NO_JUDDER)
from infra.units import PA_PER_BAR, RPM_PER_RAD_S

from .verdict import analyse_run
from .signals import amplitude_spectrum

__all__ = ["engagement_summary", "verdict_line", "judder_words",
           "display_spectra", "LOCK_VARIABLES", "lock_up", "until"]

#: Variables of a locking clutch (``Interfaces.PartialLockingClutch``:
#: ``Components.LockingCurveWetClutch``, ``LockingWetClutch``) a full
#: engagement records: how often it stuck, and broke away, by events.
LOCK_VARIABLES = ("clutch.lockups", "clutch.breakaways")


def lock_up(run):
    """When a full engagement (``TestBenchCurveLockUp``,
    ``TestBenchLockUp``) locks up: the first
    sample from which its EVEN clutch stays stuck to the end of the run
    (``clutch.lockups - clutch.breakaways`` is 1), s; None if it slips at the
    end (inside a tongue the slip swings through zero and every lock-up
    breaks away at once)."""
    stuck = run["clutch.lockups"] - run["clutch.breakaways"] > 0.5
    if not stuck[-1]:
        return None
    slipping = np.flatnonzero(~stuck)
    return float(run.time[slipping[-1] + 1 if slipping.size else 0])


def until(run, end):
    """``run`` before ``end`` (s; the whole run for None): the slipping
    part of an engagement that locks up at ``end``."""
    if end is None:
        return run
    keep = run.time < end
    return replace(run, time=run.time[keep],
                   signals={name: values[keep]
                            for name, values in run.signals.items()})


def engagement_summary(run, start, min_growth=DEFAULT_MIN_GROWTH_PER_S,
                       judder_limit_rpm=DEFAULT_JUDDER_LIMIT_RPM):
    """Spectrum peaks and judder verdict of one bench run after ``start``
    (a held-slip bench run, or a full engagement's slipping part).

    Parameters
    ----------
    run : pysim.simulation.runs.Run
        A run of a bench model (signals of :data:`drivelines.registry.SIGNALS`).
    start : float
        End of the pressure ramp, s: the analysis uses ``t >= start``.
    min_growth : float
        Growth rate from which an instability is judder, 1/s.
    judder_limit_rpm : float
        NVH limit of the dither-related oscillation, rpm.

    Returns
    -------
    dict
        ``freq_hz``, ``p_f_bar``: the dither setting (Hz, bar);
        ``speed_peak_freq_hz``, ``speed_peak_amplitude_rpm``,
        ``speed_amplitude_at_dither_rpm``: the upstream speed spectrum;
        ``pressure_peak_freq_hz``, ``pressure_peak_amplitude_bar``;
        ``peak_at_dither_frequency``: the speed peak is within two
        frequency bins of the dither frequency;
        ``judder``, ``judder_kind``, ``judder_growth_per_s``,
        ``judder_growth_std_per_s``, ``mechanism``, ``judder_limit_rpm``,
        ``oscillation_rpm``, ``forced_rpm``: the verdict, its kind, the
        growth rate of the non-periodic part and its standard
        uncertainty (1/s), why it judders and the oscillation
        compared with the limit, as :func:`pysim.bench.verdict.analyse_run`
        reads them (None without dither); ``dither_envelope_max_rpm``: the
        largest envelope at the dither frequency; ``final_slip_rad_s``.
    """
    keep = run.time >= start
    reading = None
    if run.p_f > 0:
        reading = analyse_run((run.time, run["w_upstream"]),
                              (run.time, run["actuation_pressure"]),
                              (run.time, run["w_downstream"]),
                              freq_hz=run.freq_hz,
                              p_f_bar=run.p_f / PA_PER_BAR,
                              min_growth=min_growth,
                              judder_limit_rpm=judder_limit_rpm)
        at_dither = next(c for c in reading.components
                         if c.name == "dither")
    speed = amplitude_spectrum(run.time[keep], run["w_upstream"][keep])
    pressure = amplitude_spectrum(run.time[keep],
                                  run["actuation_pressure"][keep])
    resolution = 1.0 / max(run.time[keep][-1] - run.time[keep][0], 1e-9)
    line = int(np.argmin(np.abs(speed.freq_hz - run.freq_hz)))
    return {"freq_hz": run.freq_hz, "p_f_bar": run.p_f / PA_PER_BAR,
            "speed_peak_freq_hz": speed.peak_freq_hz,
            "speed_peak_amplitude_rpm": speed.peak_amplitude * RPM_PER_RAD_S,
            "speed_amplitude_at_dither_rpm":
                float(speed.amplitude[line]) * RPM_PER_RAD_S,
            "pressure_peak_freq_hz": pressure.peak_freq_hz,
            "pressure_peak_amplitude_bar":
                pressure.peak_amplitude / PA_PER_BAR,
            "peak_at_dither_frequency":
                bool(abs(speed.peak_freq_hz - run.freq_hz) <= 2 * resolution),
            "judder": None if reading is None else reading.judder,
            "verdict": None if reading is None else reading.verdict,
            "judder_kind": None if reading is None else reading.kind,
            "judder_growth_per_s": None if reading is None
            else reading.growth_per_s,
            "judder_growth_std_per_s": None if reading is None
            else reading.growth_std_per_s,
            "mechanism": None if reading is None else reading.mechanism,
            "judder_limit_rpm": float(judder_limit_rpm),
            "oscillation_rpm": None if reading is None
            else reading.oscillation_rpm,
            "forced_rpm": None if reading is None else reading.forced_rpm,
            "dither_envelope_max_rpm": None if reading is None
            else at_dither.amplitude_rpm,
            "final_slip_rad_s": float(run["slip"][-1])}


def verdict_line(summary):
    """The judder verdict of one engagement, the Floquet verdict of its
    linearisation and its periodic orbit, a short line each for a
    figure's panel.

    ``summary`` is a dict of :func:`engagement_summary` with
    ``floquet_kind`` and ``floquet_exponent_per_s`` (and the ``orbit_*``
    fields of ``judder simulate``, and for a full engagement its
    ``lock_up_time_s``, ``lockups`` and ``duration_s``) added.
    """
    if summary["judder"] is None:  # a run without dither: its label says so
        return ("" if "lock_up_time_s" not in summary else
                lock_words(summary))
    if not summary["judder"]:
        run = f"{NO_JUDDER.lower()}, {summary['oscillation_rpm']:.3g} rpm"
    else:
        growth = summary["judder_growth_per_s"]
        run = (f"{JUDDER.lower()}, {summary['mechanism']}, "
               f"{summary['oscillation_rpm']:.3g} rpm"
               + ("" if summary["mechanism"] == "forced" else
                  f" ({summary['judder_kind']}"
                  + ("" if growth is None else f", {growth:+.2f} 1/s")
                  + ")"))
    lines = [f"run: {run} (limit {summary['judder_limit_rpm']:.3g} rpm)"
             + ("" if "lock_up_time_s" not in summary else
                " while slipping")]
    if "lock_up_time_s" in summary:
        lines.append(lock_words(summary))
    exponent = summary.get("floquet_exponent_per_s")
    if exponent is not None:
        lines.append(f"Floquet: {summary['floquet_kind']}, "
                     f"{exponent:+.2f} 1/s"
                     + ("" if summary.get("orbit_kind") is None else
                        f"; orbit: {summary['orbit_settled_rpm']:.3g} rpm, "
                        + (summary["orbit_mechanism"]
                           or NO_JUDDER.lower())))
    if summary.get("linearisation_holds") is False:
        lines.append(f"slip swing \u00b1"
                     f"{summary['forced_slip_amplitude_rad_s']:.1f} rad/s, "
                     f"curve linear over \u00b1"
                     f"{summary['friction_linear_range_rad_s']:.1f} rad/s")
    return "\n".join(lines)


def lock_words(summary):
    """How a full engagement ends: ``lock-up at 3.23 s`` or ``no lock-up
    in 2 s (41 lock-ups broke away)``."""
    if summary["lock_up_time_s"] is not None:
        return f"lock-up at {summary['lock_up_time_s']:.3g} s"
    return (f"no lock-up in {summary['duration_s']:.3g} s"
            + (f" ({summary['lockups']} lock-ups broke away)"
               if summary["lockups"] else ""))


def judder_words(summary):
    """The run's verdict in words, e.g. ``judder, forced: 276 rpm at the
    dither frequency (limit 30 rpm)``, ``judder, parametric:
    double-period, grows at 2.45 1/s; 41 rpm (limit 30 rpm)`` or ``no
    judder: 12 rpm (limit 30 rpm)``."""
    limit = f"(limit {summary['judder_limit_rpm']:.3g} rpm)"
    amplitude = f"{summary['oscillation_rpm']:.3g} rpm"
    if not summary["judder"]:
        return f"{NO_JUDDER.lower()}: {amplitude} {limit}"
    mechanism = summary["mechanism"]
    if mechanism == "forced":
        return (f"{JUDDER.lower()}, forced: {amplitude} at the dither "
                f"frequency {limit}")
    growth = summary["judder_growth_per_s"]
    instability = summary["judder_kind"] + (
        f", grows at {growth:.2f} 1/s" if growth is not None else "")
    if mechanism == "both":
        instability += (f", over a forced {summary['forced_rpm']:.3g} rpm "
                        "at the dither frequency")
    return (f"{JUDDER.lower()}, {mechanism}: {instability}; {amplitude} "
            + limit)


def display_spectra(run, start):
    """Amplitude spectra of an engagement after ``start`` (s), as Fig. 8
    shows them: the upstream speed in rpm and the actuation pressure in
    bar (each a :class:`pysim.bench.signals.Spectrum`)."""
    keep = run.time >= start
    speed = amplitude_spectrum(run.time[keep],
                               run["w_upstream"][keep] * RPM_PER_RAD_S)
    pressure = amplitude_spectrum(run.time[keep],
                                  run["actuation_pressure"][keep] / PA_PER_BAR)
    return speed, pressure
