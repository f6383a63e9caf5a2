r"""Linear time-periodic system of a driveline written in Modelica.

The project's compiler (:func:`fmu.frontend.load_flat_model`,
:func:`fmu.backend.to_ode`) turns a Modelica class into ``der(x) = f(t, x,
p)`` as CasADi expressions. :func:`linearize` takes the Jacobian
:math:`J = \partial f / \partial x` (``casadi.jacobian``) at the slipping
operating condition (the start values of the class) and splits it along
the dither amplitude ``p_f``:

.. math:: J(t) = A_0 + p_f \cos(2\pi f t)\, B

which is Eq. (6)-(7) of the paper for any driveline, not just the 4-DOF
chain: :math:`B` may have any rank (two clutches with dither, a gear). The
split is checked, not assumed: ``J`` must be affine in ``p_f``
(:math:`\partial^2 J/\partial p_f^2 = 0`), its constant part must not
depend on time, and its ``p_f`` part must be the cosine of the dither
frequency parameter times one matrix; otherwise :class:`ModelicaError`
says what differs.

A class with Integer and Boolean variables (a clutch on MSL's
``Rotational.Interfaces.PartialFriction``: stuck, forward and backward
sliding) is linearised in the mode of its operating point, found by an
event iteration at the start values (:func:`operating_mode`,
:mod:`sources.modes`); a dither setting that leaves that mode within a
period is refused (:func:`check_mode`).

The rigid-body directions of the result are removed in :mod:`stability`
(:mod:`stability.reduction`), once per model.

Nothing here knows a driveline's name: a class of ``modelica/Judder`` or
of the user's own package, with parameters set by their Modelica names.
"""

import dataclasses
from dataclasses import dataclass
from typing import ClassVar
from functools import lru_cache
from pathlib import Path

import casadi
import numpy as np

from fmu.backend import to_ode
from fmu.classes import library_folders
from fmu.frontend import (FrontEndError, find_class, load_flat_model,
                          modelica_path)
from fmu.precheck import refuse_bound, refuse_undeclared, refuse_unsupported
from infra.errors import JudderError, ParameterError

from .kinds import SourceKind
from .mode_check import first_changes
from .modes import (describe_mode, fixed_mode, mode_values,
                    on_switching_surface, uses_initial)
from drivelines.specs import ParameterSpec, allowed_names, parse_overrides

__all__ = ["LIBRARY", "ModelicaError", "LinearPeriodicModel",
           "ModelicaParameters", "compile_class", "parameter_specs",
           "linearize", "linear_periodic_model", "NamedParameters",
           "check_dither_declared",
           "check_no_acceleration"]

#: The project's Modelica library (package ``Judder``).
LIBRARY = Path(__file__).resolve().parents[1] / "modelica"
#: Relative size below which a singular value, a Jacobian entry or a
#: residual of the checks counts as zero (round-off of the compiler's
#: expressions is near 1e-16).
_ZERO = 1e-10
#: Sample times per dither period used to check the waveform.
_SAMPLES = 16


class ModelicaError(JudderError):
    """The Modelica class cannot be analysed; the message says why."""


def _source(class_name, roots):
    """The ``.mo`` file of ``class_name`` in one of the library roots."""
    try:
        return find_class(class_name, roots)[0]
    except FrontEndError:
        raise ModelicaError(
            f"modelica = {class_name!r} is not found in "
            f"{', '.join(str(r) for r in roots)} (`library`, the project's "
            "library and MODELICAPATH); allowed: a class whose file is "
            "<library>/<Package>/.../<Class>.mo or in a package.mo") from None


def _roots(library):
    """The library roots of a class: ``library`` (one folder or
    several, :func:`fmu.classes.library_folders`; a root may be a ``.mo``
    file holding a whole package, as for :mod:`fmu`), the project's and
    those of ``MODELICAPATH``."""
    folders = library_folders(library)
    for folder in folders:
        if not (folder.is_dir() or folder.suffix == ".mo"
                and folder.is_file()):
            raise ModelicaError(f"`library` {str(folder)!r} is neither a "
                                "folder nor a .mo file; allowed: a folder "
                                "holding Modelica packages, or one .mo file "
                                "holding a whole package")
    return modelica_path(folders + [LIBRARY])


