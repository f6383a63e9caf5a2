"""Reading what the user gives: parameter sets and measured boundaries.

Every reader names the file (or option) in its errors, so a command can
pass the message on as it is.
"""

import math
from pathlib import Path
import re
import stat
import zipfile

import numpy as np

from drivelines import DEFAULT_MODEL
from sources import default_preset, get_preset, load_toml
from infra.errors import JudderError
from infra.files import decode_text
from infra.units import PA_PER_BAR

__all__ = ["read_input", "check_input", "read_period", "load_parameters", "read_boundary_csv",
           "read_boundary_table", "read_boundary", "read_boundary_tested",
           "boundary_p_max", "read_boundary_min_growth",
           "read_boundary_limit", "read_chart_boundary", "read_chart_below",
           "read_chart_onset_kinds",
           "read_chart_min_growth", "read_chart_limit", "read_chart_runs",
           "empty_cell", "read_friction_table", "friction_of"]

#: Largest parameter or boundary file read, bytes.
MAX_INPUT_BYTES = 64 * 2**20


#: The arguments that name a small text file of the user's (a parameter
#: set, a boundary, a table, ranges, a measured period): each is a
#: regular file of at most :data:`MAX_INPUT_BYTES`, checked by its size
#: and type (:func:`check_input`) before anything reads or hashes it.
TEXT_INPUTS = ("param_file", "boundary", "table", "ranges", "also",
               "files", "friction")


def check_input(path, option):
    """Refuse, from its size and type alone, a path that is no regular
    file of at most :data:`MAX_INPUT_BYTES` (a folder, a device, a file
    of 16 GB), naming ``option``; nothing of it is read."""
    try:
        info = Path(path).stat()
    except OSError as exc:
        raise JudderError(f"{option} {path}: cannot read it "
                          f"({exc.strerror})") from None
    if not stat.S_ISREG(info.st_mode) or info.st_size > MAX_INPUT_BYTES:
        what = ("a folder" if stat.S_ISDIR(info.st_mode) else
                f"{info.st_size / 2**20:.0f} MiB"
                if stat.S_ISREG(info.st_mode) else "not a regular file")
        raise JudderError(f"{option} {path} is {what}; allowed: a regular "
                          f"file of at most {MAX_INPUT_BYTES // 2**20} MiB")


def read_input(path, option):
    """Text of a file the user named, or JudderError naming ``option``
    (:func:`check_input` first)."""
    check_input(path, option)
    try:
        data = Path(path).read_bytes()
    except OSError as exc:
        raise JudderError(f"{option} {path}: cannot read it "
                          f"({exc.strerror})") from None
    return decode_text(data, f"{option} {path}")


def read_period(path, option="`period`", decimal=None):
    """One measured period of pressure: the last column of each row,
    equally spaced (``--dither-wave period:FILE.csv``).

    Read as the project's other small tables are
    (:mod:`pysim.bench.tables`): ``#`` starts a comment, the fields
    split by the separator a first line ``sep=;`` declares, else ``;`` or
    tab where the first line has one, else ``,``; the numbers read as
    written, the decimal separator decided from every cell or given as
    ``decimal``. A first row whose last cell is no number names the
    columns. Every row has the first row's number of cells, and a
    ``,``-separated file cannot hold decimal commas (``1,49759`` would be
    two cells): both refused, naming the line.

    Returns
    -------
    ndarray, shape (N,)
        The samples as written (any unit).

    Examples
    --------
    >>> import os, tempfile
    >>> path = os.path.join(tempfile.mkdtemp(), "p.csv")
    >>> rows = ["t_s;p_bar", "0;1,5", "0,0025;1", "0,005;0,5", "0,0075;1"]
    >>> with open(path, "w") as f:
    ...     _ = f.write(chr(10).join(rows))
    >>> read_period(path).tolist()
    [1.5, 1.0, 0.5, 1.0]
    """
    from pysim.bench.tables import is_number, numbers, split_rows
    source = f"{option}{path}" if option.endswith(":") else \
        f"{option} {path}"
    lines = [(number, line.split("#")[0]) for number, line in
             enumerate(read_input(path, option).splitlines(), start=1)]
    lines = [(number, line) for number, line in lines if line.strip()]
    rows = split_rows(lines, source)
    if rows and not is_number(rows[0][1][-1]):
        width, rows = len(rows[0][1]), rows[1:]
    else:
        width = len(rows[0][1]) if rows else 0
    written = dict(lines)
    for number, cells in rows:
        if len(cells) != width:
            raise JudderError(f"{source}, line {number}: "
                              f"{written[number].strip()!r} has "
                              f"{len(cells)} cells; allowed: {width}, as "
                              "the first line (with decimal commas, "
                              "fields separated by ';' or tab)")
    comma_separated = bool(rows) and all(
        "," not in cell for _, cells in rows for cell in cells) and any(
        "," in written[number] for number, _ in rows)
    if comma_separated and decimal == ",":
        raise JudderError(f"{source}: its fields are separated by ',', so "
                          "it cannot hold decimal commas; allowed: `decimal` "
                          "'.', or fields separated by ';' or tab")
    values = numbers(source, {"pressure": [(number, cells[-1])
                                           for number, cells in rows]},
                     decimal)["pressure"]
    bad = [i for i, v in enumerate(values) if not math.isfinite(v)]
    if bad:
        raise JudderError(f"{source}: sample {bad[0] + 1} of {len(values)} "
                          f"is {rows[bad[0]][1][-1]} (line "
                          f"{rows[bad[0]][0]}); allowed: finite pressures, "
                          "at least 4")
    return np.asarray(values, dtype=float)


