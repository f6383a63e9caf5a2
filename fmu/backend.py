"""Structural back end: from a flat acausal DAE to an explicit ODE.

The steps are those of a Modelica tool's back end, on CasADi expressions:

1. **Parameters.** A parameter whose binding is a literal is a tunable
   input of the ODE; one bound to an expression of other parameters is
   calculated from them.
2. **Alias elimination.** Equations ``a = b`` or ``a = -b`` between two
   variables, which ``connect`` produces in numbers, remove one variable.
   A state keeps precedence over an algebraic variable, and a state with a
   fixed start value over one without.
3. **Index reduction.** After aliasing, an equation among states only
   (``phi_rel = flange_b.phi - flange_a.phi`` becomes ``phi_rel =
   inertia2.phi - inertia1.phi``) is a constraint: the states are not
   independent. One state in it is solved from it (the dummy-derivative
   choice), and its derivative is replaced by the time derivative of that
   solution, which differentiates the constraint once. The state chosen
   appears in the fewest constraints, so the bodies' absolute states are
   kept and the relative ones go. When no constraint is left, a
   derivative equal to a state (``der(phi) = w``) is substituted into an
   equation that then becomes one (``w_rel = der(b.phi) - der(a.phi)``
   gives ``w_rel = b.w - a.w``), so a clutch's stuck branch
   ``der(w_rel) = 0`` differentiates the relative angle twice.
4. **Sorting.** The remaining equations are matched to the unknowns (the
   derivatives and the algebraic variables) by
   :func:`scipy.sparse.csgraph.maximum_bipartite_matching`, and split into
   strongly connected blocks (:func:`scipy.sparse.csgraph.connected_components`)
   in dependency order (BLT form).
5. **Solving.** Each block must be linear in its unknowns; it is solved
   symbolically (one unknown: division; several: ``casadi.solve``).

The result is an :class:`OdeModel`: ``der(x) = f(t, x, p)`` and the
outputs ``y = h(t, x, p)`` as CasADi functions, ready for code generation.
"""

import dataclasses
from dataclasses import dataclass, field

import casadi
import numpy as np
from scipy.sparse import csr_matrix
from scipy.sparse.csgraph import connected_components, maximum_bipartite_matching

from .balance import excess
from .frontend import FrontEndError

__all__ = ["OdeModel", "Quantity", "to_ode"]

#: Hysteresis of an event indicator (:func:`_with_hysteresis`) in units of
#: its first-order rounding: a slip of two speeds near 105 rad/s gets
#: 4.7e-12 rad/s (the Judder clutch, locked in Model Exchange, keeps it as
#: its slip), a gap of plates 0.1 m from the origin 4e-15 m.
HYSTERESIS_ROUNDINGS = 100
#: The least hysteresis, where the rounding is zero (an indicator of
#: parameters, a state at zero): a root then still lies where the
#: relation has changed.
HYSTERESIS_FLOOR = 1e-300


class BackEndError(FrontEndError):
    """The flat model cannot be turned into an ODE; says which equations."""


@dataclass
class Quantity:
    """A named scalar of the ODE model: state, parameter or output.

    ``expression`` is the symbol (states, parameters) or the formula in
    states, parameters and time (outputs, calculated parameters); ``start``
    is a number for tunable parameters and a formula in the parameters for
    states.
    """

    name: str
    unit: str
    description: str
    expression: object
    start: object = None
    minimum: object = None
    maximum: object = None
    quantity: str = ""
    display_unit: str = ""


def _quantity(variable, expression, **values):
    """A Quantity named, typed and described like ``variable``."""
    return Quantity(variable.name, variable.unit, variable.description,
                    expression, quantity=variable.quantity,
                    display_unit=variable.display_unit, **values)


