"""Numbers of a text export read as written.

A DAQ's export writes ``1000.5``, ``1000,5``, ``1,000.5``,
``1.000,5``, ``1 000,5`` or ``1'000.5`` for the same number, as its
locale has it. Which separator is the decimal one is decided once per
file from every cell read, never per cell: ``1,000`` alone is 1000 (a
thousands comma) or 1.0 (a decimal comma), and only another cell of the
file (``0.001``, ``3,25``) tells which. A file whose cells disagree, or
that no cell decides while some cell depends on it, is refused with the
cell as the file has it. Where the cells cannot decide, the caller says
which separator is the decimal one (``decimal``, :data:`DECIMALS`); every
cell is then checked against it. The thousands separator follows from
the decimal one: ``,`` for a decimal point, ``.`` for a decimal comma,
and a space or an apostrophe for either (one kind within a cell).

Examples
--------
>>> sorted(readings("1,000"))
['comma', 'point']
>>> readings("0.001")
{'point'}
>>> value("1.000,60656", "comma"), value("1,000", "point")
(1000.60656, 1000.0)
>>> value("1 000,5", "comma"), value("1'000.5", "point")
(1000.5, 1000.5)
"""

import re

import numpy as np

from infra.errors import JudderError

__all__ = ["CONVENTIONS", "DECIMALS", "readings", "is_number", "value",
           "decide", "column_values"]

#: Thousands separators either convention takes besides its own: a
#: space (also the no-break ones) and an apostrophe (Swiss exports).
_THOUSANDS_EITHER = " \u00a0\u202f'"
#: Decimal separator -> (its name in messages, its thousands separators).
CONVENTIONS = {
    "point": ("a decimal point (thousands ',', space or apostrophe)",
              "," + _THOUSANDS_EITHER),
    "comma": ("a decimal comma (thousands '.', space or apostrophe)",
              "." + _THOUSANDS_EITHER)}
#: The decimal separator as a caller gives it -> its convention.
DECIMALS = {".": "point", ",": "comma"}
#: Cells that are numbers whatever the separators: empty, nan, inf.
_NEUTRAL = re.compile(r"|[+-]?(nan|inf|infinity)", re.IGNORECASE)


def _pattern(decimal, thousands):
    # one kind of thousands separator within a cell (the backreference)
    d, t = re.escape(decimal), re.escape(thousands)
    return re.compile(
        rf"[+-]?(?:(?:\d+|[1-9]\d{{0,2}}(?P<t>[{t}])\d{{3}}(?:(?P=t)\d{{3}})*)"
        rf"(?:{d}\d*)?|{d}\d+)(?:[eE][+-]?\d+)?")


_PATTERNS = {"point": _pattern(".", CONVENTIONS["point"][1]),
             "comma": _pattern(",", CONVENTIONS["comma"][1])}


def readings(cell):
    """The conventions (keys of :data:`CONVENTIONS`) under which a cell is
    a number; both for a cell without separators (``12``, ``nan``, empty),
    none for a cell that is no number."""
    cell = cell.strip()
    if _NEUTRAL.fullmatch(cell):
        return set(CONVENTIONS)
    return {name for name, pattern in _PATTERNS.items()
            if pattern.fullmatch(cell)}


def is_number(cell):
    """Whether a cell, not empty, reads as a number under either
    convention (``1 000``, ``1.000,5``, ``0.5``, ``nan``)."""
    return bool(cell.strip()) and bool(readings(cell))


def value(cell, convention):
    """A cell's number under a convention (NaN for an empty cell)."""
    cell = cell.strip()
    if not cell:
        return np.nan
    for thousands in CONVENTIONS[convention][1]:
        cell = cell.replace(thousands, "")
    return float(cell.replace(",", ".") if convention == "comma" else cell)


def _separated(cell):
    """A cell whose reading depends on the convention."""
    return len(readings(cell)) == 2 and ("," in cell or "." in cell)


#: A cell with a point that reads under the comma convention too
#: (``1.000``: a thousands point).
_GROUPED_POINT = re.compile(r"[+-]?[1-9]\d{0,2}(?:\.\d{3})+(?:[eE][+-]?\d+)?")


def _plain_column(cells):
    """What a column without commas whose every cell Python reads shows,
    at the cost of one pass (most exports): ``(conventions, (line,
    cell) deciding or None, (line, cell) depending on it or None)``; None
    for a column that needs the cell-by-cell reading."""
    if any("," in cell or "_" in cell for _, cell in cells):
        return None
    try:
        np.array([cell.strip() or "nan" for _, cell in cells], dtype=float)
    except ValueError:
        return None
    grouped = None
    for number, cell in cells:
        if "." in cell:
            if not _GROUPED_POINT.fullmatch(cell.strip()):
                return {"point"}, (number, cell.strip()), None
            grouped = grouped or (number, cell.strip())
    return set(CONVENTIONS), None, grouped