#: A friction table's slip column: ``slip_rpm``, ``slip [rad/s]``, ...
_SLIP_HEADER = re.compile(r"\s*(?:slip|w|omega)[\s_\[\(]*(rpm|rad/s|rad_s)"
                          r"[\]\)]?\s*", re.I)
#: A friction coefficient column: ``mu``, or ``mu_40C``, ``mu at 40 C``,
#: ``mu@40degC`` at one oil temperature.
_MU_HEADER = re.compile(r"\s*mu(?:[\s_@]*(?:at)?[\s_]*(-?\d+(?:[.,]\d+)?)"
                        r"\s*(?:°\s*C|degC|C))?\s*", re.I)


def read_friction_table(path, option="`friction`", decimal=None):
    """A clutch's friction characteristic from a friction rig's CSV
    (``--friction FILE.csv``).

    The first row names the columns: the absolute slip speed
    (``slip_rpm`` or ``slip_rad_s``, also written ``slip [rpm]``), then
    either one friction coefficient column ``mu`` or one per oil
    temperature (``mu_40C``, ``mu at 80 C``), in increasing temperature.
    The rest is read as the project's small tables are
    (:func:`read_period`: ``#`` comments, ``sep=;``, ``;`` or tab, the
    decimal separator from every cell or ``decimal``).

    Returns
    -------
    drivelines.friction.FrictionTable
        The slip in rad/s; with several temperatures, ``family`` holds
        them and ``mu`` is the first's (choose one with
        :meth:`~drivelines.friction.FrictionTable.at_oil_temperature`).

    Examples
    --------
    >>> import os, tempfile
    >>> path = os.path.join(tempfile.mkdtemp(), "mu.csv")
    >>> with open(path, "w") as f:
    ...     _ = f.write("slip_rpm;mu_40C;mu_80C" + chr(10) + "0;0,12;0,10"
    ...                 + chr(10) + "1000;0,13;0,12" + chr(10))
    >>> table = read_friction_table(path).at_oil_temperature(60)
    >>> [round(w, 3) for w in table.slip], [round(m, 3) for m in table.mu]
    ([0.0, 104.72], [0.11, 0.125])
    """
    from drivelines.friction import FrictionTable
    from infra.units import RAD_S_PER_RPM
    from pysim.bench.tables import numbers, split_rows
    source = f"{option} {path}"
    lines = [(number, line.split("#")[0]) for number, line in
             enumerate(read_input(path, option).splitlines(), start=1)]
    rows = split_rows([(n, line) for n, line in lines if line.strip()],
                      source)
    if len(rows) < 3:
        raise JudderError(f"{source}: {max(len(rows) - 1, 0)} rows of "
                          "numbers; allowed: a row naming the columns "
                          "(slip_rpm or slip_rad_s, then mu or mu_<T>C per "
                          "oil temperature) and at least 2 rows")
    (header_line, header), body = rows[0], rows[1:]
    slip_unit = _SLIP_HEADER.fullmatch(header[0])
    temperatures = [_MU_HEADER.fullmatch(cell) for cell in header[1:]]
    if slip_unit is None or not temperatures or None in temperatures or (
            len(temperatures) > 1 and any(t.group(1) is None
                                          for t in temperatures)):
        raise JudderError(f"{source}, line {header_line}: columns "
                          f"{', '.join(map(repr, header))} are not allowed; "
                          "allowed: slip_rpm or slip_rad_s, then mu, or "
                          "mu_<T>C for each oil temperature T (e.g. "
                          "slip_rpm,mu_40C,mu_80C)")
    for number, cells in body:
        if len(cells) != len(header):
            raise JudderError(f"{source}, line {number}: {len(cells)} cells; "
                              f"allowed: {len(header)}, as the names row")
    columns = numbers(source, {name: [(number, cells[i])
                                      for number, cells in body]
                               for i, name in enumerate(header)}, decimal)
    slip = columns[header[0]] * (RAD_S_PER_RPM if slip_unit.group(1).lower()
                                 == "rpm" else 1.0)
    mus = [tuple(columns[name]) for name in header[1:]]
    family = () if len(mus) == 1 else tuple(
        (float(t.group(1).replace(",", ".")), mu)
        for t, mu in zip(temperatures, mus))
    return FrictionTable(tuple(slip), mus[0], str(path),
                         family[0][0] if family else None, family)


