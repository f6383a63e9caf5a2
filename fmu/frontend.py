"""Modelica front end: rumoca flattens, this module reads its flat model.

rumoca (an independent Modelica compiler on PyPI) parses the library,
expands ``connect`` and ``flow`` and writes the flat model as a JSON-like
dictionary: variables with their role (state, algebraic, parameter,
output), attributes (unit, start, fixed, min, max, description) and
residual equations over an expression graph. :func:`load_flat_model`
turns that into CasADi SX expressions for the back end. Nothing here
knows about drivelines: the equations come from the ``.mo`` source.
"""

from dataclasses import dataclass, field
from itertools import product
from pathlib import Path
import re

import casadi
import numpy as np

from .classes import (blank, class_source, class_spans, find_class,
                      modelica_path)
from .errors import FrontEndError
from .limits import check_flat_arrays

__all__ = ["Variable", "FlatModel", "Discrete", "Assertion", "load_flat_model",
           "class_source", "find_class", "modelica_path", "FrontEndError"]


@dataclass
class Variable:
    """One scalar of the flat model.

    Attributes
    ----------
    name : str
        Flat name, e.g. ``inertia1.w``.
    role : str
        ``'state'``, ``'algebraic'``, ``'parameter'``, ``'constant'``,
        ``'input'`` or ``'output'``.
    symbol : casadi.SX
    derivative : casadi.SX or None
        ``der(name)`` for states.
    unit, description : str
    start : casadi.SX or None
        Start value (may depend on parameters).
    fixed : bool
    binding : casadi.SX or None
        Parameter binding (may depend on other parameters).
    minimum, maximum : casadi.SX or None
    where : str
        ``file:line`` of the declaration.
    causality : str
        ``'input'``, ``'output'``, ``'parameter'`` or ``'local'``.
    quantity, display_unit : str
        Of the declared type (``type Pressure = Real(quantity="Pressure",
        unit="Pa", displayUnit="bar")``), if the library defines it.
    """

    name: str
    role: str
    symbol: object
    derivative: object = None
    unit: str = ""
    description: str = ""
    start: object = None
    fixed: bool = False
    binding: object = None
    minimum: object = None
    maximum: object = None
    where: str = ""
    causality: str = ""
    quantity: str = ""
    display_unit: str = ""


@dataclass
class FlatModel:
    """Flat DAE ``0 = F(t, der(x), x, z, p)`` of one Modelica model.

    Attributes
    ----------
    name : str
        Full class name.
    variables : list of Variable
    residuals : list of casadi.SX
        One scalar residual per equation.
    initial_residuals : list of casadi.SX
        The ``initial equation`` section, one residual per equation.
    places, initial_places : list of str
        ``file:line`` of each equation of the two sections.
    relations : list of Relation
        Relations that generate events; in the equations each is replaced
        by its symbol, a value held between events.
    whens : list of When
        ``when relation then reinit(...)`` clauses.
    time : casadi.SX
    experiment : dict
        ``StopTime`` and ``Interval`` of the experiment annotation.
    description : str
    discretes : list of Discrete
        Integer and Boolean variables with their equations (read with
        ``hybrid=True`` only).
    discrete_relations : list of Relation
        The relations of :attr:`discretes`' equations that the continuous
        equations do not hold (their values are in the discrete equations;
        the FMU back end makes their indicators events).
    initial : casadi.SX or None
        The symbol of ``initial()`` in :attr:`discretes`' values and in
        the residuals (1 at initialisation, else 0).
    initial_value : float or None
        None: ``initial()`` is held in the FMU (1 while it initialises);
        a number: its value once the initial equations are solved (with
        it 1), for the ODE of one mode (:func:`sources.modes.fixed_mode`).
    assertions : list of Assertion
        The ``assert(...)`` of the equations.
    rewrites : list of fmu.rewrite.Rewrite
        The bindings rewritten as equations before rumoca read them
        (:mod:`fmu.rewrite`) that declare variables of this model.
    """

    name: str
    variables: list
    residuals: list
    time: object
    initial_residuals: list = field(default_factory=list)
    places: list = field(default_factory=list)
    initial_places: list = field(default_factory=list)
    relations: list = field(default_factory=list)
    whens: list = field(default_factory=list)
    experiment: dict = field(default_factory=dict)
    description: str = ""
    discretes: list = field(default_factory=list)
    discrete_relations: list = field(default_factory=list)
    initial: object = None
    initial_value: float = None
    assertions: list = field(default_factory=list)
    rewrites: list = field(default_factory=list)

    def by_role(self, role):
        """Variables of one role, in declaration order."""
        return [v for v in self.variables if v.role == role]


@dataclass
class Relation:
    """A relation ``lhs op rhs`` that generates events.

    ``symbol`` stands for its value (1 or 0) in the equations, held
    between events; ``value`` is the relation itself and ``indicator``
    ``lhs - rhs`` for ``>`` and ``>=``, ``rhs - lhs`` for ``<`` and
    ``<=``: positive where the relation holds (the FMU back end adds a
    hysteresis to it, :meth:`fmu.backend.OdeModel.event_functions`).
    """

    symbol: object
    value: object
    indicator: object
    where: str = ""
    #: The symbol of the relation's rounding band, 0 until the FMU finds
    #: the relation on its zero within rounding (``fmu/c/model.c``,
    #: ``P_ZEROS``): added to ``indicator`` for ``>=`` and ``<=``,
    #: subtracted for ``>`` and ``<``; ``value`` is ``indicator >= 0``
    #: or ``> 0``.
    zero: object = None


@dataclass
class Discrete:
    """An Integer or Boolean variable and its equation ``symbol = value``.

    ``value`` is a formula in the continuous variables, the parameters,
    the other discrete variables, ``previous`` (the symbol of
    ``pre(symbol)``) and the other ones' ``pre``, and
    :attr:`FlatModel.initial`; the relations in it are their values
    (``Relation.value``), not held symbols. MSL's ``PartialFriction``:
    ``free = fn <= 0``, ``mode = if free then Free else ...``.
    """

    name: str
    symbol: object
    previous: object
    value: object
    start: float
    where: str = ""
    boolean: bool = False
    #: A Real assigned in when-clauses (MSL Pulse's ``T_start``), not an
    #: Integer
    real: bool = False


@dataclass
class When:
    """``when relation then reinit(state, value); ... end when``.

    ``relation`` indexes :attr:`FlatModel.relations`; ``reinits`` are
    ``(state name, value)`` with ``pre(x)`` read as the value of ``x``
    just before the event.
    """

    relation: int
    reinits: list
    where: str = ""


@dataclass
class Assertion:
    """``assert(condition, message, level)`` of an equation section.

    ``violated`` is 1 where the condition fails: the relations in it at
    their values (each relation of an ``AssertionLevel.error`` assert is
    also an event, so that the failure is found where it happens).
    ``message`` is the message with ``%g`` for each ``String(v)`` in it,
    whose values are ``values`` (``%%`` is a percent sign).
    """

    violated: object
    message: str
    values: list
    error: bool = True
    where: str = ""


_RELATIONS = ("less", "less_equal", "greater", "greater_equal")
_BINARY = {
    "add": lambda a, b: a + b, "subtract": lambda a, b: a - b,
    "multiply": lambda a, b: a * b, "divide": lambda a, b: a / b,
    "power": lambda a, b: a ** b,
    "less": lambda a, b: a < b, "less_equal": lambda a, b: a <= b,
    "greater": lambda a, b: a > b, "greater_equal": lambda a, b: a >= b,
    "equal": lambda a, b: a == b, "not_equal": lambda a, b: a != b,
    "and": casadi.logic_and, "or": casadi.logic_or,
}
_UNARY = {"negate": lambda a: -a, "plus": lambda a: a,
          "not": casadi.logic_not}
_BUILTIN = {
    "no_event": lambda a: a, "smooth": lambda order, a: a,
    "tanh": casadi.tanh, "sinh": casadi.sinh, "cosh": casadi.cosh,
    "sin": casadi.sin, "cos": casadi.cos, "tan": casadi.tan,
    "asin": casadi.asin, "acos": casadi.acos, "atan": casadi.atan,
    "atan2": casadi.atan2, "exp": casadi.exp, "log": casadi.log,
    "log10": casadi.log10, "sqrt": casadi.sqrt, "abs": casadi.fabs,
    "min": lambda *a: _extremum(casadi.fmin, "min", a),
    "max": lambda *a: _extremum(casadi.fmax, "max", a),
    "sign": casadi.sign, "integer": casadi.floor,
}
#: Builtins on arrays (parameter tables): matrix and vector constructors,
#: sum and size, evaluated when the model is read. ``[a, b; c, d]`` is
#: ``promoted_cat1`` of rows that are each ``promoted_cat2`` of their
#: elements, and a one-row ``[a, b]`` is ``promoted_cat2`` alone: both
#: make a matrix (Modelica specification 10.6.1-10.6.2).
_ARRAY_BUILTIN = {
    "promoted_cat1": lambda *rows: _promoted_cat(rows, 0),
    "promoted_cat2": lambda *items: _promoted_cat(items, 1),
    "sum": lambda a: _sum(a),
    "product": lambda a: _product(a),
    "size": lambda a, k: casadi.SX(float(np.shape(a)[_integer(k) - 1])),
}


def _stack(rows):
    """Rows of a matrix constructor ``[a, b; c, d]`` as a 2-D array."""
    rows = [np.atleast_1d(np.asarray(r, dtype=object)) for r in rows]
    if all(r.ndim == 1 for r in rows):
        return np.stack(rows)
    return np.concatenate([np.atleast_2d(r) for r in rows])


