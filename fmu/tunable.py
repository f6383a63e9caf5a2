"""Parameters a class binds to its own, read from its source before
rumoca flattens.

A parameter bound to an expression of other parameters is calculated
from them, not a tunable input of the model (:mod:`fmu.backend`, step
1). MSL's ``Rotational.Examples.First`` declares ``Sine sine(amplitude=
amplitude, f=f)``: ``sine.f`` is declared (so
:func:`fmu.precheck.refuse_undeclared` lets it pass) but calculated, and
only the flat model told so, after a flatten of 20 to 40 s.
:func:`refuse_bound` reads it in the class's own text.
"""

import re

from .errors import FrontEndError
from .precheck import _DECLARATION, _SECTION, _Source, _place, _statements

__all__ = ["refuse_bound"]

#: A name in an expression: not a field (``a.b``'s ``b``), nor a function
#: called (``sin(``).
_NAME = re.compile(r"(?<![\w.])([A-Za-z_]\w*)(?![\w.]|\s*\()")


def _arguments(modification):
    """``(offset, name, expression)`` of the ``name = expression``
    arguments of a modification's text (without its outer brackets),
    split at commas outside brackets; prefixes (``final``, ``each``)
    dropped."""
    depth, start, parts = 0, 0, []
    for i, char in enumerate(modification + ","):
        depth += {"(": 1, "[": 1, "{": 1, ")": -1, "]": -1,
                  "}": -1}.get(char, 0)
        if char == "," and depth == 0:
            parts.append((start, modification[start:i]))
            start = i + 1
    found = []
    for offset, part in parts:
        match = re.match(r"\s*(?:(?:final|each)\s+)*(\w+)\s*=(?!=)(.*)",
                         part, re.S)
        if match:
            found.append((offset + match.start(1), match.group(1),
                          match.group(2).strip()))
    return found


def _binding(statement, after, parts):
    """``(offset, expression)`` in ``statement`` of the binding of
    ``parts`` (a name of one or two parts) whose declaration ends at
    ``after``: the declaration's own ``= expression`` for one part, the
    component's modification argument for two; None without one."""
    rest = statement[after:]
    modification = ""
    opened = re.match(r"\s*\(", rest)
    if opened:
        depth = 0
        for i in range(opened.end() - 1, len(rest)):
            depth += {"(": 1, ")": -1}.get(rest[i], 0)
            if depth == 0:
                modification = rest[opened.end():i]
                rest_at = i + 1
                break
        else:
            return None
    else:
        rest_at = 0
    if len(parts) == 1:
        bound = re.match(r"\s*=(?!=)\s*(.*?)\s*(?:\bif\b|$)",
                         rest[rest_at:], re.S)
        return None if bound is None else (
            after + rest_at + bound.start(1), bound.group(1))
    for offset, name, expression in _arguments(modification):
        if name == parts[1]:
            return after + opened.end() + offset, expression
    return None


def refuse_bound(model_name, roots, names):
    """Refuse, before flattening, a name of ``names`` (``{argument:
    Modelica name}``, as :func:`fmu.precheck.refuse_undeclared` takes
    them) that ``model_name`` binds to an expression of its own
    parameters: a parameter it declares so (``parameter Real T_c =
    mu*p_m``), or one its modification of a component binds so (``sine.f``
    of ``Sine sine(f=f)``). Names of more than two parts, and bindings
    in classes extended or deeper, pass to the flat model's check.

    Raises
    ------
    FrontEndError
        ``FILE:LINE: `argument` 'sine.f' is bound to f in CLASS, so it
        is calculated ...; allowed: a tunable parameter (f)``.
    """
    found = _Source([str(r) for r in roots]).long(model_name)
    if found is None:
        return
    path, text, _, begin, body = found
    cut = _SECTION.search(body)
    head = body[:cut.start()] if cut else body
    declared = [(offset, statement, _DECLARATION.match(statement))
                for offset, statement in _statements(head)]
    own = {match.group(4) for _, _, match in declared
           if match and "parameter" in match.group(1).split()}
    for argument, name in names.items():
        parts = name.split(".")
        if len(parts) > 2:
            continue
        for offset, statement, match in declared:
            if not match or match.group(4) != parts[0]:
                continue
            bound = _binding(statement, match.end(), parts)
            if bound is None:
                break
            at, expression = bound
            uses = [n for n in dict.fromkeys(_NAME.findall(expression))
                    if n in own]
            if uses:
                single = expression == uses[0]
                raise FrontEndError(
                    f"{_place(path, text, begin + offset + at)}: "
                    f"`{argument}` {name!r} is bound to "
                    f"{' '.join(expression.split())} in {model_name}, so "
                    f"it is calculated from {', '.join(uses)} and not a "
                    "tunable parameter (read before flattening); allowed: "
                    "a tunable parameter"
                    + (f", here {uses[0]!r}" if single else ""))
            break
