"""Constructs the back end does not compile, found in the source before
rumoca flattens.

rumoca flattens the whole model before the front end can see an Integer
mode or a ``pre()`` (MSL's ``CoupledClutches``: 400 s), and then often
stops in its own DAE stage with a miscount ("unbalanced model: 115
equations, 112 unknowns") that names neither the construct nor its place.
:func:`refuse_unsupported` instead walks the classes the model
instantiates (its components' types and the classes they extend) in the
source text, resolving names as Modelica does (nested classes, imports,
enclosing packages), and refuses the first definite obstacle with its
``file:line``, the components that lead to it and, for the MSL's
friction elements, the project library's replacement.

It refuses only what the back end certainly refuses later (the checks of
:func:`fmu.frontend._check_supported` remain for what this reading
misses). Always: String and enumeration variables, and parameters of an
``ExternalObject`` type that :mod:`fmu.rewrite` cannot inline
(:func:`fmu.rewrite.inlinable_table`: MSL's table objects). Without
``hybrid`` also Integer, Boolean and ``discrete`` variables, ``edge``,
``change``, ``sample``, and ``initial()`` and ``pre`` outside a
when-clause; with ``hybrid`` (every FMU build and a class's Floquet
view) the front end compiles those (docs/compiler.md).

Conditional components (``... if useHeatPort``) are not followed:
whether they exist is known only after the parameters are evaluated;
nor are replaceable components and classes, which a modifier may
redeclare.

The dither's parameter names are read there too:
:func:`refuse_undeclared` refuses a name the class does not declare,
:func:`refuse_bound` one it binds to its own parameters (a calculated
parameter, not a tunable input: MSL's ``Rotational.Examples.First``
declares ``Sine sine(amplitude=amplitude, f=f)``, so ``sine.f`` is
declared but calculated, and only the flat model told so, after a
flatten of 20 to 40 s).
"""

import dataclasses
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path
import re

from .errors import FrontEndError
from .classes import blank, class_spans, find_class
from .rewrite import inlinable_table

__all__ = ["refuse_unsupported", "refuse_undeclared", "refuse_bound",
           "REPLACEMENTS"]

#: What to use instead of the MSL classes the compiler refuses: the
#: project library's replacement where it has one, else a plain "none".
_ROTATIONAL = "Modelica.Mechanics.Rotational.Components."
_TRANSLATIONAL = "Modelica.Mechanics.Translational.Components."
REPLACEMENTS = {
    _ROTATIONAL + "Clutch":
        "use Judder.Components.LockingWetClutch (locks and breaks away by "
        "events) or Judder.Components.SlippingClutch (always slipping)",
    _ROTATIONAL + "Brake":
        "use Judder.Components.LockingWetClutch with its "
        "flange_b connected to a Judder.Components.Fixed (a brake is a "
        "clutch with one flange held in the housing; it is actuated by "
        "its pressure p, not by a normalised force)",
    _ROTATIONAL + "OneWayClutch":
        "the Judder library has no replacement: it has no one-way clutch "
        "(freewheel)",
    _ROTATIONAL + "LossyGear":
        "the Judder library has no replacement with losses: its "
        "Judder.Components.IdealGear is lossless (no mesh or bearing "
        "friction)",
    _ROTATIONAL + "ElastoBacklash":
        "the Judder library has no replacement: it has no backlash element",
    _ROTATIONAL + "ElastoBacklash2":
        "the Judder library has no replacement: it has no backlash element",
    _ROTATIONAL + "BearingFriction":
        "the Judder library has no replacement: it has no Coulomb bearing "
        "friction (Judder.Components.Damper is a viscous loss)",
    _TRANSLATIONAL + "Brake":
        "the Judder library has no replacement: it models rotational "
        "drivelines only (for a rotational brake, "
        "Judder.Components.LockingWetClutch with one flange on a "
        "Judder.Components.Fixed)",
    _TRANSLATIONAL + "ElastoGap":
        "the Judder library has no replacement: it models rotational "
        "drivelines only, and has no gap or backlash element",
}
_BUILTIN = {"Real", "Integer", "Boolean", "String"}
_DISCRETE = {"Integer": "an Integer variable", "Boolean": "a Boolean variable",
             "String": "a String variable",
             "enumeration": "an enumeration variable"}
_PREFIXES = ("final", "inner", "outer", "replaceable", "redeclare", "flow",
             "stream", "discrete", "parameter", "constant", "input", "output",
             "each")
