"""What rumoca cannot read, rewritten before it reads it (issue 43).

rumoca 0.10.2 miscounts a declaration whose binding calls a function
with an array argument (or an external object, which it reads alike): ``parameter Real mu0 = first(mu_pos)`` of a
one-line pure Modelica ``first`` stops it with "unbalanced model: 2
equations, 1 unknowns", as MSL's ``Clutch`` (``mu0 =
getTable1DValueNoDer2(tableID, 1, 0)``) does; the same call written in
an equation flattens. So, by one rule, each such binding of a scalar
Real variable of a model, block or class becomes an equation:

* a parameter keeps its variability and its value: ``parameter Real
  mu0(fixed = false) ...; initial equation mu0 = first(mu_pos);``, which
  the front end reads back as the calculated parameter it was
  (:func:`fmu.frontend.load_flat_model`);
* any other variable: ``Real k ...; equation k = first({1, 2});``.

The rewrite is of the source text (a tokenizer that knows Modelica's
comments, strings, quoted names, modifiers, annotations and class
nesting), in a copy of each library folder that holds such a binding,
kept under the compiler's cache folder (:mod:`fmu.cache`) in a folder
named by the sha256 of the sources' paths and contents: never in the
user's folder. Every line keeps its number (the binding's text is
blanked where it stood, its equation goes on the line of the class's
``end`` or final annotation), so rumoca's ``file:line`` points into the
user's file once the copy's folder is named back (:meth:`Prepared.named_back`).
A binding of an array, of a constant, of an input, or in a record,
connector, function or package is left as written.
"""

from dataclasses import dataclass
import hashlib
import json
import os
from pathlib import Path
import re
import shutil
import tempfile

from infra.errors import JudderError
from infra.files import atomic_write

__all__ = ["Rewrite", "Prepared", "prepare", "rewrite_text", "inline_tables",
           "inlinable_table", "unroll_reductions",
           "REWRITE_VERSION"]

#: Changes with the rule: the flat-model cache and the copies are keyed by it.
REWRITE_VERSION = "6"

_TOKEN = re.compile(r"""
    (?P<space>\s+)
  | (?P<comment>//[^\n]*|/\*.*?\*/)
  | (?P<string>"(?:\\.|[^"\\])*")
  | (?P<qident>'(?:\\.|[^'\\])*')
  | (?P<number>(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)
  | (?P<ident>[A-Za-z_]\w*)
  | (?P<op>:=|==|<=|>=|<>|\.[-+*/^]|.)
""", re.S | re.X)
_CLASSES = {"model", "block", "class", "package", "record", "connector",
            "function", "type", "operator"}
_CLASS_PREFIXES = {"within", "encapsulated", "partial", "final", "redeclare",
                   "replaceable", "inner", "outer", "expandable", "pure",
                   "impure", "operator"}
_PREFIXES = {"final", "inner", "outer", "replaceable", "redeclare", "flow",
             "stream", "discrete", "parameter", "constant", "input",
             "output", "each"}
#: Classes whose components may be rewritten (they may hold equations).
_WITH_EQUATIONS = {"model", "block", "class"}
#: Built-in functions and operators: not the calls of the rule.
_BUILTIN = {
    "abs", "sign", "sqrt", "integer", "floor", "ceil", "div", "mod", "rem",
    "min", "max", "sum", "product", "size", "ndims", "scalar", "vector",
    "matrix", "transpose", "outerProduct", "symmetric", "cross", "skew",
    "identity", "diagonal", "zeros", "ones", "fill", "linspace", "cat",
    "array", "der", "pre", "edge", "change", "initial", "terminal",
    "noEvent", "smooth", "sample", "delay", "homotopy", "semiLinear",
    "inStream", "actualStream", "cardinality", "String", "Integer",
    "Boolean", "Real", "sin", "cos", "tan", "asin", "acos", "atan", "atan2",
    "sinh", "cosh", "tanh", "exp", "log", "log10", "assert", "reinit",
    "getInstanceName", "spatialDistribution", "if"}
#: Keywords a bracket may follow (``then (a + b)``): not calls.
_KEYWORDS = {"then", "else", "elseif", "and", "or", "not", "in", "for",
             "loop", "while", "return", "equation", "algorithm"}
#: Types whose components are scalars of Real (a ``type X = Real(...)``
#: of the libraries adds its name, :func:`_real_types`).
_REAL = {"Real"}


@dataclass(frozen=True)
class Rewrite:
    """One binding made an equation.

    Attributes
    ----------
    file : str
        The user's file (not the cached copy).
    line : int
        Line of the declaration's name.
    name : str
        The variable declared.
    binding : str
        The binding's expression, on one line, comments left out.
    parameter : bool
        A parameter: its equation is an initial equation, ``fixed =
        false`` keeps it a parameter.
    at : int
        Line of its equation (its class's ``end`` or final annotation):
        the front end tells the equation apart by it, to drop it where a
        modifier sets the parameter (``d(p = 0.3)``).
    kind : str
        ``"binding"`` (above), ``"table"`` (a table object left out,
        :func:`inline_tables`: ``name`` the object, ``binding`` its
        constructor) or ``"for"`` (a for-equation unrolled,
        :func:`unroll_reductions`: ``name`` its iterator, ``binding`` its
        range, ``at`` the number of copies).
    """
    file: str
    line: int
    name: str
    binding: str
    parameter: bool
    at: int = 0
    kind: str = "binding"

    def __str__(self):
        if self.kind == "for":
            return f"{self.file}:{self.line}: for {self.name} in " \
                f"{self.binding}: a for-equation with a reduction in its " \
                f"body, unrolled into {self.at} copies of it (rumoca " \
                f"0.10.2 panics on a reduction inside a for-equation)"
        if self.kind == "table":
            return f"{self.file}:{self.line}: {self.name} = " \
                f"{self.binding}: a table given in the model, its " \
                f"getTable1DValue* lookups computed in Modelica (linear or " \
                f"constant segments, extrapolated through the last two " \
                f"points) and the object left out (rumoca 0.10.2 " \
                f"miscounts its binding)"
        made = "an initial equation (fixed = false), still a parameter" \
            if self.parameter else "an equation"
        return f"{self.file}:{self.line}: {self.name} = {self.binding}: " \
            f"the binding calls a function with an array argument, " \
            f"rewritten as {made} (rumoca 0.10.2 miscounts it)"