def _column_reading(name, cells, path):
    """:func:`_plain_column`'s answer, cell by cell where needed."""
    plain = _plain_column(cells)
    if plain is not None:
        return plain
    allowed, deciding, depending = set(CONVENTIONS), None, None
    for number, cell in cells:
        found = readings(cell)
        if not found:
            raise JudderError(f"{path}, line {number}: column {name!r}: "
                              f"{cell.strip()!r} is not a number")
        if len(found) == 1 and deciding is None:
            deciding = (number, cell.strip())
        elif depending is None and _separated(cell):
            depending = (number, cell.strip())
        allowed &= found
        if not allowed:
            raise JudderError(
                f"{path}: column {name!r} has {deciding[1]!r} (line "
                f"{deciding[0]}) and {cell.strip()!r} (line {number}), "
                "written with different decimal separators; allowed: one "
                "decimal separator in the whole file")
    return allowed, deciding, depending


def decide(path, columns, decimal=None):
    """The one convention every cell read of a file reads under.

    Parameters
    ----------
    path : path
        The file, for messages.
    columns : dict
        Column name -> list of (line number, cell as written).
    decimal : {'.', ','}, optional
        The file's decimal separator when the caller knows it (a key of
        :data:`DECIMALS`): every cell is checked against it instead of
        deciding from the cells.

    Returns
    -------
    str
        A key of :data:`CONVENTIONS`.

    Raises
    ------
    JudderError
        A cell that is no number (naming its line and column), cells that
        read only under different conventions, a cell that reads under
        both while no cell of the file decides, or a cell that does not
        read under the given ``decimal``.
    """
    if decimal is not None:
        return _given(path, columns, decimal)
    only, depending = {}, None
    for name, cells in columns.items():
        allowed, decided, depends = _column_reading(name, cells, path)
        if len(allowed) == 1:
            only.setdefault(next(iter(allowed)), (name, *decided))
        elif depending is None and depends is not None:
            depending = (name, *depends)
    if len(only) == 2:
        (a, (name_a, line_a, cell_a)), (b, (name_b, line_b, cell_b)) = \
            only.items()
        raise JudderError(
            f"{path}: column {name_a!r} has {cell_a!r} (line {line_a}), "
            f"written with {CONVENTIONS[a][0]}, and column {name_b!r} has "
            f"{cell_b!r} (line {line_b}), written with {CONVENTIONS[b][0]}; "
            "allowed: one decimal separator in the whole file")
    if only:
        return next(iter(only))
    if depending is not None:
        name, number, cell = depending
        raise JudderError(
            f"{path}: column {name!r} has {cell!r} (line {number}), "
            f"{value(cell, 'point'):g} with a thousands separator or "
            f"{value(cell, 'comma'):g} with a decimal one, and no cell of "
            "the file tells which; allowed: a file with at least one cell "
            "that only one reading fits (such as 0.5 or 0,5), or its "
            "decimal separator given as `decimal` '.' or ','")
    return "point"


def _given(path, columns, decimal):
    """The convention of a given decimal separator, once every cell reads
    under it (one pass where Python reads the column as it is)."""
    if decimal not in DECIMALS:
        raise JudderError(f"`decimal` {decimal!r}: allowed '.' (a decimal "
                          "point) or ',' (a decimal comma)")
    convention = DECIMALS[decimal]
    for name, cells in columns.items():
        if convention == "point":
            plain = _plain_column(cells)
            if plain is not None and convention in plain[0]:
                continue
        for number, cell in cells:
            found = readings(cell)
            if convention not in found:
                kind = ("is not a number" if not found else
                        f"is not a number written with "
                        f"{CONVENTIONS[convention][0]}")
                raise JudderError(
                    f"{path}, line {number}: column {name!r}: "
                    f"{cell.strip()!r} {kind}, as `decimal` {decimal!r} "
                    "says the file is written; allowed: every cell with "
                    "that decimal separator (or leave `decimal` out to "
                    "decide it from the cells)")
    return convention


def column_values(cells, convention):
    """The numbers of a column's cells under the file's convention."""
    texts = [cell.strip() or "nan" for _, cell in cells]
    if convention == "point" and not any("," in t for t in texts):
        try:
            return np.array(texts, dtype=float)
        except ValueError:      # a thousands space or apostrophe
            pass
    return np.array([value(cell, convention) for _, cell in cells],
                    dtype=float)
