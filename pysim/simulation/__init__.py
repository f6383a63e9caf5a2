"""FMU runs with fmpy: run at a dither setting
(:mod:`~pysim.simulation.runs`; the FMUs are built, read and unpacked
by :mod:`fmu.store`), engagement summaries
(:mod:`~pysim.simulation.engagement`), emulated bench campaigns
(:mod:`~pysim.simulation.campaigns`), CSV and MF4 export
(:mod:`~pysim.simulation.export`) and plots of runs
(:mod:`~pysim.simulation.plots`)."""