@dataclass(frozen=True)
class Prepared:
    """The library folders rumoca reads, and what was rewritten.

    Attributes
    ----------
    roots : list of Path
        Each library folder, or its rewritten copy.
    path : Path
        The model's file, in its copy where its folder was copied.
    rewrites : list of Rewrite
        Every binding rewritten in these folders.
    copies : dict
        ``{copy folder: the user's folder}``.
    """
    roots: list
    path: Path
    rewrites: list
    copies: dict

    def named_back(self, text):
        """``text`` (a message, a path) with each copy's folder named as
        the user's."""
        for copy, original in self.copies.items():
            text = text.replace(str(copy), str(original))
        return text


def _tokens(text):
    """``[(kind, text, start, end)]`` without spaces and comments."""
    found = []
    for match in _TOKEN.finditer(text):
        kind = match.lastgroup
        if kind not in ("space", "comment"):
            found.append((kind, match.group(), match.start(), match.end()))
    return found


def _one_line(tokens):
    """The tokens' text on one line: a space where the source had
    spaces, a line break or a comment between two tokens."""
    out = []
    for k, token in enumerate(tokens):
        if k and token[2] != tokens[k - 1][3]:
            out.append(" ")
        out.append(token[1])
    return "".join(out)


def _split(tokens, separator):
    """``tokens`` split at ``separator`` outside brackets."""
    parts, depth, current = [], 0, []
    for token in tokens:
        if token[1] in "([{" and token[0] == "op":
            depth += 1
        elif token[1] in ")]}" and token[0] == "op":
            depth -= 1
        if depth == 0 and token[0] == "op" and token[1] == separator:
            parts.append(current)
            current = []
        else:
            current.append(token)
    parts.append(current)
    return parts


def _closing(tokens, k):
    """Index of the bracket that closes the one at ``tokens[k]``."""
    depth = 0
    for j in range(k, len(tokens)):
        if tokens[j][0] == "op" and tokens[j][1] in "([{":
            depth += 1
        elif tokens[j][0] == "op" and tokens[j][1] in ")]}":
            depth -= 1
            if depth == 0:
                return j
    return len(tokens) - 1


def _is_array(argument, arrays):
    """Whether a call's argument is an array, as far as the source says:
    an array constructor, a range or ``:`` subscript, or a name declared
    with dimensions in the class, subscripted fewer times than it has
    dimensions (an external object, MSL's ``tableID``, counts as an array
    of no dimension: ``arrays`` holds it with 1 and it is never
    subscripted)."""
    if argument and argument[0][0] == "ident" and len(argument) > 1 and \
            argument[1][1] == "=":
        argument = argument[2:]   # a named argument
    if not argument:
        return False
    if argument[0][1] in ("{", "["):
        return True
    if any(t[0] == "op" and t[1] == ":" for t in argument):
        return True
    if argument[0][0] == "ident" and argument[0][1] in arrays:
        subscripts = 0
        if len(argument) > 1 and argument[1][1] == "[":
            end = _closing(argument, 1)
            if end != len(argument) - 1:
                return False
            subscripts = len(_split(argument[2:end], ","))
        elif len(argument) > 1:
            return False
        return subscripts < arrays[argument[0][1]]
    return False


def _calls_with_array(tokens, arrays):
    """Whether the expression calls a function (not a built-in) with an
    array argument, at any depth."""
    for k, token in enumerate(tokens):
        if token[0] != "ident" or k + 1 >= len(tokens) or \
                tokens[k + 1][1] != "(":
            continue
        start = k
        while start >= 2 and tokens[start - 1][1] == "." and \
                tokens[start - 2][0] == "ident":
            start -= 2
        if start == k and token[1] in _BUILTIN | _KEYWORDS:
            continue
        end = _closing(tokens, k + 1)
        if any(_is_array(argument, arrays)
               for argument in _split(tokens[k + 2:end], ",")):
            return True
    return False


class _Class:
    """A class being read: its kind, name, dimensions of its components,
    and the bindings to move to its end."""

    def __init__(self, kind, name):
        self.kind, self.name = kind, name
        self.section = "elements"
        self.arrays = {}      # component name -> number of dimensions
        self.pending = []     # (declaration tokens, component parts)
        self.last_annotation = None   # start of a trailing annotation


def _dimensions(tokens):
    """Number of subscripts of a ``[...]`` that starts ``tokens``."""
    if tokens and tokens[0][1] == "[":
        return len(_split(tokens[1:_closing(tokens, 0)], ","))
    return 0


def _section_keyword(tokens, k):
    """``(section, tokens taken)`` where a statement at ``k`` opens a
    section of a class (``equation``, ``initial algorithm``, ``public``,
    ...), else None."""
    word = tokens[k][1]
    if word in ("equation", "algorithm"):
        return "equations", 1
    if word == "initial" and k + 1 < len(tokens) and \
            tokens[k + 1][1] in ("equation", "algorithm"):
        return "equations", 2
    if word in ("public", "protected"):
        return "elements", 1
    return None