@dataclass
class OdeModel:
    """Explicit ODE of a Modelica model.

    Attributes
    ----------
    name : str
    time : casadi.SX
    states : list of Quantity
        Minimal state vector ``x``; ``start`` is a formula in ``p``.
    derivatives : casadi.SX, shape (n,)
        ``der(x)`` as a formula in ``t, x, p``.
    parameters : list of Quantity
        Tunable parameters with their default values.
    inputs : list of Quantity
        Inputs ``u`` (causality input) with their start values; in the
        functions and the C code they follow the parameters in ``p``.
    relations : list of Quantity
        Relations that generate events, whose values (held between
        events) follow the inputs in ``p``; ``expression`` is the symbol,
        ``minimum`` the relation and ``maximum`` ``lhs - rhs``, positive
        where it holds (``rhs - lhs`` for ``<``; the constant 1 for a
        combined when-condition, whose events are those of its parts),
        both formulas in ``t, x, p``.
    whens : list of (int, list of (str, casadi.SX))
        When-clauses: the relation that triggers each (index in
        ``relations``) and its reinit (state name, value in ``t, x, p``,
        ``pre(x)`` being ``x`` before the event).
    calculated : list of Quantity
        Parameters bound to formulas in ``p``.
    outputs : list of Quantity
        Outputs of the model as formulas in ``t, x, p``.
    locals : list of Quantity
        Every other variable of the model (algebraic variables, states
        removed by index reduction, outputs of components) as formulas
        in ``t, x, p``, one per distinct formula.
    aliases : list of (Quantity, str)
        Variables whose formula is that of a local, with its name.
    discretes : list of Quantity
        Integer and Boolean variables (MSL's ``PartialFriction``), held
        between events, whose values follow the relations' in ``p``;
        ``minimum`` is the equation's right-hand side in ``t, x, p``
        (the other discrete variables it names at the same instant
        substituted, the relations in it evaluated, ``pre()`` and the
        variables held in the continuous solution read from ``p``);
        ``maximum`` is 1 for a Boolean, None for an Integer.
    previous : list of Quantity
        ``pre()`` of each discrete variable, then ``initial()`` (1 while
        the FMU initialises) if the discrete equations use it; in ``p``
        after :attr:`discretes`.
    zeros : list of Quantity
        The rounding band of each relation
        (:attr:`fmu.frontend.Relation.zero`), 0 until the FMU finds the
        relation on its zero; last in ``p``.
    assertions : list of fmu.frontend.Assertion
        The model's ``assert(...)``, ``violated`` and ``values`` as
        formulas in ``t, x, p``.
    experiment : dict
    eliminated : dict
        Variables removed by aliasing and index reduction, as formulas.
    """

    name: str
    time: object
    states: list
    derivatives: object
    parameters: list
    calculated: list
    outputs: list
    experiment: dict
    eliminated: dict
    inputs: list = field(default_factory=list)
    relations: list = field(default_factory=list)
    whens: list = field(default_factory=list)
    locals: list = field(default_factory=list)
    aliases: list = field(default_factory=list)
    discretes: list = field(default_factory=list)
    previous: list = field(default_factory=list)
    assertions: list = field(default_factory=list)
    zeros: list = field(default_factory=list)

    def held(self):
        """Everything in ``p``: the tunable parameters, the inputs, the
        relations' values, the discrete variables and their ``pre()``
        (with ``initial()``)."""
        return self.parameters + self.inputs + self.relations + \
            self.discretes + self.previous + self.zeros

    def _symbols(self):
        x = _column(*[s.expression for s in self.states])
        p = _column(*[q.expression for q in self.held()])
        return x, p

    def jacobian(self):
        """CasADi function ``jacobian(t, x, p) -> J``: the derivatives of
        ``[der(x); y]`` with respect to ``[x; parameters; inputs]``
        (automatic differentiation), its structural nonzeros only, and
        its sparsity (the unknowns of FMI: the locals have no directional
        derivatives). Written densely, its C code grew as the square of
        the states (a 300-state chain: 98,400 operations, 7 min of gcc)."""
        x, p = self._symbols()
        known = len(self.parameters) + len(self.inputs)
        y = _column(*[o.expression for o in self.outputs])
        unknowns = casadi.vertcat(self.derivatives, y)
        knowns = casadi.vertcat(x, p[:known])
        jac = casadi.jacobian(unknowns, knowns)
        return (casadi.Function("jacobian", [self.time, x, p],
                                [jac]), jac.sparsity())

    def event_functions(self):
        """CasADi functions of the events: ``indicators(t, x, p) -> z``
        (each relation's indicator with its hysteresis,
        :func:`_with_hysteresis`), ``relations(t, x, p) -> r`` (the
        relations' values, 1 or 0), ``reinit(t, x, p, fired) -> x``
        (the states after the when-clauses flagged in ``fired``) and
        ``discretes(t, x, p) -> d`` (the discrete variables' equations)."""
        x, p = self._symbols()
        fired = casadi.SX.sym("fired", len(self.whens))
        after = [s.expression for s in self.states]
        names = [s.name for s in self.states]
        for k, (_, reinits) in enumerate(self.whens):
            for name, value in reinits:
                i = names.index(name)
                after[i] = casadi.if_else(fired[k] > 0.5, value, after[i])
        return (casadi.Function("indicators", [self.time, x, p], [
                    _with_hysteresis(self.relations, self.time, x, p)]),
                casadi.Function("relations", [self.time, x, p], [_column(
                    *[q.minimum for q in self.relations])]),
                casadi.Function("reinit", [self.time, x, p, fired],
                                [_column(*after)]),
                casadi.Function("discretes", [self.time, x, p], [_column(
                    *[q.minimum for q in self.discretes])]))

    def assert_function(self):
        """CasADi function ``asserts(t, x, p) -> a``: 1 for each assert
        violated (:attr:`assertions`, in order), then the values of
        their messages, one assert's after the other's."""
        x, p = self._symbols()
        return casadi.Function("asserts", [self.time, x, p], [_column(
            *[a.violated for a in self.assertions],
            *[v for a in self.assertions for v in a.values])])

    def functions(self, with_locals=False):
        """CasADi functions ``ode(t, x, p) -> der(x)``, ``outputs(t, x, p)
        -> y`` and ``start(p) -> x0``; ``p`` is the tunable parameters
        followed by the inputs; ``y`` is followed by the locals if
        ``with_locals``."""
        x, p = self._symbols()
        y = _column(*[o.expression for o in self.outputs
                      + (self.locals if with_locals else [])])
        x0 = _column(*[s.start for s in self.states])
        return (casadi.Function("ode", [self.time, x, p], [self.derivatives],
                                ["t", "x", "p"], ["xdot"]),
                casadi.Function("outputs", [self.time, x, p], [y],
                                ["t", "x", "p"], ["y"]),
                casadi.Function("start", [p], [x0], ["p"], ["x0"]))

    def parameter_vector(self, **values):
        """Default parameter (then input, relation, discrete) values, some
        changed by name."""
        names = [q.name for q in self.held()]
        unknown = sorted(set(values) - set(names))
        if unknown:
            raise KeyError(f"unknown parameter {unknown[0]!r}; tunable: "
                           f"{', '.join(names)}")
        return np.array([values.get(q.name, q.start) for q in self.held()],
                        dtype=float)


def _column(*items):
    """Column of SX expressions; an empty list gives a 0x1 SX (not a DM)."""
    return casadi.vertcat(casadi.SX(0, 1), *items)


def _value(expression):
    return float(casadi.evalf(expression))


def _split_parameters(model):
    """Tunable parameters with values, and calculated ones as formulas.

    Constants are substituted like calculated parameters but not
    exported. Returns ``(tunable, calculated, symbols, formulas)``: the
    last two substitute every calculated parameter and constant by its
    formula in the tunable parameters.
    """
    tunable, calculated, constants = [], [], []
    for v in model.variables:
        if v.role not in ("parameter", "constant"):
            continue
        binding = v.binding if v.binding is not None else v.start
        if binding is None:
            raise BackEndError(f"{v.where}: parameter {v.name} has no value")
        quantity = _quantity(v, v.symbol, minimum=v.minimum,
                             maximum=v.maximum)
        if v.role == "constant" or casadi.symvar(binding):
            quantity.expression = binding
            (constants if v.role == "constant" else calculated).append(
                (v.symbol, quantity))
        else:
            quantity.start = _value(binding)
            tunable.append(quantity)
    # resolve chains of calculated parameters down to tunable ones
    pairs = calculated + constants
    targets = _column(*[symbol for symbol, _ in pairs])
    values = _column(*[q.expression for _, q in pairs])
    for _ in range(len(pairs) + 1):
        values = casadi.substitute(values, targets, values)
    if casadi.depends_on(values, targets):
        raise BackEndError("parameter bindings are circular: " + ", ".join(
            q.name for _, q in pairs))
    for index, (_, quantity) in enumerate(pairs):
        quantity.expression = values[index]
    return tunable, [q for _, q in calculated], targets, values


