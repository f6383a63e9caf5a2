"""CSV acquisitions, as :func:`pysim.simulation.export.write_csv` writes them and as
DAQ software exports them."""

import csv
import json

import numpy as np

from infra.errors import JudderError
from infra.files import decode_text

from ._common import TIME_NAMES, column_factor, listing, split_header

__all__ = ["read"]

#: Bytes of a CSV file looked at for NUL bytes before it is read whole.
HEAD_BYTES = 64 * 1024


def read(path, wanted):
    """CSV as :func:`pysim.simulation.export.write_csv` writes it, and as DAQ software
    exports it: ``,``, ``;`` or tab between fields, a decimal comma with
    ``;`` or tab, a header block before the column names (``key;value``
    lines, kept as metadata), a units row under them."""
    lines = _csv_lines(path)
    metadata = _csv_metadata(lines)
    body = [(number, line) for number, line in enumerate(lines, 1)
            if line.strip() and not line.lstrip().startswith("#")]
    if not body:
        raise JudderError(f"{path}: no header line (time [s], name [unit], "
                          "...)")
    delimiter = _delimiter(body[len(body) // 2][1])
    rows = list(csv.reader([line for _, line in body], delimiter=delimiter))
    start = _csv_header_row(path, rows, body)
    metadata.update({row[0].strip(): row[1].strip() for row in rows[:start]
                     if len(row) == 2 and row[0].strip()})
    body, rows = body[start:], rows[start:]
    header = [split_header(cell) for cell in rows[0]]
    if len(rows) > 1 and _is_units_row(rows[1], len(header)):
        header = [(name, unit if unit is not None else
                   (rows[1][i].strip().strip("[]").strip() or None))
                  for i, (name, unit) in enumerate(header)]
        body, rows = [body[0]] + body[2:], [rows[0]] + rows[2:]
    if delimiter != ",":
        rows = [rows[0]] + [[cell.replace(",", ".") for cell in row]
                            for row in rows[1:]]
    names = [name for name, _ in header]
    time_column = _csv_time_column(path, names)
    _check_row_lengths(path, body, rows, len(header))
    time = _csv_column(path, body, rows, time_column) * column_factor(
        path, header[time_column], "time")
    raws = {}
    for name in wanted:
        if name in names and names.index(name) != time_column:
            column = names.index(name)
            raws[name] = (time, _csv_column(path, body, rows, column),
                          header[column][1])
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


def _csv_header_row(path, rows, body):
    """Index of the row that names the columns: the first with a time
    column and as many fields as the data rows (a DAQ's header block,
    ``Time;14:03:22`` among its lines, may come before it)."""
    widths = [len(row) for row in rows]
    data_width = max(set(widths), key=widths.count)
    for index, row in enumerate(rows):
        if len(row) == data_width and any(
                split_header(cell)[0].lower() in TIME_NAMES
                for cell in row):
            return index
    _check_one_separator(path, body)
    names = [split_header(cell)[0] for cell in rows[0]]
    raise JudderError(f"{path}: no time column; the line naming the "
                      "columns must name one 'time [s]' (or 'time' with a "
                      f"units row under it); columns of line {body[0][0]}: "
                      f"{listing(names)}")


def _is_units_row(row, width):
    """A row under the names that holds units, not numbers."""
    cells = [cell.strip() for cell in row]
    if len(cells) != width or not any(cells):
        return False
    for cell in cells:
        try:
            float(cell.replace(",", "."))
            return False
        except ValueError:
            pass
    return True


def _csv_lines(path):
    """The lines of a CSV file: UTF-8 (with or without BOM), else
    Windows-1252, the encoding European DAQ software writes (``°C``,
    ``µs``)."""
    with open(path, "rb") as stream:
        head = stream.read(HEAD_BYTES)
        if b"\0" in head:
            # a binary file is refused from its first block (with the
            # words the whole would get), before it is read whole
            _decoded(head, path)
        data = head + stream.read()
    return _decoded(data, path).splitlines()


def _decoded(data, path):
    """The text of a CSV file's bytes: UTF-8, else Windows-1252 without
    NUL bytes, else the UTF-8 reader's error."""
    try:
        return decode_text(data, str(path), "CSV")
    except JudderError:
        try:
            text = data.decode("cp1252")
        except UnicodeDecodeError:
            text = None
        if text is None or "\0" in text:
            raise
        return text


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


def _delimiter(line):
    """The field separator of a line of data: ``;`` or tab where there is
    one (a ``,`` there is a decimal comma), else ``,``."""
    return next((d for d in (";", "\t") if d in line), ",")


def _csv_time_column(path, names):
    for index, name in enumerate(names):
        if name.lower() in TIME_NAMES:
            return index
    raise JudderError(f"{path}: no time column; the first line of data "
                      f"must name one 'time [s]' (columns: "
                      f"{listing(names)})")


def _check_row_lengths(path, body, rows, width):
    for (number, _), row in zip(body[1:], rows[1:]):
        if len(row) != width:
            raise JudderError(f"{path}, line {number}: {len(row)} fields, "
                              f"the header has {width}")


def _csv_column(path, body, rows, column):
    cells = [row[column].strip() or "nan" for row in rows[1:]]
    try:
        return np.array(cells, dtype=float)
    except ValueError:
        for (number, _), cell in zip(body[1:], cells):
            try:
                float(cell)
            except ValueError:
                raise JudderError(f"{path}, line {number}: {cell!r} is not "
                                  "a number") from None
        raise