#: Endings of the findings the front end reads with ``hybrid``.
_HYBRID = tuple(f"({what})" for what in (*list(_DISCRETE.values())[:2],
                                          "a discrete variable")) + (
    "outside a when-clause's reinit is not supported",
    "initialisation) is not supported", "edge() is not supported",
    "change() is not supported",
    "sample(): clocked equations are not supported")
_SECTION = re.compile(r"\b(?:initial\s+)?(?:equation|algorithm)\b")
_DECLARATION = re.compile(
    r"^\s*((?:(?:" + "|".join(_PREFIXES) + r")\s+)*)"
    r"([A-Za-z_][\w.]*)\s*(\[[^\]]*\])?\s+([A-Za-z_]\w*)\s*(\[[^\]]*\])?",
    re.S)
_IMPORT = re.compile(r"^\s*import\s+(?:(\w+)\s*=\s*)?([\w.]+?)"
                     r"(?:\.(\*)|\.\{([^}]*)\})?\s*$", re.S)
_EXTENDS = re.compile(r"^\s*extends\s+([\w.]+)")
_SHORT = r"\b(?:type|connector|model|block|record|class)\s+{}\s*=\s*" \
    r"((?:(?:input|output|flow|stream|discrete)\s+)*)([\w.]+)"
_WHEN = re.compile(r"\bwhen\b(.*?)\bend\s+when\s*;", re.S)
#: The condition of a when-clause (``end when`` blanked first).
_WHEN_CONDITION = re.compile(r"\b(?:else)?when\b(.*?)\bthen\b", re.S)
_INITIAL_WHEN = "initial() in a when-condition is not supported; " \
    "allowed: initial() in equations (if initial() then ... else ... end " \
    "if)"
_OPERATORS = {"edge": "edge() is not supported",
              "change": "change() is not supported",
              "sample": "sample(): clocked equations are not supported",
              "initial": "initial() (equations that differ at the "
                         "initialisation) is not supported"}


@dataclass(frozen=True)
class _Finding:
    """One construct the back end does not compile."""

    place: str
    what: str
    chain: tuple   # (component, class name, place) from the model down
    #: the class that holds it, then those that extend that one, down to
    #: the last component's type (or the model)
    classes: tuple = ()


class _Source:
    """Class definitions of the libraries on the path, read on demand."""

    def __init__(self, roots):
        self.roots = [str(r) for r in roots]

    @lru_cache(maxsize=None)
    def _file(self, path):
        text = Path(path).read_text(encoding="utf-8", errors="replace")
        return text, blank(text), class_spans(text)

    @lru_cache(maxsize=None)
    def long(self, name):
        """``(path, text, clean, begin, body)`` of a long class definition:
        ``body`` its clean text with the nested classes blanked; or None."""
        try:
            path, _ = find_class(name, self.roots)
        except FrontEndError:
            return None
        text, clean, spans = self._file(str(path))
        span = spans.get(name)
        if span is None:
            return None
        begin, end = span
        body = list(clean[begin:end])
        for other, (a, b) in spans.items():
            if other != name and begin < a and b <= end:
                body[a - begin:b - begin] = " " * (b - a)
        head = re.match(r"\s*\w+\s+(?:extends\s+)?\w+", "".join(body))
        body[:head.end()] = " " * head.end()
        return str(path), text, clean, begin, "".join(body)

    @lru_cache(maxsize=None)
    def short(self, name):
        """``(prefixes, base name, place)`` of a short definition ``type
        T = ...`` inside its enclosing class; or None."""
        parent, _, short_name = name.rpartition(".")
        found = self.long(parent) if parent else None
        if found is None:
            return None
        path, text, _, begin, body = found
        match = re.search(_SHORT.format(re.escape(short_name)), body)
        if match is None or re.search(r"\breplaceable\s+$",
                                      body[:match.start()]):
            return None   # a replaceable class may be redeclared
        return (match.group(1).split(), match.group(2),
                _place(path, text, begin + match.start()))

    def exists(self, name):
        return self.long(name) is not None or self.short(name) is not None


def _place(path, text, offset):
    return f"{path}:{text[:offset].count(chr(10)) + 1}"