class _System:
    """Residual equations with substitution bookkeeping."""

    def __init__(self, residuals, places, eliminated=None):
        self.residuals = list(residuals)
        self.places = list(places)                 # file:line of each
        self.eliminated = dict(eliminated or {})   # name -> formula
        #: algebraic loops solved: (equations described, unknowns, slope)
        self.loops = []
        #: states with a fixed start removed: (Variable, equation)
        self.fixed_dropped = []

    def remove(self, index):
        """Drop residual ``index`` (solved or eliminated)."""
        del self.residuals[index]
        del self.places[index]

    def describe(self, indices):
        """The equations ``indices`` with their place in the source."""
        return "; ".join(f"{self.places[i]}: 0 = {self.residuals[i]}"
                         for i in indices)

    def substitute(self, symbols, formulas):
        if len(symbols) != len(formulas):
            raise ValueError("one formula per symbol")
        if not symbols:
            return
        old = _column(*symbols)
        new = _column(*formulas)
        stacked = casadi.substitute(_column(*self.residuals), old, new)
        self.residuals = [stacked[i] for i in range(stacked.shape[0])]
        if self.eliminated:
            names = list(self.eliminated)
            values = casadi.substitute(
                _column(*self.eliminated.values()), old, new)
            self.eliminated = {n: values[i] for i, n in enumerate(names)}


def _linear_pair(residual, candidates):
    """``(a, b, sign)`` if ``residual`` is ``a - sign*b`` for two candidates."""
    symbols = casadi.symvar(residual)
    if len(symbols) != 2 or not all(s.name() in candidates for s in symbols):
        return None
    a, b = symbols
    grad = casadi.jacobian(residual, casadi.vertcat(a, b))
    if casadi.symvar(grad):
        return None
    ga, gb = (_value(grad[0]), _value(grad[1]))
    rest = casadi.substitute(residual, casadi.vertcat(a, b),
                             casadi.vertcat(0, 0))
    if abs(ga) != 1 or abs(gb) != 1 or _value(rest) != 0:
        return None
    return a, b, -gb / ga


def to_ode(model):
    """Turn a :class:`~fmu.frontend.FlatModel` into an :class:`OdeModel`.

    Raises
    ------
    BackEndError
        If the model is structurally singular, or needs to solve an
        equation that is not linear in its unknowns.
    """
    try:
        return _to_ode(model)
    except RuntimeError as exc:   # CasADi on an expression it cannot handle
        message = str(exc).strip().splitlines()[-1]
        raise BackEndError(f"{model.name}: the back end cannot compile this "
                           f"model: {message}") from None


def _to_ode(model):
    tunable, calculated, parameter_symbols, parameter_values = \
        _split_parameters(model)
    if not model.discretes:
        # the relations' rounding bands act in the event iteration of
        # discrete variables only; without them (a model fixed in one
        # mode, sources.modes.fixed_mode) they are 0 in every formula
        bands = [r.zero for r in model.relations + model.discrete_relations
                 if r.zero is not None]
        if bands:
            parameter_symbols = casadi.vertcat(parameter_symbols, *bands)
            parameter_values = casadi.vertcat(parameter_values,
                                              casadi.SX.zeros(len(bands)))
    inputs = [_quantity(v, v.symbol, start=_input_start(v),
                        minimum=v.minimum, maximum=v.maximum)
              for v in model.by_role("input")]
    states = {v.name: v for v in model.by_role("state")}
    unknown_vars = {v.name: v for v in model.variables
                    if v.role in ("algebraic", "output")}
    system = _System(model.residuals + model.initial_residuals,
                     (model.places or [""] * len(model.residuals))
                     + (model.initial_places
                        or [""] * len(model.initial_residuals)))
    # calculated parameters become formulas in the tunable ones
    system.substitute([parameter_symbols[i] for i in
                       range(parameter_symbols.shape[0])],
                      [parameter_values[i] for i in
                       range(parameter_values.shape[0])])
    initial = system.residuals[len(model.residuals):]
    for index in reversed(range(len(model.residuals), len(system.residuals))):
        system.remove(index)
    parameter_names = {q.name for q in tunable} | {q.name for q in inputs}

    held = _held_discretes(model)
    _eliminate_aliases(system, states, unknown_vars, parameter_names,
                       model.time)
    _reduce_index(system, states, {q.name for q in tunable} | {"time"}
                  | {r.symbol.name() for r in model.relations}
                  | {q.name() for q in held},
                  model.time, unknown_vars)
    derivatives = _solve_sorted(system, states, unknown_vars)

    order = [v for v in model.by_role("state") if v.name in states]
    starts = []
    for v in order:
        start = v.start if v.start is not None else casadi.SX(0)
        starts.append(casadi.substitute(start, parameter_symbols,
                                        parameter_values))
    if initial:
        starts = _initial_states(initial, order, starts, derivatives,
                                 system.eliminated, model,
                                 model.initial_places or [""] * len(initial))
    if model.initial is not None and model.initial_value is not None:
        # a number after the initialisation
        after = casadi.SX(model.initial_value)
        derivatives = {name: casadi.substitute(formula, model.initial, after)
                       for name, formula in derivatives.items()}
        system.eliminated = {
            name: casadi.substitute(formula, model.initial, after)
            for name, formula in system.eliminated.items()}
    state_quantities = [_quantity(v, v.symbol, start=start)
                        for v, start in zip(order, starts)]
    _check_at_start(system, model, order, starts, tunable, inputs,
                    derivatives)
    relations, whens, discretes, previous, zeros = _events(
        model, order, derivatives, system.eliminated, parameter_symbols,
        parameter_values)
    outputs = []
    for v in model.variables:
        if v.causality != "output":
            continue
        formula = v.symbol if v.name in states else system.eliminated[v.name]
        outputs.append(_quantity(v, formula))
    assertions = [dataclasses.replace(
        a, violated=_in_states(casadi.substitute(
            casadi.SX(a.violated), parameter_symbols, parameter_values),
            order, derivatives, system.eliminated),
        values=[_in_states(casadi.substitute(
            casadi.SX(v), parameter_symbols, parameter_values), order,
            derivatives, system.eliminated) for v in a.values])
        for a in model.assertions]
    derivative_column = _column(*[derivatives[v.name] for v in order])
    locals_, aliases = _locals(model, order, derivative_column, outputs,
                               system.eliminated)
    locals_ += [dataclasses.replace(q, minimum=None, start=None,
                                    maximum=None)
                for q in discretes]   # their held values, in the results
    return OdeModel(
        name=model.name, time=model.time, states=state_quantities,
        derivatives=derivative_column,
        parameters=tunable, calculated=calculated, outputs=outputs,
        experiment=model.experiment, eliminated=system.eliminated,
        inputs=inputs, relations=relations, whens=whens,
        locals=locals_, aliases=aliases, discretes=discretes,
        previous=previous, assertions=assertions, zeros=zeros)