def rewrite_text(text, real_types=frozenset(), objects=frozenset()):
    """``(text rewritten, [(line, name, binding, parameter, line of its
    equation)])``: each
    binding of the rule (module docstring) moved to an equation at the
    end of its class, every line kept at its number. ``real_types``: names
    of types that are Real; ``objects``: names of ExternalObject
    classes."""
    tokens = _tokens(text)
    edits = []          # (start, end, replacement)
    found = []
    stack = []
    reals = _REAL | set(real_types)
    k, start = 0, 0     # token index, start of the current statement
    while k < len(tokens):
        kind, word, _, _ = tokens[k]
        top = stack[-1] if stack else None
        at_start = k == start
        if at_start and word == "end" and k + 2 < len(tokens) and \
                tokens[k + 2][1] == ";" and top and \
                tokens[k + 1][1] == top.name:
            _finish(text, tokens, top, tokens[k][2], edits, found)
            stack.pop()
            k = start = k + 3
            continue
        opened = _section_keyword(tokens, k) if at_start and top else None
        if opened:
            top.section, top.last_annotation = opened[0], None
            k = start = k + opened[1]
            continue
        if at_start and word == "external" and top:
            top.section = "external"
        if at_start:
            head = k
            while head < len(tokens) and tokens[head][1] in _CLASS_PREFIXES \
                    and tokens[head][0] == "ident":
                head += 1
            if head < len(tokens) and tokens[head][1] in _CLASSES and \
                    tokens[head][0] == "ident" and head > k - 1:
                # a class definition: long (a body to its end) or short
                j = head + 1
                while j < len(tokens) and tokens[j][1] in _CLASSES:
                    j += 1   # operator record, operator function
                if j < len(tokens) and tokens[j][1] == "extends":
                    j += 1
                if j + 1 < len(tokens) and tokens[j][0] == "ident" and \
                        tokens[j + 1][1] != "=":
                    name = tokens[j][1]
                    j += 1
                    if j < len(tokens) and tokens[j][1] == "(":
                        j = _closing(tokens, j) + 1   # model extends X(..)
                    while j < len(tokens) and tokens[j][0] == "string" or \
                            (j < len(tokens) and tokens[j][1] == "+"):
                        j += 1   # its description
                    stack.append(_Class(tokens[head][1], name))
                    k = start = j
                    continue
        # a statement: to its ';' outside brackets
        end, depth = k, 0
        while end < len(tokens):
            if tokens[end][0] == "op" and tokens[end][1] in "([{":
                depth += 1
            elif tokens[end][0] == "op" and tokens[end][1] in ")]}":
                depth -= 1
            elif depth == 0 and tokens[end][1] == ";":
                break
            end += 1
        statement = tokens[start:end]
        if top and statement and statement[0][1] == "annotation":
            top.last_annotation = statement[0][2]
        elif top:
            top.last_annotation = None
            if top.section == "elements" and statement:
                _declaration(statement, top, reals, objects)
        k = start = end + 1
    return _apply(text, edits), found


def _declaration(statement, owner, reals, objects):
    """Note the dimensions of the components declared and the bindings
    of the rule (module docstring) in ``owner``."""
    k, prefixes = 0, set()
    while k < len(statement) and statement[k][1] in _PREFIXES:
        prefixes.add(statement[k][1])
        k += 1
    if k >= len(statement) or statement[k][0] != "ident" or \
            statement[k][1] in ("extends", "import", "annotation"):
        return
    type_name = [statement[k][1]]
    k += 1
    while k + 1 < len(statement) and statement[k][1] == "." and \
            statement[k + 1][0] == "ident":
        type_name.append(statement[k + 1][1])
        k += 2
    type_dims = _dimensions(statement[k:])
    if type_dims:
        k = _closing(statement, k) + 1
    for part in _split(statement[k:], ","):
        if not part or part[0][0] != "ident":
            continue
        dims = type_dims + _dimensions(part[1:])
        if dims or type_name[-1] in objects:
            owner.arrays[part[0][1]] = dims or 1
        elif owner.kind in _WITH_EQUATIONS and \
                type_name[-1] in reals and \
                not prefixes & {"constant", "input", "outer", "redeclare",
                                "each"}:
            owner.pending.append((part, "parameter" in prefixes))


def _binding(part):
    """``(index of '=', index after the expression)`` of a component's
    binding, or None."""
    k = 1
    if k < len(part) and part[k][1] == "[":
        k = _closing(part, k) + 1
    if k < len(part) and part[k][1] == "(":
        k = _closing(part, k) + 1
    if k >= len(part) or part[k][1] != "=":
        return None
    end, depth = k + 1, 0
    conditional = part[k + 1][1] != "if" if k + 1 < len(part) else False
    while end < len(part):
        token = part[end]
        if token[0] == "op" and token[1] in "([{":
            depth += 1
        elif token[0] == "op" and token[1] in ")]}":
            depth -= 1
        elif depth == 0 and (token[0] == "string" or
                             token[1] == "annotation" or
                             (conditional and token[1] == "if")):
            break
        end += 1
    return k, end


