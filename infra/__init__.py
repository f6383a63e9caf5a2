"""Infrastructure every package of the project uses, and nothing else.

:mod:`infra.errors`
    The exceptions for bad input, the check of a number a user gives and
    the exit codes.
:mod:`infra.contract`
    The exit-code contract of every command line (``judder`` and
    ``python -m fmu``): what escapes a command becomes an exit status
    and one line on stderr.
:mod:`infra.files`
    Atomic output: a result file is complete or absent, never partial.
:mod:`infra.units`
    The project's one table of units (SI factor and dimension of each),
    and the factors between SI and the units engineers read (bar, rpm).
:mod:`infra.quantities`
    Numbers the user types, with or without a unit.
:mod:`infra.numbers`
    Numbers as an engineer reads them: a value with the digits its
    uncertainty supports.
:mod:`infra.environment`
    Settings given through the environment (time limits), read with one
    rule.
:mod:`infra.parallel`
    The executor that runs independent jobs on Dask (all cores, or an
    existing cluster).
:mod:`infra.children`
    One job in a child process (compiled code that may crash or hang).
:mod:`infra.lifecycle`
    Worker processes that die with their parent and clean up on the way.
:mod:`infra.memory`
    How much memory this process may still use.
:mod:`infra.criteria`
    When an oscillation is judder: the growth rate, the NVH limit and the
    mechanisms.
:mod:`infra.pdf`
    An HTML file printed to PDF by a headless Chromium.
:mod:`infra.spectrum`
    The amplitude spectrum both views read (Hann window,
    amplitude-corrected), on the bins or at given frequencies.
:mod:`infra.plotstyle`
    The look every plot shares (imports matplotlib; only plotting modules
    import it).
:mod:`infra.provenance`
    Where a result came from: the tool's version and a digest of its
    inputs, carried by every output.

This package imports no other package of the project: ``fmu``,
``sources``, ``drivelines``, ``stability``, ``pysim`` and the ``judder``
application all stand on it.
"""
