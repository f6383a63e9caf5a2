"""What the compiler refuses before it allocates: arrays too large to
compile, read from the source before rumoca runs and from the flat model
before the front end makes a symbol per element; and C code too large
for gcc, estimated from the model's CasADi functions before any C is
written (:func:`compile_estimate`), with the estimate said on a terminal
for a long compile (:func:`announce`).

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
import sys

from infra.environment import positive_setting

from .errors import FrontEndError

__all__ = ["MAX_ARRAY_ELEMENTS", "check_source_arrays", "check_flat_arrays",
           "compile_estimate", "check_compile", "announce"]

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


# -- the C compile -----------------------------------------------------

#: gcc -O2 on the generated C, measured on this project's 2-core machine
#: shared with other work: chains of 50, 100 and 200 states with the
#: Jacobian written densely (3,900, 12,800 and 45,600 CasADi operations:
#: 4.0, 20.6 and 130 s, 87, 216 and 598 MB) and chains of 200, 300 and
#: 1500 states with its nonzeros only (6,000, 9,000 and 45,000: 8.6, 11.9
#: and 41 s, 82, 110 and 393 MB; 100 states 3,000: 2.2 s, 59 MB). Fitted
#: to all seven, within a factor 2 of each:
#: seconds = GCC_S * (operations / 1000) ** GCC_POWER,
#: bytes = GCC_BASE_BYTES + GCC_BYTES_PER_OPERATION * operations.
GCC_S = 0.77
GCC_POWER = 1.22
GCC_BASE_BYTES = 40e6
GCC_BYTES_PER_OPERATION = 10e3
#: Estimates above this (s) are said on stderr, with a progress bar, on
#: a terminal.
ANNOUNCE_S = 10.0
#: Longest compile allowed without ``JUDDER_MAX_HOURS`` (the variable of
#: every command's time limit), hours.
MAX_HOURS = 24.0


def compile_estimate(functions):
    """``(operations, seconds, bytes)`` gcc needs for the CasADi
    ``functions`` of a model, from their instruction counts (read before
    any C is written)."""
    operations = sum(f.n_instructions() for f in functions)
    seconds = GCC_S * (operations / 1000) ** GCC_POWER
    return operations, seconds, GCC_BASE_BYTES + \
        GCC_BYTES_PER_OPERATION * operations


def _hours():
    return positive_setting("JUDDER_MAX_HOURS", MAX_HOURS, "hours",
                            FrontEndError)


def check_compile(model_name, states, estimate, memory):
    """Refuse a model whose C code gcc could not compile in the memory
    available (``memory`` bytes) or within the time limit, naming the
    model, its size, the estimate and the limit."""
    operations, seconds, needed = estimate
    size = f"{states} states, {operations:,} operations in its C code"
    if needed > memory:
        raise FrontEndError(
            f"{model_name}: compiling it ({size}) would need about "
            f"{needed / 1e9:.3g} GB for gcc, more than the "
            f"{memory / 1e9:.3g} GB available; allowed: a model that fits "
            f"(about {int((memory - GCC_BASE_BYTES) / GCC_BYTES_PER_OPERATION):,}"
            " operations)")
    hours = _hours()
    if seconds > 3600 * hours:
        raise FrontEndError(
            f"{model_name}: compiling it ({size}) would take about "
            f"{seconds / 3600:.3g} h, more than the limit of {hours:g} h "
            "(JUDDER_MAX_HOURS=HOURS allows more)")


def announce(model_name, states, estimate, stream=None):
    """Say a long compile on ``stream`` (stderr) when it is a terminal,
    as the project's commands announce long work."""
    stream = stream if stream is not None else sys.stderr
    operations, seconds, needed = estimate
    if seconds < ANNOUNCE_S or not stream.isatty():
        return False
    stream.write(f"fmu: compiling {model_name} ({states} states, "
                 f"{operations:,} operations of C) takes about "
                 f"{_duration(seconds)} and {needed / 1e9:.2g} GB with gcc"
                 "\n")
    stream.flush()
    return True


def _duration(seconds):
    if seconds < 120:
        return f"{seconds:.0f} s"
    if seconds < 7200:
        return f"{seconds / 60:.0f} min"
    return f"{seconds / 3600:.1f} h"