def _promoted_cat(items, axis):
    """``cat(axis + 1, ...)`` of ``[...]``, each operand promoted to a
    matrix first: a scalar to 1 x 1, a vector to a column."""
    matrices = []
    for item in items:
        item = np.asarray(item, dtype=object)
        matrices.append(item.reshape(1, 1) if item.ndim == 0 else
                        item.reshape(-1, 1) if item.ndim == 1 else item)
    try:
        return np.concatenate(matrices, axis=axis)
    except ValueError:
        shapes = " and ".join(str(m.shape) for m in matrices)
        raise FrontEndError(f"a matrix of parts of shapes {shapes} (rows "
                            "of different lengths)") from None


def _sum(array):
    items = list(np.asarray(array, dtype=object).ravel())
    total = casadi.SX(0)
    for item in items:
        total = total + item
    return total


def _product(array):
    total = casadi.SX(1)
    for item in np.asarray(array, dtype=object).ravel():
        total = total * item
    return total


def _extremum(pick, name, args):
    """``min(a, b)``, ``max(a, b)`` of two scalars, or the least or
    greatest element of one array (``max({a, 2})``)."""
    if len(args) == 2:
        return pick(*args)
    items = list(np.asarray(args[0], dtype=object).ravel()) \
        if len(args) == 1 else []
    if not items:
        raise FrontEndError(f"{name}() of {len(args)} arguments or of an "
                            "empty array; allowed: two scalars or one "
                            "array")
    found = casadi.SX(items[0])
    for item in items[1:]:
        found = pick(found, item)
    return found


def _integer(value):
    """An array subscript or dimension: a constant integer."""
    if isinstance(value, np.ndarray) or casadi.symvar(casadi.SX(value)):
        raise FrontEndError("an array subscript that is not a constant "
                            "integer is not supported by the FMU back end")
    number = float(casadi.evalf(value))
    if number != int(number):
        raise FrontEndError(f"array subscript {number} is not an integer")
    return int(number)


#: Expression kinds of rumoca's graph, as a Modelica user names them.
_KINDS = {"index": "array indexing", "array": "array constructor",
          "call": "function call", "range": "range expression"}


