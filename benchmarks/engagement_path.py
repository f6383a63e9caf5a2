"""Engagements whose slip decays: the quasi-static path through the map
against the bench FMU.

For each held-out engagement (a friction table whose slope lasts over a
band of slips, the bench's load clutch taking a share of the EVEN
clutch's torque so that the slip falls through the band in 0.6-5 s;
settings in tongues 2, 4, 5 and outside them) this script runs the bench
FMU (``judder simulate``: the Modelica model integrated by the FMU's
solver, the independent reference) and compares it with the path
through the map (:mod:`stability.engagement_path`: the Floquet exponent of
Eq. 13 at each mean slip, integrated over time):

- the amplitude gain of the growing motion between two windows of the
  run (the Hann amplitude of the slip at its frequency, ``f/2`` in a
  double-period tongue, the strongest of ``nu + k f`` in a combination
  tongue, ``nu`` from the leading multiplier) against
  ``exp(int sigma dt)`` between the windows' centres, where the motion
  stays in the table's segment (linear range) and above the noise;
- the engagement's verdict: the run's (judder where its oscillation
  exceeds the limit) against the path's (the forced oscillation of the
  orbit at the start slip over the limit, or the growing motion's
  amplitude at the path's start times the path's largest gain).

Run: ``.venv/bin/python benchmarks/engagement_path.py [--json FILE]``.
Prints one row per engagement and the agreement counts.
"""

import argparse
import json
import math
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from infra.criteria import DEFAULT_JUDDER_LIMIT_RPM    # noqa: E402
from infra.spectrum import hann_amplitude              # noqa: E402
from infra.units import PA_PER_BAR, RPM_PER_RAD_S      # noqa: E402

#: The held-out characteristic: its slope 0.0028 s/rad from 60 to 90
#: rad/s (mu 0.02 to 0.105), nearly flat outside; 0.09 at the bench's
#: 84.72 rad/s, so that the mean torque stays the preset's.
TABLE = ("slip_rad_s,mu\n0,0.018\n60,0.02\n90,0.105\n120,0.108\n"
         "300,0.11\n")

#: (frequency Hz, amplitude bar, expected region) of the settings.
SETTINGS = [(205.0, 1.6, "tongue 4"), (206.0, 2.0, "tongue 4"),
            (205.5, 2.6, "tongue 4"), (86.4, 1.8, "tongue 5"),
            (86.4, 2.6, "tongue 5"), (119.5, 1.9, "tongue 6"),
            (103.0, 0.3, "tongue 2"), (150.0, 1.5, "stable"),
            (60.0, 1.0, "stable")]
#: Load shares: the slip falls 84.7 -> 0 rad/s in about 0.64 / (1 -
#: load_share) s (0.6-5 s).
LOAD_SHARES = (0.0, 0.5, 0.7, 0.8, 0.87)
#: Width of the windows the run's amplitude is read in, s.
WINDOW_S = 0.12
#: Below this amplitude (rpm of slip) the growing motion is noise.
FLOOR_RPM = 0.02


def growing_frequency(path_kind, leading_angle, freq_hz, time_s, slip):
    """Frequency of the growing motion, Hz: ``f/2`` (double-period),
    ``f`` (single-period), else the strongest of ``nu + k f`` in the
    run's slip (``nu`` from the leading multiplier's angle)."""
    if path_kind == "double-period":
        return freq_hz / 2
    if path_kind == "single-period":
        return freq_hz
    nu = abs(leading_angle) / (2 * np.pi) * freq_hz
    candidates = [c for c in (nu, freq_hz - nu, freq_hz + nu)
                  if 0 < c < 0.45 / np.median(np.diff(time_s))]
    amplitudes = hann_amplitude(time_s, slip - slip.mean(), candidates)
    return candidates[int(np.argmax(amplitudes))]


def window_amplitude(time_s, slip, centre, freq_hz):
    """Hann amplitude of the slip at ``freq_hz`` in the window of width
    :data:`WINDOW_S` about ``centre``, rpm."""
    keep = np.abs(time_s - centre) <= WINDOW_S / 2
    values = slip[keep] - np.polyval(np.polyfit(time_s[keep], slip[keep], 1),
                                     time_s[keep])
    return float(hann_amplitude(time_s[keep], values, [freq_hz])[0]) \
        * RPM_PER_RAD_S


