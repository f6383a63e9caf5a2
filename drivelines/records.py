"""Values of the Modelica library's parameter records (``Judder.Data``).

The paper's Appendix A and the set fitted to the bench (section 4.2) are
written once, as records of ``modelica/Judder/Data``; the examples extend
them, and the registry's presets are read from them here. A record file
holds declarations ``parameter TYPE NAME(ATTRIBUTES)=VALUE "...";`` and
``extends BASE(NAME=VALUE, ...);`` of a record in the same folder; a
VALUE is a number or a product or quotient of numbers (``32885*1.06``),
evaluated in floating point in the order written, as a Modelica compiler
evaluates it. Anything else is refused: a record of data holds data.

This module reads text with regular expressions only (no numpy, no
Modelica compiler), so that the registry, which every command imports,
stays fast; each record is read once per process.
"""

from functools import cache
from pathlib import Path
import re
from types import MappingProxyType

__all__ = ["DATA", "RecordError", "record_values"]

#: Folder of the library's parameter records (package ``Judder.Data``).
DATA = Path(__file__).resolve().parents[1] / "modelica" / "Judder" / "Data"

_NUMBER = r"\d+(?:\.\d*)?(?:[eE][-+]?\d+)?"
#: A VALUE: a number, or numbers joined by ``*`` and ``/``.
_VALUE = re.compile(rf"\s*([-+]?)\s*({_NUMBER}(?:\s*[*/]\s*{_NUMBER})*)\s*")
_FACTOR = re.compile(rf"([*/]?)\s*({_NUMBER})")
_STRING = re.compile(r'"(?:[^"\\]|\\.)*"', re.S)
_COMMENT = re.compile(r"//[^\n]*|/\*.*?\*/", re.S)
_CLASS = re.compile(r"\brecord\s+(\w+)\b(.*?)\bend\s+\1\s*;", re.S)
_EXTENDS = re.compile(r"\bextends\s+(\w+)\s*(?:\((.*?)\))?\s*;", re.S)
_PARAMETER = re.compile(r"\bparameter\s+[\w.]+\s+(\w+)\s*(?:\([^()]*\))?"
                        r'\s*=\s*([^;"]*?)\s*(?:"")?\s*;')


class RecordError(ValueError):
    """A record of the library cannot be read; the message says where."""


def _number(text, where):
    """The value of ``text``: a signed product or quotient of numbers."""
    found = _VALUE.fullmatch(text)
    if found is None:
        raise RecordError(f"{where}: value {text.strip()!r} is not allowed; "
                          "allowed: a number or a product or quotient of "
                          "numbers")
    sign, product = found.groups()
    value = None
    for operator, number in _FACTOR.findall(product):
        number = float(number)
        value = (number if value is None else value * number
                 if operator == "*" else value / number)
    return -value if sign == "-" else value


def _modifiers(text, where):
    """``NAME=VALUE, ...`` of an extends clause as ``{NAME: value}``."""
    values = {}
    for item in filter(str.strip, text.split(",")):
        name, equals, value = item.partition("=")
        if not equals or not name.strip().isidentifier():
            raise RecordError(f"{where}: modifier {item.strip()!r} is not "
                              "allowed; allowed: NAME=VALUE")
        values[name.strip()] = _number(value, where)
    return values


@cache
def record_values(name, folder=DATA):
    """The parameter values of the record ``name`` of ``folder``.

    Parameters
    ----------
    name : str
        Record class, e.g. ``'Driveline4DOFData'`` (file ``NAME.mo``).
    folder : pathlib.Path
        Folder of the record files (default: the library's ``Data``).

    Returns
    -------
    mapping of str to float
        Its own parameters in the order declared, then those of the
        records it extends, with the extends clause's modifiers applied
        (SI units, as the record declares them).

    Raises
    ------
    RecordError
        If the file is missing or holds something that is not data: the
        message names the file and what is not allowed.

    Examples
    --------
    >>> record_values("Driveline4DOFFitted")["c12"]
    10.0
    """
    path = Path(folder) / f"{name}.mo"
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as exc:
        raise RecordError(f"record {name!r}: {path} cannot be read "
                          f"({exc.strerror})") from None
    text = _COMMENT.sub("", _STRING.sub('""', text))
    body = _CLASS.search(text)
    if body is None:
        raise RecordError(f"{path}: no 'record {name} ... end {name};'")
    body = re.sub(r"\bannotation\s*\(.*", "", body.group(2), flags=re.S)
    values = {parameter: _number(value, f"{path}: {parameter}")
              for parameter, value in _PARAMETER.findall(body)}
    for base, modifiers in _EXTENDS.findall(body):
        inherited = record_values(base, folder)
        changed = _modifiers(modifiers, f"{path}: extends {base}")
        unknown = sorted(set(changed) - set(inherited))
        if unknown:
            raise RecordError(f"{path}: extends {base}: {unknown[0]!r} is not "
                              f"a parameter of {base}; allowed: "
                              f"{', '.join(inherited)}")
        values.update({key: changed.get(key, value)
                       for key, value in inherited.items()
                       if key not in values})
    return MappingProxyType(values)
