"""Calibrate the per-unit costs of judder/commands/_preflight.py on this machine.

Run ``.venv/bin/python benchmarks/time_calibration.py``: it times, in CPU
seconds of one thread (``time.process_time`` under
``threadpool_limits(1)``, so other users of the machine do not enter the
numbers), the pieces the estimate adds up, and prints one JSON object
with the constants to copy into :mod:`studies._preflight`:

``frequency_s``
    the fixed cost of one frequency of a Dyson map (node exponentials,
    leading multipliers), from maps of 1 amplitude at 100-250 Hz;
``subinterval_s``
    the cost of building the series on one sub-interval, from the slope
    of the build time over 1..10 Hz (many sub-intervals);
``product_s``
    one amplitude on one sub-interval (Horner evaluation and the matrix
    product), from a 1 Hz column of 200 amplitudes;
``tongue_frequency_s``, ``tongue_fixed_s``
    one frequency of ``tongues`` (default solver, :func:`judder.api.tongues`
    on the paper's 4-DOF set) and its fixed cost, from 50 and 500
    frequencies at 10-220 Hz.

The FMU costs of ``crosscheck`` and ``campaign`` are taken from the user
time of those commands (see :mod:`studies._preflight`).
"""

import json
import time

import numpy as np
from threadpoolctl import threadpool_limits

from sources import get_preset
from judder import api
from stability import build_driveline
from stability.maps import stability_map
from stability.monodromy import DysonPropagator

BAR = 1e5


def _cpu(function, *args, repeat=3, **kwargs):
    best = np.inf
    for _ in range(repeat):
        start = time.process_time()
        function(*args, **kwargs)
        best = min(best, time.process_time() - start)
    return best


def calibrate():
    driveline = build_driveline(get_preset("paper-4dof"))
    system = driveline.periodic_system()
    steps, build = [], []
    for freq in (1.0, 2.0, 5.0, 10.0):
        steps.append(DysonPropagator(system, freq, 1.5 * BAR)
                     ._coefficients[0].shape[0])
        build.append(_cpu(DysonPropagator, system, freq, 1.5 * BAR))
    subinterval = float(np.polyfit(steps, build, 1)[0])
    high = np.linspace(100.0, 250.0, 20)
    frequency = _cpu(stability_map, driveline, high, [1.5 * BAR]) / len(high)
    propagator = DysonPropagator(system, 1.0, 1.5 * BAR)
    amplitudes = np.linspace(0, 1.5 * BAR, 200)
    product = (_cpu(propagator.monodromy, amplitudes)
               / len(amplitudes) / propagator._coefficients[0].shape[0])
    api.tongues(np.linspace(20.0, 120.0, 6))          # warm up
    few, many = (_cpu(api.tongues, np.linspace(10.0, 220.0, n), repeat=1)
                 for n in (50, 500))
    tongue = (many - few) / 450
    result = {"frequency_s": frequency, "subinterval_s": subinterval,
              "product_s": product, "tongue_frequency_s": tongue,
              "tongue_fixed_s": few - 50 * tongue}
    return result


if __name__ == "__main__":
    with threadpool_limits(1):
        print(json.dumps(calibrate()))
