"""Time histories: FMUs run in the time domain, and runs read and judged.

Two subpackages, each with one job, neither importing the other:

- :mod:`pysim.simulation` runs FMUs: runs one at a dither setting
  (``runs``; the FMUs are built, read and unpacked by :mod:`fmu.store`),
  emulates bench campaigns (``campaigns``) and writes their runs as CSV
  and MF4 (``export``), as a bench would;
- :mod:`pysim.bench` reads runs, measured or simulated, and judges them:
  the files benches write, the judder verdict of one run and the
  summary of an engagement, and the charts and figures of runs.

Which FMU belongs to which driveline is the registry's knowledge
(:mod:`drivelines.registry`).
"""