def friction_of(values, friction, oil_temperature_c=None, decimal=None):
    """``values`` with the clutch's friction characteristic ``friction``:
    a built-in name (:data:`drivelines.friction.BUILT_INS`; ``bounded``,
    the default, leaves ``values`` as they are) or a friction table file
    (:func:`read_friction_table`), at the oil temperature
    ``oil_temperature_c`` (C) where the table has several. The chain's
    ``mu0`` and ``mu_g`` become the characteristic's value and slope at
    the bench's slip (:func:`stability.bench.operating_slip`)."""
    from drivelines.friction import BUILT_INS, straight_line
    from stability.bench import operating_slip
    if friction is None or friction == "bounded":
        if oil_temperature_c is not None:
            raise JudderError("`oil_temperature_c` is for a friction table "
                              "with a column per oil temperature; allowed: "
                              "with `friction` FILE.csv")
        return values
    if not values.source_kind.is_chain:
        raise JudderError(f"`friction` {friction} is not allowed with the "
                          f"class {values.model}; allowed: a preset or its "
                          "parameter file (a class of your own takes its "
                          "characteristic in Modelica, e.g. "
                          "Judder.Components.TableWetClutch)")
    slip = operating_slip(values)
    if friction == "straight":
        table = straight_line(values["mu0"], values["mu_g"], slip)
    elif friction in BUILT_INS:
        raise JudderError(f"`friction` {friction!r} is not allowed; "
                          f"allowed: {', '.join(BUILT_INS)} or FILE.csv")
    else:
        table = read_friction_table(friction, "`friction`", decimal)
    if oil_temperature_c is not None:
        table = table.at_oil_temperature(oil_temperature_c)
    elif table.family:
        from pysim.simulation.campaigns import REFERENCE_TEMPERATURE_C
        measured = [t for t, _ in table.family]
        if not measured[0] <= REFERENCE_TEMPERATURE_C <= measured[-1]:
            raise JudderError(
                f"`friction` {friction} has a column per oil temperature "
                f"({', '.join(f'{t:g}' for t in measured)} C) and no "
                "`oil_temperature_c` was given; allowed: an "
                f"`oil_temperature_c` from {measured[0]:g} to "
                f"{measured[-1]:g} C")
        table = table.at_oil_temperature(REFERENCE_TEMPERATURE_C)
    return values.with_friction(table, slip)


def load_parameters(preset=None, model=None, param_file=None):
    """The parameter set named by a preset, a model or a TOML file.

    Parameters
    ----------
    preset : str, optional
        A preset name (:data:`drivelines.PRESETS`).
    model : str, optional
        A driveline (:data:`drivelines.MODELS`); alone, its paper preset.
        With ``preset`` or ``param_file``, it must match their model.
    param_file : path, optional
        A TOML file as written by ``judder params --save``.

    Returns
    -------
    drivelines.Parameters
        With nothing given, the paper preset of the default driveline.
    """
    if param_file is not None:
        if preset is not None:
            raise JudderError("give either `param_file` or `preset`, not "
                              "both")
        params = load_toml(read_input(param_file, "`param_file`"),
                           source=str(param_file))
    else:
        params = get_preset(preset or default_preset(model or DEFAULT_MODEL))
    if model is not None and model != params.model:
        raise JudderError(f"`model` {model} does not match the "
                          f"{params.model} parameter set given")
    return params


#: Columns of a boundary CSV besides freq_hz and p_f_bar that are
#: ignored: those ``judder tongues --out`` adds.
BOUNDARY_EXTRA_COLUMNS = ("single_period_bar", "double_period_bar",
                          "combination_bar")


#: Columns of a boundary CSV that give the range tested at each frequency
#: (``judder chart --boundary`` writes them), bar, empty where unknown:
#: the highest amplitude tried without judder (below the onset) and the
#: largest amplitude tried. A point without judder is censored at its
#: ``tried_bar``.
BOUNDARY_TESTED_COLUMNS = ("no_judder_bar", "tried_bar")
#: Numbers a boundary file states in comments, ``# NAME: VALUE``
#: (``judder chart --boundary`` writes them): the growth rate (1/s) and
#: the NVH limit (rpm) its onsets were called judder from.
BOUNDARY_STATED = ("min_growth_per_s", "judder_limit_rpm")
_STATED = re.compile(rf"#\s*({'|'.join(BOUNDARY_STATED)})\s*[:=]\s*"
                     r"([^\s#]+)")