@lru_cache(maxsize=16)
def flat_class(class_name, library=None):
    """The flat model of a Modelica class with its Integer and Boolean
    variables (:func:`fmu.frontend.load_flat_model` with ``hybrid``),
    cached per class and library; see :func:`compile_class`."""
    roots = _roots(library)
    return load_flat_model(_source(class_name, roots), class_name,
                           roots=[str(r) for r in roots], hybrid=True)


@lru_cache(maxsize=16)
def check_dither_declared(class_name, library=None, amplitude="p_f",
                          frequency="f_dither"):
    """Refuse, from the source and before the class is flattened (10-30
    s for an MSL example), what the linearisation in one mode does not
    compile (:func:`fmu.precheck.refuse_unsupported` with ``hybrid``: an
    external table object), then a dither amplitude or frequency name
    the class certainly does not declare
    (:func:`fmu.precheck.refuse_undeclared`): MSL's ``Backlash`` or
    ``ElastoGap`` examples compile in one mode but have no dither, and
    without it there is nothing to linearise; then one the class binds
    to its own parameters, calculated rather than tunable
    (:func:`fmu.precheck.refuse_bound`: ``sine.f`` of MSL's ``First``)."""
    roots = _roots(library)
    folders = [str(r) for r in roots]
    refuse_unsupported(_source(class_name, roots), class_name, folders,
                       hybrid=True)
    names = {"amplitude": amplitude, "frequency": frequency}
    refuse_undeclared(class_name, folders, names)
    refuse_bound(class_name, folders, names)


@lru_cache(maxsize=64)
def compile_class(class_name, library=None, mode=None):
    """The compiled ODE of a Modelica class (cached per class, library and
    mode).

    Parameters
    ----------
    class_name : str
        Full name, e.g. ``Judder.Examples.Driveline4DOF``.
    library : str, tuple of str or None
        Folder (or folders, searched in order) holding the user's
        top-level packages; the project's library
        (:data:`LIBRARY`) and the folders of ``MODELICAPATH`` (the
        Modelica Standard Library, say) follow it on the path, so a
        user's model can use ``Judder.Components`` and
        ``Modelica.Mechanics.Rotational``.
    mode : tuple or None
        For a class with Integer and Boolean variables (MSL's
        ``PartialFriction``): ``(current, previous, initial)``, their
        values, those of their ``pre()`` and that of ``initial()``, fixed
        in the equations (:func:`sources.modes.fixed_mode`); None for
        their start values at the initialisation.

    Returns
    -------
    fmu.backend.OdeModel
        With a local ``judder_mode<k>`` per discrete variable: the value
        its equation gives in the mode (:func:`sources.modes.mode_values`).
    """
    flat = flat_class(class_name, library)
    if not flat.discretes:
        # initial() is false after the initialisation, where the
        # linearisation is
        return to_ode(fixed_mode(flat, (), (), 0.0) if uses_initial(flat)
                      else flat)
    if mode is None:
        starts = tuple(d.start for d in flat.discretes)
        mode = (starts, starts, 1.0)
    return to_ode(fixed_mode(flat, *mode))


@dataclass(frozen=True, eq=False)
class LinearPeriodicModel:
    r"""Eq. (6)-(7) of a compiled Modelica class or an FMU.

    .. math:: \dot x = (A_0 + p_f \cos(\omega t) B) x

    The rigid-body reduction is :class:`stability.reduction.Reduction`
    of ``A0`` and ``B``. Compared by identity: one linearisation is one
    model.

    Attributes
    ----------
    class_name : str
    state_names : tuple of str
        The compiler's states ``x`` (e.g. ``inertia1.phi``, ``inertia1.w``).
    A0, B : ndarray, shape (n, n)
        Constant part (1/s) and modulation per Pa (1/(s Pa)) of the full
        Jacobian.
    omega2 : ndarray
        Eigenvalues of the undamped stiffness ``M^{-1} K`` read from the
        Jacobian (rows of speeds, columns of the angles whose derivative
        they are), (rad/s)^2, ascending; empty if the states are not
        angle/speed pairs.
    values : dict
        Every tunable parameter's value used, by Modelica name (SI).
    amplitude, frequency : str
        Names of the dither amplitude and frequency parameters.
    source_kind : sources.kinds.SourceKind
        ``MODELICA`` or ``FMU``: where the Jacobian was read.
    mode : tuple of (str, str)
        The Integer and Boolean variables of a hybrid class (MSL's
        ``PartialFriction``) and their values in the mode it is
        linearised in (``("clutch.mode", "1 (clutch.Forward)")``); empty
        for a class without.
    frequency_dependent : bool
        ``A0`` or ``B`` change with the frequency parameter beyond the
        dither's cosine (a valve's roll-off written with ``f_dither``):
        the model holds at ``values[frequency]`` only, and a study at
        another frequency must be linearised there.
    """

    class_name: str
    state_names: tuple
    A0: np.ndarray
    B: np.ndarray
    omega2: np.ndarray
    values: dict
    amplitude: str
    frequency: str
    source_kind: SourceKind
    frequency_dependent: bool = False
    mode: tuple = ()