class _Expressions:
    """Converts rumoca's expression nodes to CasADi SX, memoised."""

    def __init__(self, storage, symbols, derivatives, time):
        graph = storage["expressions"]
        self._functions = storage.get("functions") or []
        self._known = {raw["name"] for raw in storage["variables"]
                       if raw["role"] in ("parameter", "constant")}
        self._relation_count = len(storage.get("relations") or [])
        self._no_event = 0   # depth of noEvent(...) being converted
        self._frames = []   # values of the inlined functions' variables
        self._nodes = graph["nodes"]
        self._operands = graph["operands"]
        self._symbols, self._derivatives = symbols, derivatives
        self._time = time
        self._cache = {}
        self.where = ""   # file:line of what is being converted
        #: relation node -> position in storage["relations"]
        self.relation_of = {}
        self.relations = {}   # position -> Relation
        self.pre_is_state = False   # pre(x) allowed (reinit values)
        #: variable index -> symbol of pre(x), for discrete variables
        #: (set by load_flat_model with ``hybrid``; else pre is refused)
        self.previous = {}
        self.initial = None   # symbol of initial(), with ``hybrid``
        self._conditions = storage.get("conditions") or []
        self._domains = storage.get("domains") or []
        #: (domain, ordinal) -> value of the iterator of a reduction or
        #: array comprehension being converted
        self._binders = {}
        # nodes with a variable number of operands take them, in node
        # order, from the flat operand list
        self._offsets = {}
        offset = 0
        for index, node in enumerate(self._nodes):
            kind, body = next(iter(node.items()))
            if isinstance(body, dict) and "operand_count" in body:
                self._offsets[index] = offset
                offset += body["operand_count"]
        # index nodes likewise take their subscripts, in node order, from
        # the flat subscript list: {'index': node}, 'whole' (``:``) or
        # {'slice': range node} (``2:3``)
        self._subscripts = {}
        listed, offset = graph.get("subscripts") or [], 0
        for index, node in enumerate(self._nodes):
            kind, body = next(iter(node.items()))
            if kind == "index":
                count = body["subscript_count"]
                self._subscripts[index] = [
                    item["kind"] for item in listed[offset:offset + count]]
                offset += count

    def __call__(self, index):
        """The expression of node ``index``.

        The nodes below it are converted first, children before parents,
        from an explicit stack: a long expression (a sum of 5,000 terms
        is a chain of 5,000 nodes) needs no Python recursion. Only the
        operands of ``noEvent(...)``, whose conversion depends on that
        context, and the bodies of inlined functions (a frame of their
        own) are converted by a nested call.
        """
        if index is None:
            return None
        pending = [(index, False)]   # (node, its children are done)
        while pending:
            node, ready = pending.pop()
            if node in self._cache:
                continue
            if ready:
                self._cache[node] = self._convert(node)
                continue
            pending.append((node, True))
            pending.extend((child, False) for child in self._children(node)
                           if child is not None and child not in self._cache)
        return self._cache[index]

    def _children(self, index):
        """The operand nodes of node ``index`` that :meth:`_convert`
        converts in the same context (see :meth:`__call__`)."""
        kind, body = next(iter(self._nodes[index].items()))
        if kind == "binary":
            return (body["lhs"], body["rhs"])
        if kind == "unary":
            return (body["operand"],)
        if kind == "index":
            return (body["base"], *(
                next(iter(item.values())) for item in self._subscripts[index]
                if isinstance(item, dict) and "index" in item))
        if kind == "builtin" and body["builtin"] == "no_event":
            return ()
        if kind in ("array", "builtin", "conditional", "call") and \
                index in self._offsets:
            start = self._offsets[index]
            return self._operands[start:start + body["operand_count"]]
        return ()

    def _relation(self, index, body):
        """The symbol of an event-generating relation, recorded once."""
        position = self.relation_of[index]
        if self._binders:
            raise FrontEndError(f"{self.where}: a relation that generates "
                                "events inside a for-expression is not "
                                "supported; allowed: noEvent(...) around it")
        if position not in self.relations:
            op = body["operator"]
            if op not in _RELATIONS:
                raise FrontEndError(f"{self.where}: relation {op!r} on "
                                    "continuous variables is not supported "
                                    "(use <, <=, > or >=)")
            lhs, rhs = self(body["lhs"]), self(body["rhs"])
            zero = casadi.SX.sym(f"zero{position + 1}")
            difference = lhs - rhs if op in ("greater", "greater_equal") \
                else rhs - lhs
            if op in ("greater_equal", "less_equal"):
                indicator = difference + zero
                value = indicator >= 0
            else:
                indicator = difference - zero
                value = indicator > 0
            self.relations[position] = Relation(
                symbol=casadi.SX.sym(f"relation{position + 1}"),
                value=value, indicator=indicator, where=self.where,
                zero=zero)
        return self.relations[position].symbol

    def _is_time_event(self, body):
        """Whether a relation compares time with parameters (``time <
        startTime`` of MSL's Step and Ramp): rumoca lists it as a time
        event, not as a relation; it generates an event all the same,
        located by its indicator ``time - startTime``."""
        lhs, rhs = self(body["lhs"]), self(body["rhs"])
        if isinstance(lhs, np.ndarray) or isinstance(rhs, np.ndarray):
            return False
        names = {v.name() for v in casadi.symvar(casadi.SX(lhs - rhs))}
        return "time" in names and names - {"time"} <= self._known

    def _args(self, index, count):
        start = self._offsets[index]
        return [self(i) for i in self._operands[start:start + count]]

    def _convert(self, index):
        kind, body = next(iter(self._nodes[index].items()))
        if kind == "literal":
            value = next(iter(body.values()))
            return casadi.SX(float(value))
        if kind == "coordinate":
            if body == "time":
                return self._time
            role, position = next(iter(body.items()))
            if role == "derivative":
                return self._derivatives[position]
            if role == "pre_state" and self.pre_is_state:
                return self._symbols[position]
            if role in ("pre_discrete_value", "pre_discrete_real") and \
                    position in self.previous:
                return self.previous[position]
            if role in _DISCRETE_ROLES and self.previous:
                return self._symbols[position]
            if role == "condition" and self.initial is not None and \
                    self._conditions[position].get("node") == "initial":
                return self.initial
            if role.startswith("function_"):
                return self._function_variable(role, position)
            if role == "binder":
                return self._binder(position)
            if role not in _ROLES:
                raise FrontEndError(f"{self.where}: {role.replace('_', ' ')} "
                                    "references (pre, edge, change) are not "
                                    "supported by the FMU back end")
            return self._symbols[position]
        if kind == "binary" and index in self.relation_of and \
                body["operator"] in ("equal", "not_equal") and self.previous:
            # Integer comparisons of the mode logic (pre(mode) == Stuck):
            # they change at events only, and generate none
            return _BINARY[body["operator"]](self(body["lhs"]),
                                             self(body["rhs"]))
        if kind == "binary" and index in self.relation_of:
            return self._relation(index, body)
        if kind == "binary" and body["operator"] in _RELATIONS and \
                not self._no_event and self._is_time_event(body):
            self.relation_of[index] = self._relation_count
            self._relation_count += 1
            return self._relation(index, body)
        if kind == "binary":
            op = body["operator"]
            if op not in _BINARY:
                raise FrontEndError(f"{self.where}: operator {op!r} is not "
                                    "supported by the FMU back end")
            return _BINARY[op](self(body["lhs"]), self(body["rhs"]))
        if kind == "unary":
            op = body["operator"]
            if op not in _UNARY:
                raise FrontEndError(f"{self.where}: operator {op!r} is not "
                                    "supported by the FMU back end")
            return _UNARY[op](self(body["operand"]))
        if kind == "array":
            items = self._args(index, body["operand_count"])
            return np.array(items, dtype=object) if not any(
                isinstance(i, np.ndarray) for i in items) else _stack(items)
        if kind == "index":
            base = self(body["base"])
            try:
                subscripts = tuple(self._subscript(item) for item in
                                   self._subscripts[index])
                if any(isinstance(k, casadi.SX) for k in subscripts):
                    return _select(base, subscripts)
                if not isinstance(base, np.ndarray) or \
                        len(subscripts) != base.ndim or \
                        any(not 0 <= k < n for k, n in zip(subscripts,
                                                           base.shape)
                            if isinstance(k, int)) or \
                        any(not all(0 <= j < n for j in k)
                            for k, n in zip(subscripts, base.shape)
                            if isinstance(k, list)):
                    raise FrontEndError(f"array index {subscripts} out of "
                                        f"range")
            except FrontEndError as exc:
                raise FrontEndError(f"{self.where}: {exc}") from None
            picked = base[tuple(slice(None) if k is None else k
                                for k in subscripts)]
            return picked if isinstance(picked, np.ndarray) and \
                picked.ndim else picked[()] if isinstance(
                    picked, np.ndarray) else picked
        if kind == "builtin" and body["builtin"] in _ARRAY_BUILTIN:
            try:
                return _ARRAY_BUILTIN[body["builtin"]](
                    *self._args(index, body["operand_count"]))
            except FrontEndError as exc:
                raise FrontEndError(f"{self.where}: {exc}") from None
        if kind == "builtin":
            name = body["builtin"]
            if name not in _BUILTIN:
                raise FrontEndError(f"{self.where}: function {name}() is not "
                                    "supported by the FMU back end")
            self._no_event += name == "no_event"
            try:
                args = self._args(index, body["operand_count"])
            finally:
                self._no_event -= name == "no_event"
            return _BUILTIN[name](*args)
        if kind == "conditional":
            args = self._args(index, body["operand_count"])
            try:
                return _conditional(args)
            except FrontEndError as exc:
                raise FrontEndError(f"{self.where}: {exc}") from None
        if kind == "call":
            return self._call(index, body)
        if kind == "comprehension":
            return self._comprehension(body)
        if kind == "function_value":
            return self._definition(body)
        raise FrontEndError(f"{self.where}: {_KINDS.get(kind, kind)} is not "
                            "supported by the FMU back end")

    def _subscript(self, item):
        """A subscript, 0-based: an integer, None for ``:``, or the list
        of a range ``2:3`` (``a:b:c``)."""
        if item == "whole":
            return None
        kind, node = next(iter(item.items()))
        if kind == "index":
            value = self(node)
            if self._frames and not isinstance(value, np.ndarray) and \
                    casadi.symvar(casadi.SX(value)):
                return casadi.SX(value) - 1   # a function's loop index
            return _integer(value) - 1
        span = next(iter(self._nodes[node].values()))
        start = _integer(self(span["start_expression"]))
        stop = _integer(self(span["stop_expression"]))
        step = span.get("explicit_step_expression")
        step = 1 if step is None else _integer(self(step))
        if step == 0:
            raise FrontEndError("a range subscript with step 0")
        return [k - 1 for k in range(start, stop + (1 if step > 0 else -1),
                                     step)]

    def _binder(self, reference):
        key = (reference["domain"], reference["ordinal"])
        if key not in self._binders:
            raise FrontEndError(f"{self.where}: the iterator of a for-"
                                "expression is used outside it")
        return casadi.SX(float(self._binders[key]))

    def _ranges(self, body):
        """The integer range of each iterator of a comprehension's or a
        structured equation's domain (rumoca evaluates the bounds)."""
        ranges = []
        for binder in self._domains[body["domain"]]["domain"].get(
                "binders") or []:
            lower, upper, step = (binder.get(k) for k in
                                  ("lower", "upper", "step"))
            if not all(isinstance(v, (int, float)) and v == int(v)
                       for v in (lower, upper, step)) or not step:
                raise FrontEndError(
                    f"{self.where}: the range of {binder.get('display_name')}"
                    f" ({binder}) is not supported; allowed: a range a:b or "
                    "a:step:b of integers known when the model is read")
            ranges.append(range(int(lower), int(upper) + (1 if step > 0
                                                          else -1),
                                int(step)))
        return ranges

    def _comprehension(self, body):
        """``{expr for k in a:b}`` (and the operand of ``sum(expr for k in
        a:b)``, ``product``, ``min``, ``max``): the vector of ``expr`` at
        each value of the iterator, its range constant (rumoca evaluates
        it). The body is converted once per value, in a cache of its
        own, as an inlined function's is."""
        ranges = self._ranges(body)
        if len(ranges) != 1:
            raise FrontEndError(f"{self.where}: a for-expression with "
                                f"{len(ranges)} iterators is not supported;"
                                " allowed: one iterator (sum(a[k] for k in "
                                "1:n))")
        items = []
        saved, self._cache = self._cache, {}
        try:
            for value in ranges[0]:
                self._binders[(body["domain"], 0)] = value
                self._cache = {}
                items.append(self(body["body"]))
        finally:
            self._binders.pop((body["domain"], 0), None)
            self._cache = saved
        if any(isinstance(i, np.ndarray) for i in items):
            return np.stack([np.asarray(i, dtype=object) for i in items])
        return np.array(items, dtype=object)

    def structured(self, body):
        """The scalar residuals of an array equation, rumoca's structured
        equation over a domain of element indices (``__array_i1`` in
        ``1:2``), in row-major order: each body converted whole where it
        does not name the indices (``s - (if c then {1, 1} else {-1,
        -1})``, its elements taken), else once per element."""
        ranges = self._ranges(body)
        shape = tuple(len(r) for r in ranges)
        residuals = []
        for node in body.get("bodies") or []:
            try:
                whole = self(node)
            except FrontEndError as exc:
                if "used outside it" not in str(exc):
                    raise
                whole = None
            if whole is not None:
                value = np.asarray(whole, dtype=object)
                if value.shape != shape:
                    raise FrontEndError(
                        f"{self.where}: this array equation has shape "
                        f"{value.shape}, not that of its elements {shape}")
                residuals.extend(value[p] for p in np.ndindex(shape))
                continue
            saved, self._cache = self._cache, {}
            try:
                for position in product(*ranges):
                    for ordinal, value in enumerate(position):
                        self._binders[(body["domain"], ordinal)] = value
                    self._cache = {}
                    residuals.append(self(node))
            finally:
                for ordinal in range(len(ranges)):
                    self._binders.pop((body["domain"], ordinal), None)
                self._cache = saved
        return residuals

    def _function_variable(self, role, reference):
        """A parameter, output or local of the function being inlined."""
        key = (role, reference.get("ordinal"))
        if not self._frames or key not in self._frames[-1]:
            raise FrontEndError(f"{self.where}: {role.replace('_', ' ')} "
                                f"{reference} is used before it has a value")
        return self._frames[-1][key]

    def _call(self, index, body):
        """Inline a call of a Modelica function whose algorithm is a
        sequence of assignments (``Modelica.Math``'s wrappers of the
        builtins, small user functions); the requested output's value."""
        function = self._functions[body["function"]]
        name = function["name"]
        args = self._args(index, body["operand_count"])
        declared = function.get("parameters") or []
        if len(args) > len(declared):
            raise FrontEndError(f"{self.where}: {name}() takes "
                                f"{len(declared)} arguments, not {len(args)}")
        if len(args) < len(declared) or function.get("external") \
                or len(self._frames) > 20:
            why = "external functions" if function.get("external") else \
                "default arguments" if len(args) < len(declared) else \
                "recursive functions"
            raise FrontEndError(f"{self.where}: {name}(): {why} are not "
                                "supported by the FMU back end")
        frame = {("function_parameter", k): value
                 for k, value in enumerate(args)}
        saved, self._cache = self._cache, {}
        self._frames.append(frame)
        try:
            self._statements(name, function.get("statements") or [], frame,
                             [0])
        finally:
            self._frames.pop()
            self._cache = saved
        key = ("function_output", body["output"])
        if key not in frame:
            raise FrontEndError(f"{self.where}: {name}(): output "
                                f"{body['output'] + 1} is never assigned")
        return frame[key]

    def _statements(self, name, statements, frame, counter):
        """Run a function's statements as rumoca writes them, in single
        assignment form: each assignment is a new definition of its
        target (``function_value`` nodes read a definition by its
        ordinal, numbered in the order the statements are written); an
        ``if`` is an ``assignment_group`` of conditional values; a
        ``while`` or ``for`` loop whose trips rumoca bounds is a ``for``
        over a domain whose targets are carried from one trip to the next
        (definitions at its start, the fold parameters, and after it, the
        fold outputs). ``counter`` holds the next ordinal."""
        for statement in statements:
            kind, step = next(iter(statement.items()))
            if kind in ("assignment", "assignment_group"):
                items = [step] if kind == "assignment" else \
                    step["assignments"]
                values = [self(item["rhs"]) for item in items]
                for item, value in zip(items, values):
                    frame[("function_output", item["target"])] = value
                    frame[("definition", counter[0])] = value
                    counter[0] += 1
                self._cache = {}
            elif kind == "for" and not step.get("iteration_locals"):
                self._loop(name, step, frame, counter)
            else:
                raise FrontEndError(
                    f"{self.where}: {name}(): {kind} statements in a "
                    "function are not supported by the FMU back end "
                    "(assignments, if and for loops are)")

    def _loop(self, name, step, frame, counter):
        """A ``for`` statement of :meth:`_statements`."""
        targets = step["targets"]
        folded = counter[0]
        first = folded + len(targets)
        after = first + _definitions(step["statements"])
        (values,) = self._ranges(step)
        for value in values:
            for k, target in enumerate(targets):
                frame[("definition", folded + k)] = \
                    frame.get(("function_output", target))
            self._binders[(step["domain"], 0)] = value
            self._cache = {}
            counter[0] = first
            try:
                self._statements(name, step["statements"], frame, counter)
            finally:
                self._binders.pop((step["domain"], 0), None)
        for k, target in enumerate(targets):
            if not values:
                frame[("definition", folded + k)] = \
                    frame.get(("function_output", target))
            frame[("definition", after + k)] = \
                frame.get(("function_output", target))
        counter[0] = after + len(targets)
        self._cache = {}

    def _definition(self, body):
        """The value of a ``function_value`` node: a definition of the
        function being inlined (:meth:`_statements`)."""
        key = ("definition", body["definition_ordinal"])
        if not self._frames or self._frames[-1].get(key) is None:
            raise FrontEndError(f"{self.where}: a local of a function is "
                                "used before it has a value")
        return self._frames[-1][key]