def read_boundary_csv(text, source="boundary file", decimal=None):
    """Parse a measured boundary: columns ``freq_hz,p_f_bar``.

    ``#`` starts a comment. A header line names the columns (in any
    order); without one the columns are ``freq_hz,p_f_bar``. The columns
    of :data:`BOUNDARY_TESTED_COLUMNS` may follow (see
    :func:`read_boundary_table`); the further columns of ``judder tongues
    --out`` are ignored (so its CSV can be read back); any other column is
    refused. An empty ``p_f_bar`` means no judder up to the largest
    amplitude tried. Fields and numbers (and ``decimal``) are read as
    :func:`read_boundary_table` reads them.

    Returns
    -------
    freq_hz, p_f : ndarray
        Hz and Pa (NaN for censored points).

    Examples
    --------
    >>> f, p = read_boundary_csv("freq_hz,p_f_bar\\n100,0.3\\n60,\\n")
    >>> f.tolist(), p.tolist()
    ([100.0, 60.0], [30000.0, nan])
    >>> f, p = read_boundary_csv("p_f_bar,freq_hz\\n0.3,100\\n")
    >>> f.tolist(), p.tolist()
    ([100.0], [30000.0])
    """
    table = read_boundary_table(text, source, decimal)
    return table["freq_hz"], table["p_f"]


def read_boundary_table(text, source="boundary file", decimal=None):
    """Parse a measured boundary with the range tested at each frequency.

    The format of :func:`read_boundary_csv`, with the optional columns
    ``no_judder_bar`` (the highest amplitude tried without judder, below
    the onset where there is one) and ``tried_bar`` (the largest amplitude
    tried), bar, empty where unknown. Fields are separated by ``,``, or
    by ``;`` or tab where the first line has one; numbers are read as
    written, as a bench export's are
    (:func:`pysim.bench.tables.numbers`): the decimal and thousands
    separators decided from every cell read (``0,3`` in a
    ``;``-separated file is 0.3), or given as ``decimal`` (``'.'`` or
    ``','``), and a file no cell decides is refused naming a cell.

    The numbers of :data:`BOUNDARY_STATED` comments are read with the
    cells: ``# min_growth_per_s: 0,5`` in a file of decimal commas is 0.5.
    A stated number that the file's separators read with a thousands
    separator and the other decimal separator reads too (``1.000`` in a
    file of decimal commas: 1000 or 1) is refused, naming its line and
    the number as written: a threshold is one number a program wrote,
    often with a decimal point into a file whose cells a spreadsheet
    wrote with decimal commas, and a factor 1000 in it is no guess to
    make silently.

    Returns
    -------
    dict
        ``freq_hz`` (Hz), ``p_f``, ``no_judder``, ``tried`` (Pa, NaN where
        empty or the column is absent), ``columns`` (the header's
        names), ``lines`` (the line number of each row) and ``stated``
        (name -> (line number, value as written, value) of the
        :data:`BOUNDARY_STATED` comments, the first of each name).

    Examples
    --------
    >>> t = read_boundary_table("freq_hz,p_f_bar,no_judder_bar,tried_bar\\n"
    ...                         "100,0.3,0.2,0.6\\n60,,0.6,0.6\\n")
    >>> (t["no_judder"] / 1e5).tolist(), (t["tried"] / 1e5).tolist()
    ([0.2, 0.6], [0.6, 0.6])
    >>> t = read_boundary_table("freq_hz;p_f_bar;no_judder_bar;tried_bar\\n"
    ...                         "105;0,3;0,2;0,6\\n")
    >>> (t["p_f"] / 1e5).tolist()
    [0.3]
    """
    from pysim.bench.tables import numbers, split_rows
    names = ("freq_hz", "p_f_bar") + BOUNDARY_TESTED_COLUMNS
    stated, said = {}, {}
    for number, line in enumerate(text.splitlines(), start=1):
        match = _STATED.match(line.strip())
        if match:
            stated.setdefault(match.group(1), (number, match.group(2)))
            said.setdefault(match.group(1), []).append(
                (number, match.group(2)))
    # not stripped: Excel's "sep=" line may declare a tab
    lines = [(number, line.split("#")[0])
             for number, line in enumerate(text.splitlines(), start=1)]
    lines = [(number, line) for number, line in lines if line.strip()]
    rows = split_rows(lines, source)
    written = {number: line.strip() for number, line in lines}
    columns = None if not rows else _boundary_columns(
        rows[0][1], source, rows[0][0], written[rows[0][0]])
    if columns is None:
        columns = {"freq_hz": 0, "p_f_bar": 1, "width": 2}
    else:
        rows = rows[1:]
    if not rows:
        raise JudderError(f"{source}: no data lines; allowed: a header "
                          "freq_hz,p_f_bar[,no_judder_bar,tried_bar] and "
                          "one line per frequency tested")
    for number, cells in rows:
        if len(cells) != columns["width"]:
            raise JudderError(f"{source}, line {number}: "
                              f"{written[number]!r} has {len(cells)} cells; "
                              f"allowed: {columns['width']}, as the header "
                              "(freq_hz,p_f_bar; p_f_bar empty for no "
                              "judder)")
    read = [name for name in names if name in columns]
    values = numbers(source, {**{name: [(number, cells[columns[name]])
                                        for number, cells in rows]
                                 for name in read},
                              **{name: cells for name, cells in
                                 said.items()}}, decimal)
    for name, cells in said.items():
        # each threshold once: a NaN is no threshold, and two lines that
        # differ leave the file's own verdict unknown
        for (number, text), read in zip(cells, values[name]):
            if not math.isfinite(float(read)):
                raise JudderError(f"{source}, line {number}: {name} "
                                  f"{text!r} is not allowed; allowed: a "
                                  "finite number")
            _check_stated(source, number, name, text, float(read))
        differ = [(number, text) for (number, text), read in
                  zip(cells, values[name])
                  if float(read) != float(values[name][0])]
        if differ:
            raise JudderError(
                f"{source}: {name} is {cells[0][1]} on line {cells[0][0]} "
                f"and {differ[0][1]} on line {differ[0][0]}; allowed: one "
                f"{name} comment (or the same number on each)")
    table = {name: [] for name in names}
    for index, (number, cells) in enumerate(rows):
        line = written[number]
        texts = {name: cells[columns[name]] if name in columns else ""
                 for name in names}
        freq = float(values["freq_hz"][index])
        amps = {name: float(values[name][index]) * PA_PER_BAR
                if texts[name] else np.nan for name in names[1:]}
        if not texts["freq_hz"]:
            raise empty_cell(source, number, "freq_hz", "a frequency > 0 Hz")
        gaps = [name for name in amps if texts[name] and np.isnan(amps[name])]
        if gaps:
            # censored is written as an empty cell; a NaN is a gap in the
            # data, not "no judder up to the largest amplitude"
            raise JudderError(f"{source}, line {number}: {gaps[0]} is "
                              f"{texts[gaps[0]]!r}; allowed: a number >= 0 "
                              "bar, or empty for no judder up to the largest "
                              "amplitude tried")
        if not np.isfinite(freq) or freq <= 0 or any(
                a < 0 or a == np.inf for a in amps.values()):
            raise JudderError(f"{source}, line {number}: {line!r}: allowed: "
                              "frequency > 0 Hz and amplitude >= 0 bar, "
                              "finite")
        _check_tested(amps, source, number, line)
        table["freq_hz"].append(freq)
        for name, value in amps.items():
            table[name].append(value)
    return {"freq_hz": np.array(table["freq_hz"]),
            "p_f": np.array(table["p_f_bar"]),
            "no_judder": np.array(table["no_judder_bar"]),
            "tried": np.array(table["tried_bar"]),
            "columns": [n for n in columns if n != "width"],
            "lines": [number for number, _ in rows],
            "stated": {name: (number, text, float(values[name][0]))
                       for name, (number, text) in stated.items()}}


