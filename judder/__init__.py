"""The application layer: the ``judder`` command line and its Python API.

:mod:`judder.api` has one function per command, returning the result
objects of :mod:`judder.results`; :mod:`judder.cli` only parses options
and formats those results. :mod:`judder.inputs` reads what the user gives
(parameter files, measured boundaries); :mod:`judder.crosscheck` holds the
time-domain and Floquet views of one model against each other.

Beneath this layer: :mod:`stability` (Floquet kernels and their plots),
:mod:`pysim` (FMU runs and bench data), :mod:`fmu` (the Modelica-to-FMU
compiler), :mod:`drivelines` (the registry of models and parameter sets)
and :mod:`infra` (errors, atomic files, units, the parallel executor).
"""
