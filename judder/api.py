"""The Python API: one function per ``judder`` command.

Each function takes SI parameter sets and the units of the command line
(dither frequency in Hz, amplitude in bar), runs the kernels of
:mod:`stability` and :mod:`pysim`, and returns the result object of its
command (``as_dict()``, ``save()``, ``figure()``); the command line calls
the same functions and only formats what they return. The functions live
in their command's module (:mod:`judder.commands`); this facade names
them from the command registry and imports a command's module on first
use.

Every function takes the parameter set as ``params`` (a
:class:`drivelines.Parameters`; default: the paper preset of the default
driveline, see :func:`judder.inputs.load_parameters` for files; or a
driveline of one's own, a Modelica class
:class:`sources.modelica.ModelicaParameters` or an FMU
:class:`sources.fmus.FmuParameters`) and ``changes``, the values
the user set explicitly (``--set``), applied on top. What needs a
time-domain run (:func:`crosscheck`, :func:`simulate`) refuses an FMU,
what needs the bench (``fit(bench=...)``) or the paper's chains
(:func:`threshold`) refuses both, with a :class:`~infra.errors.JudderError`
that says why. The Floquet views judge a preset's driveline on its
test bench (the one :func:`simulate` runs) unless ``driveline='chain'``
(:func:`judder.bench.driveline_view`). Monodromy engines (``method``)
are the keys of :data:`stability.monodromy.METHODS`. ``progress`` is called as
``progress(done, total)`` on long work.

Examples
--------
>>> from judder import api
>>> result = api.floquet(102.9, 0.3, driveline="chain")
>>> result.result.kind, round(result.result.leading_abs, 4)
('single-period', 1.0261)
"""

from .commands import API_FUNCTIONS, command_module

__all__ = sorted(API_FUNCTIONS)


def __getattr__(name):
    if name not in API_FUNCTIONS:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    return getattr(command_module(API_FUNCTIONS[name]), name)


def __dir__():
    return __all__