def _select(base, subscripts):
    """``base[subscripts]`` where some subscripts are expressions (0-based,
    known only when the model runs: a function's loop index that a
    condition on parameters sets, as ``i := nrow`` of MSL's
    ``Matrices.isEqual``): the element picked by a chain of if_else over
    the positions they may take; an index outside the array is an
    error, as in Modelica."""
    if not isinstance(base, np.ndarray) or len(subscripts) != base.ndim or \
            any(not isinstance(k, (int, casadi.SX)) for k in subscripts):
        raise FrontEndError("an array subscript that is not a constant "
                            "integer is allowed on an element of an array "
                            "only (a[i, j])")
    if base.size > 10000:
        raise FrontEndError(f"an array subscript that is not a constant "
                            f"integer on an array of {base.size} elements; "
                            f"allowed: up to 10,000")
    result = casadi.SX(np.nan)   # out of range: not a number
    for position in np.ndindex(base.shape):
        if any(isinstance(k, int) and k != p
               for k, p in zip(subscripts, position)):
            continue
        here = casadi.SX(1)
        for k, p in zip(subscripts, position):
            if isinstance(k, casadi.SX):
                here = casadi.logic_and(here, k == p)
        result = casadi.if_else(here, base[position], result)
    return result


def _definitions(statements):
    """How many definitions :meth:`_Expressions._statements` numbers in
    ``statements``."""
    count = 0
    for statement in statements:
        kind, step = next(iter(statement.items()))
        if kind == "assignment":
            count += 1
        elif kind == "assignment_group":
            count += len(step["assignments"])
        elif kind == "for":
            count += 2 * len(step["targets"]) + _definitions(
                step["statements"])
    return count


def _conditional(args):
    """``if c1 then v1 elseif c2 then v2 ... else v`` as nested if_else."""
    *pairs, otherwise = args
    if any(isinstance(a, np.ndarray) for a in args[1::2] + [otherwise]):
        # array branches ({1, 1} of MSL's Clutch table_signs): element-wise
        shapes = {np.shape(a) for a in args[1::2] + [otherwise]}
        if len(shapes) != 1:
            raise FrontEndError(f"the branches of an if-expression have "
                                f"shapes {sorted(shapes)}; allowed: one shape")
        shape = shapes.pop()
        result = np.empty(shape, dtype=object)
        for position in np.ndindex(shape):
            result[position] = _conditional(
                [c for pair in zip(pairs[::2], pairs[1::2]) for c in
                 (pair[0], np.asarray(pair[1], dtype=object)[position])] +
                [np.asarray(otherwise, dtype=object)[position]])
        return result
    result = otherwise
    for condition, value in reversed(list(zip(pairs[::2], pairs[1::2]))):
        result = casadi.if_else(condition, value, result, True)
    return result


def package_version(model_name, roots):
    """The ``version`` annotation of the top-level package of
    ``model_name`` (``Judder`` of ``Judder.Examples.Driveline4DOF``), or
    ``""`` for a class outside a package or a package without one.

    The class annotation of a package stands last in its body (Modelica's
    grammar), so it is read between the last nested ``end Name;`` and the
    package's own ``end``.
    """
    import re
    if "." not in model_name:
        return ""
    top = model_name.split(".")[0]
    for root in roots:
        try:
            text = class_source(root, top).read_text()
        except FrontEndError:
            continue
        ends = list(re.finditer(r"\bend\s+([\w.]+)\s*;", text))
        if not ends or ends[-1].group(1) != top:
            continue
        body = text[ends[-2].end() if len(ends) > 1 else 0:ends[-1].start()]
        found = re.search(r"\bversion\s*=\s*\"([^\"]*)\"", body)
        return found.group(1) if found else ""
    return ""


def _flatten(path, model_name, roots, use_cache=True, hybrid=False):
    """rumoca's flat model of ``model_name``, from the cache
    (:mod:`fmu.cache`) while no source under ``roots`` has changed, and
    the bindings rewritten for rumoca (:mod:`fmu.rewrite`).

    The source checks run before the cache is read: the flat model
    stored does not depend on ``hybrid``, the refusals do (a class
    flattened with its Integer variables read is refused all the same
    where they are not). rumoca reads the libraries as
    :func:`fmu.rewrite.prepare` rewrote them, in copies; the flat model's
    files and rumoca's messages name the user's files."""
    import tempfile
    import rumoca
    from . import cache
    from .limits import check_source_arrays
    from .precheck import refuse_unsupported
    from .rewrite import REWRITE_VERSION, prepare
    check_source_arrays(path, check_source_text(path))
    refuse_unsupported(path, model_name, roots, hybrid)
    roots = _with_modelica_path(roots)
    with tempfile.TemporaryDirectory(prefix="judder-rewritten-") as scratch:
        if not use_cache:
            prepared = prepare(roots, path, scratch=scratch, remember=False)
            return _named_back(_flatten_with_rumoca(
                path, model_name, roots, use_cache=False,
                prepared=prepared), prepared), prepared.rewrites
        stamp = cache.sources_stamp(path, roots)
        prepared = prepare(roots, path, scratch=scratch, stamp=stamp)
        key = cache.cache_key(path, model_name, roots, f"{rumoca.version()}"
                              f"+rewrite{REWRITE_VERSION}", stamp=stamp)
        flat = cache.load(key)
        if flat is not None and "refused" in flat:
            raise FrontEndError(flat["refused"] + " (refused before, "
                                "from the flat-model cache)")
        if flat is None:
            try:
                flat = _named_back(_flatten_with_rumoca(
                    path, model_name, roots, prepared=prepared), prepared)
            except FrontEndError as exc:
                if _RUMOCA_OWN in str(exc):
                    cache.store(key, {"refused": str(exc)})
                raise
            cache.store(key, flat)
    return flat, prepared.rewrites


def _with_modelica_path(roots):
    """``roots`` and then the folders of ``MODELICAPATH``
    (:func:`fmu.classes.modelica_path`), each folder once: rumoca is
    given them all and does not read the variable itself
    (:mod:`fmu.rumoca_child`), so the rewrite (:mod:`fmu.rewrite`) and
    the flat-model cache's key cover the MSL a caller finds there
    (pysim's FMUs pass only the user's folders and the project's)."""
    from .classes import modelica_path
    seen, found = set(), []
    for root in modelica_path(roots):
        key = Path(root).resolve()
        if key not in seen:
            seen.add(key)
            found.append(root)
    return found


def _named_back(flat, prepared):
    """``flat`` with the files of rumoca's source map named as the
    user's, not as their rewritten copies."""
    if not prepared.copies:
        return flat
    source_map = flat.get("source_map", {})
    source_map["files"] = [
        [entry[0], prepared.named_back(entry[1]), *entry[2:]]
        for entry in source_map.get("files", [])]
    return flat


def _flatten_with_rumoca(path, model_name, roots, use_cache=True,
                         prepared=None):
    """rumoca's flat model, flattened in a child process
    (:mod:`fmu.rumoca_child`): a crash, an abort or a hang of rumoca
    becomes a :class:`FrontEndError`, never the end of this process.
    ``prepared`` (:func:`fmu.rewrite.prepare`) gives the rewritten
    copies rumoca reads."""
    from .rumoca_child import flatten_isolated
    try:
        if prepared is None:
            return flatten_isolated(path, model_name, roots)
        return flatten_isolated(prepared.path, model_name, prepared.roots)
    except FrontEndError as exc:
        message = str(exc) if prepared is None else \
            prepared.named_back(str(exc))
    from .balance import explain_unbalanced   # scipy, on failure only
    if use_cache:
        message += explain_unbalanced(message, model_name, roots,
                                      load_flat_model)
    if "function shape proof" in message:
        message += _shape_proof_words(message, roots)
    raise FrontEndError(message)


#: rumoca's refusal of a model in its DAE stage: it depends on the
#: sources and rumoca's version only (kept by the flat-model cache).
_RUMOCA_OWN = "todae failed"


