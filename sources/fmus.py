r"""Linear time-periodic system of a driveline given as an FMU.

A third-party FMI 2.0 or 3.0 Model Exchange FMU is analysed without its
equations: the state Jacobian :math:`J = \partial\,\dot x / \partial x`
is read column by column with ``fmi2GetDirectionalDerivative`` (unknowns
``der(x)``, knowns ``x``; ``fmi3GetDirectionalDerivative``) where the FMU
provides directional derivatives, else by central differences of the
derivatives (:data:`sources.fmu_host.DIFFERENCE_STEP`, the checks below
then within :data:`_ZERO_DIFFERENCES`), at the FMU's initial state (its start
values: a steady slip), at :data:`SAMPLES` times over one dither period
and at the dither amplitudes ``0``, ``a/2`` and ``a`` (``a`` the set's
amplitude, or 1 bar if that is zero, at most the declared maximum). From
these

.. math:: J(t) = A_0 + p_f \cos(2\pi f t)\, B

is built as :func:`sources.modelica.linearize` builds it from the
symbolic equations (Eq. (6)-(7) of the paper), and checked the same way:
the amplitude enters affinely, the part without dither does not change
with time, the dither part is the cosine of the frequency parameter times
one matrix, and the Jacobian stays fixed along the slip. The rigid-body
directions are removed in :mod:`stability` (:mod:`stability.reduction`),
as for the Modelica path: the result is a
:class:`~sources.modelica.LinearPeriodicModel` that
:class:`stability.LinearDriveline` turns into every study.

The FMU is read here (not in :mod:`pysim`, the time-domain runs),
because the stability layer needs the matrices and may import only
:mod:`drivelines`; its model description and its unpacked folder come
from the one door to FMU files (:mod:`fmu.store`); its binary runs in a
child process
(:mod:`sources.fmu_host`), so that a crash, a hang or a non-finite
Jacobian of a third-party FMU is one error naming the call.
"""

from dataclasses import dataclass
from typing import ClassVar
from functools import lru_cache
from pathlib import Path

import numpy as np

from fmu.store import FmuFileError, digest, model_description
from infra.errors import JudderError

from .fmu_host import SampleJob, sample_isolated
from .modelica import (OTHER_FREQUENCY, NamedParameters,
                       check_no_acceleration, checked_values,
                       linear_periodic_model)
from .kinds import SourceKind
from drivelines.specs import ParameterSpec

__all__ = ["FmuError", "FmuParameters", "fmu_description", "linearize_fmu",
           "SAMPLES"]

#: Sample times per dither period at which the Jacobian is read.
SAMPLES = 16
#: Largest dither amplitude (Pa) of the difference quotients when the
#: parameter set has none: J is affine in it, so any size is exact up to
#: round-off.
_AMPLITUDE_STEP = 1e5
#: Relative size below which a residual of the checks counts as zero,
#: with directional derivatives (exact up to round-off) ...
_ZERO = 1e-10
#: ... and with central differences (truncation error of the step).
_ZERO_DIFFERENCES = 1e-6
#: Model Exchange FMI versions read, and the type names of a Real.
FMI_VERSIONS = ("2.0", "3.0")
_REAL_TYPES = ("Real", "Float64")


class FmuError(JudderError):
    """The FMU cannot be analysed; the message says why."""


def _require(condition, message):
    if not condition:
        raise FmuError(message)


@dataclass(frozen=True)
class FmuDescription:
    """What the analysis needs of an FMU's ``modelDescription.xml``.

    Attributes
    ----------
    path : str
    model_name : str
    guid, model_identifier : str
    fmi_version : str
    directional : bool
        The FMU provides directional derivatives.
    states, derivatives : tuple of int
        Value references of ``x`` and ``der(x)``, in the order of
        ``<Derivatives>`` (the order of ``fmi2GetContinuousStates``).
    state_names : tuple of str
    specs : dict of str to ParameterSpec
        The Real parameters (tunable or fixed), by name.
    starts : dict of str to float
    references : dict of str to int
    """

    path: str
    model_name: str
    guid: str
    model_identifier: str
    fmi_version: str
    directional: bool
    states: tuple
    derivatives: tuple
    state_names: tuple
    specs: dict
    starts: dict
    references: dict


def _number(text):
    return None if text is None else float(text)