def empty_cell(source, number, column, allowed):
    """The error of an empty cell of a table the user gives, worded the
    same wherever it is found: the file (``source``, with the option that
    gave it where it has one), the line, the column, what is allowed."""
    return JudderError(f"{source}, line {number}: column {column!r} is "
                       f"empty; allowed: {allowed}")


def _check_stated(source, number, name, text, read):
    """Refuse a stated number (``text``, read as ``read`` with the file's
    separators) that reads with a thousands separator under the file's
    convention and as another number under the other one."""
    from pysim.bench._numbers import CONVENTIONS, readings, value
    if len(readings(text)) < 2:
        return
    both = {name: value(text, name) for name in CONVENTIONS}
    if len(set(both.values())) < 2:
        return      # 12, 1 000: the same number either way
    files = next(c for c, v in both.items() if v == read)
    other = next(c for c in both if c != files)
    raise JudderError(
        f"{source}, line {number}: {name} {text!r} is {both[files]:g} as "
        f"the file's cells are written, with {CONVENTIONS[files][0]}, but "
        f"{both[other]:g} with {CONVENTIONS[other][0]}; allowed: the "
        "number without a thousands "
        "separator (such as 1000, or 1 written with the file's decimal "
        "separator)")


def _check_tested(amps, source, number, line):
    """A row's tested range is consistent: no judder below the onset, and
    nothing above the largest amplitude tried."""
    onset, quiet, tried = (amps["p_f_bar"], amps["no_judder_bar"],
                           amps["tried_bar"])
    if quiet >= onset or tried < onset or tried < quiet:
        raise JudderError(f"{source}, line {number}: {line!r}: allowed: "
                          "no_judder_bar < p_f_bar <= tried_bar and "
                          "no_judder_bar <= tried_bar (the highest amplitude "
                          "without judder lies below the onset, and no "
                          "amplitude above the largest one tried)")


def _boundary_columns(cells, source, number, line):
    """Column indices of a boundary header line (its ``cells``, the
    ``line`` as written), or None if the line is data."""
    from pysim.bench.tables import is_number
    if is_number(cells[0]):
        return None
    allowed = (("freq_hz", "p_f_bar") + BOUNDARY_TESTED_COLUMNS
               + BOUNDARY_EXTRA_COLUMNS)
    unknown = [c for c in cells if c not in allowed]
    if unknown or len(set(cells)) != len(cells) or not {
            "freq_hz", "p_f_bar"} <= set(cells):
        raise JudderError(f"{source}, line {number}: header {line!r} is not "
                          "allowed"
                          + (f" (unknown column {unknown[0]!r})" if unknown
                             else "")
                          + "; allowed: freq_hz and p_f_bar once each, in "
                          "any order, optionally "
                          + " and ".join(BOUNDARY_TESTED_COLUMNS)
                          + ", and the columns judder tongues "
                          "writes (" + ", ".join(BOUNDARY_EXTRA_COLUMNS) + ")")
    return {**{name: cells.index(name) for name in cells
               if name not in BOUNDARY_EXTRA_COLUMNS}, "width": len(cells)}