def _shape_proof_words(message, roots):
    """What rumoca 0.10.2's "function shape proof: `q`: axis 1 requires
    extent 2 but the call site proves 3" means, with the functions whose
    array input ``q`` it confused: it takes functions of one short name
    declared in different classes (MSL's ``position`` of
    ``Sources.Move`` and of ``AngleToTorqueAdaptor.Move_w``) for one,
    and the sizes of their array inputs then disagree
    (docs/compiler.md)."""
    import re
    found = re.search(r"function shape proof`?: `?(\w+)`?", message)
    if not found:
        return ""
    argument = found.group(1)
    declared = re.compile(rf"\binput\s+Real\s+{argument}\s*\[")
    function = re.compile(r"\bfunction\s+(\w+)")
    texts = {}
    for root in map(Path, roots):
        files = [root] if root.is_file() else sorted(root.rglob("*.mo"))
        for source in files:
            try:
                texts[source] = source.read_text(encoding="utf-8",
                                                 errors="replace")
            except OSError:
                continue
    names = set()
    for text in texts.values():
        for hit in declared.finditer(text):
            owners = list(function.finditer(text, 0, hit.start()))
            if owners:
                names.add(owners[-1].group(1))
    places = [f"{hit.group(1)}() at {source}:"
              f"{text.count(chr(10), 0, hit.start()) + 1}"
              for source, text in texts.items() for hit in function.finditer(
                  text) if hit.group(1) in names]
    words = (f"; rumoca 0.10.2 takes functions of one name declared in "
             f"different classes for one function, and their array input "
             f"{argument} then has two sizes (a minimal model is in "
             f"docs/compiler.md); allowed: functions of distinct names")
    if places:
        words += (f"; the functions of these names: {', '.join(places[:6])}"
                  + (f" and {len(places) - 6} more" if len(places) > 6
                     else ""))
    return words


def check_source_text(path):
    """The text of ``path``; refuse a source that is not UTF-8 text
    (Modelica's encoding), naming the file, the byte, its offset and its
    line."""
    data = Path(path).read_bytes()
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = data[:exc.start].count(b"\n") + 1
        raise FrontEndError(
            f"{path}: not UTF-8 text (byte 0x{data[exc.start]:02x} at "
            f"offset {exc.start}, line {line}); allowed: UTF-8 text, as "
            "Modelica requires (save the file as UTF-8)") from None


#: rumoca's roles of Integer and Boolean variables (``discrete_value``)
#: and of Real variables assigned in when-clauses (``discrete_real``,
#: MSL's ``Pulse.T_start``): held between events, read with ``hybrid``.
_DISCRETE_ROLES = ("discrete_value", "discrete_real")
#: Roles of rumoca's flat variables that the back end compiles.
_ROLES = ("state", "algebraic", "parameter", "constant", "input", "output")
#: Sections of rumoca's flat model the back end does not compile (yet),
#: with the Modelica construct that produces them.
_REFUSED = {
    "model_event_transactions": "when-equations",
    "discrete_real_equations": "discrete-time equations (when, sample)",
    "previous_values": "pre()",
    "structured_roots": "event conditions",
    "discrete_value_owners": "Integer or Boolean variables",
    "clocks": "clocked equations", "clock_ownerships": "clocked equations",
    "delays": "delay()",
    "domains": "for-equations and array equations",
    "terminals": "terminal()",
    "initial_discrete_values": "initial values of discrete variables",
    "initial_parameter_values": "parameters with fixed = false",
}


class _Locator:
    """``file:line`` of rumoca's source spans."""

    def __init__(self, flat):
        self._files = {entry[0]: (entry[1], entry[2]) for entry in
                       flat.get("source_map", {}).get("files", [])}

    def __call__(self, item):
        span = _first_span(item)
        if not span or span.get("source") not in self._files:
            return "(generated)"
        path, text = self._files[span["source"]]
        return f"{path}:{text[:span['start']].count(chr(10)) + 1}"


def _first_span(item):
    """The first source span found in a (nested) rumoca record."""
    if isinstance(item, dict):
        if isinstance(item.get("span"), dict) and "start" in item["span"]:
            return item["span"]
        children = item.values()
    elif isinstance(item, list):
        children = item
    else:
        return None
    for child in children:
        found = _first_span(child)
        if found:
            return found
    return None


def _check_supported(storage, model_name, where, hybrid=False):
    """Refuse, with the place in the source, what cannot be compiled
    (with ``hybrid``, Integer and Boolean variables defined by equations
    are read)."""
    for raw in storage["variables"]:
        place = where({"span": raw.get("declaration", {}).get("span")})
        if hybrid and raw["role"] in _DISCRETE_ROLES and not \
                storage["value_types"][raw["value_type"]].get("dimensions"):
            continue
        if raw["role"] not in _ROLES:
            kind = "arrays of Integer and Boolean variables are" if hybrid \
                and raw["role"] == "discrete_value" else \
                "Integer, Boolean and discrete variables are" \
                if "discrete" in raw["role"] else \
                f"variables of role {raw['role']!r} are"
            raise FrontEndError(f"{place}: {raw['name']}: {kind} not "
                                "supported by the FMU back end")
        value_type = storage["value_types"][raw["value_type"]]
        if value_type.get("dimensions") and \
                raw["role"] not in ("parameter", "constant", "algebraic"):
            raise FrontEndError(f"{place}: {raw['name']}: arrays of "
                                "variables are not supported by the FMU back "
                                "end (arrays of parameters and of algebraic "
                                "variables are)")
        if value_type.get("scalar") != "real" and \
                raw["role"] not in ("parameter", "constant"):
            raise FrontEndError(f"{place}: {raw['name']}: "
                                f"{value_type.get('scalar')} variables are "
                                "not supported by the FMU back end")
    for key, construct in _REFUSED.items():
        items = storage.get(key) or []
        if hybrid and key in ("discrete_value_owners",
                              "discrete_real_equations",
                              "initial_discrete_values"):
            continue
        if hybrid and key == "clocks" and all(
                isinstance(c.get("kind"), dict) and
                "lattice" in c["kind"].get("periodic", {})
                for c in items):
            continue   # sample(start, interval): _WhenConditions._sample
        if hybrid and key == "clock_ownerships" and not any(
                o.get("sampled") for o in items):
            continue   # the variables assigned in when sample(...) clauses
        if key == "domains":   # for-expressions, array equations: compiled
            items = [d for k, d in enumerate(items)
                     if k not in _comprehension_domains(storage)
                     and k not in _equation_domains(storage)
                     and k not in _function_domains(storage)]
        if items:
            place = where(items[0]) if isinstance(items[0], dict) else \
                model_name
            raise FrontEndError(f"{place}: {construct} are not supported "
                                f"by the FMU back end (model {model_name})")


def _comprehension_domains(storage):
    """The domains (iterator ranges) of for-expressions, ``sum(a[k] for k
    in 2:n)`` and ``{k*a[k] for k in 1:n}``, as rumoca writes them in
    bindings and function bodies (it unrolls those of equations)."""
    return {next(iter(node.values()))["domain"]
            for node in storage["expressions"]["nodes"]
            if "comprehension" in node}


def _function_domains(storage):
    """The domains of the loops of functions (rumoca writes a ``while``
    whose trips it bounds as a ``for``), run when a call is inlined."""
    found, pending = set(), [statement for function in
                             storage.get("functions") or []
                             for statement in function.get("statements")
                             or []]
    while pending:
        kind, step = next(iter(pending.pop().items()))
        if kind == "for":
            found.add(step["domain"])
            pending.extend(step.get("statements") or [])
    return found


def _equation_domains(storage):
    """The domains of array equations (``s = if c then {1, 1} else {-1,
    -1}`` of MSL's ``Clutch``), which rumoca keeps as one structured
    equation over the elements instead of unrolling it."""
    return {body["domain"]
            for section in ("continuous_equation_operations",
                            "initialization_equation_operations")
            for operation in storage.get(section) or []
            for kind, body in operation.items() if kind == "structured"}


