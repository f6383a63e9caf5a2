"""The application layer: the ``judder`` command line and its Python API.

:mod:`judder.commands` holds one module per command (its options, its
work, its API function and its result), registered in one table from
which :mod:`judder.cli` makes the command line and :mod:`judder.api` the
Python API. :mod:`studies.inputs` reads what the user gives
(parameter files, measured boundaries); :mod:`studies.crosscheck` holds the
time-domain and Floquet views of one model against each other.

Beneath this layer: :mod:`stability` (Floquet kernels and their plots),
:mod:`pysim` (FMU runs and bench data), :mod:`fmu` (the Modelica-to-FMU
compiler), :mod:`sources` (the parameter sets of the presets, Modelica
classes and FMUs, and their linearisation), :mod:`drivelines` (the
registry of models) and :mod:`infra` (errors, atomic files, units, the
parallel executor).
"""