def _check_at_start(system, model, order, starts, tunable, inputs,
                    derivatives):
    """:func:`check_loops` and :func:`_check_fixed_starts` at the start
    values: time 0, parameters and inputs at their defaults, states at
    their starts, each relation at its value there."""
    if not system.loops and not system.fixed_dropped:
        return
    symbols = [q.expression for q in tunable + inputs]
    values = [casadi.SX(q.start if q.start is not None else 0.0)
              for q in tunable + inputs]
    known, defaults = _column(*symbols), _column(*values)
    state_values = casadi.substitute(_column(*starts), known, defaults)
    symbols += [v.symbol for v in order] + [model.time]
    values += [state_values[i] for i in range(len(order))] + [casadi.SX(0)]
    relations = casadi.substitute(
        _column(*[r.value for r in model.relations]), _column(*symbols),
        _column(*values))
    symbols += [r.symbol for r in model.relations]
    values += [relations[i] for i in range(len(model.relations))]
    symbols, values = _column(*symbols), _column(*values)
    check_loops(system.loops, symbols, values)
    _check_fixed_starts(system, order, derivatives, symbols, values,
                        known, defaults)


def _check_fixed_starts(system, order, derivatives, symbols, values, known,
                        defaults):
    """Refuse a state with ``fixed = true`` that an equation removed
    (alias elimination, index reduction) when that equation gives it
    another value at the start: ``z = y + 5*x`` with ``y = z`` forces
    ``0 = 5 x``, which ``x(start = 1, fixed = true)`` contradicts; the
    FMU would silently start elsewhere."""
    for variable, where in system.fixed_dropped:
        if variable.start is None or variable.name not in \
                system.eliminated:
            continue
        formula = _in_states(system.eliminated[variable.name], order,
                             derivatives, system.eliminated)
        got = casadi.substitute(formula, symbols, values)
        wanted = casadi.substitute(casadi.SX(variable.start), known,
                                   defaults)
        if casadi.symvar(got) or casadi.symvar(wanted):
            continue
        got, wanted = _value(got), _value(wanted)
        if abs(got - wanted) > 1e-9 * max(1.0, abs(wanted)):
            raise BackEndError(
                f"{variable.where}: {variable.name} has the fixed start "
                f"value {wanted:g}, but {where} makes it {got:g} at the "
                "start; allowed: start values the equations agree with "
                f"(or fixed = false on {variable.name})")


def _locals(model, order, derivatives, outputs, eliminated):
    """Every variable that is neither a state nor an output kept, as a
    formula in ``t, x, p``: ``(locals, aliases)``, where a variable whose
    formula is that of an earlier local is an alias of it (connections
    make most flange angles and torques equal). States, derivatives and
    outputs have no aliases: fmpy's FMI 3 validator takes an alias for
    the state a derivative belongs to, so a flange angle equal to a
    body's angle is a local of its own."""
    shown = {v.name for v in order} | {o.name for o in outputs}
    hidden = [v for v in model.variables
              if v.role in ("state", "algebraic", "output")
              and v.name not in shown]
    if not hidden:
        return [], []
    formulas = _in_states(_column(*[eliminated[v.name] for v in hidden]),
                          order, {v.name: derivatives[i]
                                  for i, v in enumerate(order)}, eliminated)
    known = {}   # unit, printed formula -> name of the local that has it
    locals_, aliases = [], []
    for i, v in enumerate(hidden):
        formula = formulas[i]
        key = (v.unit, str(formula))   # a torque is no alias of an angle
        if key in known:
            aliases.append((_quantity(v, formula), known[key]))
        else:
            known[key] = v.name
            locals_.append(_quantity(v, formula))
    return locals_, aliases


