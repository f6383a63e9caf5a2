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
   kept and the relative ones go.
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

from dataclasses import dataclass

import casadi
import numpy as np
from scipy.sparse import csr_matrix
from scipy.sparse.csgraph import connected_components, maximum_bipartite_matching

from .frontend import FrontEndError

__all__ = ["OdeModel", "Quantity", "to_ode"]


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
        Tunable parameters ``p`` with their default values.
    calculated : list of Quantity
        Parameters bound to formulas in ``p``.
    outputs : list of Quantity
        Outputs of the model as formulas in ``t, x, p``.
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

    def _symbols(self):
        x = casadi.vertcat(*[s.expression for s in self.states])
        p = casadi.vertcat(*[q.expression for q in self.parameters])
        return x, p

    def functions(self):
        """CasADi functions ``ode(t, x, p) -> der(x)``, ``outputs(t, x, p)
        -> y`` and ``start(p) -> x0``."""
        x, p = self._symbols()
        y = casadi.vertcat(*[o.expression for o in self.outputs])
        x0 = casadi.vertcat(*[s.start for s in self.states])
        return (casadi.Function("ode", [self.time, x, p], [self.derivatives],
                                ["t", "x", "p"], ["xdot"]),
                casadi.Function("outputs", [self.time, x, p], [y],
                                ["t", "x", "p"], ["y"]),
                casadi.Function("start", [p], [x0], ["p"], ["x0"]))

    def parameter_vector(self, **values):
        """Default parameter values, with some changed by name."""
        names = [q.name for q in self.parameters]
        unknown = sorted(set(values) - set(names))
        if unknown:
            raise KeyError(f"unknown parameter {unknown[0]!r}; tunable: "
                           f"{', '.join(names)}")
        return np.array([values.get(q.name, q.start) for q in self.parameters],
                        dtype=float)


def _value(expression):
    return float(casadi.evalf(expression))


def _split_parameters(model):
    """Tunable parameters with values, and calculated ones as formulas."""
    tunable, calculated = [], []
    for v in model.by_role("parameter"):
        binding = v.binding if v.binding is not None else v.start
        if binding is None:
            raise BackEndError(f"parameter {v.name} has no value")
        quantity = Quantity(v.name, v.unit, v.description, v.symbol,
                            minimum=v.minimum, maximum=v.maximum)
        if casadi.symvar(binding):
            quantity.expression = binding
            calculated.append(quantity)
        else:
            quantity.start = _value(binding)
            tunable.append(quantity)
    # resolve chains of calculated parameters down to tunable ones
    symbols = [q.expression for q in calculated]
    targets = casadi.vertcat(*[v.symbol for v in model.by_role("parameter")
                               if any(v.name == q.name for q in calculated)])
    values = casadi.vertcat(*symbols)
    if not calculated:
        # vertcat of nothing is a numeric DM, which substitute refuses
        targets = values = casadi.SX(0, 1)
    for _ in range(len(calculated) + 1):
        values = casadi.substitute(values, targets, values)
    for index, quantity in enumerate(calculated):
        quantity.expression = values[index]
    return tunable, calculated, targets, values


class _System:
    """Residual equations with substitution bookkeeping."""

    def __init__(self, residuals, eliminated=None):
        self.residuals = list(residuals)
        self.eliminated = dict(eliminated or {})   # name -> formula

    def substitute(self, symbols, formulas):
        if len(symbols) != len(formulas):
            raise ValueError("one formula per symbol")
        if not symbols:
            return
        old = casadi.vertcat(*symbols)
        new = casadi.vertcat(*formulas)
        stacked = casadi.substitute(casadi.vertcat(*self.residuals), old, new)
        self.residuals = [stacked[i] for i in range(stacked.shape[0])]
        if self.eliminated:
            names = list(self.eliminated)
            values = casadi.substitute(
                casadi.vertcat(*self.eliminated.values()), old, new)
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
    tunable, calculated, parameter_symbols, parameter_values = \
        _split_parameters(model)
    states = {v.name: v for v in model.by_role("state")}
    unknown_vars = {v.name: v for v in model.variables
                    if v.role in ("algebraic", "output")}
    system = _System(model.residuals)
    # calculated parameters become formulas in the tunable ones
    system.substitute([parameter_symbols[i] for i in
                       range(parameter_symbols.shape[0])],
                      [parameter_values[i] for i in
                       range(parameter_values.shape[0])])
    parameter_names = {q.name for q in tunable}

    _eliminate_aliases(system, states, unknown_vars, parameter_names,
                       model.time)
    _reduce_index(system, states, parameter_names | {"time"}, model.time,
                  unknown_vars)
    derivatives = _solve_sorted(system, states, unknown_vars)

    order = [v for v in model.by_role("state") if v.name in states]
    state_quantities = []
    for v in order:
        start = v.start if v.start is not None else casadi.SX(0)
        start = casadi.substitute(start, parameter_symbols, parameter_values)
        state_quantities.append(Quantity(v.name, v.unit, v.description,
                                         v.symbol, start=start))
    outputs = [Quantity(v.name, v.unit, v.description,
                        system.eliminated[v.name])
               for v in model.by_role("output")]
    return OdeModel(
        name=model.name, time=model.time, states=state_quantities,
        derivatives=casadi.vertcat(*[derivatives[v.name] for v in order]),
        parameters=tunable, calculated=calculated, outputs=outputs,
        experiment=model.experiment, eliminated=system.eliminated)


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
            del system.residuals[index]
            _replace(system, states, unknowns, drop, formula, time)
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