def _finish(text, tokens, owner, end_at, edits, found):
    """The edits of ``owner``'s rewritten bindings: each ``= expr``
    blanked, ``fixed = false`` on a parameter, and the equations put
    before its final annotation or its ``end``."""
    equations, initial, mine = [], [], []
    for part, parameter in owner.pending:
        where = _binding(part)
        if where is None:
            continue
        eq, stop = where
        expression = part[eq + 1:stop]
        if not expression or not _calls_with_array(expression,
                                                    owner.arrays):
            continue
        if parameter and any(t[1] == "fixed" for t in part[1:eq]):
            continue   # a fixed of its own: left as written
        name = part[0][1]
        binding = _one_line(expression)
        edits.append((part[eq][2], expression[-1][3],
                      re.sub(r"[^\n]", "", text[part[eq][2]:
                                                expression[-1][3]])))
        if parameter:
            if eq > 1 and part[eq - 1][1] == ")":
                # name(...): the modifier joins the others
                opening = next(j for j in range(1, eq)
                               if part[j][1] == "(")
                edits.append((part[opening][3], part[opening][3],
                              "fixed = false, "))
            else:
                edits.append((part[eq - 1][3], part[eq - 1][3],
                              "(fixed = false)"))
        (initial if parameter else equations).append(f"{name} = {binding};")
        line = text.count("\n", 0, part[0][2]) + 1
        mine.append((line, name, binding, parameter))
    if not (equations or initial):
        return
    added = ""
    if initial:
        added += "initial equation " + " ".join(initial) + " "
    if equations:
        added += "equation " + " ".join(equations) + " "
    at = owner.last_annotation if owner.last_annotation is not None \
        else end_at
    edits.append((at, at, added))
    line = text.count("\n", 0, at) + 1
    found += [(*item, line) for item in mine]


def _apply(text, edits):
    """``text`` with the edits ``(start, end, replacement)`` made."""
    out, at = [], 0
    for start, end, replacement in sorted(edits, key=lambda e: (e[0], e[1])):
        out.append(text[at:start])
        out.append(replacement)
        at = max(at, end)
    out.append(text[at:])
    return "".join(out)


#: MSL's lookups of a 1-D table object (``Modelica.Blocks.Tables.Internal``):
#: their value does not depend on which one is called, only on the
#: object's ``smoothness`` (the name says which derivatives it provides).
_TABLE_LOOKUPS = {"getTable1DValue", "getTable1DValueNoDer",
                  "getTable1DValueNoDer2"}
#: The only extrapolation the Modelica expression implements.
_EXTRAPOLATION = "LastTwoPoints"
_SMOOTHNESS = "Modelica.Blocks.Types.Smoothness"


def _named_arguments(tokens):
    """``{name: tokens}`` of a call's named arguments."""
    named = {}
    for argument in _split(tokens, ","):
        if len(argument) > 2 and argument[0][0] == "ident" and \
                argument[1][1] == "=":
            named[argument[0][1]] = argument[2:]
    return named


def _table_constructor(tokens, k, objects):
    """``(object name, named arguments, index of the closing bracket)``
    where ``tokens[k]`` starts ``ExternalCombiTable1D tableID =
    ExternalCombiTable1D(...)`` (the type's last name in ``objects``),
    with a table given in the model (``tableName = "NoName"``) and
    extrapolation through the last two points; else None."""
    if not (k + 3 < len(tokens) and tokens[k][0] == "ident" and
            tokens[k][1] in objects and tokens[k + 1][0] == "ident" and
            tokens[k + 2][1] == "="):
        return None
    j = k + 3
    while j + 1 < len(tokens) and tokens[j][0] == "ident" and \
            tokens[j + 1][1] == ".":
        j += 2
    if not (j + 1 < len(tokens) and tokens[j][1] == tokens[k][1] and
            tokens[j + 1][1] == "("):
        return None
    close = _closing(tokens, j + 1)
    named = _named_arguments(tokens[j + 2:close])
    name = named.get("tableName")
    extrapolation = named.get("extrapolation")
    if "table" not in named or "columns" not in named or not name or \
            _one_line(name) != '"NoName"' or not extrapolation or \
            extrapolation[-1][1] != _EXTRAPOLATION:
        return None
    return tokens[k + 1][1], named, close


def inlinable_table(statement):
    """Whether the declaration ``statement`` (its source text) is a table
    object :func:`inline_tables` replaces (used by the source check,
    :mod:`fmu.precheck`, to let it pass)."""
    tokens = _tokens(statement)
    for k, token in enumerate(tokens):
        if token[0] == "ident" and k + 2 < len(tokens) and \
                tokens[k + 1][0] == "ident" and tokens[k + 2][1] == "=":
            return _table_constructor(tokens, k, {token[1]}) is not None
    return False


def _column(columns, icol):
    """The text of the table column of lookup ``icol`` (its text) for the
    ``columns`` argument: ``{2}``, ``{2, 3, 4, 5}`` (an arithmetic
    progression of integers) or ``a:b``; None otherwise."""
    text = _one_line(columns)
    icol = _one_line(icol)
    if columns[0][1] == "{":
        items = [_one_line(part) for part in _split(columns[1:-1], ",")]
        if not all(re.fullmatch(r"\d+", item) for item in items):
            return None
        values = [int(item) for item in items]
        if re.fullmatch(r"\d+", icol):
            picked = int(icol)
            return str(values[picked - 1]) if 1 <= picked <= len(values) \
                else None
        step = values[1] - values[0] if len(values) > 1 else 0
        if any(b - a != step for a, b in zip(values, values[1:])):
            return None
        return f"({values[0]} + ({icol} - 1)*{step})"
    parts = _split(columns, ":")
    if len(parts) == 2:
        return f"({_one_line(parts[0])} + ({icol}) - 1)"
    return None if "{" in text else None


