"""Time-domain simulation with fmpy, and bench data.

Three subpackages, each with one job:

- :mod:`pysim.simulation` runs FMUs: builds the FMU of a library class
  when it is stale (``fmus``), runs it at a dither setting (``runs``),
  sums up an engagement (``engagement``), emulates bench campaigns
  (``campaigns``), writes CSV and MF4 (``export``) and draws runs
  (``plots``);
- :mod:`pysim.bench_data` reads the files benches write (MF4, CSV, TDMS,
  MAT) and makes experimental stability charts of many runs;
- :mod:`pysim.analysis` reads a time history, simulated or measured:
  spectra and growth rates (``signals``) and the judder verdict of one
  run (``verdict``). Both of the others use it; it uses neither.

Which FMU belongs to which driveline is the registry's knowledge
(:mod:`drivelines.registry`).
"""