def _statements(body, separator=";"):
    """``(offset, text)`` of the statements of a clean class body (split
    at ``;`` outside brackets), or of the parts of a text ending in
    another ``separator`` (a modification's arguments, at ``,``)."""
    depth, start = 0, 0
    for found in re.finditer(r"[;,()\[\]{}]", body):
        char, i = found.group(0), found.start()
        if char in "([{":
            depth += 1
        elif char in ")]}":
            depth -= 1
        elif depth == 0 and char == separator:
            yield start, body[start:i]
            start = i + 1


def _after_brackets(text, opening):
    """Offset just after the bracket group ``(...)`` opening at
    ``text[opening]``; None if it does not close."""
    depth = 0
    for i in range(opening, len(text)):
        depth += {"(": 1, ")": -1}.get(text[i], 0)
        if depth == 0:
            return i + 1
    return None


def _imports(statements):
    """``{alias: full name}`` and the packages imported whole (``.*``)."""
    named, whole = {}, []
    for _, statement in statements:
        found = _IMPORT.match(statement)
        if not found:
            continue
        alias, target, star, listed = found.groups()
        if star:
            whole.append(target)
        elif listed:
            named.update({n.strip(): f"{target}.{n.strip()}"
                          for n in listed.split(",")})
        else:
            named[alias or target.rsplit(".", 1)[-1]] = target
    return named, whole


