"""What an engagement run shows: the judder at the dither frequency.

:func:`engagement_summary` reduces the time histories of one bench
engagement (Fig. 7) to the numbers an engineer reads off it: the spectrum
peaks of the upstream speed and of the pressure (Fig. 8), whether the
speed peak sits at the dither frequency, and how the oscillation at the
dither frequency grows or decays after the pressure ramp.
"""

import numpy as np

from infra.units import PA_PER_BAR, RPM_PER_RAD_S

from .signals import amplitude_spectrum, dither_envelope

__all__ = ["engagement_summary"]


def engagement_summary(run, start):
    """Spectrum peaks and judder growth of one engagement after ``start``.

    Parameters
    ----------
    run : pysim.runs.Run
        A run of a bench model (signals of :data:`drivelines.registry.SIGNALS`).
    start : float
        End of the pressure ramp, s: the analysis uses ``t >= start``.

    Returns
    -------
    dict
        ``freq_hz``, ``p_f_bar``: the dither setting (Hz, bar);
        ``speed_peak_freq_hz``, ``speed_peak_amplitude_rpm``,
        ``speed_amplitude_at_dither_rpm``: the upstream speed spectrum;
        ``pressure_peak_freq_hz``, ``pressure_peak_amplitude_bar``;
        ``peak_at_dither_frequency``: the speed peak is within two
        frequency bins of the dither frequency;
        ``judder_growth_per_s``: growth rate of the envelope at the dither
        frequency, 1/s (None without dither);
        ``dither_envelope_max_rpm``; ``final_slip_rad_s``.
    """
    keep = run.time >= start
    if run.p_f > 0:
        envelope, growth = dither_envelope(run.time, run["w_upstream"],
                                           run.freq_hz, start)
    else:
        envelope, growth = np.zeros(1), None
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
            "judder_growth_per_s": growth,
            "dither_envelope_max_rpm": float(envelope.max()) * RPM_PER_RAD_S,
            "final_slip_rad_s": float(run["slip"][-1])}