def _lookup(table, column, smoothness, u):
    """A Modelica expression of MSL's 1-D table lookup of ``table`` (text)
    at ``u`` in ``column``, as ``ModelicaStandardTables.c`` computes it
    for extrapolation ``LastTwoPoints``: with linear segments ``y =
    T[1,c] + sum_k (s_k - s_(k-1)) r_k``, the slopes ``s_k`` of the
    segments and the ramps ``r_1 = u - T[1,1]``, ``r_k = max(u - T[k,1],
    0)``; with constant segments ``y = T[1,c] + sum_k (T[k,c] -
    T[k-1,c]) [u >= T[k,1]]``. A one-row table is its value. The
    indices are clipped so that every subscript stays in range (rumoca
    evaluates the expression for each ``k``) and no range is empty."""
    n = f"size({table}, 1)"
    k2 = f"min(k + 1, {n})"
    j = "max(k - 1, 1)"
    j2 = f"min({j} + 1, {n})"
    slope = f"({table}[{k2}, {column}] - {table}[k, {column}])/" \
        f"({table}[{k2}, 1] - {table}[k, 1] + 1 + k - {k2})"
    before = f"({table}[{j2}, {column}] - {table}[{j}, {column}])/" \
        f"({table}[{j2}, 1] - {table}[{j}, 1] + 1 + {j} - {j2})"
    ramp = f"(({u}) - {table}[k, 1] + min(k - 1, 1)*noEvent(max(" \
        f"{table}[k, 1] - ({u}), 0)))"
    linear = f"{table}[1, {column}] + sum(({slope} - min(k - 1, 1)*" \
        f"{before})*{ramp} for k in 1:max({n} - 1, 1))"
    steps = f"{table}[1, {column}] + sum(min(k - 1, 1)*({table}[k, " \
        f"{column}] - {table}[{j}, {column}])*noEvent(if ({u}) >= " \
        f"{table}[k, 1] then 1 else 0) for k in 1:{n})"
    return f"(if {smoothness} == {_SMOOTHNESS}.ConstantSegments then " \
        f"{steps} else {linear})"


def _class_ranges(tokens):
    """``[(first token, its end token)]`` of each long class definition."""
    ranges, stack = [], []
    for k, token in enumerate(tokens):
        if token[0] != "ident":
            continue
        if token[1] == "end" and k + 2 < len(tokens) and stack and \
                tokens[k + 1][1] == stack[-1][0] and tokens[k + 2][1] == ";":
            name, first = stack.pop()
            ranges.append((first, k))
        elif token[1] in _CLASSES and k + 2 < len(tokens) and \
                tokens[k + 1][0] == "ident" and tokens[k + 2][1] != "=" and \
                (k == 0 or tokens[k - 1][1] != "end"):
            stack.append((tokens[k + 1][1], k))
    return ranges


def inline_tables(text, objects):
    """``(text, [(line, object, constructor)])``: each table object
    declared with its table in the model (MSL's ``tableID =
    ExternalCombiTable1D(tableName="NoName", ..., table=mu_pos, columns={2},
    smoothness=smoothness, extrapolation=Extrapolation.LastTwoPoints)``)
    left out, and each ``getTable1DValue*(tableID, icol, u)`` of its class
    replaced by the lookup in Modelica (:func:`_lookup`), every line kept
    at its number. A smoothness other than linear or constant segments is
    an ``assert`` that fails, naming the object and what is allowed.
    rumoca 0.10.2 counts the object's binding as an equation ("115
    equations, 112 unknowns" in MSL's ``CoupledClutches``, one per
    clutch); the table itself is a parameter array, so the lookup is
    compiled like any expression and follows the parameters."""
    if not objects or not any(o in text for o in objects):
        return text, []
    tokens = _tokens(text)
    ranges = _class_ranges(tokens)
    edits, found = [], []
    for k in range(len(tokens)):
        table = _table_constructor(tokens, k, objects)
        if table is None:
            continue
        name, named, close = table
        inside = [r for r in ranges if r[0] < k < r[1]]
        if not inside:
            continue
        first, last = max(inside)
        start = k
        while start > 0 and (tokens[start - 1][1] in _PREFIXES or
                             tokens[start - 1][1] == "." or
                             (tokens[start - 1][0] == "ident" and
                              tokens[start][1] == ".")):
            start -= 1   # prefixes and the type's package path
        end = close
        while end < len(tokens) and tokens[end][1] != ";":
            end += 1
        smoothness = _one_line(named.get("smoothness") or []) or \
            f"{_SMOOTHNESS}.LinearSegments"
        calls = []
        for c in range(first, last):
            if not (tokens[c][0] == "ident" and tokens[c][1] in
                    _TABLE_LOOKUPS and c + 1 < len(tokens) and
                    tokens[c + 1][1] == "("):
                continue
            shut = _closing(tokens, c + 1)
            arguments = _split(tokens[c + 2:shut], ",")
            if len(arguments) != 3 or _one_line(arguments[0]) != name:
                continue
            column = _column(named["columns"], arguments[1])
            if column is None:
                calls = None
                break
            begin = c
            while begin >= 2 and tokens[begin - 1][1] == "." and \
                    tokens[begin - 2][0] == "ident":
                begin -= 2
            calls.append((tokens[begin][2], tokens[shut][3], _lookup(
                _one_line(named["table"]), column, smoothness,
                _one_line(arguments[2]))))
        if calls is None:
            continue   # columns it cannot read: the object stays (refused)
        blank = text[tokens[start][2]:tokens[end][3]]
        edits.append((tokens[start][2], tokens[end][3],
                      re.sub(r"[^\n]", " ", blank)))
        edits += calls
        check = next((e for e in range(first, last)
                      if tokens[e][1] == "equation" and
                      tokens[e - 1][1] != "initial" and
                      tokens[e][0] == "ident"), None)
        if check is not None:
            edits.append((tokens[check][3], tokens[check][3],
                          f" assert({smoothness} == {_SMOOTHNESS}."
                          f"LinearSegments or {smoothness} == {_SMOOTHNESS}."
                          f"ConstantSegments, \"{name}: smoothness \" + "
                          f"String(Integer({smoothness})) + \" of "
                          f"{_SMOOTHNESS} is not supported by the FMU "
                          f"compiler; allowed: LinearSegments (1), "
                          f"ConstantSegments (3)\");"))
        found.append((text.count("\n", 0, tokens[k][2]) + 1, name,
                      _one_line(tokens[k + 3:close + 1])))
    return _apply(text, edits), found


