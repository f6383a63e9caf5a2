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

from fmu.frontend import Variable

__all__ = ["fixed_mode", "mode_values", "mode_indicators", "describe_mode",
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


def _arguments(ode):
    x = casadi.vertcat(casadi.SX(0, 1), *[s.expression for s in ode.states])
    p = casadi.vertcat(casadi.SX(0, 1), *[q.expression for q in
                                          ode.parameters])
    return [ode.time, x, p]


def mode_values(ode):
    """``values(t, x, p)``: the discrete variables' equations in the mode
    of ``ode`` (:func:`fixed_mode` compiled), one per variable; ``p`` the
    tunable parameters (the relations in them are values, not held)."""
    return casadi.Function("mode", _arguments(ode),
                           [_column(_mode_formulas(ode))])


#: CasADi's relational operations, whose sign of ``lhs - rhs`` decides them.
_RELATIONS = (casadi.OP_LT, casadi.OP_LE, casadi.OP_EQ, casadi.OP_NE)


def mode_indicators(ode):
    """``indicators(t, x, p)``: ``lhs - rhs`` of each relation in the
    discrete variables' equations (:func:`mode_values`), whose zero
    crossings are the only places the mode's values can change (the
    event indicators of the relations, for an integrator's events)."""
    found, seen = {}, set()
    stack = [f[i] for f in _mode_formulas(ode) for i in range(f.numel())]
    while stack:
        node = stack.pop()
        key = node.element_hash()
        if key in seen or node.is_leaf():
            continue
        seen.add(key)
        if node.op() in _RELATIONS:
            found[key] = node.dep(0) - node.dep(1)
        stack += [node.dep(i) for i in range(node.n_dep())]
    return casadi.Function("indicators", _arguments(ode),
                           [_column(list(found.values()))])


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