def _events(model, order, derivatives, eliminated, parameter_symbols,
            parameter_values):
    """Relations, when-clauses, discrete variables and their ``pre()``
    (:attr:`OdeModel.discretes`, :attr:`OdeModel.previous`) as formulas
    in ``t, x, p``. The relations only the discrete equations use
    follow the others: held like them, their indicators are events."""
    def formula(expression):
        expression = casadi.substitute(expression, parameter_symbols,
                                       parameter_values)
        return _in_states(expression, order, derivatives, eliminated)
    held = model.relations + (model.discrete_relations
                              if model.discretes else [])
    relations = [Quantity(r.symbol.name(), "", f"relation at {r.where}",
                          r.symbol, start=0.0, minimum=formula(r.value),
                          maximum=formula(r.indicator))
                 for r in held]
    zeros = [Quantity(f"zero({r.symbol.name()})", "", "rounding band of "
                      f"the relation at {r.where}", r.zero if r.zero is not
                      None else casadi.SX.sym(f"zero_{r.symbol.name()}"),
                      start=0.0) for r in held]
    kept = {v.name for v in order}
    whens = []
    for clause in model.whens:
        for name, _ in clause.reinits:
            if name not in kept:
                raise BackEndError(f"{clause.where}: reinit({name}, ...): "
                                   f"{name} is not a state of the reduced "
                                   "model (index reduction removed it)")
        whens.append((clause.relation, [(name, formula(value))
                                        for name, value in clause.reinits]))
    values = _discrete_equations(model.discretes)
    described = {v.name: v.description for v in model.variables}
    kinds = {(True, False): "(Boolean, 1 for true)",
             (False, True): "(discrete Real)", (False, False): "(Integer)"}
    discretes = [Quantity(d.name, "", " ".join(filter(None, (
                     described.get(d.name), kinds[d.boolean, d.real]))),
                          d.symbol,
                          start=d.start, minimum=formula(value),
                          maximum=1.0 if d.boolean else None)
                 for d, value in zip(model.discretes, values)]
    previous = [Quantity(f"pre({d.name})", "", f"pre() of {d.name}",
                         d.previous, start=d.start) for d in model.discretes]
    if _uses_initial(model) and model.initial_value is None:
        previous.append(Quantity("initial()", "", "1 while initialising",
                                 model.initial, start=0.0))
    return relations, whens, discretes, previous, zeros


def _held_discretes(model):
    """The symbols of the discrete variables, their ``pre()`` and
    ``initial()``, which the continuous equations read as held values
    (``initial()`` in them: an equation that differs at the
    initialisation, MSL's ``ElastoBacklash``)."""
    held = [s for d in model.discretes for s in (d.symbol, d.previous)]
    return held + [model.initial] if _uses_initial(model) else held


def _uses_initial(model):
    """Whether the continuous or the discrete equations of ``model`` read
    ``initial()``."""
    return model.initial is not None and any(
        casadi.depends_on(casadi.SX(e), model.initial)
        for e in model.residuals + [d.value for d in model.discretes])


def _discrete_equations(discretes):
    """The right-hand sides of the discrete variables' equations with the
    other discrete variables they name (at the same instant, not through
    ``pre()`` or a continuous variable) replaced by their own right-hand
    sides: one evaluation of all of them is their evaluation in order
    (``locked`` after ``startForward``). rumoca refuses a cycle of such
    references ("participates in a current-value dependency cycle");
    one left is refused here, naming its equations."""
    names = {d.symbol.name(): k for k, d in enumerate(discretes)}
    values = [casadi.SX(d.value) for d in discretes]
    for _ in range(len(discretes) + 1):
        column = _column(*values)
        used = [v for v in casadi.symvar(column) if v.name() in names]
        if not used:
            return values
        column = casadi.substitute(column, _column(*used), _column(
            *[values[names[v.name()]] for v in used]))
        values = [column[k] for k in range(len(discretes))]
    cycle = [d for d, v in zip(discretes, values) if casadi.depends_on(
        v, _column(*[d.symbol for d in discretes]))]
    raise BackEndError(
        "; ".join(f"{d.where}: {d.name}" for d in cycle) + ": these "
        "Integer and Boolean variables are defined by each other at the "
        "same instant (a loop of discrete equations), which the FMU back "
        "end does not solve; allowed: equations that name the others "
        "through pre() or continuous variables")


def _input_start(variable):
    """Start value of an input: a number (0 if not given)."""
    if variable.start is None:
        return 0.0
    if casadi.symvar(variable.start):
        raise BackEndError(f"{variable.where}: the start value of input "
                           f"{variable.name} depends on other variables; "
                           "give a number")
    return _value(variable.start)


def _with_hysteresis(relations, time, x, p=None):
    """The event indicators of ``relations`` (:attr:`OdeModel.relations`)
    in ``t, x, p``, each shifted by its hysteresis ``h`` away from the
    value held since the last event: ``d - h`` while the relation is
    false, ``d + h`` while it holds (``d`` positive where it holds).

    ``h`` is :data:`HYSTERESIS_ROUNDINGS` times the rounding of ``d``
    to first order in that of its states, time and parameters (``p``,
    with the values held at events), ``eps (sum_i |dd/dx_i| |x_i| +
    |dd/dt| |t| + sum_j |dd/dp_j| |p_j|)``, and at least
    :data:`HYSTERESIS_FLOOR`: in the
    unit of the relation and the scale of its variables, so the state
    at a located root makes the relation change. Without it fmpy's CVode
    located roots exactly on an indicator's zero, where a strict
    relation is still false, and did not report the crossing again: a
    slip that is the difference of two speeds near 105 rad/s moves in
    steps of 1.4e-14 rad/s and rose from exactly zero after a
    break-away, and MSL's friction ``mode`` stayed ``Stuck`` while the
    clutch slid at 1.9 rad/s (docs/compiler.md). Without the
    parameters' share, a relation of terms that cancel to a rounding
    error whose sign follows the Booleans it decides (LossyGearDemo3's
    ``tau_eta >= 0`` at w = 0) changed at every round of the event
    iteration."""
    indicators = []
    for relation in relations:
        difference = casadi.SX(relation.maximum)
        rounding = casadi.dot(casadi.fabs(casadi.jacobian(difference, x)).T,
                              casadi.fabs(x)) + casadi.fabs(
            casadi.jacobian(difference, time)) * casadi.fabs(time)
        if p is not None:
            # terms of parameters that cancel (MSL LossyGear's driving
            # side tau_eta = flange_a.tau - tau_bf_a, exactly zero in
            # LossyGearDemo3) round as those of states do
            rounding += casadi.dot(casadi.fabs(casadi.jacobian(
                difference, p)).T, casadi.fabs(p))
        hysteresis = casadi.fmax(
            HYSTERESIS_ROUNDINGS * np.finfo(float).eps * rounding,
            HYSTERESIS_FLOOR)
        indicators.append(difference + hysteresis *
                          (2 * relation.expression - 1))
    return _column(*indicators)