def load_flat_model(path, model_name, roots=(), cache=True, hybrid=False):
    """Flatten ``model_name`` from ``path`` with rumoca; return a FlatModel.

    Parameters
    ----------
    path : str or Path
        The ``.mo`` file that holds the model.
    model_name : str
        Full class name, e.g. ``Judder.Examples.Driveline4DOF``.
    roots : sequence of paths
        Library folders the model uses.
    cache : bool
        Read and keep rumoca's flat model in :mod:`fmu.cache`.
    hybrid : bool
        Also read Integer and Boolean variables defined by equations,
        with ``pre()`` and ``initial()`` (MSL's ``PartialFriction``), into
        :attr:`FlatModel.discretes`, and ``initial()`` in the continuous
        equations (MSL's ``ElastoBacklash``): for a linearisation in one mode
        (:mod:`sources.modelica`) and for the FMU's event iteration
        (:mod:`fmu.backend`).

    Raises
    ------
    FrontEndError
        With rumoca's diagnostics (file, line, what is wrong), or the
        place of a construct the back end does not compile.
    """
    path = Path(path)
    flat, rewrites = _flatten(path, model_name, roots or [path.parent],
                              cache, hybrid)
    storage = flat["storage"]
    where = _Locator(flat)
    _check_supported(storage, model_name, where, hybrid)
    check_flat_arrays(storage, where)
    time = casadi.SX.sym("time")
    symbols, derivatives, variables = [], {}, []
    for index, raw in enumerate(storage["variables"]):
        shape = storage["value_types"][raw["value_type"]].get("dimensions")
        symbols.append(_element_symbols(raw["name"], shape) if shape
                       else casadi.SX.sym(raw["name"]))
        if raw["role"] == "state":
            derivatives[index] = casadi.SX.sym(f"der({raw['name']})")
    convert = _Expressions(storage, symbols, derivatives, time)
    if hybrid:
        convert.initial = casadi.SX.sym("initial()")
        convert.previous = {
            index: casadi.SX.sym(f"pre({raw['name']})")
            for index, raw in enumerate(storage["variables"])
            if raw["role"] in _DISCRETE_ROLES}
    types = _declared_types(roots or [path.parent], path)
    files = {entry[0]: entry[2] for entry in
             flat.get("source_map", {}).get("files", [])}
    for position, item in enumerate(storage.get("relations") or []):
        convert.relation_of[item["relation"]["expression"]] = position
    for index, raw in enumerate(storage["variables"]):
        attributes = raw.get("attributes", {})
        convert.where = where({"span": raw.get("declaration", {})
                               .get("span")})
        values = {key: convert(attributes.get(key))
                  for key in ("start", "binding", "min", "max")}
        elements = symbols[index]
        if not isinstance(elements, np.ndarray):
            elements, values = np.array([elements], dtype=object), \
                {k: np.array([v], dtype=object) for k, v in values.items()}
        quantity, display_unit = types.get(_type_of(raw, files), ("", ""))
        role = "discrete" if raw["role"] in _DISCRETE_ROLES else raw["role"]
        if role == "parameter" and \
                storage["value_types"][raw["value_type"]].get("scalar") \
                != "real":
            role = "constant"   # Boolean, Integer: evaluated at translation
        for position in np.ndindex(elements.shape):
            symbol = elements[position]
            variables.append(Variable(
                name=symbol.name(), role=role, symbol=symbol,
                derivative=derivatives.get(index),
                unit=attributes.get("unit") or "",
                description=attributes.get("description") or "",
                start=_element(values["start"], position, convert.where),
                fixed=_is_fixed(attributes.get("fixed")),
                binding=_element(values["binding"], position, convert.where),
                minimum=_element(values["min"], position, convert.where),
                maximum=_element(values["max"], position, convert.where),
                where=convert.where,
                causality=attributes.get("causality") or "",
                quantity=quantity, display_unit=display_unit))
    sections, places = {}, {}
    for section in ("continuous_equation_operations",
                    "initialization_equation_operations"):
        sections[section], places[section] = [], []
        for operation in storage.get(section) or []:
            kind, body = next(iter(operation.items()))
            convert.where = where(body)
            if kind == "structured":
                for residual in convert.structured(body):
                    sections[section].append(residual)
                    places[section].append(convert.where)
                continue
            if kind != "residual":
                raise FrontEndError(f"{convert.where}: equations of kind "
                                    f"{kind!r} are not supported by the FMU "
                                    "back end")
            sections[section].append(convert(body["residual"]))
            places[section].append(convert.where)
    for v in variables:
        # a fixed start of a variable that is not a state is an initial
        # equation (MSL's Spring(phi_rel(fixed=true)))
        if v.role in ("algebraic", "output") and v.fixed and \
                v.start is not None:
            sections["initialization_equation_operations"].append(
                v.symbol - v.start)
            places["initialization_equation_operations"].append(v.where)
    _modified_rewritten_parameters(variables, sections, places, rewrites)
    _parameters_of_initial_equations(variables, sections, places)
    declared = {(v.where, _last_name(v.name)) for v in variables}
    used = {v.where.rsplit(":", 1)[0] for v in variables}
    rewrites = [r for r in rewrites
                if (f"{r.file}:{r.line}", r.name) in declared or
                (r.kind in ("table", "for") and r.file in used)]
    assertions = _assertions(storage, convert, where)
    whens = _whens(storage, convert, where, variables)
    discretes, discrete_relations = _discretes(
        storage, convert, where, variables) if hybrid else ([], [])
    return FlatModel(
        name=model_name, variables=variables,
        residuals=sections["continuous_equation_operations"],
        initial_residuals=sections["initialization_equation_operations"],
        places=places["continuous_equation_operations"],
        initial_places=places["initialization_equation_operations"],
        relations=[convert.relations[k] for k in sorted(convert.relations)],
        whens=whens, discretes=discretes, initial=convert.initial,
        discrete_relations=discrete_relations, assertions=assertions,
        time=time, experiment=_experiment(path, model_name),
        rewrites=rewrites)


def _last_name(name):
    """``p`` of ``d[2].p``: the name a declaration gives."""
    return re.sub(r"\[[^\]]*\]", "", name).rsplit(".", 1)[-1]


def _modified_rewritten_parameters(variables, sections, places, rewrites):
    """A parameter whose binding :mod:`fmu.rewrite` made an initial
    equation, set by a modifier (``Rates d(p = 0.3)``, ``extends
    Rates(p = 0.3)``): the modifier's binding replaces the declared one,
    as in Modelica, so the initial equation of the declared binding is
    dropped and the parameter is fixed (else the initialisation is
    overdetermined: the modifier's binding and the equation).

    The equations of a class's rewrites share a line (its ``end``,
    :attr:`fmu.rewrite.Rewrite.at`); each is told apart as the one of its
    line that names one rewritten variable not yet matched (a binding
    may name another rewritten parameter of its class, never its own).

    Raises
    ------
    FrontEndError
        Where the equation cannot be told apart, naming the declaration.
    """
    rewritten = {(f"{r.file}:{r.line}", r.name): f"{r.file}:{r.at}"
                 for r in rewrites if r.parameter and r.at}
    if not rewritten:
        return
    at = {}   # the place of its equation -> the rewritten variables
    for v in variables:
        place = rewritten.get((v.where, _last_name(v.name)))
        if place is not None and v.role == "parameter":
            at.setdefault(place, []).append(v)
    modified = [v for group in at.values() for v in group
                if v.binding is not None]
    if not modified:
        return
    residuals = sections["initialization_equation_operations"]
    where = places["initialization_equation_operations"]
    owner = {}   # variable name -> index of its equation
    for place, group in at.items():
        names = {v.name for v in group}
        named = {k: {s.name() for s in casadi.symvar(casadi.SX(
            residuals[k]))} & names for k in range(len(residuals))
            if where[k] == place}
        grown = True
        while grown:
            grown = False
            for k, found in named.items():
                left = found - set(owner)
                if len(left) == 1 and k not in owner.values():
                    owner[left.pop()] = k
                    grown = True
    dropped = []
    for v in modified:
        if v.name not in owner:
            raise FrontEndError(
                f"{v.where}: {v.name} is set by a modifier, and its "
                "declared binding, rewritten as an initial equation "
                "(fmu/rewrite.py, rumoca 0.10.2 miscounts it), cannot be "
                "told apart from the other equations of its class; give "
                "the binding without a function of an array, or do not "
                "modify it")
        dropped.append(owner[v.name])
        v.fixed = True
    for k in sorted(dropped, reverse=True):
        del residuals[k], where[k]


def _parameters_of_initial_equations(variables, sections, places):
    """Read ``parameter Real p(fixed = false); initial equation p =
    f(...);`` as the calculated parameter ``p = f(...)``, where the
    initial equation is linear in ``p`` and names parameters and
    constants only: the form :mod:`fmu.rewrite` gives a parameter's
    binding that rumoca cannot read (MSL's ``Clutch.mu0``). The initial
    equation is removed; any other stays for the back end."""
    known = {v.name for v in variables if v.role in ("parameter",
                                                     "constant")}
    residuals = sections["initialization_equation_operations"]
    where = places["initialization_equation_operations"]
    for v in variables:
        if v.role != "parameter" or v.fixed or v.binding is not None:
            continue
        for k, residual in enumerate(residuals):
            names = {s.name() for s in casadi.symvar(casadi.SX(residual))}
            if v.name not in names or not names <= known:
                continue
            slope = casadi.jacobian(residual, v.symbol)
            if casadi.depends_on(slope, v.symbol) or \
                    casadi.SX(slope).is_zero():
                continue
            v.binding = casadi.simplify(-casadi.substitute(
                residual, v.symbol, casadi.SX(0)) / slope)
            v.fixed = True
            del residuals[k], where[k]
            break


