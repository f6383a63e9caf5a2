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

from dataclasses import dataclass, replace
from functools import cache
import math
from pathlib import Path
import re
from types import MappingProxyType

__all__ = ["DATA", "RecordError", "RecordParameter", "record_values",
           "record_parameters", "experiment_stop_time"]

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
_PARAMETER = re.compile(r"\bparameter\s+([\w.]+)\s+(\w+)\s*(?:\(([^()]*)\))?"
                        r'\s*=\s*([^;"]*?)\s*(?:"(\d+)")?\s*;')
_TYPE = re.compile(r"\btype\s+(\w+)\s*=\s*Real\s*\(([^;]*)\)[^;]*;")


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
    return MappingProxyType({parameter: declared.value for parameter, declared
                             in record_parameters(name, folder).items()})


@dataclass(frozen=True)
class RecordParameter:
    """One parameter of a record, as declared.

    Attributes
    ----------
    value : float
        Its value (SI), with the modifiers of the extends clauses applied.
    unit : str
        The Modelica unit of its type (``'N.m.s/rad'``; ``'1'`` for
        ``Real``), from the library's ``Units`` package.
    low, high : float
        Its ``min`` and ``max``, or its type's (infinite where neither
        declares one).
    description : str
    """

    value: float
    unit: str
    low: float
    high: float
    description: str


@cache
def record_parameters(name, folder=DATA):
    """The parameters of the record ``name`` of ``folder`` with their
    units, bounds and descriptions (:class:`RecordParameter`), in the
    order of :func:`record_values`."""
    path = Path(folder) / f"{name}.mo"
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as exc:
        raise RecordError(f"record {name!r}: {path} cannot be read "
                          f"({exc.strerror})") from None
    strings = []

    def keep(string):
        strings.append(string.group(0)[1:-1])
        return f'"{len(strings) - 1}"'
    text = _COMMENT.sub("", _STRING.sub(keep, text))
    body = _CLASS.search(text)
    if body is None:
        raise RecordError(f"{path}: no 'record {name} ... end {name};'")
    body = re.sub(r"\bannotation\s*\(.*", "", body.group(2), flags=re.S)
    units = _unit_types(Path(folder).parent / "Units.mo")
    parameters = {}
    for kind, parameter, attributes, value, text_index in \
            _PARAMETER.findall(body):
        where = f"{path}: {parameter}"
        unit, low, high = units.get(kind.rsplit(".", 1)[-1],
                                    ("1", -math.inf, math.inf))
        bounds = _modifiers(",".join(
            item for item in attributes.split(",")
            if item.strip().startswith(("min", "max"))), where)
        parameters[parameter] = RecordParameter(
            _number(value, where), unit, bounds.get("min", low),
            bounds.get("max", high),
            strings[int(text_index)] if text_index else "")
    for base, modifiers in _EXTENDS.findall(body):
        inherited = record_parameters(base, folder)
        changed = _modifiers(modifiers, f"{path}: extends {base}")
        unknown = sorted(set(changed) - set(inherited))
        if unknown:
            raise RecordError(f"{path}: extends {base}: {unknown[0]!r} is not "
                              f"a parameter of {base}; allowed: "
                              f"{', '.join(inherited)}")
        parameters.update({
            key: replace(declared, value=changed.get(key, declared.value))
            for key, declared in inherited.items() if key not in parameters})
    return MappingProxyType(parameters)


@cache
def _unit_types(path):
    """``{type name: (Modelica unit, min, max)}`` of the library's
    ``Units`` package (``Judder/Units.mo``); empty where it is absent."""
    try:
        text = _COMMENT.sub("", Path(path).read_text(encoding="utf-8"))
    except OSError:
        return {}
    types = {}
    for kind, attributes in _TYPE.findall(text):
        unit = re.search(r'\bunit\s*=\s*"([^"]*)"', attributes)
        bounds = {bound: float(number) for bound, number in re.findall(
            rf"\b(min|max)\s*=\s*([-+]?{_NUMBER})", attributes)}
        types[kind] = (unit.group(1) if unit else "1",
                       bounds.get("min", -math.inf),
                       bounds.get("max", math.inf))
    return types


@cache
def experiment_stop_time(modelica_class, library=DATA.parent.parent):
    """The ``StopTime`` of the ``experiment`` annotation of a class of
    the library (``'Judder.Examples.TestBenchEngagement'``), s."""
    path = Path(library).joinpath(*modelica_class.split(".")).with_suffix(
        ".mo")
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as exc:
        raise RecordError(f"class {modelica_class}: {path} cannot be read "
                          f"({exc.strerror})") from None
    found = re.search(rf"\bexperiment\s*\([^)]*\bStopTime\s*=\s*"
                      rf"({_NUMBER})", text)
    if found is None:
        raise RecordError(f"{path}: no experiment(StopTime=...) annotation")
    return float(found.group(1))