def _in_states(expression, order, derivatives, eliminated):
    """An expression in any variables as a formula in ``t, x, p``: the
    eliminated variables and der(x) replaced by their formulas."""
    for _ in range(len(eliminated) + 1):   # eliminated names in formulas
        found = [s for s in casadi.symvar(expression)
                 if s.name() in eliminated]
        if not found:
            break
        expression = casadi.substitute(
            expression, _column(*found),
            _column(*[eliminated[s.name()] for s in found]))
    return casadi.substitute(
        expression, _column(*[v.derivative for v in order]),
        _column(*[derivatives[v.name] for v in order]))


def _initial_states(initial, order, starts, derivatives, eliminated, model,
                    places):
    """Start values of the states from the ``initial equation`` section.

    The initial equations, with der(x) and the algebraic variables
    replaced by their formulas in ``x`` and ``p`` (``initial()`` true in
    them: the equations of the initialisation), are matched to the
    states whose start is not ``fixed``; the matched states are solved
    from them (the equations must be linear in them), the other states
    keep their start values.

    Returns
    -------
    list of casadi.SX
        One start formula in ``p`` per state of ``order``.
    """
    residuals = [_in_states(r, order, derivatives, eliminated)
                 for r in initial]
    if model.initial is not None:
        residuals = [casadi.substitute(r, model.initial, casadi.SX(1))
                     for r in residuals]
    for place, residual in zip(places, residuals):
        if casadi.depends_on(residual, model.time):
            raise BackEndError(f"{place}: initial equations that depend on "
                               "time are not supported by the FMU back end")
    free = [i for i, v in enumerate(order) if not v.fixed]
    stacked = _column(*residuals)
    incidence = np.array([[casadi.depends_on(r, order[i].symbol)
                           for i in free] for r in residuals], dtype=float)
    if not free or incidence.size == 0:
        raise BackEndError(f"{places[0]}: {len(residuals)} initial "
                           "equation(s) but no "
                           "state with fixed = false to solve them for "
                           "(the initialisation is overdetermined)")
    match = maximum_bipartite_matching(csr_matrix(incidence),
                                       perm_type="column")
    if np.any(match < 0):
        lost = np.flatnonzero(match < 0)
        raise BackEndError(
            f"{places[lost[0]]}: the initialisation is overdetermined or "
            f"singular: the initial equation 0 = {residuals[lost[0]]} has "
            "no state with fixed = false left to solve for")
    unknown_index = [free[j] for j in match]
    unknown = _column(*[order[i].symbol for i in unknown_index])
    others = [i for i in range(len(order)) if i not in unknown_index]
    stacked = casadi.substitute(
        stacked, _column(*[order[i].symbol for i in others]),
        _column(*[starts[i] for i in others]))
    slope = casadi.jacobian(stacked, unknown)
    if casadi.depends_on(slope, unknown):
        raise BackEndError(
            f"{places[0]}: the initial equations " + ", ".join(
                f"0 = {r}" for r in residuals) + " are not linear in the states they determine ("
            + ", ".join(order[i].name for i in unknown_index)
            + "); nonlinear initialisation is not supported")
    rest = casadi.substitute(stacked, unknown,
                             casadi.SX.zeros(unknown.shape))
    value = -casadi.solve(slope, rest)
    starts = list(starts)
    for k, i in enumerate(unknown_index):
        starts[i] = value[k]
    return starts


def _eliminate_aliases(system, states, unknowns, parameters, time):
    """Remove ``a = +-b`` equations (step 2)."""
    changed = True
    while changed:
        changed = False
        candidates = set(states) | set(unknowns) | parameters
        for index, residual in enumerate(system.residuals):
            pair = _linear_pair(residual, candidates)
            if pair is None:
                continue
            a, b, sign = pair
            keep, drop = _alias_choice(a, b, states, parameters)
            if drop.name() in parameters:
                continue
            formula = keep * sign if drop is b else keep / sign
            where = system.describe([index])
            system.remove(index)
            _replace(system, states, unknowns, drop, formula, time, where)
            changed = True
            break


def _alias_choice(a, b, states, parameters):
    """Which of two aliased variables stays."""
    def rank(symbol):
        name = symbol.name()
        if name in parameters:
            return 3
        if name in states:
            return 2 if states[name].fixed else 1
        return 0
    return (a, b) if rank(a) >= rank(b) else (b, a)


def _replace(system, states, unknowns, drop, formula, time, where=""):
    """Substitute a variable (and, for a state, its derivative); a state
    with a fixed start is remembered with the equation ``where`` that
    removed it (:func:`_check_fixed_starts`)."""
    name = drop.name()
    # dense: a structural zero (d/dt of a constant) is no valid value
    symbols, formulas = [drop], [casadi.densify(formula)]
    if name in states:
        derivative = states[name].derivative
        if states[name].fixed:
            system.fixed_dropped.append((states[name], where))
        del states[name]
        symbols.append(derivative)
        formulas.append(casadi.densify(
            _time_derivative(formula, states, time)))
    else:
        unknowns.pop(name, None)
    system.eliminated[name] = formula
    system.substitute(symbols, formulas)


def _time_derivative(formula, states, time):
    """d/dt of a formula in states, parameters and time."""
    x = [v.symbol for v in states.values()]
    dx = [v.derivative for v in states.values()]
    explicit = casadi.jacobian(formula, time)
    if not x:
        return explicit
    return explicit + casadi.jtimes(formula, _column(*x),
                                    _column(*dx))