def _discretes(storage, convert, where, variables):
    """The equations of the Integer and Boolean variables, one each,
    their relations as values (:class:`Discrete`), and the relations only
    they use.

    A variable assigned in a when-clause (``when c1 then n = v1;
    elsewhen c2 then n = v2; end when;``) has the equation ``n = if
    fires1 then v1 else if fires2 then v2 else pre(n)``, where ``fires``
    is ``not initial() and c and not pre(c)``: the clause acts where its
    condition becomes true, not during the initialisation (the
    Modelica specification writes a when-equation as ``v = if edge(b)
    then expr else pre(v)`` with ``b`` the condition, and its clauses act
    at the initialisation only through ``initial()``). Each condition
    ``c`` is a Boolean of its own (:class:`_WhenConditions`), whose
    ``pre()`` the event iteration holds like the others'."""
    by_name = {v.name: v for v in variables}
    relations = {r.symbol.name(): r.value for r in convert.relations.values()}
    held = dict(convert.relations)   # those of the continuous equations
    bound = [(v.symbol, v.binding if v.binding is not None else v.start)
             for v in variables if v.role in ("constant", "parameter")
             and not isinstance(v.binding if v.binding is not None
                                else v.start, (type(None), np.ndarray))]
    constants = (casadi.vertcat(casadi.SX(0, 1), *[s for s, _ in bound]),
                 casadi.vertcat(casadi.SX(0, 1), *[b for _, b in bound]))
    found, conditions = [], _WhenConditions(storage, convert, where)
    for owner in storage.get("discrete_value_owners") or []:
        convert.where = where(owner)
        branches = owner.get("branches") or []
        if len(owner.get("targets") or []) != 1 or not branches or \
                any(len(b.get("values") or []) != 1 for b in branches) or (
                    any(b.get("activation") == "always" for b in branches)
                    and len(branches) != 1):
            raise FrontEndError(f"{convert.where}: this equation of Integer "
                                "or Boolean variables is not supported; "
                                "allowed: one variable defined by an "
                                "equation that holds at all times (as MSL's "
                                "PartialFriction has) or assigned in the "
                                "branches of one when-clause")
        index = owner["targets"][0]
        variable = by_name[storage["variables"][index]["name"]]
        if branches[0].get("activation") == "always":
            value = convert(branches[0]["values"][0]["value"])
        else:
            value = convert.previous[index]
            for branch in reversed(branches):
                fires = conditions.fires(branch["activation"], where(branch))
                value = casadi.if_else(fires, convert(
                    branch["values"][0]["value"]), value)
        relations.update({r.symbol.name(): r.value
                          for r in convert.relations.values()})
        value = _with_values(value, relations)
        start = casadi.SX(variable.start if variable.start is not None
                          else 0.0)
        for _ in range(len(variables)):   # constants bound to constants
            if not casadi.symvar(start):
                break
            start = casadi.substitute(start, *constants)
        if casadi.symvar(start):
            raise FrontEndError(f"{variable.where}: {variable.name}: a start "
                                "value that is not a constant expression is "
                                "not supported (Integer and Boolean "
                                "variables)")
        found.append(Discrete(
            name=variable.name, symbol=variable.symbol,
            previous=convert.previous[index], value=value,
            start=float(casadi.evalf(start)), where=convert.where,
            boolean=storage["value_types"][storage["variables"][index][
                "value_type"]].get("scalar") == "boolean"))
    found += _discrete_reals(storage, convert, where, by_name, conditions)
    initial = {item["target"]: item for item in
               storage.get("initial_discrete_values") or []}
    for discrete in found:
        index = next((k for k, raw in enumerate(storage["variables"])
                      if raw["name"] == discrete.name), None)
        if index in initial:
            # an initial algorithm's (or initial equation's) value: the
            # discrete equation while initial() holds
            convert.where = where(initial[index])
            discrete.value = casadi.if_else(
                convert.initial, convert(initial[index]["value"]),
                discrete.value)
    relations.update({r.symbol.name(): r.value
                      for r in convert.relations.values()})
    for discrete in found:
        discrete.value = _with_values(discrete.value, relations)
    for condition in conditions.found:
        condition.value = _with_values(condition.value, relations)
    found += conditions.found
    extra = [r for k, r in sorted(convert.relations.items()) if k not in held]
    convert.relations = held
    return found, extra


def _discrete_reals(storage, convert, where, by_name, conditions):
    """The Real variables assigned in when-clauses (rumoca's
    ``discrete_real_equations``, MSL ``Pulse``'s ``T_start = time``), as
    :class:`Discrete` of their own, held like an Integer: ``v = if fires1
    then v1 else ... else pre(v)``, each ``v_k`` solved from its
    equation's residual (linear in ``v``)."""
    clauses = {}
    for equation in storage.get("discrete_real_equations") or []:
        convert.where = where(equation)
        residual = convert(equation["residual"])
        targets = [index for index in convert.previous
                   if storage["variables"][index]["role"] == "discrete_real"
                   and casadi.depends_on(casadi.SX(residual),
                                         convert._symbols[index])]
        if len(targets) != 1:
            raise FrontEndError(f"{convert.where}: this equation of discrete "
                                "Real variables is not supported; allowed: "
                                "one variable assigned in a when-clause "
                                "(v = expression)")
        symbol = convert._symbols[targets[0]]
        slope = casadi.jacobian(residual, symbol)
        if casadi.depends_on(slope, symbol) or casadi.is_equal(slope, 0):
            raise FrontEndError(f"{convert.where}: this equation of a "
                                "discrete Real variable is not linear in it; "
                                "allowed: v = expression")
        value = casadi.substitute(symbol - residual / slope, symbol,
                                  casadi.SX(0))
        clauses.setdefault(targets[0], []).append(
            (conditions.fires(equation.get("activation"), convert.where),
             value, convert.where))
    found = []
    for index, branches in clauses.items():
        variable = by_name[storage["variables"][index]["name"]]
        value = convert.previous[index]
        for fires, branch, _ in reversed(branches):
            value = casadi.if_else(fires, branch, value)
        start = variable.start if variable.start is not None else 0.0
        try:
            start = float(casadi.evalf(casadi.SX(start)))
        except RuntimeError:
            raise FrontEndError(f"{variable.where}: {variable.name}: a start "
                                "value that is not a constant expression is "
                                "not supported (discrete Real variables)"
                                ) from None
        found.append(Discrete(
            name=variable.name, symbol=variable.symbol,
            previous=convert.previous[index], value=value, start=start,
            where=branches[0][2], boolean=False, real=True))
    return found


class _WhenConditions:
    """The conditions of the when-clauses that assign Integer and Boolean
    variables, each a Boolean :class:`Discrete` of its own (named
    ``'when k'``, a quoted name no Modelica variable of the model has),
    built from rumoca's condition tree: relations, Boolean expressions
    (``edge(b)``, ``b``), ``and``, ``or`` and ``not`` of these."""

    def __init__(self, storage, convert, where):
        self._storage, self._convert, self._where = storage, convert, where
        self._by_trigger = {}
        self.found = []

    def fires(self, activation, place):
        """``not initial() and c and not pre(c)`` of the clause whose
        activation is ``activation`` (rumoca's ``{"when": {"trigger",
        "guard"}}``)."""
        when = activation.get("when") if isinstance(activation, dict) \
            else None
        if when is None or when.get("trigger") != when.get("guard"):
            raise FrontEndError(f"{place}: this activation of an Integer or "
                                f"Boolean variable ({activation}) is not "
                                "supported; allowed: always, or when-clauses "
                                "(when, elsewhen)")
        trigger = when["trigger"]
        if trigger not in self._by_trigger:
            name = f"'when {len(self.found) + 1}'"
            node = self._storage["conditions"][trigger]["node"]
            if isinstance(node, dict) and set(node) == {"clock"}:
                value = self._sample(node["clock"], trigger, place)
            else:
                value = _condition(self._storage, self._convert, trigger,
                                   place)
            self.found.append(Discrete(
                name=name, symbol=casadi.SX.sym(name),
                previous=casadi.SX.sym(f"pre({name})"),
                value=value, start=0.0, where=place, boolean=True))
            self._by_trigger[trigger] = self.found[-1]
        condition = self._by_trigger[trigger]
        return casadi.logic_and(casadi.logic_not(self._convert.initial),
                                casadi.logic_and(condition.symbol,
                                                 casadi.logic_not(
                                                     condition.previous)))


    def _sample(self, clock, trigger, place):
        """The condition of ``when sample(start, interval)`` (rumoca's
        periodic clock of phase ``start`` and period ``interval``, both
        numbers): a relation ``time >= start + pre(k) interval`` that
        becomes true at each tick, where ``k`` counts the ticks (an
        Integer of its own, ``'sample N'``, one more at each tick after
        the initialisation): a time event, located by its indicator."""
        kind = (self._storage.get("clocks") or [{}])[clock].get("kind", {})
        lattice = kind.get("periodic", {}).get("lattice") if isinstance(
            kind, dict) else None
        if not lattice or kind["periodic"].get("anchor") != "absolute":
            raise FrontEndError(f"{place}: this clock ({kind}) is not "
                                "supported; allowed: when sample(start, "
                                "interval) with numbers")
        period = lattice["period"]["num"] / lattice["period"]["den"]
        phase = lattice["phase"]["num"] / lattice["phase"]["den"]
        if period <= 0:
            raise FrontEndError(f"{place}: sample(): an interval of "
                                f"{period} s; allowed: an interval > 0")
        name = f"'sample {clock + 1}'"
        ticks = Discrete(name=name, symbol=casadi.SX.sym(name),
                         previous=casadi.SX.sym(f"pre({name})"), value=None,
                         start=0.0, where=place)
        convert = self._convert
        position = len(self._storage.get("relations") or []) + \
            len(self._storage.get("conditions") or []) + clock
        zero = casadi.SX.sym(f"zero{position + 1}")
        indicator = convert._time - (phase + ticks.previous * period) + zero
        relation = Relation(symbol=casadi.SX.sym(f"relation{position + 1}"),
                            value=indicator >= 0, indicator=indicator,
                            where=place, zero=zero)
        convert.relations[position] = relation
        ticks.value = casadi.if_else(
            casadi.logic_and(casadi.logic_not(convert.initial),
                             relation.symbol),
            ticks.previous + 1, ticks.previous)
        self.found.append(ticks)
        return relation.symbol