@lru_cache(maxsize=16)
def parameter_specs(class_name, library=None):
    """Unit, bounds and description of every tunable parameter of a class.

    Returns
    -------
    dict of str to drivelines.specs.ParameterSpec
        In the order of the compiled model; bounds from ``min``/``max``.
    """
    specs = {}
    for quantity in compile_class(class_name, library).parameters:
        bounds = {}
        for key, bound in (("lower", quantity.minimum),
                           ("upper", quantity.maximum)):
            if bound is not None and not casadi.symvar(casadi.SX(bound)):
                bounds[key] = float(casadi.evalf(bound))
        specs[quantity.name] = ParameterSpec(
            quantity.name, quantity.unit or "1",
            quantity.description or quantity.name, **bounds)
    return specs


def _parameter_values(ode, overrides, class_name, library):
    specs = parameter_specs(class_name, library)
    return checked_values(specs, {q.name: q.start for q in ode.parameters},
                          overrides, f"a tunable parameter of {class_name}")


def checked_values(specs, starts, overrides, what):
    """Every parameter's value: its override, else its start, each checked
    against the bounds of its declaration (``specs``).

    Raises
    ------
    ParameterError
        For an override of a name not in ``specs`` (``what`` says what the
        names are) or a value outside its bounds.
    """
    unknown = sorted(set(overrides) - set(specs))
    if unknown:
        raise ParameterError(
            f"{unknown[0]} = {overrides[unknown[0]]!r} is not {what}; "
            f"allowed: {allowed_names(specs)}")
    return {name: specs[name].check(overrides.get(name, start))
            for name, start in starts.items()}


class NamedParameters:
    """``--set`` and lookup by name for a parameter set whose names come
    from a model (a Modelica class, an FMU): the subclass gives
    ``values``, ``specs``, ``model`` and ``replace``."""

    #: A class or an FMU carries its friction law in its own equations:
    #: no friction table (:attr:`sources.Parameters.friction`).
    friction = None

    def __getitem__(self, name):
        try:
            return self.values[name]
        except KeyError:
            raise ParameterError(
                f"{name!r} is not a tunable parameter of {self.model}; "
                f"allowed: {allowed_names(self.values)}") from None

    def with_overrides(self, assignments):
        """Apply ``NAME=VALUE`` strings, as given to ``--set`` (see
        :func:`drivelines.specs.parse_overrides`)."""
        return self.replace(**parse_overrides(assignments, self.specs,
                                              self.model))

    def as_dict(self):
        """Plain ``dict`` of the values (SI)."""
        return dict(self.values)


@dataclass(frozen=True)
class ModelicaParameters(NamedParameters):
    """A parameter set of a Modelica class, by Modelica names (SI).

    The parameter-set interface the application uses for the paper's
    drivelines (:class:`drivelines.Parameters`: ``model``, ``specs``,
    ``replace``, ``with_overrides``, ``as_dict``, ``source_kind``), plus
    :meth:`linear_model`, the linear time-periodic system, which
    :func:`stability.source.build_driveline` uses instead of the paper's
    matrices.

    Attributes
    ----------
    class_name : str
    library : str, tuple of str or None
        As :func:`compile_class` takes it.
    values : dict
        Every tunable parameter, SI.
    amplitude, frequency : str
        Names of the dither amplitude and frequency parameters.
    """

    class_name: str
    library: object = None
    values: dict = None
    amplitude: str = "p_f"
    frequency: str = "f_dither"
    #: A Modelica class: linearised from its equations, its FMU runs.
    source_kind: ClassVar[SourceKind] = SourceKind.MODELICA

    def __post_init__(self):
        ode = compile_class(self.class_name, self.library)
        object.__setattr__(self, "values", _parameter_values(
            ode, dict(self.values or {}), self.class_name, self.library))

    @property
    def model(self):
        """The class name (what the results report as ``model``)."""
        return self.class_name

    @property
    def specs(self):
        """:func:`parameter_specs` of the class."""
        return parameter_specs(self.class_name, self.library)

    def replace(self, **changes):
        """A copy with some values changed (validated)."""
        return ModelicaParameters(self.class_name, self.library,
                                  {**self.values, **changes},
                                  self.amplitude, self.frequency)

    @property
    def speed_states(self):
        """Names of the states in rad/s (the bodies' speeds)."""
        return [s.name for s in compile_class(self.class_name,
                                              self.library).states
                if s.unit == "rad/s"]

    def check_mode(self, freq_hz, p_f):
        """Refuse dither settings (Hz, Pa; scalars or sequences of one
        length) at which a hybrid class leaves the mode it is linearised
        in (:func:`check_mode`), once per values and setting (the
        report's tongues and sensitivity check the same ones)."""
        check_mode(self.class_name, self.library, self.values,
                   self.frequency, self.amplitude, freq_hz, p_f)

    def linear_model(self):
        """:func:`linearize` of the class at these values, once per class
        and values (the studies of one command share it)."""
        return _linearized(self.class_name, self.library,
                           tuple(self.values.items()), self.amplitude,
                           self.frequency)


