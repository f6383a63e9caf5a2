"""What the compiler refuses before it allocates: arrays too large to
compile, read from the source before rumoca runs and from the flat model
before the front end makes a symbol per element.

Every element of a parameter array is a tunable parameter of the FMU (a
CasADi symbol, a variable of the model description, an entry of the C
arrays): 4,000 elements compile in 12.6 s on this project's 2-core
machines, about 3 ms each. rumoca itself holds an array literal element
by element (``fill(1.0, n)`` with ``n = 1e8`` asked for 7.2 GB, then
aborted; ``n = 1e7`` took minutes and GBs before the front end refused
``fill``). An array above :data:`MAX_ARRAY_ELEMENTS` is refused, naming
the variable, its size and the limit.
"""

import math
import re

__all__ = ["MAX_ARRAY_ELEMENTS", "check_source_arrays", "check_flat_arrays"]

#: Elements of one array the compiler accepts (about 2.5 min of
#: compiling at 3 ms per element).
MAX_ARRAY_ELEMENTS = 50_000

_COMMENT = re.compile(r"//[^\n]*|/\*.*?\*/", re.S)
_STRING = re.compile(r'"(?:\\.|[^"\\])*"')
#: ``Integer n = 100`` (also with ``parameter``/``constant`` and a
#: modifier such as ``(min=1)``).
_INTEGER = re.compile(r"\bInteger\s+(\w+)\s*(?:\([^()]*\))?\s*=\s*"
                      r"([-+]?\d+(?:\.\d*)?(?:[eE][-+]?\d+)?)\s*[;\"]")
#: ``Real p[n, 2]`` (a component with dimensions) and ``Real[n] p``.
_DECLARED = re.compile(r"\b([A-Za-z_][\w.]*)\s+(\w+)\s*\[([^\[\]]*)\]")
_TYPE_DIMS = re.compile(r"\b(Real|Integer|Boolean)\s*\[([^\[\]]*)\]\s*(\w+)")
#: ``fill(v, n, m)``, ``zeros(n)``, ``ones(n)``: arrays of the sizes given.
_FILLED = re.compile(r"\b(fill|zeros|ones)\s*\(([^()]*)\)")
_KEYWORDS = {"parameter", "constant", "input", "output", "flow", "stream",
             "discrete", "final", "inner", "outer", "replaceable",
             "redeclare", "each", "if", "then", "else", "elseif", "for",
             "in", "loop", "when", "while", "return", "and", "or", "not",
             "der", "end", "equation", "algorithm", "extends", "import"}


def _size(text, known):
    """The number of elements of dimensions ``text`` (``n, 2``), or None
    where one is neither an integer nor a known Integer name."""
    total = 1
    for item in text.split(","):
        item = item.strip()
        if re.fullmatch(r"\d+", item):
            total *= int(item)
        elif item in known:
            total *= known[item]
        else:
            return None
    return total


def _refusal(place, what, size, dims, known):
    from .frontend import FrontEndError
    values = ", ".join(f"{name} = {known[name]:,}" for name in
                       re.findall(r"\w+", dims) if name in known)
    raise FrontEndError(
        f"{place}: {what}: {size:,} elements"
        f"{f' ({values})' if values else ''}; allowed: at most "
        f"{MAX_ARRAY_ELEMENTS:,} elements per array (every element is a "
        "variable of its own; about 3 ms of compiling each)")


def check_source_arrays(path, text):
    """Refuse, before rumoca reads ``path``, an array declared (or built
    with ``fill``, ``zeros``, ``ones``) in ``text`` with more than
    :data:`MAX_ARRAY_ELEMENTS` elements, its dimensions integers or
    Integers bound to integers in the same file. Arrays sized otherwise
    (in other files, by expressions) are checked in the flat model
    (:func:`check_flat_arrays`) and by the memory limit of rumoca's
    process."""
    clean = _STRING.sub('""', _COMMENT.sub(
        lambda m: "\n" * m.group(0).count("\n"), text))
    known = {}
    for name, value in _INTEGER.findall(clean):
        number = float(value)
        if number.is_integer() and abs(number) < 1e18:
            known[name] = int(number)

    def line(at):
        return f"{path}:{clean[:at].count(chr(10)) + 1}"

    found = [(m.start(), m.group(2), m.group(3))
             for m in _DECLARED.finditer(clean)
             if m.group(1) not in _KEYWORDS and m.group(2) not in _KEYWORDS]
    found += [(m.start(), m.group(3), m.group(2))
              for m in _TYPE_DIMS.finditer(clean)]
    for at, name, dims in found:
        size = _size(dims, known)
        if size is not None and size > MAX_ARRAY_ELEMENTS:
            _refusal(line(at), f"{name}[{dims.strip()}]", size, dims, known)
    for m in _FILLED.finditer(clean):
        args = m.group(2).split(",")
        dims = ",".join(args[1:] if m.group(1) == "fill" else args)
        size = _size(dims, known) if dims.strip() else None
        if size is not None and size > MAX_ARRAY_ELEMENTS:
            _refusal(line(m.start()), f"{m.group(1)}({m.group(2).strip()})",
                     size, dims, known)


def check_flat_arrays(storage, where):
    """Refuse an array of the flat model (rumoca's ``storage``) with more
    than :data:`MAX_ARRAY_ELEMENTS` elements, before the front end makes
    a symbol for each; ``where`` gives a declaration's ``file:line``."""
    from .frontend import FrontEndError
    for raw in storage["variables"]:
        shape = storage["value_types"][raw["value_type"]].get("dimensions")
        if not shape:
            continue
        size = math.prod(int(n) for n in shape)
        if size > MAX_ARRAY_ELEMENTS:
            place = where({"span": raw.get("declaration", {}).get("span")})
            raise FrontEndError(
                f"{place}: {raw['name']}"
                f"[{', '.join(str(n) for n in shape)}]: {size:,} elements; "
                f"allowed: at most {MAX_ARRAY_ELEMENTS:,} elements per "
                "array (every element is a variable of its own; about 3 ms "
                "of compiling each)")