@lru_cache(maxsize=8)
def _described(path, content):
    try:
        md = model_description(path)
    except FmuFileError as exc:
        raise FmuError(f"`path` {exc}") from None
    _require(md.fmiVersion in FMI_VERSIONS,
             f"`path` {path}: fmiVersion {md.fmiVersion}; allowed: "
             f"{' or '.join(FMI_VERSIONS)}")
    _require(md.modelExchange is not None,
             f"`path` {path}: no Model Exchange interface (Co-Simulation "
             "only); allowed: an FMI 2.0 or 3.0 Model Exchange FMU")
    _require(md.derivatives, f"`path` {path}: the FMU has no states")
    specs, starts, references = {}, {}, {}
    for v in md.modelVariables:
        if v.causality != "parameter" or v.type not in _REAL_TYPES or \
                v.variability not in ("fixed", "tunable") or v.start is None:
            continue
        declared = v.declaredType
        unit = v.unit or (declared.unit if declared is not None else None)
        bounds = {key: _number(b) for key, b in (("lower", v.min),
                                                 ("upper", v.max))
                  if b is not None}
        specs[v.name] = ParameterSpec(v.name, unit or "1",
                                      v.description or v.name, **bounds)
        starts[v.name] = float(v.start)
        references[v.name] = v.valueReference
    states = [d.variable.derivative for d in md.derivatives]
    return FmuDescription(
        path=path, model_name=md.modelName, guid=md.guid,
        model_identifier=md.modelExchange.modelIdentifier,
        fmi_version=md.fmiVersion,
        directional=bool(md.modelExchange.providesDirectionalDerivative),
        states=tuple(s.valueReference for s in states),
        derivatives=tuple(d.variable.valueReference for d in md.derivatives),
        state_names=tuple(s.name for s in states), specs=specs,
        starts=starts, references=references)


def fmu_description(path):
    """The :class:`FmuDescription` of an FMU file (cached per file
    content, :func:`fmu.store.digest`).

    Raises
    ------
    FmuError
        If the file is missing or not an FMI 2.0 or 3.0 Model Exchange
        FMU.
    """
    path = Path(path)
    _require(path.is_file(), f"`path` {path}: no such file; allowed: an "
             ".fmu file")
    return _described(str(path.resolve()), digest(path))


def linearize_fmu(path, values=None, amplitude="p_f", frequency="f_dither"):
    r"""Linear time-periodic system of an FMU, Eq. (6)-(7).

    Parameters
    ----------
    path : str or Path
        FMI 2.0 or 3.0 Model Exchange FMU (with directional derivatives,
        or read by central differences).
    values : dict, optional
        Parameters by name (SI); the others keep their start values.
    amplitude, frequency : str
        Names of the dither amplitude (Pa) and frequency (Hz) parameters.

    Returns
    -------
    sources.modelica.LinearPeriodicModel
        Named after the FMU's ``modelName``.

    Raises
    ------
    FmuError
        If the FMU cannot be analysed, or its Jacobian is not of the form
        ``A0 + p_f cos(2 pi f t) B`` along a steady slip.
    ParameterError
        For an unknown parameter or a value outside its bounds.
    """
    d = fmu_description(path)
    values = _values(d, dict(values or {}))
    for role, name in (("amplitude", amplitude), ("frequency", frequency)):
        if name not in d.specs:
            raise FmuError(f"`{role}` {name!r} is not a Real "
                           f"parameter of {d.model_name}; allowed: "
                           f"{', '.join(d.specs)}")
    f0 = values[frequency]
    _require(f0 > 0, f"{frequency} = {f0!r} Hz is not allowed; allowed: > 0")
    # amplitudes 0, step, 2 step: up to the set's (or the declared maximum)
    largest = min(abs(values[amplitude]) or _AMPLITUDE_STEP,
                  d.specs[amplitude].upper)
    _require(largest > 0, f"{amplitude}: its declared maximum is 0; "
             "allowed: a dither amplitude parameter that can be > 0")
    step = largest / 2
    times = np.arange(SAMPLES) / (SAMPLES * f0)
    # the period's samples, and t = 0 with the frequency parameter at
    # OTHER_FREQUENCY times its value (for _frequency_dependent)
    other = {**values, frequency: f0 * OTHER_FREQUENCY}
    sampled, at_other = _sampled(
        d.path, digest(d.path), amplitude, step,
        ((_without(values, amplitude), tuple(times)),
         (_without(other, amplitude), (0.0,))))
    A, Ja, J2a = sampled["jacobians"]
    zero = _ZERO if d.directional else _ZERO_DIFFERENCES
    _steady_slip(d, A[0], sampled["rate"], sampled["moved"],
                 sampled["along"], zero)
    A0 = A[0]
    B0 = (Ja[0] - A0) / step
    scale = max(np.abs(A0).max(), 1.0)
    bscale = max(np.abs(B0).max() * step, np.finfo(float).tiny)
    name = d.model_name
    _require(np.abs(J2a - 2 * Ja + A).max() <= zero * scale,
             f"{name}: the Jacobian is not affine in {amplitude} (the dither "
             "amplitude multiplies the states nonlinearly); allowed: "
             "J = A0 + p_f cos(2 pi f t) B")
    _require(np.abs(A - A0).max() <= zero * scale,
             f"{name}: the Jacobian without dither changes with time; "
             "allowed: time enters through the dither only")
    shape = np.cos(2 * np.pi * f0 * times)[:, None, None]
    _require(np.abs(Ja - A - step * shape * B0).max() <= zero * max(
        bscale, scale),
             f"{name}: the dither does not enter as {amplitude}*cos(2*pi*"
             f"{frequency}*time); allowed: the paper's cosine dither")
    return linear_periodic_model(
        name, d.state_names, A0, B0, values, amplitude, frequency,
        SourceKind.FMU, _frequency_dependent(at_other, step, A0, B0, zero))


