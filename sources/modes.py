"""A hybrid Modelica class fixed in one mode.

MSL's friction elements (``Rotational.Interfaces.PartialFriction``: the
Booleans ``free``, ``startForward``, ``startBackward``, ``locked`` and the
Integer ``mode`` with ``pre()``) switch their continuous equations by
Integer and Boolean variables. Between events those are constant; a
linearisation in one mode (a clutch slipping forward) fixes them as
numbers (:func:`fixed_mode`) and keeps their equations beside, as
variables ``judder_mode<k>`` (:func:`mode_values`), to find the mode of
an operating point and to check that it holds
(:func:`sources.modelica.linearize`).
"""

import dataclasses

import casadi
import numpy as np

from fmu.frontend import Variable

__all__ = ["fixed_mode", "arguments", "mode_values", "mode_relations",
           "mode_indicators", "on_switching_surface", "describe_mode",
           "uses_initial", "MODE_PREFIX"]

#: Name of the variable holding the k-th discrete variable's equation.
MODE_PREFIX = "judder_mode"


def _column(items):
    return casadi.vertcat(casadi.SX(0, 1), *items)


def fixed_mode(flat, current, previous, initial):
    """``flat`` with its Integer and Boolean variables fixed.

    Parameters
    ----------
    flat : fmu.frontend.FlatModel
        Read with ``hybrid=True``.
    current, previous : tuple of float
        Values of :attr:`~fmu.frontend.FlatModel.discretes` and of their
        ``pre()`` (Booleans as 1 and 0).
    initial : float
        The value of ``initial()`` in the equations of the mode; the
        initial equations are solved with it true (as an FMU does:
        :attr:`~fmu.frontend.FlatModel.initial_value`).

    Returns
    -------
    fmu.frontend.FlatModel
        Without discrete variables: each is its number in the equations,
        and ``judder_mode<k> = value_k`` (the k-th one's equation with the
        same numbers) is an algebraic variable of its own; relations the
        equations no longer use are dropped.
    """
    symbols = _column([d.symbol for d in flat.discretes]
                      + [d.previous for d in flat.discretes])
    numbers = _column([casadi.SX(v) for v in (*current, *previous)])
    residuals = [casadi.substitute(casadi.SX(r), symbols, numbers)
                 for r in flat.residuals]
    variables = [v for v in flat.variables if v.role != "discrete"]
    places = list(flat.places)
    for k, discrete in enumerate(flat.discretes):
        check = casadi.SX.sym(f"{MODE_PREFIX}{k}")
        variables.append(Variable(
            name=check.name(), role="algebraic", symbol=check,
            description=f"equation of {discrete.name} in the mode",
            where=discrete.where))
        residuals.append(check - casadi.substitute(
            casadi.SX(discrete.value), symbols, numbers))
        places.append(discrete.where)
    used = {s.name() for r in residuals + list(flat.initial_residuals)
            for s in casadi.symvar(casadi.SX(r))}
    relations = [r for r in flat.relations if r.symbol.name() in used]
    whens = flat.whens
    if len(relations) != len(flat.relations) and whens:
        relations = flat.relations   # when-clauses index them
    # a when-clause's condition on discrete variables (n == 2) is a
    # relation of its own in them
    relations = [dataclasses.replace(
        r, value=casadi.substitute(casadi.SX(r.value), symbols, numbers))
        for r in relations]
    return dataclasses.replace(flat, variables=variables, residuals=residuals,
                               places=places, relations=relations,
                               discretes=[], initial_value=float(initial))


def uses_initial(flat):
    """Whether the equations of ``flat`` use ``initial()`` (MSL's
    ``ElastoBacklash``), which :func:`fixed_mode` makes a number after the
    initialisation."""
    return flat.initial is not None and any(
        casadi.depends_on(casadi.SX(r), flat.initial) for r in flat.residuals)


def _mode_formulas(ode):
    """The discrete variables' equations in the mode of ``ode``, in
    ``t, x, p``, one per variable."""
    formulas = {q.name: q.expression for q in ode.locals}
    formulas.update({q.name: formulas.get(name, q.expression)
                     for q, name in ode.aliases})
    count = sum(name.startswith(MODE_PREFIX) for name in formulas)
    return [casadi.SX(formulas[f"{MODE_PREFIX}{k}"]) for k in range(count)]


def arguments(ode):
    """The symbols ``[t, x, p]`` of the compiled functions of ``ode``: time,
    its states and its tunable parameters, as columns."""
    x = casadi.vertcat(casadi.SX(0, 1), *[s.expression for s in ode.states])
    p = casadi.vertcat(casadi.SX(0, 1), *[q.expression for q in
                                          ode.parameters])
    return [ode.time, x, p]