class _Walker:
    """Finds what the back end does not compile in the classes a model
    instantiates (each class read once)."""

    def __init__(self, roots):
        self.source = _Source(roots)
        self.done = {}
        self.imports = {}

    def _scope_imports(self, scope):
        """The imports of class ``scope`` (see :func:`_imports`), read
        once per class."""
        if scope not in self.imports:
            found = self.source.long(scope)
            self.imports[scope] = _imports(
                (0, statement) for statement in re.findall(
                    r"\bimport\s[^;]*", found[4])) if found else ({}, [])
        return self.imports[scope]

    def resolve(self, name, scope):
        """The full name of ``name`` used in class ``scope`` (lexical
        lookup: nested classes and imports of the class and of its
        enclosing packages, then the top level); None if not found."""
        if name in _BUILTIN or name == "ExternalObject":
            return name
        first, _, rest = name.partition(".")
        parts = scope.split(".")
        for count in range(len(parts), 0, -1):
            enclosing = ".".join(parts[:count])
            candidate = f"{enclosing}.{name}"
            if self.source.exists(f"{enclosing}.{first}"):
                return candidate
            named, whole = self._scope_imports(enclosing)
            if first in named:
                return named[first] + (f".{rest}" if rest else "")
            for package in whole:
                if self.source.exists(f"{package}.{first}"):
                    return f"{package}.{name}"
        return name if self.source.exists(name) else None

    def kind(self, name, scope, seen=()):
        """``(full name, builtin base or None, extends ExternalObject)``
        of a type, following short definitions."""
        full = self.resolve(name, scope)
        if full is None or full in _BUILTIN:
            return full, full, False
        short = self.source.short(full)
        if short is not None and full not in seen:
            base = short[1]
            if base == "enumeration":
                return full, "enumeration", False
            return self.kind(base, full.rpartition(".")[0], seen + (full,))
        found = self.source.long(full)
        if found is not None and re.search(r"\bextends\s+ExternalObject\b",
                                           found[4]):
            return full, None, True
        if found is not None and re.search(r"\benumeration\s*\(", found[4]):
            return full, "enumeration", False
        return full, None, False

    def findings(self, name):
        """What class ``name`` (and what it extends and instantiates)
        holds that the back end does not compile."""
        if name in self.done:
            return self.done[name]
        self.done[name] = []    # a class that instantiates itself
        found = self.source.long(name)
        if found is None:
            return []
        path, text, _, begin, body = found
        cut = _SECTION.search(body)
        result = []
        for at, statement in _statements(body[:cut.start()] if cut
                                         else body):
            statement = re.sub(r"^(\s*)(?:protected|public)\b",
                               lambda m: m.group(1) + " " * (
                                   len(m.group(0)) - len(m.group(1))),
                               statement)
            where = _place(path, text, begin + at + len(statement)
                           - len(statement.lstrip()))
            self.raw = text[begin + at:begin + at + len(statement)]
            result += self._statement(statement, name, where)
        if cut:
            result += self._equations(body[cut.start():], path, text,
                                      begin + cut.start(), name)
        self.done[name] = result
        return result

    def _statement(self, statement, scope, where):
        extends = _EXTENDS.match(statement)
        if extends:
            full = self.resolve(extends.group(1), scope)
            return [dataclasses.replace(f, classes=f.classes + (scope,))
                    for f in self.findings(full)] if full else []
        found = _DECLARATION.match(statement)
        if not found or re.match(r"\s*(?:import|annotation)\b", statement):
            return []
        prefixes, type_name, dims, component, more = found.groups()
        prefixes = prefixes.split()
        if _conditional(statement[found.end():]) or \
                "replaceable" in prefixes:
            return []     # may not exist, or be redeclared another type
        full, base, external = self.kind(type_name, scope)
        if external and inlinable_table(getattr(self, "raw", statement)):
            return []   # its lookups are computed in Modelica (fmu.rewrite)
        if external:
            return [_Finding(where, f"{component}: an external object "
                             f"({full}) is not supported", (), (scope,))]
        if "parameter" in prefixes or "constant" in prefixes:
            return []
        if "discrete" in prefixes or base in _DISCRETE:
            what = _DISCRETE.get(base, "a discrete variable")
            return [_Finding(where, f"{component}: Integer, Boolean and "
                             f"discrete variables are not supported ({what})",
                             (), (scope,))]
        if base is None and full is not None:
            return [dataclasses.replace(
                f, chain=((component, full, where),) + f.chain)
                for f in self.findings(full)]
        return []

    def declares(self, name, parts, _extending=()):
        """Whether class ``name`` (or a class it extends) declares the
        component ``parts`` (``("clutch", "p_f")`` for ``clutch.p_f``):
        False only when every class on the way was read and none has it,
        None when that is not known from the source (a class not found,
        a replaceable or conditional component, a redeclaration).
        ``_extending``: the classes whose ``extends`` led here; a class
        met again among them extends itself, refused in words
        (:class:`FrontEndError`, at its definition) rather than followed
        until Python's recursion limit."""
        found = self.source.long(name)
        if found is None:
            return None
        if name in _extending:
            path, text, _, begin, _ = found
            chain = " extends ".join(_extending[_extending.index(name):]
                                     + (name,))
            raise FrontEndError(
                f"{_place(path, text, begin)}: {name} extends itself "
                f"({chain}); allowed: classes whose extends clauses end "
                "in a class that extends none of them")
        body = found[4]
        cut = _SECTION.search(body)
        head = body[:cut.start()] if cut else body
        if not re.search(rf"(?<![\w.]){re.escape(parts[0])}\b", head):
            unknown = False
            for extends in re.finditer(r"\bextends\s+([\w.]+)([^;]*)",
                                       head):
                full = self.resolve(extends.group(1), name)
                if full is None or (len(parts) > 1
                                    and "redeclare" in extends.group(2)):
                    unknown = True
                    continue
                inherited = self.declares(full, parts,
                                          _extending + (name,))
                if inherited:
                    return True
                unknown = unknown or inherited is None
            return None if unknown else False
        if len(parts) == 1:
            return True
        for _, statement in _statements(head):
            match = _DECLARATION.match(statement)
            if match and match.group(4) == parts[0]:
                if "replaceable" in match.group(1).split() or \
                        _conditional(statement[match.end():]):
                    return None
                full, base, _ = self.kind(match.group(2), name)
                return None if full is None or base is not None else \
                    self.declares(full, parts[1:])
        return None

    def _equations(self, sections, path, text, begin, scope):
        outside = _WHEN.sub(lambda m: " " * len(m.group(0)), sections)
        ends = re.sub(r"\bend\s+when\b", lambda m: " " * len(m.group(0)),
                      sections)
        hits = [(condition.start(1) + found.start(), _INITIAL_WHEN)
                for condition in _WHEN_CONDITION.finditer(ends)
                for found in re.finditer(r"\binitial\s*\(",
                                         condition.group(1))]
        hits += [(found.start(), what) for operator, what in
                 _OPERATORS.items()
                 for found in re.finditer(rf"\b{operator}\s*\(", sections)]
        hits += [(found.start(), "pre() outside a when-clause's reinit is not "
                  "supported")
                 for found in re.finditer(r"\bpre\s*\(", outside)]
        return [_Finding(_place(path, text, begin + at), what, (), (scope,))
                for at, what in sorted(hits)]


def _conditional(rest):
    """Whether the text after a component's name (its modification,
    binding, condition and comment) makes it conditional (``... if
    useSupport``)."""
    rest = rest.lstrip()
    if rest.startswith("("):
        closed = _after_brackets(rest, 0)
        rest = rest[closed:].lstrip() if closed else rest
    return re.match(r"if\b", rest) is not None


