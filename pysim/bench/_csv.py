"""CSV acquisitions, as :func:`pysim.simulation.export.write_csv` writes them and as
DAQ software exports them."""

import codecs
import csv
import json
import re

import numpy as np

from infra.errors import JudderError
from infra.files import decode_text

from ._common import (column_factor, is_time_name, listing, split_header,
                      time_unit)
from ._numbers import column_values, decide, is_number

__all__ = ["read", "declared_separator", "SEPARATORS"]

#: Bytes of a CSV file looked at for NUL bytes before it is read whole.
HEAD_BYTES = 64 * 1024
#: The field separators read.
SEPARATORS = (",", ";", "\t")
#: The line Excel writes first in a CSV export to declare its field
#: separator: ``sep=;`` (quoted by some writers, and padded with the
#: separator to the width of the rows when a spreadsheet saves it again).
_SEPARATOR_LINE = re.compile(r'"?sep=(.)"?(?:\1|[ \r\n])*', re.IGNORECASE)


def read(path, wanted, time=None, decimal=None):
    """CSV as :func:`pysim.simulation.export.write_csv` writes it, and as DAQ software
    exports it: ``,``, ``;`` or tab between fields, a decimal point or
    comma and thousands separators as the file's cells show them, or as
    ``decimal`` (``'.'`` or ``','``) says where given
    (:mod:`pysim.bench._numbers`), a time column of numbers or of
    date-times (s from the first), a header block before the column names
    (``key;value`` lines, kept as metadata), a units row under them."""
    lines = _csv_lines(path)
    metadata = _csv_metadata(lines)
    body = [(number, line) for number, line in enumerate(lines, 1)
            if line.strip() and not line.lstrip().startswith("#")]
    declared = declared_separator(path, *body[0]) if body else None
    body = body[1:] if declared else body
    if not body:
        raise JudderError(f"{path}: no header line (time [s], name [unit], "
                          "...)")
    delimiter = declared or _delimiter(body[len(body) // 2][1])
    rows = list(csv.reader([line for _, line in body], delimiter=delimiter))
    start = _csv_header_row(path, rows, body, time)
    metadata.update({row[0].strip(): row[1].strip() for row in rows[:start]
                     if len(row) == 2 and row[0].strip()})
    body, rows = body[start:], rows[start:]
    header = [split_header(cell) for cell in rows[0]]
    if len(rows) > 1 and _is_units_row(rows[1], len(header)):
        header = [(name, unit if unit is not None else
                   (rows[1][i].strip().strip("[]").strip() or None))
                  for i, (name, unit) in enumerate(header)]
        body, rows = [body[0]] + body[2:], [rows[0]] + rows[2:]
    names = [name for name, _ in header]
    time_column = _csv_time_column(path, names, time)
    _check_row_lengths(path, body, rows, len(header))
    columns = [time_column] + [names.index(name) for name in wanted
                               if name in names
                               and names.index(name) != time_column]
    cells = {c: [(number, row[c]) for (number, _), row in
                 zip(body[1:], rows[1:])] for c in columns}
    stamps = _date_times(path, cells[time_column])
    if stamps is not None:
        del cells[time_column]
    convention = decide(path, {names[c]: cells[c] for c in cells}, decimal)
    if stamps is None:
        name, unit = header[time_column]
        stamps = column_values(cells[time_column], convention) * \
            column_factor(path, (name, time_unit(time, unit)), "time")
    raws = {names[c]: (stamps, column_values(cells[c], convention),
                       header[c][1]) for c in columns[1:]}
    return [n for i, n in enumerate(names) if i != time_column], metadata, \
        raws


def _check_one_separator(path, body):
    """Refuse a file whose lines are split by different separators (where
    no line naming a time column was found)."""
    first = {}
    for number, line in body:
        first.setdefault(_delimiter(line), number)
    if len(first) > 1:
        (a, m), (b, n) = sorted(first.items(), key=lambda item: item[1])[:2]
        raise JudderError(
            f"{path}: mixed field separators: line {m} is separated by "
            f"{a!r}, line {n} by {b!r}; allowed: one separator throughout "
            "(',', ';' or tab)")


def _csv_header_row(path, rows, body, time):
    """Index of the row that names the columns: the first with a time
    column and as many fields as the data rows (a DAQ's header block,
    ``Time;14:03:22`` among its lines, may come before it)."""
    widths = [len(row) for row in rows]
    data_width = max(set(widths), key=widths.count)
    for index, row in enumerate(rows):
        if len(row) == data_width and any(is_time_name(cell, time)
                                          for cell in row):
            return index
    _check_one_separator(path, body)
    # the names line: the first as wide as the data with a cell that is
    # no number (a header block's key;value lines come before it)
    named = next((index for index, row in enumerate(rows)
                  if len(row) == data_width and not all(
                      is_number(cell) for cell in row if cell.strip())), 0)
    names = [split_header(cell)[0] for cell in rows[named]]
    raise JudderError(f"{path}: no time column"
                      + (f" {time.name!r}" if time else "")
                      + "; the line naming the columns must name one "
                      + ("" if time else "'time [s]' (or 'time' with a "
                         "units row under it), or give its name with "
                         "`channels` time=NAME[:UNIT]")
                      + f"; columns of line {body[named][0]}: "
                      f"{listing(names)}")


def _is_units_row(row, width):
    """A row under the names that holds units, not numbers: a row with a
    cell that reads as a number under either decimal separator
    (:func:`pysim.bench._numbers.is_number`: ``1 000``, ``1.000,5``,
    ``1'000.5`` too) is data."""
    cells = [cell.strip() for cell in row]
    if len(cells) != width or not any(cells):
        return False
    return not any(is_number(cell) for cell in cells)


#: Byte-order marks of UTF-16, as Excel's "Unicode text" and some DAQ
#: software write it (every other byte of ASCII text NUL).
_UTF16_BOMS = (codecs.BOM_UTF16_LE, codecs.BOM_UTF16_BE)


def _csv_lines(path):
    """The lines of a CSV file: UTF-8 (with or without BOM), UTF-16 with
    its BOM (Excel's "Unicode text"), else Windows-1252, the encoding
    European DAQ software writes (``°C``, ``µs``)."""
    with open(path, "rb") as stream:
        head = stream.read(HEAD_BYTES)
        if b"\0" in head and not head.startswith(_UTF16_BOMS):
            # a binary file is refused from its first block (with the
            # words the whole would get), before it is read whole
            _decoded(head, path)
        data = head + stream.read()
    return _decoded(data, path).splitlines()


def _decoded(data, path):
    """The text of a CSV file's bytes: UTF-16 where it starts with its
    BOM, else UTF-8, else Windows-1252 without NUL bytes, else the UTF-8
    reader's error."""
    if data.startswith(_UTF16_BOMS):
        try:
            text = data.decode("utf-16")
        except UnicodeDecodeError as exc:
            raise JudderError(
                f"{path}: not UTF-8 text, and not the UTF-16 text its "
                f"byte-order mark announces (offset {exc.start}); save the "
                "CSV as UTF-8 (or UTF-16 with its byte-order mark)") from None
        if "\0" not in text:
            return text
    try:
        return decode_text(data, str(path), "CSV")
    except JudderError:
        try:
            text = data.decode("cp1252")
        except UnicodeDecodeError:
            text = None
        if text is None or "\0" in text:
            if _utf16_without_bom(data):
                raise JudderError(
                    f"{path}: UTF-16 text without its byte-order mark (every "
                    "other byte NUL), which cannot be told from binary; save "
                    "the CSV as UTF-8, or as UTF-16 with its byte-order mark "
                    "(Excel's \"Unicode text\")") from None
            raise
        return text


def _utf16_without_bom(data):
    """Whether bytes look like ASCII text in UTF-16 without a BOM: of the
    first 1024 byte pairs, nearly all have one NUL byte, always on the
    same side."""
    head = np.frombuffer(data[:2048][:len(data[:2048]) // 2 * 2],
                         dtype=np.uint8).reshape(-1, 2)
    if len(head) < 4:
        return False
    return any(np.mean((head[:, side] == 0) & (head[:, 1 - side] != 0))
               > 0.95 for side in (0, 1))


def _csv_metadata(lines):
    """``# key: json-value`` lines; a value that is not JSON stays text."""
    metadata = {}
    for line in lines:
        stripped = line.strip()
        if not stripped.startswith("#") or ":" not in stripped:
            continue
        key, _, value = stripped[1:].partition(":")
        try:
            metadata[key.strip()] = json.loads(value)
        except ValueError:
            metadata[key.strip()] = value.strip()
    return metadata


def declared_separator(path, number, line):
    """The field separator a line declares as Excel writes it first in a
    CSV export (``sep=;``), or None for any other line.

    Raises
    ------
    JudderError
        A declared separator other than those of :data:`SEPARATORS`,
        naming the file and the line.

    Examples
    --------
    >>> declared_separator("a.csv", 1, "sep=;"), declared_separator(
    ...     "a.csv", 1, '"sep=;";;'), declared_separator(
    ...     "a.csv", 1, "freq_hz;p_f_bar")
    (';', ';', None)
    """
    match = _SEPARATOR_LINE.fullmatch(line.lstrip(" "))
    if match is None:
        return None
    if match.group(1) not in SEPARATORS:
        raise JudderError(f"{path}, line {number}: {line.strip()!r} "
                          f"declares the field separator {match.group(1)!r}; "
                          "allowed: ',', ';' or tab")
    return match.group(1)


def _delimiter(line):
    """The field separator of a line of data: ``;`` or tab where there is
    one (a ``,`` there is a decimal comma), else ``,``."""
    return next((d for d in (";", "\t") if d in line), ",")


def _csv_time_column(path, names, time):
    for index, name in enumerate(names):
        if is_time_name(name, time):
            return index
    raise JudderError(f"{path}: no time column; the first line of data "
                      f"must name one 'time [s]' (columns: "
                      f"{listing(names)})")


def _check_row_lengths(path, body, rows, width):
    for (number, _), row in zip(body[1:], rows[1:]):
        if len(row) != width:
            raise JudderError(f"{path}, line {number}: {len(row)} fields, "
                              f"the header has {width}")


#: A date-time cell: an ISO date (``2026-12-03T07:41:22.5``), a German
#: one (``03.12.2026 07:41:22,5``) or a time of day (``07:41:22.5``).
_DATE_TIME = re.compile(
    r"(?:(?P<y>\d{4})-(?P<m>\d{2})-(?P<d>\d{2})[T ]"
    r"|(?P<d2>\d{1,2})\.(?P<m2>\d{1,2})\.(?P<y2>\d{4}) )?"
    r"(?P<H>\d{1,2}):(?P<M>\d{2}):(?P<S>\d{2})(?:[.,](?P<f>\d{1,9}))?Z?")


def _date_times(path, cells):
    """A time column of date-times as s from its first cell, or None if
    its first cell is not one (a column of numbers)."""
    stamps = []
    for number, cell in cells:
        match = _DATE_TIME.fullmatch(cell.strip())
        if match is None:
            if not stamps:
                return None
            raise JudderError(f"{path}, line {number}: time "
                              f"{cell.strip()!r} is "
                              "not a date-time as the lines before it")
        g = match.groupdict()
        year, month, day = ((g["y"], g["m"], g["d"]) if g["y"] else
                            (g["y2"], g["m2"], g["d2"]) if g["y2"] else
                            ("1970", "1", "1"))
        stamps.append(np.datetime64(
            f"{year}-{int(month):02d}-{int(day):02d}T{int(g['H']):02d}:"
            f"{g['M']}:{g['S']}.{(g['f'] or '0'):0<9}", "ns"))
    stamps = np.array(stamps)
    return (stamps - stamps[0]) / np.timedelta64(1, "s")