def case(values, freq_hz, p_f_bar, load_share, limit_rpm):
    from judder import api
    from stability.bench import linearisation_at
    from stability.multipliers import floquet
    result = api.simulate(freq_hz, p_f_bar, parameters=values,
                          bench={"load_share": load_share})
    run, summary, path = result.runs[0][1], result.summaries[0], \
        result.paths[0]
    t, slip = run.time, run["slip"]
    start = result.start
    # the growing motion: the leading solution at the path's most
    # unstable slip
    peak = int(np.argmax(path.growth_per_s))
    lead = floquet(linearisation_at(values, {"load_share": load_share})(
        path.slip[peak]), freq_hz, p_f_bar * PA_PER_BAR)
    kind = str(path.kind[peak])
    after = t >= start
    f_grow = growing_frequency(kind, np.angle(lead.leading), freq_hz,
                               t[after], slip[after])
    # the windows: from the path's start to where the path's gain peaks
    # (the motion grows until there), inside the run
    first = start + WINDOW_S / 2
    top = float(path.time[int(np.argmax(path.accumulated))])
    last = min(max(top, first + WINDOW_S), t[-1] - WINDOW_S / 2)
    a0 = window_amplitude(t, slip, first, f_grow)
    a1 = window_amplitude(t, slip, last, f_grow)
    predicted_gain = path.gain(first, last)
    measured_gain = a1 / a0 if a0 > 0 else math.nan
    linear = (max(a0, a1) / RPM_PER_RAD_S
              <= values.friction.linear_range(path.slip[peak]))
    comparable = linear and min(a0, a1) > FLOOR_RPM and last > first
    # the engagement's verdicts
    simulated = bool(summary["judder"])
    forced = api.check([freq_hz], [p_f_bar], parameters=values,
                       sensitivity=()).records()[0]["mechanism"] == "forced"
    upstream0 = window_amplitude(t, run["w_upstream"], first, f_grow)
    grown = upstream0 * float(np.exp(path.accumulated.max()
                                     - np.interp(first, path.time,
                                                 path.accumulated)))
    predicted = forced or grown >= limit_rpm
    return {"freq_hz": freq_hz, "p_f_bar": p_f_bar,
            "load_share": load_share,
            "slip_start_rad_s": float(path.slip[0]),
            "slip_end_rad_s": float(path.slip[-1]),
            # from the end of the ramp until the slip is gone (or the run
            # ends)
            "engagement_s": float((path.time[np.argmax(path.slip < 1.0)]
                                   if (path.slip < 1.0).any()
                                   else path.time[-1]) - start),
            "kind": kind, "growing_hz": float(f_grow),
            "max_growth_per_s": float(path.growth_per_s.max()),
            "window_s": [first, last], "amplitude_rpm": [a0, a1],
            "upstream_grown_rpm": grown,
            "predicted_gain": predicted_gain, "measured_gain": measured_gain,
            "ratio": (predicted_gain / measured_gain
                      if comparable else None),
            "linear": bool(linear), "comparable": bool(comparable),
            "simulated_judder": simulated, "predicted_judder": predicted,
            "mechanism": summary["mechanism"]}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--json", help="write the rows to this file")
    args = parser.parse_args(argv)
    from sources import get_preset
    from studies.inputs import friction_of
    table = Path("/tmp") / "engagement_path_table.csv"
    table.write_text(TABLE)
    values = friction_of(get_preset("paper-4dof"), str(table))
    rows, started = [], time.perf_counter()
    for freq, p_f, region in SETTINGS:
        for share in LOAD_SHARES:
            row = {"region": region,
                   **case(values, freq, p_f, share, DEFAULT_JUDDER_LIMIT_RPM)}
            rows.append(row)
            ratio = row["ratio"]
            print(f"{region:9s} {freq:6.1f} Hz {p_f:4.2f} bar "
                  f"load_share {share:4.2f}: slip {row['slip_start_rad_s']:5.1f}"
                  f"->{row['slip_end_rad_s']:5.1f} rad/s in "
                  f"{row['engagement_s']:4.2f} s, "
                  f"max {row['max_growth_per_s']:+5.2f} 1/s ({row['kind']}), "
                  f"gain predicted {row['predicted_gain']:7.3g} measured "
                  f"{row['measured_gain']:7.3g}"
                  + (f" ratio {ratio:5.2f}" if ratio else " (not compared)")
                  + f"; judder run {row['simulated_judder']}, path "
                    f"{row['predicted_judder']}", flush=True)
    compared = [r for r in rows if r["ratio"]]
    within = [r for r in compared if 1 / 1.5 <= r["ratio"] <= 1.5]
    agree = [r for r in rows
             if r["simulated_judder"] == r["predicted_judder"]]
    print(f"gain within a factor 1.5: {len(within)} of {len(compared)} "
          f"compared ({len(rows)} engagements); verdicts agree: "
          f"{len(agree)} of {len(rows)} "
          f"({100 * len(agree) / len(rows):.0f} %); "
          f"{time.perf_counter() - started:.0f} s")
    if args.json:
        Path(args.json).write_text(json.dumps(rows, indent=1))


if __name__ == "__main__":
    main()