_REAL_TYPE = re.compile(r"\btype\s+(\w+)\s*=\s*(?:[\w.]*\.)?(\w+)\b")


def _real_types(files):
    """Names of the types the libraries define as Real (``type Torque =
    Real(...)``, ``type Speed = AngularVelocity``), by their last name."""
    defined = {}
    for text in files.values():
        for name, base in _REAL_TYPE.findall(text):
            defined.setdefault(name, set()).add(base)
    reals, grown = set(_REAL), True
    while grown:
        new = {name for name, bases in defined.items()
               if bases <= reals and name not in reals}
        reals |= new
        grown = bool(new)
    return reals


_OBJECT = re.compile(r"\bclass\s+(\w+)\s*(?:\"[^\"]*\"\s*)?extends\s+"
                     r"ExternalObject\b")


def _external_objects(files):
    """Names of the ExternalObject classes of the libraries (MSL's
    ``ExternalCombiTable1D``)."""
    return {name for text in files.values() for name in _OBJECT.findall(text)}


def _copies_folder():
    """Where the rewritten copies live: beside the flat models of
    :mod:`fmu.cache` (``sources/``), or None when the cache is off."""
    from .cache import cache_folder
    folder = cache_folder()
    return None if folder is None else folder / "sources"


def prepare(roots, path, scratch=None, stamp=None, remember=True):
    """The folders for rumoca: each root holding a binding of the rule
    as a rewritten copy, the others as they are.

    What it found is kept under the cache folder (``prepared/``), keyed
    by the rule's version, ``path``, ``roots`` and the content of every
    source under them (the key of the flat models,
    :func:`fmu.cache.sources_stamp`): while no file changes, the
    libraries are not tokenized again (reading and tokenizing the MSL's
    2,600 files costs 4-5 s of CPU, more than the rest of a build from
    the flat-model cache).

    Parameters
    ----------
    roots : sequence of paths
        Library folders (a ``.mo`` file is a single-file package).
    path : path
        The model's file.
    scratch : path, optional
        A folder for the copies when the cache is off
        (``JUDDER_FMU_CACHE=off``); without one a temporary folder.
    stamp : bytes, optional
        :func:`fmu.cache.sources_stamp` of ``path`` and ``roots``, when
        the caller has it.
    remember : bool
        Whether to look up and keep what was found (False: read every
        file, keep nothing, as a build without the flat-model cache).

    Returns
    -------
    Prepared
    """
    from .cache import sources_stamp
    folder = _copies_folder()
    if folder is None or not remember:
        return _prepare(roots, path, scratch)
    if stamp is None:
        stamp = sources_stamp(path, roots)
    digest = hashlib.sha256(REWRITE_VERSION.encode() + b"\0")
    for item in (path, *roots):
        digest.update(str(Path(item).resolve()).encode() + b"\0")
    digest.update(stamp)
    record = folder.parent / "prepared" / f"{digest.hexdigest()}.json"
    prepared = _load_prepared(record)
    if prepared is None:
        prepared = _prepare(roots, path, scratch)
        _store_prepared(record, prepared)
    return prepared


def _load_prepared(record):
    """The :class:`Prepared` kept in ``record``, or None (absent,
    unreadable, or a copy it names is gone)."""
    try:
        kept = json.loads(record.read_text())
        prepared = Prepared(
            roots=[Path(r) for r in kept["roots"]], path=Path(kept["path"]),
            rewrites=[Rewrite(*r) for r in kept["rewrites"]],
            copies={Path(c): Path(b) for c, b in kept["copies"]})
    except (OSError, ValueError, KeyError, TypeError):
        return None
    if not all((copy.parent / "complete").is_file()
               for copy in prepared.copies):
        return None
    return prepared


def _store_prepared(record, prepared):
    """Keep ``prepared`` in ``record`` (best effort, as the flat
    models)."""
    text = json.dumps({
        "roots": [str(r) for r in prepared.roots],
        "path": str(prepared.path),
        "rewrites": [[r.file, r.line, r.name, r.binding, r.parameter,
                      r.at, r.kind] for r in prepared.rewrites],
        "copies": [[str(c), str(b)] for c, b in prepared.copies.items()],
    }).encode()
    try:
        record.parent.mkdir(parents=True, exist_ok=True)
        atomic_write(record, lambda out: out.write(text))
    except (OSError, JudderError):
        pass


