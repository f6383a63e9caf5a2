"""Time-domain simulation of the driveline FMUs with fmpy, and bench data.

:mod:`pysim.runs` runs an FMU at a dither setting, :mod:`pysim.signals`
analyses time histories (spectrum, growth rates), :mod:`pysim.crosscheck`
compares FMU growth with the Floquet exponents, :mod:`pysim.bench`
emulates bench campaigns, :mod:`pysim.export` writes CSV and MF4, and
:mod:`pysim.plotting` draws them.
"""