def _reduce_index(system, states, known, time, unknowns=None):
    """Solve constraints among states for one state each (step 3).

    ``known`` are the names of parameters and time: a residual whose
    symbols are states and knowns only is a constraint.
    """
    while True:
        constraints = []
        for index, residual in enumerate(system.residuals):
            names = {s.name() for s in casadi.symvar(residual)}
            involved = names & set(states)
            if involved and names <= set(states) | known:
                constraints.append((index, involved))
        if not constraints:
            if _substitute_state_derivatives(system, states, known):
                continue
            if unknowns and _expose_constraint(system, states, known, time,
                                               unknowns):
                continue
            if _substitute_state_derivatives(system, states, known,
                                             anywhere=True):
                continue
            return
        count = {}
        for _, involved in constraints:
            for name in involved:
                count[name] = count.get(name, 0) + 1
        index, involved = constraints[0]
        residual = system.residuals[index]
        choices = sorted(involved, key=lambda n: (count[n], states[n].fixed,
                                                  -list(states).index(n)))
        for name in choices:
            symbol = states[name].symbol
            slope = casadi.jacobian(residual, symbol)
            if not casadi.depends_on(slope, symbol) and _nonzero(slope):
                rest = casadi.substitute(residual, symbol, casadi.SX(0))
                formula = -rest / slope
                where = system.describe([index])
                system.remove(index)
                _replace(system, states, {}, symbol, formula, time, where)
                break
        else:
            raise BackEndError(f"cannot reduce the index: no state appears "
                               f"linearly in the constraint {residual}")


def _substitute_state_derivatives(system, states, known, anywhere=False):
    """Turn equations in derivatives into the constraints they hide.

    After the bodies' angles replace a relative angle, ``w_rel =
    der(phi_rel)`` reads ``w_rel = der(b.phi) - der(a.phi)``. With the
    bodies' ``w = der(phi)`` (a derivative equal to a state) substituted
    it is ``w_rel = b.w - a.w``: a constraint among states, which the next
    pass of index reduction differentiates (a second time for the angles).
    Only equations that become constraints are rewritten, or, with
    ``anywhere``, equations left without a derivative (MSL's ``Speed``
    source writes ``w = der(phi)`` with its ``phi`` a body's angle whose
    ``w`` is a state, and ``w = w_ref``: with the body's speed in it,
    ``w = body.w`` exposes the constraint ``body.w = w_ref(t)``); the
    equations ``w = der(phi)`` themselves stay. Returns whether one was
    rewritten.
    """
    names = set(states)
    derivatives = {v.derivative.name(): v.derivative for v in states.values()}
    definitions, defining = {}, set()
    for index, residual in enumerate(system.residuals):
        pair = _linear_pair(residual, names | set(derivatives))
        if pair is None:
            continue
        a, b, sign = pair
        if a.name() in derivatives and b.name() in names:
            a, b, sign = b, a, 1 / sign
        if b.name() in derivatives and a.name() in names \
                and b.name() not in definitions:
            definitions[b.name()] = sign * a     # der(x) = sign*w
            defining.add(index)
    if not definitions:
        return False
    old = _column(*[derivatives[n] for n in definitions])
    new = _column(*definitions.values())
    for index, residual in enumerate(system.residuals):
        used = {s.name() for s in casadi.symvar(residual)}
        if index in defining or not used & set(definitions):
            continue
        rewritten = casadi.substitute(residual, old, new)
        found = {s.name() for s in casadi.symvar(rewritten)}
        if found & names and (found <= names | known or anywhere and not
                              found & set(derivatives)):
            system.residuals[index] = rewritten
            return True
    return False


def _expose_constraint(system, states, known, time, unknowns):
    """Eliminate one algebraic variable that hides a constraint.

    An ideal gear between a body and a spring writes ``phi_body = ratio *
    flange.phi`` and ``phi_rel = phi_other - flange.phi``: each equation
    holds states, knowns and the one algebraic ``flange.phi``, so neither
    is a constraint among states until ``flange.phi`` is solved from the
    first (linear in it) and substituted into the second. MSL's
    ``IdealGear`` hides it one level deeper (``phi_a = flange_a.phi -
    phi_support``, ``phi_b = ...``, ``phi_a = ratio*phi_b``): the
    variables determined by the states through a chain of such equations
    are followed until an equation holds only them, states and knowns.
    Returns whether such a variable was eliminated.
    """
    plain = set(states) | known
    defined = {}   # algebraic name -> equation that gives it from plain ones
    progress = True
    while progress:
        progress = False
        for index, residual in enumerate(system.residuals):
            if index in defined.values():
                continue
            names = {s.name() for s in casadi.symvar(residual)}
            extra = names - plain - set(defined)
            if len(extra) != 1:
                continue
            name = extra.pop()
            if name not in unknowns or name in system.eliminated:
                continue
            symbol = unknowns[name].symbol
            slope = casadi.jacobian(residual, symbol)
            if casadi.depends_on(slope, symbol) or not _nonzero(slope):
                continue
            defined[name] = index
            progress = True
    users = set(defined.values())
    for index, residual in enumerate(system.residuals):
        names = {s.name() for s in casadi.symvar(residual)}
        if index in users or not names & set(defined) or \
                not names <= plain | set(defined):
            continue
        # sorted: in a set's order (the hash seed's) the variable
        # eliminated first, and so the formulas, differed from build to
        # build (ElastoGap's contact indicator held mass1.s - mass1.s)
        needed, pending = set(), sorted(names & set(defined))
        touched = names & set(states)
        while pending:   # the defined variables this constraint rests on
            name = pending.pop()
            if name not in needed:
                needed.add(name)
                used = {s.name() for s in casadi.symvar(
                    system.residuals[defined[name]])}
                touched |= used & set(states)
                pending += [n for n in used if n in defined]
        if not touched:
            continue   # among parameters only: not a constraint on states
        for name in sorted(needed):
            index = defined[name]
            residual = system.residuals[index]
            if {s.name() for s in casadi.symvar(residual)} - plain \
                    != {name}:
                continue
            symbol = unknowns[name].symbol
            slope = casadi.jacobian(residual, symbol)
            formula = -casadi.substitute(residual, symbol,
                                         casadi.SX(0)) / slope
            system.remove(index)
            _replace(system, states, unknowns, symbol, formula, time)
            return True
    return False


def _nonzero(expression):
    if casadi.symvar(expression):
        return True
    return _value(expression) != 0