def _prepare(roots, path, scratch):
    """:func:`prepare`, reading every file."""
    path = Path(path).resolve()
    folders = [Path(r).resolve() for r in roots]
    texts = {}
    for root in folders:
        for source in [root] if root.is_file() else sorted(root.rglob("*.mo")):
            texts[source] = source.read_text(encoding="utf-8",
                                             errors="replace")
    reals, objects = _real_types(texts), _external_objects(texts)
    new_roots, copies, rewrites, mapped = [], {}, [], path
    for root in folders:
        base = root.parent if root.is_file() else root
        mine = {s: t for s, t in texts.items()
                if (s == root if root.is_file() else s.is_relative_to(root))}
        changed = {}
        for source, text in mine.items():
            inlined, tables = inline_tables(text, objects)
            unrolled, loops = unroll_reductions(inlined)
            new, found = rewrite_text(unrolled, reals, objects)
            if found or tables or loops:
                changed[source] = new
                rewrites += [Rewrite(str(source), line, name, binding, False,
                                     0, "table")
                             for line, name, binding in tables]
                rewrites += [Rewrite(str(source), line, name, span, False,
                                     copies, "for")
                             for line, name, span, copies in loops]
                rewrites += [Rewrite(str(source), *item) for item in found]
        if not changed:
            new_roots.append(root)
            continue
        digest = hashlib.sha256(REWRITE_VERSION.encode() + b"\0")
        for source in sorted(mine):
            digest.update(str(source.relative_to(base)).encode() + b"\0")
            digest.update(mine[source].encode() + b"\0")
        copy = _copy(base, root, mine, changed, digest.hexdigest(), scratch)
        copies[copy] = base
        new_roots.append(copy / root.name if root.is_file() else copy)
        if path in mine:
            mapped = copy / path.relative_to(base)
    return Prepared(roots=new_roots, path=mapped, rewrites=rewrites,
                    copies=copies)


def _copy(base, root, texts, changed, digest, scratch):
    """The copy of ``root``'s ``.mo`` files (and ``package.order``) under
    ``digest``, written once."""
    folder = _copies_folder()
    if folder is None:
        folder = Path(scratch) if scratch else Path(tempfile.mkdtemp(
            prefix="judder-rewritten-"))
    copy = folder / digest / base.name
    done = copy.parent / "complete"
    if done.is_file():
        return copy
    for source, text in texts.items():
        target = copy / source.relative_to(base)
        target.parent.mkdir(parents=True, exist_ok=True)
        data = changed.get(source, text).encode("utf-8")
        atomic_write(target, lambda out, data=data: out.write(data))
    if root.is_dir():
        for order in root.rglob("package.order"):
            target = copy / order.relative_to(base)
            target.parent.mkdir(parents=True, exist_ok=True)
            shutil.copyfile(order, target)
    done.write_text("")
    os.utime(copy)
    return copy


#: At most this many copies of a for-equation's body are written.
UNROLL_LIMIT = 256


def _sections(tokens):
    """For each token, the section of its class it stands in:
    ``"equation"``, ``"algorithm"`` or ``"elements"`` (read from the
    section keywords outside brackets)."""
    sections, section, depth = [], "elements", 0
    for k, token in enumerate(tokens):
        if token[0] == "op" and token[1] in "([{":
            depth += 1
        elif token[0] == "op" and token[1] in ")]}":
            depth -= 1
        elif depth == 0 and token[0] == "ident":
            if token[1] in ("equation", "algorithm"):
                section = token[1]
            elif token[1] in ("public", "protected") or (
                    token[1] in _CLASSES and k + 1 < len(tokens) and
                    tokens[k + 1][0] == "ident" and
                    (k == 0 or tokens[k - 1][1] != "end")):
                section = "elements"
        sections.append(section)
    return sections


def _declared_dimensions(tokens, first, last, name):
    """The dimensions of ``name`` as declared in the class spanning
    ``tokens[first:last]`` (``Real y[1, 4]``: ``[1, 4]``; None for a
    dimension that is not an integer literal), or None where no
    ``TYPE name[...]`` is seen."""
    for k in range(first + 1, last - 1):
        if tokens[k][0] != "ident" or tokens[k][1] != name or \
                tokens[k + 1][1] != "[":
            continue
        before = tokens[k - 1]
        if before[0] != "ident" or before[1] in _KEYWORDS | _PREFIXES | {
                "end", "if", "elseif", "when", "elsewhen", "initial"}:
            continue   # a use of name, not its declaration
        shut = _closing(tokens, k + 1)
        return [int(_one_line(part)) if re.fullmatch(r"\d+", _one_line(part))
                else None for part in _split(tokens[k + 2:shut], ",")]
    return None


def _integer(expression, tokens, first, last):
    """The value of ``expression`` (tokens): integer literals and
    ``size(x, d)`` of an array the class (``tokens[first:last]``)
    declares with literal dimensions, joined by ``+``, ``-`` and ``*``;
    None for anything else."""
    terms, signs, sign = [], [], 1
    for part in _split_terms(expression):
        if part in ("+", "-"):
            sign = 1 if part == "+" else -1
            continue
        product = 1
        for factor in _split(part, "*"):
            value = _factor(factor, tokens, first, last)
            if value is None:
                return None
            product *= value
        terms.append(product)
        signs.append(sign)
        sign = 1
    if not terms:
        return None
    return sum(s * t for s, t in zip(signs, terms))


def _split_terms(expression):
    """``expression`` split into terms and the ``+``/``-`` between them
    (outside brackets)."""
    out, current, depth = [], [], 0
    for token in expression:
        if token[0] == "op" and token[1] in "([{":
            depth += 1
        elif token[0] == "op" and token[1] in ")]}":
            depth -= 1
        if depth == 0 and token[0] == "op" and token[1] in "+-":
            if current:
                out.append(current)
            out.append(token[1])
            current = []
        else:
            current.append(token)
    if current:
        out.append(current)
    return out