def read_boundary(path, option="`boundary`", decimal=None):
    """A measured boundary file (see :func:`read_boundary_csv`)."""
    return read_boundary_csv(read_input(path, option), source=str(path),
                             decimal=decimal)


def read_boundary_tested(path, option="`boundary`", decimal=None):
    """A measured boundary file with its tested range (see
    :func:`read_boundary_table`; ``decimal``, its decimal separator where
    its cells cannot tell it)."""
    return read_boundary_table(read_input(path, option), source=str(path),
                               decimal=decimal)


def boundary_p_max(table, pf_max_bar, path, option="`boundary`",
                   pf_option="`p_max_bar`"):
    """The largest amplitude tried (bar) that a boundary's censored points
    mean "no judder up to".

    ``pf_max_bar`` (``--pf-max``) if given; else the largest ``tried_bar``
    of ``table`` (:func:`read_boundary_table`), as ``judder fit --chart``
    takes the chart's. A point without judder whose file does not say up
    to which amplitude it was tried is refused, naming it, rather than
    assumed tried to some amplitude (the refusal names ``pf_option`` as
    the way round, unless None); a boundary with an onset at every
    frequency and no ``tried_bar`` is taken as tried to its highest onset.
    """
    if pf_max_bar is not None:
        return pf_max_bar
    censored = np.isnan(table["p_f"])
    unknown = censored & np.isnan(np.fmax(table["tried"],
                                          table["no_judder"]))
    if unknown.any():
        freqs = ", ".join(f"{f:g}" for f in table["freq_hz"][unknown][:5])
        raise JudderError(
            f"{option} {path}: {int(unknown.sum())} point(s) without judder "
            f"({freqs} Hz) do not say up to which amplitude they were "
            "tried; allowed: a tried_bar column (a chart's boundary file "
            "has it)" + ("" if pf_option is None else
                            f" or {pf_option} BAR, the largest amplitude "
                            "tried"))
    return float(np.nanmax(np.concatenate(
        [table["tried"], table["no_judder"], table["p_f"]]))) / PA_PER_BAR


def _boundary_comment(path, option, name, unit, positive, decimal=None):
    """The number of a boundary file's comment ``# NAME: VALUE`` (finite,
    >= 0, or > 0 with ``positive``), or None where the file has none; read
    with the file's cells (:func:`read_boundary_tested`, ``decimal`` its
    decimal separator where given)."""
    stated = read_boundary_tested(path, option, decimal)["stated"]
    if name not in stated:
        return None
    number, text, value = stated[name]
    if not (math.isfinite(value) and (value > 0 if positive else value >= 0)):
        raise JudderError(f"{option} {path}, line {number}: {name} = {text} "
                          "is not allowed; allowed: a finite number "
                          f"{'>' if positive else '>='} 0 ({unit})")
    return value


def read_boundary_min_growth(path, option="`boundary`", decimal=None):
    r"""The growth rate (1/s) a boundary file says its onsets were called
    judder from (a comment ``# min_growth_per_s: 1``, which ``judder chart
    --boundary`` writes), or None; read as the file's cells are read
    (``decimal``, :func:`read_boundary_table`).

    Examples
    --------
    >>> import os, tempfile
    >>> folder = tempfile.mkdtemp()
    >>> path = os.path.join(folder, "b.csv")
    >>> with open(path, "w") as f:
    ...     _ = f.write("# min_growth_per_s: 0,5\nfreq_hz;p_f_bar\n"
    ...                 "105;0,3\n")
    >>> read_boundary_min_growth(path)
    0.5
    """
    return _boundary_comment(path, option, "min_growth_per_s", "1/s", False,
                             decimal)


def read_boundary_limit(path, option="`boundary`", decimal=None):
    """The NVH limit (rpm) a boundary file says its onsets were called
    judder from (a comment ``# judder_limit_rpm: 30``, which ``judder
    chart --boundary`` writes), or None (onsets of an instability alone);
    read as the file's cells are read (``decimal``)."""
    return _boundary_comment(path, option, "judder_limit_rpm", "rpm", True,
                             decimal)