@lru_cache(maxsize=16)
def _linearized(class_name, library, values, amplitude, frequency):
    """:func:`linearize`, cached by its (hashable) arguments."""
    return linearize(class_name, library, dict(values), amplitude, frequency)


#: Ratio of the second value of the frequency parameter at which ``A0``
#: and ``B`` are read, to tell whether they depend on it beyond the
#: dither's cosine (:attr:`LinearPeriodicModel.frequency_dependent`).
OTHER_FREQUENCY = 0.8


def _require(condition, message):
    if not condition:
        raise ModelicaError(message)


def _require_dither(names, class_name, amplitude, frequency):
    """The dither's amplitude and frequency are among the parameters
    ``names`` of the class."""
    for role, name in (("amplitude", amplitude), ("frequency", frequency)):
        _require(name in names, f"{role} = {name!r} is not a parameter of "
                 f"{class_name}; allowed: {allowed_names(names)}")


def _undamped_omega2(A0, names):
    """``M^-1 K`` from the rows ``der(w)`` and the columns ``phi`` with
    ``der(phi) = w``; empty if the states are not such pairs."""
    size = len(A0)
    pairs = {}
    for i in range(size):
        row = A0[i]
        hits = np.flatnonzero(row)
        if len(hits) == 1 and row[hits[0]] == 1.0 and hits[0] != i:
            pairs[i] = int(hits[0])
    positions = list(pairs)
    speeds = [pairs[i] for i in positions]
    if len(set(speeds)) != len(speeds) or \
            len(positions) + len(speeds) != size:
        return np.array([])
    stiffness = -A0[np.ix_(speeds, positions)]
    return np.sort(np.linalg.eigvals(stiffness).real)