def _factor(factor, tokens, first, last):
    """The value of one factor of :func:`_integer`, or None."""
    text = _one_line(factor)
    if re.fullmatch(r"\d+", text):
        return int(text)
    if len(factor) > 2 and factor[0][1] == "size" and factor[1][1] == "(" \
            and _closing(factor, 1) == len(factor) - 1:
        arguments = _split(factor[2:-1], ",")
        if len(arguments) != 2 or len(arguments[0]) != 1 or \
                not re.fullmatch(r"\d+", _one_line(arguments[1])):
            return None
        dims = _declared_dimensions(tokens, first, last, arguments[0][0][1])
        d = int(_one_line(arguments[1]))
        if dims and 1 <= d <= len(dims):
            return dims[d - 1]
    return None


def _range(expression, tokens, first, last):
    """The integers of a for-equation's range ``a:b`` or ``a:s:b`` whose
    bounds :func:`_integer` reads, or None."""
    parts = _split(expression, ":")
    if len(parts) not in (2, 3):
        return None
    values = [_integer(p, tokens, first, last) for p in parts]
    if any(v is None for v in values):
        return None
    start, stop = values[0], values[-1]
    step = values[1] if len(values) == 3 else 1
    if step == 0:
        return None
    return list(range(start, stop + (1 if step > 0 else -1), step))


def unroll_reductions(text):
    """``(text, [(line, iterator, range, copies)])``: each for-equation
    whose body holds a reduction or comprehension with an iterator
    (``sum(t[k, i]*x for k in 1:3)``) written as one copy of its body per
    value of its iterator, the iterator replaced by the value, all on
    the line of its ``for`` and every later line kept at its number.
    rumoca 0.10.2 panics on such a for-equation ("analysis proves the
    exact comprehension occurrence"), MSL's ``LossyGear`` among them once
    its table lookups are written in Modelica (:func:`inline_tables`);
    the unrolled equations flatten. A range is unrolled where it is
    known from the source: integer literals and ``size(x, d)`` of an
    array the class declares with literal dimensions (``Real
    interpolation_result[1, 4]``), at most :data:`UNROLL_LIMIT` values;
    other for-equations are left as written."""
    found = []
    for _ in range(8):   # nested for-equations: the outer one first
        text, more = _unroll_once(text)
        found += more
        if not more:
            break
    return text, found


def _unroll_once(text):
    """One pass of :func:`unroll_reductions` over the outermost
    for-equations."""
    if "for" not in text:
        return text, []
    tokens = _tokens(text)
    sections = _sections(tokens)
    ranges = _class_ranges(tokens)
    edits, found, depth, k = [], [], 0, 0
    while k < len(tokens):
        token = tokens[k]
        if token[0] == "op" and token[1] in "([{":
            depth += 1
        elif token[0] == "op" and token[1] in ")]}":
            depth -= 1
        if not (depth == 0 and token[1] == "for" and
                token[0] == "ident" and sections[k] == "equation" and
                tokens[k - 1][1] != "end"):
            k += 1
            continue
        loop = _loop_end(tokens, k)
        if loop is None:
            k += 1
            continue
        body_start, stop = loop   # tokens of the body; 'end for ;' after
        head = tokens[k + 1:body_start - 1]   # i in a:b
        body = tokens[body_start:stop]
        if len(head) < 3 or head[0][0] != "ident" or head[1][1] != "in" or \
                not _has_iterator(body):
            k = stop + 3
            continue
        name = head[0][1]
        inside = [r for r in ranges if r[0] < k < r[1]]
        values = _range(head[2:], tokens, *max(inside)) if inside else None
        if values is None or len(values) > UNROLL_LIMIT or \
                _shadows(body, name):
            k = stop + 3
            continue
        copies = " ".join(_one_line([
            (t[0], f"({value})" if t[0] == "ident" and t[1] == name and
             (j == 0 or body[j - 1][1] != ".") and
             (j + 1 == len(body) or body[j + 1][1] != "=")   # f(i = 1)
             else t[1], t[2], t[3])
            for j, t in enumerate(body)]) for value in values)
        begin, end = token[2], tokens[stop + 2][3]
        lines = text.count("\n", begin, end)
        edits.append((begin, end, copies + "\n" * lines))
        found.append((text.count("\n", 0, begin) + 1, name,
                      _one_line(head[2:]), len(values)))
        k = stop + 3
    return _apply(text, edits), found


def _loop_end(tokens, k):
    """``(first token of the body, index of its 'end')`` of the
    for-equation at ``tokens[k]``, or None."""
    depth, j = 0, k + 1
    while j < len(tokens) and not (depth == 0 and tokens[j][1] == "loop"):
        if tokens[j][0] == "op" and tokens[j][1] in "([{":
            depth += 1
        elif tokens[j][0] == "op" and tokens[j][1] in ")]}":
            depth -= 1
        j += 1
    body, nested = j + 1, 0
    for j in range(body, len(tokens) - 2):
        if tokens[j][1] == "loop" and tokens[j][0] == "ident":
            nested += 1   # a nested for-equation (or while) opens
        elif tokens[j][1] == "end" and tokens[j + 1][1] in ("for", "while") \
                and tokens[j + 2][1] == ";":
            if nested == 0:
                return body, j
            nested -= 1
    return None


def _has_iterator(body):
    """Whether ``body`` holds a ``for`` inside brackets (a reduction or
    comprehension with an iterator)."""
    depth = 0
    for token in body:
        if token[0] == "op" and token[1] in "([{":
            depth += 1
        elif token[0] == "op" and token[1] in ")]}":
            depth -= 1
        elif depth > 0 and token[1] == "for" and token[0] == "ident":
            return True
    return False


def _shadows(body, name):
    """Whether an iterator inside ``body`` has the name ``name``."""
    return any(t[1] == "for" and j + 1 < len(body) and
               body[j + 1][1] == name for j, t in enumerate(body))