def _chart_scalar(path, key, option, positive):
    """A chart NPZ's number ``key`` (finite, >= 0, or > 0 with
    ``positive``), or None for a chart written before it had one."""
    try:
        with np.load(path, allow_pickle=False) as npz:
            if key not in npz.files:
                return None
            value = float(npz[key])
    except OSError as exc:
        raise JudderError(f"{option} {path}: cannot read it "
                          f"({exc.strerror or exc})") from None
    except (EOFError, zipfile.BadZipFile):
        raise _damaged(option, path) from None
    except (ValueError, TypeError):
        raise JudderError(f"{option} {path}: not a chart written by judder "
                          "chart (an NPZ file)") from None
    if not (np.isfinite(value) and (value > 0 if positive else value >= 0)):
        raise JudderError(f"{option} {path}: its {key} = {value!r} is not "
                          "allowed; allowed: a finite number "
                          f"{'>' if positive else '>='} 0")
    return value


def read_chart_limit(path, option="`chart`"):
    """The NVH limit (rpm) of the chart's verdict (``judder chart
    --limit``), or None for a chart written before it had one."""
    return _chart_scalar(path, "judder_limit_rpm", option, True)


def read_chart_boundary(path, group=None, option="`chart`"):
    """The experimental boundary of a chart written by ``judder chart
    --out``.

    Parameters
    ----------
    path : path
        The chart's NPZ file.
    group : str, optional
        Which group (``'65-70'``, ``'65-70/1000'``, ...); needed when the
        chart has several.

    Returns
    -------
    freq_hz, p_f : ndarray
        Hz and Pa (NaN where no run had judder).
    tried_bar : float
        The largest amplitude tried, bar.
    """
    groups, freq, p_bar, tried, aliased = _boundary_arrays(path, option)
    names = list(dict.fromkeys(groups.tolist()))
    if not names:
        raise JudderError(
            f"{option} {path}: the chart has no boundary: " + (
                f"each of its {len(aliased)} run(s) has a dither frequency "
                "estimated that may be an alias (on no boundary); allowed: "
                "a chart with runs whose frequency is given (freq_hz in "
                "the index)" if len(aliased) and aliased.all() else
                "no run could be read into it"))
    chosen = _chosen_group(path, group, names, option)
    keep = groups == chosen
    return (freq[keep].astype(float), p_bar[keep] * PA_PER_BAR,
            float(tried[keep].max()))


def _boundary_arrays(path, option):
    """A chart's boundary arrays (group, Hz, bar with NaN where censored,
    largest tried, bar) and its runs' ``dither_aliased`` (none where not
    stored), or the error naming what is wrong with the file."""
    try:
        with np.load(path, allow_pickle=False) as npz:
            groups = npz["boundary_group"]
            freq, p_bar = npz["boundary_freq_hz"], npz["boundary_p_f_bar"]
            tried = npz["boundary_tried_bar"]
            aliased = npz["dither_aliased"] if "dither_aliased" in \
                npz.files else np.zeros(0, dtype=bool)
    except OSError as exc:
        raise JudderError(f"{option} {path}: cannot read it "
                          f"({exc.strerror or exc})") from None
    except (EOFError, zipfile.BadZipFile):
        raise _damaged(option, path) from None
    except (ValueError, KeyError):
        raise JudderError(f"{option} {path}: not a chart written by judder "
                          "chart (an NPZ file)") from None
    return groups, freq, p_bar, tried, aliased


def _chosen_group(path, group, names, option):
    """The group of a chart to read (``names``, its groups): ``group``, or
    its one group."""
    if group is None and len(names) > 1:
        raise JudderError(f"{option} {path} has {len(names)} groups; give "
                          f"`group`, one of {', '.join(names)}")
    chosen = names[0] if group is None else group
    if chosen not in names:
        if names == [""]:        # judder chart without --group-by
            raise JudderError(f"`group` {group!r}: {path} has one group of "
                              "runs (charted without `group_by`); allowed: "
                              "no `group`")
        raise JudderError(f"`group` {group!r} is not in {path}; allowed: "
                          f"{', '.join(names)}")
    return chosen


def read_chart_below(path, group=None, option="`chart`"):
    """Per point of :func:`read_chart_boundary`: the highest amplitude
    run without judder below the onset, Pa (NaN: none, or a chart written
    before this was stored). The boundary lies between it and the onset.
    """
    freq, _, _ = read_chart_boundary(path, group, option)
    with np.load(path, allow_pickle=False) as npz:
        if "boundary_below_bar" not in npz.files:
            return np.full(len(freq), np.nan)
        groups = npz["boundary_group"]
        below = npz["boundary_below_bar"].astype(float)
    chosen = list(dict.fromkeys(groups.tolist()))[0] if group is None \
        else group
    return below[groups == chosen] * PA_PER_BAR