def linearize(class_name, library=None, values=None, amplitude="p_f",
              frequency="f_dither"):
    """Linear time-periodic system of a Modelica driveline, Eq. (6)-(7).

    Parameters
    ----------
    class_name : str
        Full Modelica class name.
    library : str, tuple of str or None
        Folder(s) of the user's packages (see :func:`compile_class`).
    values : dict, optional
        Parameters by Modelica name (SI); the others keep their defaults.
    amplitude, frequency : str
        Names of the dither amplitude (Pa) and frequency (Hz) parameters.

    Returns
    -------
    LinearPeriodicModel

    Raises
    ------
    ModelicaError
        If the class does not compile, or its Jacobian is not of the form
        ``A0 + p_f cos(2 pi f t) B`` along a steady slip.
    ParameterError
        For an unknown parameter or a value outside its bounds.

    Examples
    --------
    >>> m = linearize("Judder.Examples.Driveline4DOF")
    >>> m.A0.shape, m.B.shape
    ((8, 8), (8, 8))
    """
    check_dither_declared(class_name, library, amplitude, frequency)
    ode = compile_class(class_name, library)
    values = _parameter_values(ode, dict(values or {}), class_name, library)
    names = [q.name for q in ode.parameters]
    _require_dither(names, class_name, amplitude, frequency)
    mode = ()
    if flat_class(class_name, library).discretes:
        _require(values[frequency] > 0, f"{frequency} = "
                 f"{values[frequency]!r} Hz is not allowed; allowed: > 0")
        ode, current = operating_mode(class_name, library,
                                      tuple(values.items()), frequency)
        mode = describe_mode(flat_class(class_name, library), current)
    x = casadi.vertcat(*[s.expression for s in ode.states])
    p = casadi.vertcat(*[q.expression for q in ode.parameters])
    t, pf = ode.time, ode.parameters[names.index(amplitude)].expression
    start = casadi.Function("start", [p], [casadi.vertcat(
        *[s.start for s in ode.states])])
    vector = np.array([values[n] for n in names])
    x0 = np.asarray(start(vector)).ravel()
    f0 = values[frequency]
    _require(f0 > 0, f"{frequency} = {f0!r} Hz is not allowed; allowed: > 0")
    times = np.arange(_SAMPLES) / (_SAMPLES * f0)
    derivatives = _held_relations(class_name, ode, x, p, x0, vector, times)

    jac = casadi.jacobian(derivatives, x)
    d_pf = casadi.jacobian(casadi.vec(jac), pf)
    _require(not casadi.depends_on(d_pf, pf),
             f"{class_name}: the Jacobian is not affine in {amplitude} (the "
             "dither amplitude multiplies the states nonlinearly); allowed: "
             "J = A0 + p_f cos(2 pi f t) B")
    functions = casadi.Function("lin", [t, x, p], [
        jac, casadi.reshape(d_pf, jac.shape), derivatives])
    mean = vector.copy()
    mean[names.index(amplitude)] = 0.0

    def evaluate(time, params):
        return [np.asarray(out) for out in functions(time, x0, params)]

    A0, B0, rate = evaluate(0.0, mean)
    scale = max(np.abs(A0).max(), 1.0)
    for time in times:
        b = evaluate(time, vector)[1]
        a_mean = evaluate(time, mean)[0]
        _require(np.abs(a_mean - A0).max() <= _ZERO * scale,
                 f"{class_name}: the Jacobian without dither changes with "
                 "time; allowed: time enters through the dither only")
        _require(np.abs(b - np.cos(2 * np.pi * f0 * time) * B0).max()
                 <= _ZERO * max(np.abs(B0).max(), 1e-300),
                 f"{class_name}: the dither does not enter as "
                 f"{amplitude}*cos(2*pi*{frequency}*time); allowed: the "
                 "cosine of Sources.DitherPressure")
    _steady_slip(class_name, ode, jac, x, A0, rate, vector, x0, t, p)
    # A0 and B read again with another value of the frequency parameter
    other = vector.copy()
    other[names.index(frequency)] *= OTHER_FREQUENCY
    other_mean = other.copy()
    other_mean[names.index(amplitude)] = 0.0
    frequency_dependent = bool(
        np.abs(evaluate(0.0, other_mean)[0] - A0).max() > _ZERO * scale
        or np.abs(evaluate(0.0, other)[1] - B0).max()
        > _ZERO * max(np.abs(B0).max(), 1e-300))
    model = linear_periodic_model(class_name,
                                  tuple(s.name for s in ode.states), A0, B0,
                                  values, amplitude, frequency,
                                  SourceKind.MODELICA, frequency_dependent)
    return dataclasses.replace(model, mode=mode)


#: Event iterations allowed to find the mode of the operating point.
_EVENT_ITERATIONS = 20


@lru_cache(maxsize=16)
def operating_mode(class_name, library, values, frequency):
    """The ODE in the mode of the operating point and that mode's values
    (of :attr:`fmu.frontend.FlatModel.discretes`), cached; ``values`` the
    parameters as ``(name, value)`` pairs (:func:`linearize`'s).

    The discrete variables start at their start values with
    ``initial()`` true, as at the initialisation; their equations are
    evaluated at the start values of the states (time 0, the parameters
    ``values``) and iterated, as an event iteration: until they give the
    values they were fixed at, then with ``pre()`` equal to those values
    and ``initial()`` false, until nothing changes. The mode must then
    hold over one dither period of the equations in that mode integrated
    from the start values (dither included): a slip that reaches zero or
    a normal force that drops to zero changes it, and is refused.
    """
    flat = flat_class(class_name, library)
    values = dict(values)
    vector = np.array(list(values.values()))
    current = previous = tuple(d.start for d in flat.discretes)
    initial = 1.0
    for _ in range(_EVENT_ITERATIONS):
        ode = compile_class(class_name, library, (current, previous, initial))
        now = tuple(np.asarray(mode_values(ode)(
            0.0, _start(ode, vector), vector)).ravel())
        if now != current:
            current = now
        elif previous != current or initial:
            previous, initial = current, 0.0
        else:
            _off_switching_surfaces(class_name, ode, flat, vector)
            _modes_hold(class_name, ode, flat, current, vector[None, :],
                        np.array([values[frequency]]))
            return ode, current
    raise ModelicaError(
        f"{class_name}: the Integer and Boolean variables do not settle in "
        f"{_EVENT_ITERATIONS} event iterations at the operating point (the "
        "start values); allowed: an operating point in one mode (a clutch "
        "slipping)")


