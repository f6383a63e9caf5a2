"""The Python API: one function per ``judder`` command.

Each function takes SI parameter sets and the units of the command line
(dither frequency in Hz, amplitude in bar), runs the kernels of
:mod:`stability` and :mod:`pysim`, and returns the result object of its
command (``as_dict()``, ``save()``, ``figure()``); the command line calls
the same functions and only formats what they return. The functions are
the studies (:mod:`studies`, one module each, no command line in them);
this facade names them from :data:`studies.STUDIES` and imports a
study's module on first use.

Every function takes the parameter set as ``params`` (a
:class:`drivelines.Parameters`; default: the paper preset of the default
driveline, see :func:`studies.inputs.load_parameters` for files; or a
driveline of one's own, a Modelica class
:class:`sources.modelica.ModelicaParameters` or an FMU
:class:`sources.fmus.FmuParameters`) and ``changes``, the values
the user set explicitly (``--set``), applied on top. What needs a
time-domain run (:func:`crosscheck`, :func:`simulate`) refuses an FMU,
what needs the bench (``fit(bench=...)``) or the paper's chains
(:func:`threshold`) refuses both, with a :class:`~infra.errors.JudderError`
that says why. The Floquet views judge a preset's driveline on its
test bench (the one :func:`simulate` runs) unless ``driveline='chain'``
(:func:`stability.bench.driveline_view`). Monodromy engines (``method``)
are the keys of :data:`stability.monodromy.METHODS`. ``progress`` is called as
``progress(done, total)`` on long work.

Examples
--------
>>> from judder import api
>>> result = api.floquet(102.9, 0.3, driveline="chain")
>>> result.result.kind, round(result.result.leading_abs, 4)
('single-period', 1.0261)
"""

from studies import STUDIES, study

__all__ = sorted(STUDIES)


def __getattr__(name):
    if name not in STUDIES:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    return study(name)


def __dir__():
    return __all__