def read_chart_onset_kinds(path, group=None, option="`chart`"):
    """Per point of :func:`read_chart_boundary`: the kind of judder its
    onset run showed (``'single-period'``, ``'double-period'`` or
    ``'combination'``, as the chart labelled it; None where the point has
    no judder, or its run's kind is not one of the three), for the fit
    to match each onset to the model's tongue of that kind."""
    from stability.tongues import TONGUE_KINDS
    labels = {kind.label for kind in TONGUE_KINDS}
    freq, onset, _ = read_chart_boundary(path, group, option)
    groups, *_ = _boundary_arrays(path, option)
    chosen = list(dict.fromkeys(groups.tolist()))[0] if group is None \
        else group
    with np.load(path, allow_pickle=False) as npz:
        keep = (npz["group"] == chosen) & npz["judder"].astype(bool)
        runs_f = npz["freq_hz"][keep].astype(float)
        runs_p = npz["p_f_bar"][keep].astype(float)
        kinds = npz["kind"][keep].tolist()
    found = []
    for f, p in zip(freq, onset / PA_PER_BAR):
        at = np.flatnonzero(np.isclose(runs_f, f) & np.isclose(runs_p, p))
        kind = kinds[at[0]] if np.isfinite(p) and len(at) else None
        found.append(kind if kind in labels else None)
    return found


def read_chart_runs(path, group=None, option="`chart`"):
    """The runs of one group of a chart written by ``judder chart --out``,
    to draw it again (:func:`pysim.bench.plots.runs_figure`).

    Returns
    -------
    runs : dict
        Arrays ``source_file``, ``freq_hz``, ``p_f_bar``,
        ``amplitude_rpm``, ``judder``, ``mechanism`` of the group's runs;
        ``freq_given`` and ``p_f_given``, whether the run's ``freq_hz``
        and ``p_f_bar`` were given (else estimated from the pressure);
        the pressure's estimate (:func:`_dither_estimates`):
        ``freq_std_hz``, the standard uncertainty of a frequency
        estimated, ``dither_p_f_bar`` and ``p_f_std_bar``, the pressure's
        amplitude and its standard uncertainty (NaN where nothing was
        estimated, and for a chart written before they were stored), and
        ``dither_warnings``, what the pressure's sampling could not
        support and the given values it contradicts ('' where nothing,
        or not stored), and ``dither_aliased``, a frequency estimated that
        may be an alias (on no boundary; False where not stored).
    boundary : list of (float, float or None, float)
        Per set point: Hz, the onset (bar; None: no judder) and the largest
        amplitude tried (bar).
    """
    groups, freq, p_bar, tried, _ = _boundary_arrays(path, option)
    with np.load(path, allow_pickle=False) as npz:
        # a group whose every run may be at an alias has no boundary
        names = list(dict.fromkeys(groups.tolist()
                                   + npz["group"].tolist()))
        chosen = _chosen_group(path, group, names, option)
        keep = npz["group"] == chosen
        runs = {key: npz[key][keep] for key in (
            "source_file", "freq_hz", "p_f_bar", "amplitude_rpm", "judder",
            "mechanism")}
        runs.update(_dither_estimates(
            {key: npz[key][keep] for key in npz.files if key.startswith(
                "dither_") or key in ("freq_given", "p_f_given")},
            runs["p_f_bar"]))
    on = groups == chosen
    boundary = [(float(f), None if np.isnan(p) else float(p), float(top))
                for f, p, top in zip(freq[on], p_bar[on], tried[on])]
    return runs, boundary


def _dither_estimates(stored, p_f_bar):
    """The pressure's dither estimates of a chart's runs from its
    ``stored`` arrays (``dither_*``, ``freq_given``, ``p_f_given``), as
    :func:`read_chart_runs` returns them.

    A chart written before ``freq_given`` and ``p_f_given`` were stored
    says a setting was estimated by a finite amplitude uncertainty, and a
    frequency given by an uncertainty of 0 (NaN now); one written before
    the uncertainties were stored has none (NaN, and every value given).
    """
    count = len(p_f_bar)
    std = stored.get("dither_p_f_std_bar", np.full(count, np.nan))
    freq_std = stored.get("dither_freq_std_hz", np.full(count, np.nan))
    freq_std = np.where(freq_std == 0, np.nan, freq_std)
    estimated = np.isfinite(std)
    p_f_given = stored.get("p_f_given", ~estimated)
    return {"freq_given": stored.get("freq_given", ~np.isfinite(freq_std)),
            "p_f_given": p_f_given, "freq_std_hz": freq_std,
            "dither_p_f_bar": stored.get("dither_p_f_bar", np.where(
                estimated & ~p_f_given, p_f_bar, np.nan)),
            "p_f_std_bar": std,
            "dither_warnings": stored.get("dither_warnings",
                                          np.full(count, "")),
            "dither_aliased": stored.get("dither_aliased",
                                         np.zeros(count, dtype=bool))}


def _damaged(option, path):
    """A zip archive cut short (its directory is at the end) or with a
    member cut short: numpy raises BadZipFile or EOFError."""
    return JudderError(f"{option} {path}: a truncated or damaged NPZ file "
                       "(its zip archive is incomplete); allowed: a chart "
                       "judder chart wrote")


def read_chart_min_growth(path, option="`chart`"):
    """The growth rate (1/s) from which the chart's verdict called a run
    judder (``judder chart --min-growth``); 0 for a chart without it."""
    value = _chart_scalar(path, "min_growth_per_s", option, False)
    return 0.0 if value is None else value