#: Characters of a relation written in a message (CasADi's text of a
#: long one is cut).
_RELATION_TEXT = 80


def _off_switching_surfaces(class_name, ode, flat, vector):
    """Refuse an operating point on a switching surface: a relation of
    the discrete variables' equations whose two sides are equal at the
    start values (a relay ``w > 0`` at ``w = 0``) and on whose two sides
    the mode differs (:func:`sources.modes.on_switching_surface`): the
    mode found there depends on whether the relation is strict, not on
    the states."""
    for k, text, value, below, above in on_switching_surface(ode, vector):
        if len(text) > _RELATION_TEXT:
            text = text[:_RELATION_TEXT - 3] + "..."
        discrete = flat.discretes[k]
        raise ModelicaError(
            f"{class_name}: the operating point (the start values) is on "
            f"the switching surface of the relation {text} in the "
            f"discrete equations ({discrete.name}, {discrete.where}): both "
            f"its sides are {value:g}, and {discrete.name} is "
            f"{describe_mode(flat, below)[k][1]} on one side, "
            f"{describe_mode(flat, above)[k][1]} on the other, so the mode "
            "is ambiguous and a linearisation holds on one side only; "
            "allowed: start values off the surface (a slip or an angle "
            "not at the switching value)")


def _start(ode, vector):
    """The start values of the states of ``ode`` at the parameters
    ``vector``."""
    return np.asarray(casadi.Function("start", [casadi.vertcat(
        *[q.expression for q in ode.parameters])], [casadi.vertcat(
            *[s.start for s in ode.states])])(vector)).ravel()


#: Dither settings whose mode check passed, by class, library, values,
#: dither names and setting (the report's tongues and sensitivity check
#: the same ones); emptied when it holds :data:`_REMEMBERED` of them.
_PASSED = set()
_REMEMBERED = 65536


def check_mode(class_name, library, values, frequency, amplitude, freq_hz,
               p_f):
    """Refuse dither settings (``freq_hz``, ``p_f``: Hz and Pa, scalars or
    sequences of one length) at which a hybrid class leaves the mode it
    is linearised in within a dither period (see
    :func:`operating_mode`); nothing for a class without Integer and
    Boolean variables. A setting that passed is remembered; the others
    are checked together (:func:`sources.mode_check.first_changes`), the
    first one in the order given that fails is named."""
    if not flat_class(class_name, library).discretes:
        return
    _require_dither(list(values), class_name, amplitude, frequency)
    key = (class_name, library, tuple(values.items()), frequency, amplitude)
    settings = [(float(f), float(p)) for f, p in np.broadcast(
        np.atleast_1d(freq_hz), np.atleast_1d(p_f))]
    settings = list(dict.fromkeys(
        setting for setting in settings if key + setting not in _PASSED))
    if not settings:
        return
    ode, current = operating_mode(class_name, library, tuple(values.items()),
                                  frequency)
    vectors = np.array([list({**values, frequency: f,
                              amplitude: p}.values()) for f, p in settings])
    _modes_hold(class_name, ode, flat_class(class_name, library), current,
                vectors, np.array([f for f, _ in settings]), [
                    f"the dither setting {frequency} = {f:g} Hz, "
                    f"{amplitude} = {p:g} Pa" for f, p in settings])
    if len(_PASSED) > _REMEMBERED:
        _PASSED.clear()
    _PASSED.update(key + setting for setting in settings)