def _condition(storage, convert, index, place):
    """The value of when-condition ``index`` of rumoca's condition tree:
    relations (their held symbols), Boolean expressions (``edge(b)``,
    ``b``, ``n == 2``), and ``and``, ``or``, ``not`` of these."""
    node = storage["conditions"][index]["node"]
    kind, body = next(iter(node.items())) if isinstance(node, dict) else \
        (node, None)     # "initial"
    if kind == "relation":
        return convert(storage["relations"][body]["relation"]["expression"])
    if kind == "discrete":
        return convert(body)
    if kind == "not":
        return casadi.logic_not(_condition(storage, convert, body, place))
    if kind in ("and", "or"):
        return _BINARY[kind](_condition(storage, convert, body["lhs"], place),
                             _condition(storage, convert, body["rhs"], place))
    raise FrontEndError(f"{place}: this when-condition ({kind}) is not "
                        "supported; allowed: relations and Boolean "
                        "expressions joined by and, or, not")


def _with_values(expression, relations):
    """``expression`` with the relations' symbols it holds replaced by the
    relations themselves (``relations``: symbol name -> value)."""
    used = [s for s in casadi.symvar(casadi.SX(expression))
            if s.name() in relations]
    if not used:
        return expression
    return casadi.substitute(expression, casadi.vertcat(*used),
                             casadi.vertcat(*[relations[s.name()]
                                              for s in used]))


def _when_relation(storage, convert, trigger, place):
    """The position in ``convert.relations`` of the relation that fires a
    reinit's when-clause: the condition's own when it is one relation of
    Real variables; else (``h < 0 and v < 0``, ``n == 2``) a relation of
    its own whose value is the condition, the relations in it at their
    values, and whose indicator is 1: it changes only where the relations
    and discrete variables in it do, at their events."""
    node = storage["conditions"][trigger]["node"]
    if isinstance(node, dict) and set(node) == {"clock"}:
        raise FrontEndError(f"{place}: reinit in a when sample(...) clause: "
                            "clocked equations are not supported; allowed: "
                            "when sample(start, interval) assigning "
                            "Integer, Boolean or Real variables, or reinit "
                            "in a when-clause of relations")
    if isinstance(node, dict) and set(node) == {"relation"}:
        expression = storage["relations"][node["relation"]]["relation"][
            "expression"]
        convert(expression)   # records the relation
        if node["relation"] in convert.relations:
            return node["relation"]
    value = _with_values(_condition(storage, convert, trigger, place), {
        r.symbol.name(): r.value for r in convert.relations.values()})
    position = len(storage.get("relations") or []) + trigger
    convert.relations[position] = Relation(
        symbol=casadi.SX.sym(f"relation{position + 1}"), value=value,
        indicator=casadi.SX(1), where=place)
    return position


#: rumoca's event actions of ``assert``: ``assert`` (level error, its
#: guard the condition's negation) and ``warning`` (its condition in
#: ``noEvent``, guard and trigger always).
_ASSERT_KINDS = ("assert", "warning")


def _assertions(storage, convert, where):
    """The ``assert(...)`` of the equations (:class:`Assertion`)."""
    conditions = storage.get("conditions") or []
    found = []
    for action in storage.get("event_actions") or []:
        kind, body = next(iter(action["kind"].items()))
        if kind not in _ASSERT_KINDS:
            continue
        convert.where = where(action)
        always = [k for k, c in enumerate(conditions)
                  if c.get("node") == "always"]
        if action["trigger"] not in always or (
                kind == "warning" and action["guard"] not in always):
            raise FrontEndError(f"{convert.where}: assert in a when-clause "
                                "is not supported by the FMU back end; "
                                "allowed: assert(...) in equations")
        if kind == "assert":
            violated = _condition(storage, convert, action["guard"],
                                  convert.where)
        else:
            violated = casadi.logic_not(convert(body["condition"]))
        violated = _with_values(violated, {
            r.symbol.name(): r.value for r in convert.relations.values()})
        message, values = _message(storage, convert, body["message"])
        found.append(Assertion(violated=violated, message=message,
                               values=values, error=kind == "assert",
                               where=convert.where))
    return found


def _message(storage, convert, index):
    """An assert's message as ``(text with %g for each String(v),
    [v, ...])``: string literals, ``+`` and ``String(v)``."""
    kind, body = next(iter(storage["expressions"]["nodes"][index].items()))
    if kind == "literal" and "string" in body:
        return body["string"].replace("%", "%%"), []
    if kind == "binary" and body["operator"] == "add":
        left, first = _message(storage, convert, body["lhs"])
        right, second = _message(storage, convert, body["rhs"])
        return left + right, first + second
    if kind == "string_conversion":
        value = convert(body["value"])
        if isinstance(value, np.ndarray):
            return "{...}", []
        return "%g", [value]
    return "(message)", []


def _whens(storage, convert, where, variables):
    """``when`` clauses with ``reinit`` (rumoca's event actions).

    The relations are renumbered in the order of ``convert.relations``
    after every one is converted.
    """
    conditions = storage.get("conditions") or []
    clauses = {}
    for action in storage.get("event_actions") or []:
        convert.where = where(action)
        kind, body = next(iter(action["kind"].items()))
        if kind in _ASSERT_KINDS:
            continue   # _assertions
        if kind != "reinitialize":
            raise FrontEndError(f"{convert.where}: {kind} in a when-clause "
                                "is not supported by the FMU back end")
        if action["guard"] != action["trigger"] or \
                action["trigger"] >= len(conditions):
            raise FrontEndError(f"{convert.where}: this when-clause (its "
                                "guard differs from its condition in "
                                "rumoca's flat model) is not supported by "
                                "the FMU back end; allowed: when-clauses "
                                "with reinit on relations and Boolean "
                                "expressions")
        node = conditions[action["trigger"]]["node"]
        if isinstance(node, dict) and set(node) == {"clock"}:
            convert.where = where(conditions[action["trigger"]])   # sample
        relation = _when_relation(storage, convert, action["trigger"],
                                  convert.where)
        convert.pre_is_state = True
        try:
            value = convert(body["value"])
        finally:
            convert.pre_is_state = False
        target = storage["variables"][body["state"]]["name"]
        clause = clauses.setdefault(action["trigger"], When(
            relation=relation, reinits=[], where=convert.where))
        clause.reinits.append((target, value))
    order = sorted(convert.relations)
    for clause in clauses.values():
        clause.relation = order.index(clause.relation)
    return list(clauses.values())


_TYPE = re.compile(r"\btype\s+(\w+)\s*=\s*Real\s*\(([^;]*?)\)\s*(?:\"|;)")


def _declared_types(roots, model_file):
    """``{type name: (quantity, displayUnit)}`` of the Real types defined
    in the library's sources; a name defined twice differently is left
    out (ambiguous)."""
    found, ambiguous = {}, set()
    files = {Path(model_file)}
    for root in roots:
        files |= set(Path(root).rglob("*.mo"))
    for source in sorted(files):
        for name, body in _TYPE.findall(source.read_text(errors="replace")):
            quantity = re.search(r'quantity\s*=\s*"([^"]*)"', body)
            display = re.search(r'displayUnit\s*=\s*"([^"]*)"', body)
            value = (quantity.group(1) if quantity else "",
                     display.group(1) if display else "")
            if found.setdefault(name, value) != value:
                ambiguous.add(name)
    return {k: v for k, v in found.items() if k not in ambiguous}


def _type_of(raw, files):
    """Short name of the declared type of a variable (``Pressure`` for
    ``Units.Pressure p_m``), read at its declaration."""
    span = raw.get("declaration", {}).get("span") or {}
    if span.get("source") not in files:
        return ""
    text = files[span["source"]][span["start"]:span["end"]].split()
    return text[0].split(".")[-1] if len(text) > 1 else ""


def _element_symbols(name, shape):
    """One SX symbol per element of an array, named ``name[i,j]``."""
    symbols = np.empty(shape, dtype=object)
    for position in product(*(range(n) for n in shape)):
        symbols[position] = casadi.SX.sym(
            f"{name}[{','.join(str(k + 1) for k in position)}]")
    return symbols


def _element(value, position, where):
    """Element ``position`` of an array attribute (a scalar applies to all)."""
    if value is None:
        return None
    if not isinstance(value, np.ndarray):
        return value
    if value.ndim == 1 and value.shape == (1,) and len(position) > 1:
        return value[0]
    if value.ndim == 0:
        return value[()]
    try:
        if value.ndim != len(position):
            raise IndexError
        return value[position]
    except IndexError:
        raise FrontEndError(f"{where}: the array value has shape "
                            f"{value.shape}, not that of the declaration") \
            from None


def _is_fixed(value):
    """rumoca writes ``fixed`` as a literal list such as ``[true]``."""
    if isinstance(value, list):
        return bool(value and value[0])
    return bool(value)


def _experiment(path, model_name):
    """StopTime and Interval of the class's own ``experiment``
    annotation: the one in its body, outside the classes nested in it
    (a package file holds many examples, each with its own)."""
    text = Path(path).read_text(encoding="utf-8")
    spans = class_spans(text)
    own = spans.get(model_name)
    if own is None:   # a file without its within clause
        short = [v for k, v in spans.items()
                 if model_name.endswith("." + k) or k == model_name]
        own = short[0] if len(short) == 1 else None
    if own is None:
        return {}
    clean = blank(text)
    begin, end = own
    body = list(clean[begin:end])
    for other, (a, b) in spans.items():
        if other != model_name and begin < a and b <= end:
            body[a - begin:b - begin] = " " * (b - a)
    body = "".join(body)
    values = {}
    found = re.search(r"\bexperiment\s*\(([^)]*)\)", body)
    if found:
        for key, value in re.findall(r"(\w+)\s*=\s*([-+\d.eE]+)",
                                     found.group(1)):
            values[key] = float(value)
    return values