def _solve_sorted(system, states, unknown_vars):
    """Match, sort into blocks and solve (steps 4-5); der(x) formulas."""
    derivative_of = {v.derivative.name(): n for n, v in states.items()}
    unknowns = [v.derivative for v in states.values()] + \
        [v.symbol for n, v in unknown_vars.items() if n not in
         system.eliminated]
    residuals = system.residuals
    if not unknowns and not residuals:
        return {}
    sparsity = casadi.jacobian_sparsity(_column(*residuals),
                                        _column(*unknowns))
    rows, cols = sparsity.get_triplet()
    incidence = csr_matrix((np.ones(len(rows)), (rows, cols)),
                           shape=(len(residuals), len(unknowns)))
    if len(residuals) != len(unknowns):
        over, under = excess(incidence.toarray())
        detail = ("; over-determined: " + system.describe(over[:12])
                  if over else "") + \
            ("; under-determined: " + ", ".join(str(unknowns[j])
                                                for j in under[:12])
             if under else "")
        raise BackEndError(f"{len(residuals)} equations for {len(unknowns)} "
                           "unknowns after index reduction: the model is "
                           f"not balanced{detail}")
    match = maximum_bipartite_matching(incidence, perm_type="column")
    if np.any(match < 0):
        raise BackEndError("structurally singular: no unknown left for "
                           "the equations " + system.describe(
                               np.flatnonzero(match < 0)[:3]))
    # equation i needs the unknown solved by equation owner[j]
    owner = np.empty(len(unknowns), dtype=int)
    owner[match] = np.arange(len(residuals))
    needs = csr_matrix((np.ones(len(rows)), (rows, owner[cols])),
                       shape=(len(residuals),) * 2)
    count, labels = connected_components(needs, directed=True,
                                         connection="strong")
    blocks = _topological_blocks(needs, count, labels)
    solved_symbols, solved_values = [], []
    for block in blocks:
        eqs = _column(*[residuals[i] for i in block])
        unk = _column(*[unknowns[match[i]] for i in block])
        if solved_symbols:
            eqs = casadi.substitute(eqs, _column(*solved_symbols),
                                    _column(*solved_values))
        slope = casadi.jacobian(eqs, unk)
        names = [str(unknowns[match[i]]) for i in block]
        if casadi.depends_on(slope, unk):
            raise BackEndError(
                system.describe(block) + ": an algebraic loop nonlinear in "
                "its unknowns (" + ", ".join(names)
                + "); nonlinear systems are not supported")
        _check_structure(system.describe(block), names, slope)
        system.loops.append((system.describe(block), names, slope))
        rest = casadi.substitute(eqs, unk, casadi.DM.zeros(unk.shape))
        value = -rest / slope if len(block) == 1 else \
            -casadi.solve(slope, rest)
        for k in range(len(block)):
            solved_symbols.append(unk[k])
            solved_values.append(value[k])
    solution = dict(zip((s.name() for s in solved_symbols), solved_values))
    for name, formula in list(system.eliminated.items()):
        system.eliminated[name] = casadi.substitute(
            formula, _column(*solved_symbols),
            _column(*solved_values))
    for name in unknown_vars:
        if name in solution:
            system.eliminated[name] = solution[name]
    return {derivative_of[d]: solution[d] for d in derivative_of}


def _check_structure(equations, names, slope):
    """Refuse a block whose slope matrix (``d equations / d unknowns``,
    after the unknowns solved before are substituted) is structurally
    singular: ``y = z + x; z = y - x`` matches each equation to an
    unknown, but some unknown may cancel once the others are known."""
    rows, cols = slope.sparsity().get_triplet()
    kept = [(i, j) for i, j in zip(rows, cols) if not slope[i, j].is_zero()]
    incidence = csr_matrix((np.ones(len(kept)), ([i for i, _ in kept],
                                                 [j for _, j in kept])),
                           shape=slope.shape)
    match = maximum_bipartite_matching(incidence, perm_type="column")
    if np.any(match < 0):
        lost = sorted(set(range(len(names))) - set(match[match >= 0]))
        raise BackEndError(
            f"{equations}: this algebraic loop in {', '.join(names)} is "
            "structurally singular: its equations do not determine "
            f"{', '.join(names[j] for j in lost)}; allowed: a loop whose "
            "equations each add a condition on its unknowns")


def check_loops(loops, symbols, values):
    """Refuse an algebraic loop whose slope matrix is singular at the
    start values (``symbols`` set to ``values``: states at their starts,
    parameters and inputs at their defaults, time 0), where its linear
    solve would divide by zero: ``y + z = -5 x; 2 y + 2 z = -10 x``
    leaves ``y - z`` free, and a loop that forces ``0 = -5 x`` cannot
    hold at ``x(0) = 1``."""
    for equations, names, slope in loops:
        matrix = casadi.substitute(slope, symbols, values)
        if casadi.symvar(matrix):
            continue   # depends on something without a start value
        matrix = np.atleast_2d(np.array(casadi.evalf(matrix), dtype=float))
        if not np.all(np.isfinite(matrix)):
            raise BackEndError(
                f"{equations}: the slope of this algebraic loop in "
                f"{', '.join(names)} is not finite at the start values")
        rank = np.linalg.matrix_rank(matrix)
        if rank < len(names):
            where = " at the start values" if casadi.symvar(slope) else ""
            raise BackEndError(
                f"{equations}: this algebraic loop in {', '.join(names)} "
                f"is singular{where} (rank {rank} of "
                f"{len(names)}): its equations do not determine "
                f"{', '.join(names)} (they have no solution or infinitely "
                "many); allowed: a loop whose equations are independent")


def _topological_blocks(needs, count, labels):
    """Blocks (lists of equations) so that each needs only earlier ones."""
    members = [[] for _ in range(count)]
    for equation, label in enumerate(labels):
        members[label].append(equation)
    coo = needs.tocoo()
    edges = {(labels[i], labels[j]) for i, j in zip(coo.row, coo.col)
             if labels[i] != labels[j]}
    after = {c: set() for c in range(count)}   # c needs these first
    for c, d in edges:
        after[c].add(d)
    order, done = [], set()
    while len(order) < count:
        ready = [c for c in range(count) if c not in done and after[c] <= done]
        for c in ready:
            order.append(c)
            done.add(c)
    return [members[c] for c in order]