def _modes_hold(class_name, ode, flat, mode, vectors, frequencies,
                settings=("the operating point (the start values, dither "
                          "included)",)):
    """Refuse a mode that changes within a dither period at one of the
    settings (parameter ``vectors``, dither ``frequencies``; ``settings``
    names them in the message): the equations in the mode are integrated
    over one period from the start values and the discrete variables'
    equations evaluated at :data:`sources.mode_check.SAMPLES` times and
    just past each zero crossing of their relations
    (:func:`sources.mode_check.first_changes`)."""
    change = first_changes(ode, _live(ode, ode.derivatives), mode, vectors,
                           frequencies)
    if change is None:
        return
    member, time, now, failure = change
    period = 1.0 / frequencies[member]
    _require(not failure, f"{class_name}: the equations in the mode "
             f"{describe_mode(flat, mode)} could not be integrated over a "
             f"dither period of {period:.4g} s ({failure}); allowed: "
             "an operating point whose mode can be checked")
    k = int(np.flatnonzero(np.asarray(now) != np.asarray(mode))[0])
    raise ModelicaError(
        f"{class_name}: {flat.discretes[k].name} "
        f"({flat.discretes[k].where}) changes from "
        f"{describe_mode(flat, mode)[k][1]} to "
        f"{describe_mode(flat, tuple(now))[k][1]} at t = {time:.4g} s "
        f"within a dither period of {settings[member]}; allowed: an "
        "operating point that "
        "stays in one mode (a slip that keeps its sign, a normal "
        "force above zero)")


def _live(ode, expression):
    """``expression`` with each relation symbol of ``ode`` replaced by the
    relation itself (those inside relations too, as in ElastoBacklash):
    a formula in ``t, x, p`` evaluated as it goes, not held."""
    if not ode.relations:
        return expression
    symbols = casadi.vertcat(*[r.expression for r in ode.relations])
    values = casadi.vertcat(*[r.minimum for r in ode.relations])
    for _ in ode.relations:
        if not casadi.depends_on(values, symbols):
            break
        values = casadi.substitute(values, symbols, values)
    return casadi.substitute(expression, symbols, values)


def _off_held_surfaces(class_name, ode, x, p, x0, vector):
    """Refuse an operating point on the switching surface of a relation
    that triggers events (``if w > 0`` in an equation): its indicator
    ``lhs - rhs`` is zero at the start values and depends on the states,
    so the value held, and with it the branch linearised, is decided by
    the relation's strictness, not by the states."""
    indicators = casadi.vertcat(*[r.maximum for r in ode.relations])
    values = np.asarray(casadi.Function("indicators", [ode.time, x, p], [
        _live(ode, indicators)])(0.0, x0, vector)).ravel()
    for k in np.flatnonzero(values == 0.0):
        relation = ode.relations[k]
        node = casadi.SX(relation.minimum)
        if casadi.depends_on(casadi.SX(relation.maximum), x) and \
                node.n_dep() == 2:
            text = str(node)
            if len(text) > _RELATION_TEXT:
                text = text[:_RELATION_TEXT - 3] + "..."
            side = float(casadi.Function("side", [ode.time, x, p], [
                _live(ode, node.dep(0))])(0.0, x0, vector))
            raise ModelicaError(
                f"{class_name}: the operating point (the start values) is "
                f"on the switching surface of the {relation.description}, "
                f"{text}: both its sides are {side:g}, so the value held, "
                "and the branch of the equations linearised, is decided "
                "by the relation's strictness, not by the states, and "
                "holds on one side only; allowed: start values off the "
                "surface (a slip or an angle not at the switching value)")


def _held_relations(class_name, ode, x, p, x0, vector, times):
    """``der(x)`` with each relation that triggers events (``time <
    startTime`` of MSL's ``Step``, ``if w > 0``) held at its value at the
    operating point, as the FMU holds it between events.

    The relations are evaluated along the steady slip ``x0 + t der(x)``
    over one dither period (``times``); one that changes there has no
    single linearisation and is refused, naming its place.
    """
    if not ode.relations:
        return ode.derivatives
    symbols = casadi.vertcat(*[r.expression for r in ode.relations])
    relations = casadi.Function("relations", [ode.time, x, p], [
        _live(ode, casadi.vertcat(*[r.minimum for r in ode.relations]))])
    held = np.asarray(relations(0.0, x0, vector)).ravel()
    _off_held_surfaces(class_name, ode, x, p, x0, vector)
    derivatives = casadi.substitute(ode.derivatives, symbols,
                                    casadi.DM(held))
    rate = np.asarray(casadi.Function("rate", [ode.time, x, p], [
        derivatives])(0.0, x0, vector)).ravel()
    for time in times:
        now = np.asarray(relations(time, x0 + time * rate, vector)).ravel()
        for changed in np.flatnonzero(now != held):
            raise ModelicaError(
                f"{class_name}: the {ode.relations[changed].description} "
                f"changes at t = {time:.4g} s within a dither period of the "
                "operating point (the start values); allowed: relations "
                "that hold their value over the period (a step's startTime "
                "after it, say)")
    return derivatives


