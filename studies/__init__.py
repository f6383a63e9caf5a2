"""The studies: one module per question an engineer asks of a driveline
(``check``, ``stability_map``, ``tongues``, ``orbit``, ``fit``,
``chart``, ``advise``, ...), each holding its function and the result it
returns (``as_dict()``, ``summary()``, ``save()``, ``figure()``).

A study takes SI parameter sets and the units engineers read (dither
frequency in Hz, amplitude in bar), checks each argument where it enters
(:mod:`studies.rules`; a refusal names the argument, its value and what
is allowed), runs the kernels of :mod:`stability`, :mod:`pysim` and
:mod:`fmu`, and knows nothing of a command line: the ``judder`` commands
(:mod:`judder.commands`) parse options, call a study and print it; the
Python API (:mod:`judder.api`) hands the studies out as they are.

:data:`STUDIES` names each study's function and module; a module is
imported on first use.
"""

from importlib import import_module

__all__ = ["STUDIES", "study"]

#: Study function -> its module, ``studies.<module>``.
STUDIES = {"params": "params", "eig": "eig", "floquet": "floquet",
           "stability_map": "map", "check": "check", "advise": "advise",
           "tongues": "tongues", "compare": "compare",
           "sensitivity": "sensitivity", "threshold": "threshold",
           "fit": "fit", "simulate": "simulate", "orbit": "orbit",
           "crosscheck": "crosscheck", "campaign": "campaign",
           "chart": "chart", "report": "report", "envelope": "envelope"}


def study(name):
    """The function of study ``name`` (a key of :data:`STUDIES`),
    imported on first use."""
    return getattr(import_module(f"{__name__}.{STUDIES[name]}"), name)
