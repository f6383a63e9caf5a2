"""Time-domain simulation of the driveline FMUs with fmpy, and bench data.

:mod:`pysim.fmus` builds the FMU of a library class when it is stale,
:mod:`pysim.runs` runs an FMU at a dither setting, :mod:`pysim.signals`
analyses time histories (spectrum, growth rates, free-response fits),
:mod:`pysim.engagement` sums up an engagement, :mod:`pysim.bench`
emulates bench campaigns, :mod:`pysim.export` writes CSV and MF4,
:mod:`pysim.run_analysis` reads judder out of one run (simulated or
measured), and :mod:`pysim.plots` draws runs and spectra.
:mod:`pysim.bench_data` reads bench files (MF4, CSV, TDMS, MAT) and makes
experimental stability charts of many runs. Which FMU belongs to which
driveline is the registry's knowledge (:mod:`drivelines.registry`).
"""
