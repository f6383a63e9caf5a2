"""Infrastructure every package of the project uses, and nothing else.

:mod:`infra.errors`
    The exceptions for bad input and the exit-code contract of every
    command line (``judder`` and ``python -m fmu``).
:mod:`infra.files`
    Atomic output: a result file is complete or absent, never partial.
:mod:`infra.units`
    The project's one table of units (SI factor and dimension of each),
    and the factors between SI and the units engineers read (bar, rpm).
:mod:`infra.quantities`
    Numbers the user types, with or without a unit.
:mod:`infra.parallel`
    The executor that runs independent jobs on all cores.
:mod:`infra.children`
    One job in a child process (compiled code that may crash or hang).
:mod:`infra.memory`
    How much memory this process may still use.
:mod:`infra.criteria`
    When an oscillation is judder: the growth rate, the NVH limit and the
    mechanisms.

This package imports no other package of the project: ``fmu``,
``drivelines``, ``stability``, ``pysim`` and the ``judder`` application
all stand on it.
"""