def mode_values(ode):
    """``values(t, x, p)``: the discrete variables' equations in the mode
    of ``ode`` (:func:`fixed_mode` compiled), one per variable; ``p`` the
    tunable parameters (the relations in them are values, not held)."""
    return casadi.Function("mode", arguments(ode),
                           [_column(_mode_formulas(ode))])


#: CasADi's relational operations, whose sign of ``lhs - rhs`` decides them.
_RELATIONS = (casadi.OP_LT, casadi.OP_LE, casadi.OP_EQ, casadi.OP_NE)


def mode_relations(ode):
    """The relations in the discrete variables' equations
    (:func:`mode_values`), each once: ``(k, relation)``, ``k`` the first
    discrete variable whose equation holds it and ``relation`` its CasADi
    node (``dep(0)``, ``dep(1)`` its two sides, in ``t, x, p``)."""
    found, seen = [], set()
    for k, formula in enumerate(_mode_formulas(ode)):
        stack = [formula[i] for i in range(formula.numel())]
        while stack:
            node = stack.pop()
            key = node.element_hash()
            if key in seen or node.is_leaf():
                continue
            seen.add(key)
            if node.op() in _RELATIONS:
                found.append((k, node))
            stack += [node.dep(i) for i in range(node.n_dep())]
    return found


def mode_indicators(ode):
    """``indicators(t, x, p)``: ``lhs - rhs`` of each relation in the
    discrete variables' equations (:func:`mode_relations`), whose zero
    crossings are the only places the mode's values can change (the
    event indicators of the relations, for an integrator's events)."""
    return casadi.Function("indicators", arguments(ode), [_column(
        [node.dep(0) - node.dep(1) for _, node in mode_relations(ode)])])


#: Value of ``lhs - rhs`` (relative to the sides, at least 1) at which
#: the mode is read on either side of a switching surface.
SIDE_STEP = 1e-9


def on_switching_surface(ode, p):
    """The relations of the discrete variables' equations
    (:func:`mode_relations`) whose two sides are equal at the start
    values of the states (time 0, parameters ``p``) and that decide the
    mode there: the discrete variables' equations give other values a
    step :data:`SIDE_STEP` to either side of the surface (the states
    moved along the gradient of ``lhs - rhs``).

    Returns
    -------
    list of (int, str, float, tuple, tuple)
        ``k`` the first discrete variable whose values differ on the two
        sides, the relation as CasADi writes it, its sides' common value,
        and the mode's values below and above the surface. A relation of
        time alone (a ramp's start) is left out: time only goes forward.
    """
    t, x, _ = symbols = arguments(ode)
    start = casadi.Function("start", symbols[2:], [_column(
        [s.start for s in ode.states])])
    x0 = np.asarray(start(p)).ravel()
    values = mode_values(ode)
    found = []
    for _, node in mode_relations(ode):
        indicator = node.dep(0) - node.dep(1)
        if not casadi.depends_on(indicator, x):
            continue
        sides = casadi.Function("sides", symbols, [
            node.dep(0), node.dep(1), casadi.gradient(indicator, x)])
        lhs, rhs, slope = (np.asarray(v).ravel()
                           for v in sides(0.0, x0, p))
        if lhs[0] != rhs[0] or not slope.any():
            continue
        step = SIDE_STEP * max(1.0, abs(lhs[0])) * slope / (slope @ slope)
        below, above = (tuple(np.asarray(values(0.0, x0 + sign * step,
                                                p)).ravel())
                        for sign in (-1.0, 1.0))
        if below != above:
            k = int(np.flatnonzero(np.array(below) != np.array(above))[0])
            found.append((k, str(node), float(lhs[0]), below, above))
    return found


def describe_mode(flat, values):
    """``((name, value), ...)`` of the discrete variables: a Boolean as
    ``true``/``false``, an Integer with the constants of its component
    that equal it (``1 (clutch.Forward)``)."""
    constants = {}
    for v in flat.variables:
        if v.role == "constant" and v.binding is not None and \
                not casadi.symvar(casadi.SX(v.binding)):
            constants.setdefault(v.name.rsplit(".", 1)[0], []).append(
                (v.name, float(casadi.evalf(casadi.SX(v.binding)))))
    described = []
    for discrete, value in zip(flat.discretes, values):
        owner = discrete.name.rsplit(".", 1)[0]
        named = [n for n, c in constants.get(owner, []) if c == value]
        if discrete.boolean:
            text = "true" if value else "false"
        else:
            text = f"{value:g}" + (f" ({named[0]})" if named else "")
        described.append((discrete.name, text))
    return tuple(described)

