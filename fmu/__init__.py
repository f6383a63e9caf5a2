"""Modelica to FMU: rumoca front end, the project's own back end.

:mod:`fmu.frontend` reads the flat model rumoca writes for a ``.mo``
model; :mod:`fmu.backend` eliminates aliases, reduces the index, sorts
and solves the equations into an explicit ODE (CasADi expressions);
:mod:`fmu.build` writes the C code and packs the FMU.

A leaf of the project: it knows nothing of drivelines or of the other
packages, and uses only :mod:`infra` (errors and their exit codes, atomic
files).
"""
