"""Modelica to FMU: rumoca front end, the project's own back end.

:mod:`fmu.frontend` reads the flat model rumoca writes for a ``.mo``
model; :mod:`fmu.backend` eliminates aliases, reduces the index, sorts
and solves the equations into an explicit ODE (CasADi expressions);
:mod:`fmu.build` writes the C code and packs the FMU. :mod:`fmu.store`
is the one door to FMU files: it builds the FMU of a class where none
of its sources' content exists, reads model descriptions, unpacks FMUs
into the user's cache and runs them with fmpy.

A leaf of the project: it knows nothing of drivelines or of the other
packages, and uses only :mod:`infra` (errors and their exit codes, atomic
files).
"""