def _replace(system, states, unknowns, drop, formula, time):
    """Substitute a variable (and, for a state, its derivative)."""
    name = drop.name()
    symbols, formulas = [drop], [formula]
    if name in states:
        derivative = states[name].derivative
        del states[name]
        symbols.append(derivative)
        formulas.append(_time_derivative(formula, states, time))
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
    return explicit + casadi.jtimes(formula, casadi.vertcat(*x),
                                    casadi.vertcat(*dx))


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
            if unknowns and _expose_constraint(system, states, known, time,
                                               unknowns):
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
                del system.residuals[index]
                _replace(system, states, {}, symbol, formula, time)
                break
        else:
            raise BackEndError(f"cannot reduce the index: no state appears "
                               f"linearly in the constraint {residual}")


def _expose_constraint(system, states, known, time, unknowns):
    """Eliminate one algebraic variable that hides a constraint.

    An ideal gear between a body and a spring writes ``phi_body = ratio *
    flange.phi`` and ``phi_rel = phi_other - flange.phi``: each equation
    holds states, knowns and the one algebraic ``flange.phi``, so neither
    is a constraint among states until ``flange.phi`` is solved from the
    first (linear in it) and substituted into the second. Returns whether
    such a variable was eliminated.
    """
    plain = set(states) | known
    candidates = {}
    for index, residual in enumerate(system.residuals):
        names = {s.name() for s in casadi.symvar(residual)}
        extra = names - plain
        if len(extra) == 1 and names & set(states):
            name = extra.pop()
            if name in unknowns and name not in system.eliminated:
                candidates.setdefault(name, []).append(index)
    for name, indices in candidates.items():
        if len(indices) < 2:
            continue
        index = indices[0]
        residual = system.residuals[index]
        symbol = unknowns[name].symbol
        slope = casadi.jacobian(residual, symbol)
        if casadi.depends_on(slope, symbol) or not _nonzero(slope):
            continue
        formula = -casadi.substitute(residual, symbol, casadi.SX(0)) / slope
        del system.residuals[index]
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
    if len(residuals) != len(unknowns):
        raise BackEndError(f"{len(residuals)} equations for {len(unknowns)} "
                           "unknowns after index reduction: the model is "
                           "not balanced")
    if not unknowns:
        return {}
    sparsity = casadi.jacobian_sparsity(casadi.vertcat(*residuals),
                                        casadi.vertcat(*unknowns))
    rows, cols = sparsity.get_triplet()
    incidence = csr_matrix((np.ones(len(rows)), (rows, cols)),
                           shape=(len(residuals), len(unknowns)))
    match = maximum_bipartite_matching(incidence, perm_type="column")
    if np.any(match < 0):
        lost = [str(residuals[i]) for i in np.flatnonzero(match < 0)][:3]
        raise BackEndError("structurally singular: no unknown left for "
                           f"the equations {lost}")
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
        eqs = casadi.vertcat(*[residuals[i] for i in block])
        unk = casadi.vertcat(*[unknowns[match[i]] for i in block])
        if solved_symbols:
            eqs = casadi.substitute(eqs, casadi.vertcat(*solved_symbols),
                                    casadi.vertcat(*solved_values))
        slope = casadi.jacobian(eqs, unk)
        if casadi.depends_on(slope, unk):
            raise BackEndError("the equations " + ", ".join(
                str(residuals[i]) for i in block) + " are not linear in "
                "their unknowns; nonlinear systems are not supported yet")
        rest = casadi.substitute(eqs, unk, casadi.DM.zeros(unk.shape))
        value = -rest / slope if len(block) == 1 else \
            -casadi.solve(slope, rest)
        for k in range(len(block)):
            solved_symbols.append(unk[k])
            solved_values.append(value[k])
    solution = dict(zip((s.name() for s in solved_symbols), solved_values))
    for name, formula in list(system.eliminated.items()):
        system.eliminated[name] = casadi.substitute(
            formula, casadi.vertcat(*solved_symbols),
            casadi.vertcat(*solved_values))
    for name in unknown_vars:
        if name in solution:
            system.eliminated[name] = solution[name]
    return {derivative_of[d]: solution[d] for d in derivative_of}


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
