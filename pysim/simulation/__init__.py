"""FMU runs with fmpy: a run at a dither setting
(:mod:`~pysim.simulation.runs`; the FMUs are built, read and unpacked
by :mod:`fmu.store`), emulated bench campaigns
(:mod:`~pysim.simulation.campaigns`) and their CSV and MF4 files
(:mod:`~pysim.simulation.export`). What a run shows is read by
:mod:`pysim.bench`, as a measured one is."""