def _describe(finding):
    chain = ", in ".join(f"{component} ({name}, {place})" for component,
                         name, place in reversed(finding.chain))
    return f"{finding.place}: {finding.what}" + \
        (f", in {chain}" if chain else "")


def _replaced(finding, model_name):
    """The MSL class of :data:`REPLACEMENTS` a finding is in: a
    component's type on the way from the model, else the class holding
    the construct or one extending it (a model of one's own that extends
    MSL's Clutch), else the model; None if none is listed."""
    return next((name for name in [name for _, name, _ in finding.chain]
                 + list(finding.classes) + [model_name]
                 if name in REPLACEMENTS), None)


def _replacement_words(findings, model_name):
    """``; use ...`` for the MSL class the first finding is in, and ``for
    Clutch: ...; for Brake: ...`` when the findings are in several (MSL's
    Examples.Friction holds a clutch and a brake; classes with the same
    words share them); "" for none listed."""
    classes = {}
    for finding in findings:
        name = _replaced(finding, model_name)
        if name is not None:
            classes.setdefault(REPLACEMENTS[name], []).append(
                name.rsplit(".", 1)[-1])
    one = [words for words, names in classes.items()
           if len(classes) == 1 and len(set(names)) == 1]
    if one:
        return f"; {one[0]}"
    return "".join(f"; for {', '.join(dict.fromkeys(names))}: {words}"
                   for words, names in classes.items())


def refuse_unsupported(path, model_name, roots, hybrid=False):
    """Refuse ``model_name`` if the classes it instantiates hold a
    construct the back end does not compile, before rumoca flattens it.

    With ``hybrid`` Integer, Boolean and discrete variables, ``pre()`` and
    ``initial()`` pass: the front end reads their equations, and
    ``initial()`` in the others too (MSL's ``ElastoBacklash`` has it in an
    if-equation of Reals).

    Raises
    ------
    FrontEndError
        ``FILE:LINE: construct``, the components that lead there from the
        model, and the replacement of :data:`REPLACEMENTS` when one of
        them is an MSL class listed there.
    """
    walker = _Walker(roots)
    findings = [f for f in walker.findings(model_name)
                if not (hybrid and f.what.endswith(_HYBRID))]
    if not findings:
        return
    first = findings[0]
    message = f"{_describe(first)}, in model {model_name} ({path})" + \
        _replacement_words(findings, model_name)
    others = sorted({f.place for f in findings[1:]} - {first.place})
    if others:
        message += (f"; also at {', '.join(others[:4])}"
                    + (f" and {len(others) - 4} more" if len(others) > 4
                       else ""))
    raise FrontEndError(message + " (found before flattening)")


#: A name in an expression: not a field (``a.b``'s ``b``), nor a function
#: called (``sin(``).
_NAME = re.compile(r"(?<![\w.])([A-Za-z_]\w*)(?![\w.]|\s*\()")


def _arguments(modification):
    """``(offset, name, expression)`` of the ``name = expression``
    arguments of a modification's text (without its outer brackets),
    split at commas outside brackets; prefixes (``final``, ``each``)
    dropped."""
    found = []
    for offset, part in _statements(modification + ",", ","):
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
        rest_at = _after_brackets(rest, opened.end() - 1)
        if rest_at is None:
            return None
        modification = rest[opened.end():rest_at - 1]
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


def refuse_undeclared(model_name, roots, names):
    """Refuse, before rumoca flattens, a parameter name that
    ``model_name`` certainly does not declare: ``names`` maps each
    argument to a Modelica name (``{"amplitude": "p_f"}``, or
    ``clutch.p_f``), looked up in the class, the classes it extends and
    the types of its components (see :meth:`_Walker.declares`; a name the
    source alone does not settle passes, for the flat model to check).

    Raises
    ------
    FrontEndError
        ``FILE:LINE: `argument` 'name' is not declared in CLASS ...``,
        the place being the class's definition.
    """
    walker = _Walker(roots)
    for argument, name in names.items():
        if walker.declares(model_name, tuple(name.split("."))) is False:
            path, text, _, begin, _ = walker.source.long(model_name)
            raise FrontEndError(
                f"{_place(path, text, begin)}: `{argument}` {name!r} is not "
                f"declared in {model_name} (read with the classes it "
                "extends and its components' types, before flattening); "
                f"allowed: a parameter of {model_name} by its Modelica "
                "name")