def _without(values, name):
    """``values`` without ``name``, as a hashable tuple of pairs."""
    return tuple((n, v) for n, v in values.items() if n != name)


def _frequency_dependent(at_other, step, A0, B0, zero):
    """Whether ``A0`` or ``B0`` change with the frequency parameter beyond
    the dither's cosine: ``at_other`` is the Jacobian read again at t = 0
    with the frequency at :data:`OTHER_FREQUENCY` times its value."""
    A, Ja, _ = at_other["jacobians"]
    scale = max(np.abs(A0).max(), 1.0)
    return bool(np.abs(A[0] - A0).max() > zero * scale
                or np.abs((Ja[0] - A[0]) / step - B0).max()
                > zero * max(np.abs(B0).max(), np.finfo(float).tiny))


@lru_cache(maxsize=8)
def _sampled(path, content, amplitude, step, requests):
    """The Jacobians of :func:`sources.fmu_host.sample` (read-only) for
    each ``(values, times)`` of ``requests``, read in one child process,
    once per FMU content and parameter set (a command asks for the same
    linearisation for its estimates and its work). The FMU's binary
    runs in a child process: a crash, a hang or a NaN of it becomes an
    :class:`FmuError` naming the call."""
    d = _described(path, content)
    sampled = sample_isolated([SampleJob(
        path=d.path, folder="", guid=d.guid,
        model_identifier=d.model_identifier, fmi_version=d.fmi_version,
        directional=d.directional, states=d.states,
        derivatives=d.derivatives, references=d.references,
        values=dict(values), amplitude=amplitude,
        amplitudes=(0.0, step, 2 * step), times=times)
        for values, times in requests], FmuError)
    for arrays in sampled:
        for array in arrays.values():
            array.setflags(write=False)
    return tuple(sampled)


def _steady_slip(d, A0, rate, moved, along, zero):
    """The start is a steady slip along which the Jacobian is fixed.

    As :func:`sources.modelica.linearize` checks it, with Jacobians
    instead of expressions (residuals below ``zero`` relative count as
    none): a Jacobian that a generic move of the states
    (``moved``) leaves unchanged is free of the states (the paper's
    linear clutch) and needs nothing more; otherwise ``A0 der(x) = 0``
    (no acceleration builds up) and the Jacobian one period further
    along the slip (``along``) must still be ``A0``.
    """
    size = max(np.abs(A0).max(), 1.0)
    if np.abs(moved - A0).max() <= zero * size:
        return
    check_no_acceleration(d.model_name, d.state_names, A0, rate, FmuError)
    _require(np.abs(along - A0).max() <= zero * size,
             f"{d.model_name}: the linearisation changes along the slip; "
             "allowed: forces that depend on angles linearly")


def _values(d, overrides):
    return checked_values(d.specs, d.starts, overrides,
                          f"a Real parameter of {d.model_name}")


@dataclass(frozen=True)
class FmuParameters(NamedParameters):
    """A parameter set of an FMU, by the FMU's variable names (SI).

    The parameter-set interface of
    :class:`sources.modelica.ModelicaParameters`; :meth:`linear_model`
    is :func:`linearize_fmu`, which :func:`stability.build_driveline`
    uses instead of the paper's matrices.

    Attributes
    ----------
    path : str
    values : dict
        Every Real parameter, SI.
    amplitude, frequency : str
    """

    path: str
    values: dict = None
    amplitude: str = "p_f"
    frequency: str = "f_dither"
    #: A third-party FMU: its Jacobian only, no time-domain run.
    source_kind: ClassVar[SourceKind] = SourceKind.FMU

    def __post_init__(self):
        object.__setattr__(self, "values", _values(
            fmu_description(self.path), dict(self.values or {})))

    @property
    def model(self):
        """The FMU's ``modelName``."""
        return fmu_description(self.path).model_name

    @property
    def specs(self):
        """Unit, bounds and description of the Real parameters."""
        return fmu_description(self.path).specs

    def replace(self, **changes):
        """A copy with some values changed (validated)."""
        return FmuParameters(self.path, {**self.values, **changes},
                             self.amplitude, self.frequency)

    def linear_model(self):
        """:func:`linearize_fmu` of the FMU at these values, once per FMU
        content and values (the studies of one command share it)."""
        return _linearized(self.path, digest(self.path),
                           tuple(self.values.items()), self.amplitude,
                           self.frequency)


@lru_cache(maxsize=8)
def _linearized(path, content, values, amplitude, frequency):
    """:func:`linearize_fmu`, cached by its arguments and the FMU's
    content (:func:`fmu.store.digest`)."""
    return linearize_fmu(path, dict(values), amplitude, frequency)
