"""The small CSV tables a test engineer hands the tool beside the
acquisitions (an index of runs and their settings, a measured boundary),
read as the acquisitions' CSVs are: the fields split by the file's
separator (the one a first line ``sep=;`` declares, as Excel writes it,
else ``;`` or tab where the first line has one, else ``,``), and
the numbers read as written, their decimal and thousands separators
decided once per file from every cell read, or given (``decimal``), by
:mod:`pysim.bench._numbers`.

Examples
--------
>>> rows = split_rows([(1, "freq_hz;p_f_bar"), (2, "105;0,3")], "b.csv")
>>> rows
[(1, ['freq_hz', 'p_f_bar']), (2, ['105', '0,3'])]
>>> split_rows([(1, "sep=;"), (2, "freq_hz;p_f_bar")], "b.csv")
[(2, ['freq_hz', 'p_f_bar'])]
>>> numbers("b.csv", {"p_f_bar": [(2, "0,3")]})["p_f_bar"].tolist()
[0.3]
"""

import csv

from ._csv import _delimiter, declared_separator
from ._numbers import column_values, decide, is_number

__all__ = ["split_rows", "numbers", "is_number"]


def split_rows(lines, source):
    """The cells of each line, split by the separator a first line
    ``sep=;`` declares (Excel writes it; the line is not a row), else by
    the separator of the first.

    Parameters
    ----------
    lines : list of (int, str)
        Line number and text of the lines to read (without empty or
        comment lines), the first naming the columns where there is such a
        line.
    source : str
        The file as messages name it.

    Returns
    -------
    list of (int, list of str)
        Line number (the first, for a quoted cell over several lines) and
        cells (stripped), quotes read as CSV has them.
    """
    declared = declared_separator(source, *lines[0]) if lines else None
    lines = lines[1:] if declared else lines
    if not lines:
        return []
    reader = csv.reader((text + "\n" for _, text in lines),
                        delimiter=declared or _delimiter(lines[0][1]))
    rows, consumed = [], 0
    for cells in reader:
        rows.append((lines[consumed][0], [cell.strip() for cell in cells]))
        consumed = reader.line_num
    return rows


def numbers(source, columns, decimal=None):
    """The numbers of a file's columns, read as the file writes them.

    Parameters
    ----------
    source : str
        The file as messages name it.
    columns : dict
        Column name -> list of (line number, cell as written).
    decimal : {'.', ','}, optional
        The file's decimal separator, where the caller knows it
        (:func:`pysim.bench._numbers.decide`).

    Returns
    -------
    dict
        Column name -> ndarray (NaN for an empty cell).

    Raises
    ------
    JudderError
        A cell that is no number, cells written with different decimal
        separators, a cell that reads both ways while no cell decides, or
        a cell not written with ``decimal``: naming the file, the column,
        the line and the cell as written.
    """
    convention = decide(source, columns, decimal)
    return {name: column_values(cells, convention)
            for name, cells in columns.items()}
