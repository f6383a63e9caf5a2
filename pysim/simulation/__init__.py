"""FMU runs with fmpy: build (:mod:`~pysim.simulation.fmus`), run at a
dither setting (:mod:`~pysim.simulation.runs`), engagement summaries
(:mod:`~pysim.simulation.engagement`), emulated bench campaigns
(:mod:`~pysim.simulation.campaigns`), CSV and MF4 export
(:mod:`~pysim.simulation.export`) and plots of runs
(:mod:`~pysim.simulation.plots`)."""