def linear_periodic_model(name, state_names, A0, B0, values, amplitude,
                          frequency, source_kind, frequency_dependent=False):
    """The :class:`LinearPeriodicModel` of ``A0 + p_f cos(2 pi f t) B0``.

    Checks that the dither enters and reads the undamped ``w^2``; shared
    by :func:`linearize` and the FMU path (:mod:`sources.fmus`).

    Parameters
    ----------
    name : str
        Where the system comes from (class name or FMU).
    state_names : tuple of str
    A0, B0 : ndarray, shape (n, n)
        Constant part (1/s) and modulation per Pa of the Jacobian.
    values : dict
        Parameter values used (SI).
    amplitude, frequency : str
        Names of the dither amplitude and frequency parameters.
    source_kind : sources.kinds.SourceKind
    frequency_dependent : bool
        See :class:`LinearPeriodicModel`.

    Returns
    -------
    LinearPeriodicModel
    """
    # without a modulated damping (no clutch, or the dither parameter
    # unused) there is nothing to analyse
    _require(np.isfinite(B0).all() and np.abs(B0).max() > 0,
             f"{name}: the dither {amplitude} does not enter the "
             "linearised equations (no clutch damping is modulated); "
             "allowed: a driveline with a clutch whose pressure is "
             f"{amplitude}")
    return LinearPeriodicModel(
        class_name=name, state_names=state_names, A0=A0, B=B0,
        omega2=_undamped_omega2(A0, state_names), values=values,
        amplitude=amplitude, frequency=frequency, source_kind=source_kind,
        frequency_dependent=frequency_dependent)


def _derivative_state(row):
    """Index of the state whose value ``der(x_i)`` is, from row ``i`` of
    the Jacobian (``der(phi) = w``: one entry, 1), or None."""
    size = np.abs(row).max()
    entries = np.flatnonzero(np.abs(row) > 1e-12 * size) if size else []
    if len(entries) == 1 and np.isclose(row[entries[0]], 1.0, rtol=1e-9,
                                        atol=0):
        return int(entries[0])
    return None


def check_no_acceleration(name, state_names, A0, rate, error):
    """``A0 der(x) = 0`` at the start: no acceleration builds up along the
    slip, else ``error`` naming what changes: the acceleration
    ``der(w)`` of a speed ``w`` that is the derivative of an angle state
    (the row of the angle), else the derivative of the state whose
    derivative changes most."""
    scale = np.abs(A0).max() * max(np.abs(rate).max(), 1.0)
    drift = A0 @ rate
    moving = np.flatnonzero(np.abs(drift) > 1e-8 * scale)
    if not len(moving):
        return
    speeds = {i: _derivative_state(A0[i]) for i in moving}
    named = [i for i in moving if speeds[i] is not None]
    worst = max(named or moving, key=lambda i: abs(drift[i]))
    what = (f"der({state_names[speeds[worst]]}) = {drift[worst]:.3g} at "
            "the start, not 0" if speeds[worst] is not None else
            f"der({state_names[worst]}) changes at {drift[worst]:.3g} per "
            "second")
    raise error(f"{name}: the start values are not a steady slip ({what}); "
                "allowed: start speeds and spring deflections in "
                "equilibrium without dither")


def _steady_slip(class_name, ode, jac, x, A0, rate, vector, x0, t, p):
    """The operating condition is a steady slip along which ``J`` is fixed.

    Along ``x0 + t der(x)(x0)`` the Jacobian stays ``A0`` if it does not
    depend on the states that move (the angles) and ``A0 der(x) = 0``
    (no acceleration builds up). A Jacobian free of the states (the
    paper's linear clutch) needs neither.
    """
    rate = np.asarray(rate).ravel()
    if not any(casadi.depends_on(jac, x[i]) for i in range(x.shape[0])):
        return
    check_no_acceleration(class_name, [q.name for q in ode.states], A0,
                          rate, ModelicaError)
    for i, quantity in enumerate(ode.states):
        if abs(rate[i]) > _ZERO * max(np.abs(rate).max(), 1.0) and \
                casadi.depends_on(jac, x[i]):
            raise ModelicaError(
                f"{class_name}: the linearisation depends on "
                f"{quantity.name}, which drifts along the slip; allowed: "
                "forces that depend on angles linearly")
