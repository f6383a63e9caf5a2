"""Reading bench acquisitions: channels with their own time bases, in SI.

The experimental stability charts of section 3.2 are drawn from bench
time histories: the speeds upstream and downstream of the EVEN clutch and
its actuation pressure. :func:`read_acquisition` reads them from the file
formats benches write, by the channel names of the user's file:

* ``.mf4`` / ``.mdf``: ASAM MDF 4 (and 3) with asammdf; every channel
  keeps the time base of its channel group, its unit is the file's; a
  name in several groups is named ``GROUP/NAME`` (the group's
  acquisition name or index);
* ``.csv``: a ``time [s]`` (or ``time``, ``t``, ``Zeit``, ``timestamp``)
  column, headers ``name [unit]`` or plain names with a units row under
  them, ``# key: json-value`` metadata lines (what
  :func:`pysim.export.write_csv` writes) or a DAQ's header block of
  ``key;value`` lines before the names; ``,``, ``;`` or tab between
  fields, a decimal comma with ``;`` or tab; a BOM;
* ``.tdms``: NI TDMS with npTDMS; a waveform channel
  (``wf_increment``, ``wf_start_offset``) has its time track, any other
  takes the ``time`` channel of its group; units from ``unit_string``;
  a channel is named ``channel`` or ``group/channel``;
* ``.mat``: MATLAB with scipy (up to v7) or h5py (v7.3, HDF5); each
  signal is a variable (or a
  field of a struct, ``struct.field``) with a time vector ``NAME_time``,
  ``t_NAME`` or a shared ``time`` / ``t``; units from a ``units`` struct.

Every channel keeps its own time base: a pick-up speed is sampled at tooth
passages (non-uniform), the pressure at its own rate. NaN samples are
dropped channel by channel, samples within :data:`SAME_INSTANT` of each
other are one (their mean), and values no bench records are refused
(:data:`PLAUSIBLE`).

Units are converted with a small explicit table (:data:`SPEED_UNITS`,
:data:`PRESSURE_UNITS`) built on :mod:`infra.units`, not with pint
(0.25, which installs): pint reads ``Hz`` and ``1/min`` as 1/s and 1/60 s,
i.e. 1 Hz = 1 rad/s, where a rotational speed in Hz or 1/min counts
revolutions (1 Hz = 2 pi rad/s), it does not know ``rev``, and it accepts
anything of dimension 1/time (``kHz``, ``1/h``, even ``U/min`` as enzyme
units); every speed unit would need a correcting table anyway, for the
price of three more packages and 0.4 s to build its registry. The table
accepts exactly the units a bench writes and lists them when one is not.

Every bad input raises :class:`infra.errors.JudderError` with a one-line
message naming the file, what is wrong and what is allowed; a corrupt
file does too.

Examples
--------
>>> round(unit_factor("rpm", "speed"), 9)
0.104719755
>>> unit_factor("bar", "pressure")
100000.0
>>> parse_channel_option("pressure=PressEVEN:bar")
('pressure', ChannelSpec(name='PressEVEN', unit='bar', kind=None))
>>> round(angle_factor("counts/1024"), 9)
0.006135923
"""

from dataclasses import dataclass
import csv
import gc
import json
import math
from pathlib import Path
import re
import sys
import xml.etree.ElementTree as ET

import numpy as np

from infra.errors import JudderError
from infra.files import decode_text
from infra.units import PA_PER_BAR, RAD_S_PER_RPM

from .speed_channels import SPEED_KINDS, detect_speed_kind, interval_means

__all__ = ["ChannelSpec", "Channel", "Acquisition", "read_acquisition",
           "parse_channel_option", "unit_factor", "ROLES", "FORMATS",
           "SPEED_UNITS", "PRESSURE_UNITS", "PLAUSIBLE",
           "SAME_INSTANT", "angle_factor"]

#: Roles a channel plays, and the kind of quantity of each.
ROLES = {"upstream_speed": "speed", "pressure": "pressure",
         "downstream_speed": "speed"}
#: The one role every acquisition must give.
REQUIRED_ROLES = ("upstream_speed",)

#: File suffixes read, and what they are.
FORMATS = {".mf4": "ASAM MDF4", ".mdf": "ASAM MDF", ".csv": "CSV",
           ".tdms": "NI TDMS", ".mat": "MATLAB MAT"}

#: rad/s per unit of speed; Hz and 1/min count revolutions.
SPEED_UNITS = {
    "rpm": RAD_S_PER_RPM, "rev/min": RAD_S_PER_RPM, "1/min": RAD_S_PER_RPM,
    "min^-1": RAD_S_PER_RPM, "min-1": RAD_S_PER_RPM, "r/min": RAD_S_PER_RPM,
    "U/min": RAD_S_PER_RPM,
    "rad/s": 1.0, "rad/sec": 1.0, "rad s^-1": 1.0,
    "Hz": 2.0 * math.pi, "rev/s": 2.0 * math.pi, "rps": 2.0 * math.pi,
}
#: rad per unit of a shaft angle (an encoder's), read as a speed channel.
ANGLE_UNITS = {"rad": 1.0, "deg": math.pi / 180.0, "°": math.pi / 180.0,
               "rev": 2.0 * math.pi}
#: Pa per unit of pressure (psi: lbf/in^2 from the exact pound and inch).
PRESSURE_UNITS = {
    "Pa": 1.0, "hPa": 1e2, "kPa": 1e3, "MPa": 1e6, "bar": PA_PER_BAR,
    "mbar": PA_PER_BAR / 1000, "psi": 0.45359237 * 9.80665 / 0.0254 ** 2,
}
#: Physical range of each kind (SI low, SI high, SI per unit shown, unit):
#: a driveline shaft below 100 000 rpm either way, a clutch pressure from
#: -1 bar (a sensor's offset) to 1000 bar.
PLAUSIBLE = {"speed": (-1e5 * RAD_S_PER_RPM, 1e5 * RAD_S_PER_RPM,
                       RAD_S_PER_RPM, "rpm"),
             "pressure": (-PA_PER_BAR, 1000 * PA_PER_BAR, PA_PER_BAR,
                          "bar")}
#: Time stamps closer than this (s) are one instant (a 1 MHz DAQ's step).
SAME_INSTANT = 1e-6
#: s per unit of a time column or track.
TIME_UNITS = {"s": 1.0, "sec": 1.0, "ms": 1e-3, "us": 1e-6, "µs": 1e-6,
              "min": 60.0}
_UNITS = {"speed": SPEED_UNITS, "pressure": PRESSURE_UNITS,
          "time": TIME_UNITS, "angle": ANGLE_UNITS}
#: Units whose case carries a prefix (milli/mega): matched exactly only.
_CASE_SENSITIVE = {"mpa", "mbar"}
#: Names of a time channel, column or variable (lower case).
_TIME_NAMES = ("time", "t", "zeit", "timestamp")
#: First 8 bytes of an MDF file (finalised, unfinalised).
_MDF_MAGIC = (b"MDF     ", b"UnFinMF ")
#: Channel names listed in a message, at most.
_LISTED = 40


@dataclass(frozen=True)
class ChannelSpec:
    """Which channel of a file plays a role.

    Attributes
    ----------
    name : str
        Channel name in the file (TDMS: ``channel`` or ``group/channel``;
        MAT: ``variable`` or ``struct.field``).
    unit : str, optional
        Unit of the file's values; overrides the file's unit, and is
        needed where the file has none.
    kind : str, optional
        For a speed: what its samples are, a key of
        :data:`pysim.speed_channels.SPEED_KINDS`; default: ``angle`` for
        an angle unit, else told from the time stamps.
    """

    name: str
    unit: str = None
    kind: str = None


@dataclass(frozen=True)
class Channel:
    """One channel on its own time base.

    Attributes
    ----------
    time : ndarray
        s, non-decreasing, NaN samples dropped.
    values : ndarray
        SI: rad/s for speeds (rad for an encoder angle), Pa for pressure.
    unit_in_file : str
        Unit the file's values are in: the file's, or the one given.
    name : str
        Channel name in the file.
    kind : str
        For a speed role, what the samples are (a key of
        :data:`pysim.speed_channels.SPEED_KINDS`): ``values`` are rad
        for ``angle``; :meth:`interval_means` gives the speed as the
        analysis reads it. None for a pressure.
    """

    time: np.ndarray
    values: np.ndarray
    unit_in_file: str
    name: str
    kind: str = None

    def interval_means(self):
        """``(time, speed)``: the mean speed over each sample interval
        (rad/s), a pick-up's convention, whatever the kind
        (:func:`pysim.speed_channels.interval_means`)."""
        if self.kind is None:
            return self.time, self.values
        return interval_means(self.time, self.values, self.kind)


@dataclass(frozen=True)
class Acquisition:
    """A bench acquisition read from a file.

    Attributes
    ----------
    path : pathlib.Path
    format : str
        The suffix without its dot: ``mf4``, ``mdf``, ``csv``, ``tdms``,
        ``mat``.
    channels : dict
        Role (:data:`ROLES`) -> :class:`Channel`.
    metadata : dict
        What the file carries (e.g. ``dither_frequency_hz``,
        ``dither_amplitude_bar``, ``oil_temperature_degC``,
        ``engine_speed_rpm`` in files of :mod:`pysim.bench`).
    """

    path: Path
    format: str
    channels: dict
    metadata: dict


# --- units -----------------------------------------------------------------

def _normalise_unit(unit):
    """A unit string with unicode minus and superscripts spelt in ASCII."""
    text = str(unit).strip().replace("⁻¹", "^-1").replace("−", "-")
    return re.sub(r"\s*/\s*", "/", text)


def _allowed_units(kind):
    text = ", ".join(_UNITS[kind])
    if kind == "speed":
        text += "; or an encoder's angle: " + ", ".join(ANGLE_UNITS) \
            + ", counts/N (N a revolution)"
    return text


def unit_factor(unit, kind):
    """SI units per ``unit`` of a quantity of ``kind``.

    Parameters
    ----------
    unit : str
    kind : {'speed', 'pressure', 'time'}

    Returns
    -------
    float
        rad/s, Pa or s per ``unit``.

    Raises
    ------
    JudderError
        The unit is unknown, or of another kind.
    """
    text = _normalise_unit(unit)
    for table_kind, table in _UNITS.items():
        factor = _lookup(table, text)
        if factor is None:
            continue
        if table_kind != kind:
            raise JudderError(f"unit {unit!r} is a {table_kind} unit, not a "
                              f"{kind} unit; allowed: "
                              f"{_allowed_units(kind)}")
        return factor
    raise JudderError(f"unit {unit!r} is unknown; allowed for a {kind}: "
                      f"{_allowed_units(kind)}")


def _lookup(table, text):
    """Factor of ``text`` in ``table``: exact, or ignoring the case where
    the case carries no prefix."""
    if text in table:
        return table[text]
    if text.lower() in _CASE_SENSITIVE:
        return None
    by_lower = {key.lower(): value for key, value in table.items()}
    return by_lower.get(text.lower())


# --- options ---------------------------------------------------------------

def parse_channel_option(text):
    """``ROLE=NAME``, ``ROLE=NAME:UNIT`` or ``ROLE=NAME:UNIT:KIND`` (the
    ``--channel`` option); KIND, for a speed, is a key of
    :data:`pysim.speed_channels.SPEED_KINDS`.

    A name containing ``:`` needs its unit appended.

    Returns
    -------
    role : str
    spec : ChannelSpec
    """
    role, equals, rest = str(text).partition("=")
    role = role.strip()
    if not equals or not rest.strip():
        raise JudderError(f"--channel {text!r}: give ROLE=NAME, "
                          f"ROLE=NAME:UNIT or ROLE=NAME:UNIT:KIND with ROLE "
                          f"one of {', '.join(ROLES)}")
    _check_role(role, f"--channel {text!r}")
    kind = None
    head, colon, last = rest.rpartition(":")
    if colon and last.strip() in SPEED_KINDS:
        if ROLES[role] != "speed":
            raise JudderError(f"--channel {text!r}: a kind is for a speed "
                              f"channel, not the {role}")
        rest, kind = head, last.strip()
    name, colon, unit = rest.rpartition(":")
    if not colon:
        if kind is not None:
            raise JudderError(f"--channel {text!r}: give the unit before "
                              f"the kind (ROLE=NAME:UNIT:{kind})")
        return role, ChannelSpec(rest.strip())
    if not (ROLES[role] == "speed" and _is_angle_unit(unit)):
        try:
            unit_factor(unit, ROLES[role])
        except JudderError as exc:
            raise JudderError(f"--channel {text!r}: {exc}") from None
    return role, ChannelSpec(name.strip(), unit.strip(), kind)


def _check_role(role, where):
    if role not in ROLES:
        raise JudderError(f"{where}: role {role!r} is unknown; allowed: "
                          f"{', '.join(ROLES)}")


def _specs(path, channels):
    """The role -> ChannelSpec mapping, checked."""
    specs = {}
    for role, spec in dict(channels).items():
        _check_role(role, str(path))
        if isinstance(spec, str):
            spec = ChannelSpec(spec)
        if not isinstance(spec, ChannelSpec) or not str(spec.name).strip():
            raise JudderError(f"{path}: role {role}: give a ChannelSpec "
                              f"(NAME, UNIT) or a channel name, not "
                              f"{spec!r}")
        specs[role] = spec
    missing = [role for role in REQUIRED_ROLES if role not in specs]
    if missing:
        raise JudderError(f"{path}: no channel given for {missing[0]}; give "
                          f"it with --channel {missing[0]}=NAME[:UNIT]")
    return specs


# --- reading ---------------------------------------------------------------

def read_acquisition(path, channels):
    """Read the channels of a bench acquisition file, in SI units.

    Parameters
    ----------
    path : str or pathlib.Path
        ``.mf4``, ``.mdf``, ``.csv``, ``.tdms`` or ``.mat`` (see
        :data:`FORMATS`).
    channels : dict
        Role (``upstream_speed`` required, ``pressure`` and
        ``downstream_speed`` optional) -> :class:`ChannelSpec` (or a
        channel name).

    Returns
    -------
    Acquisition
        An optional channel may be left with no samples (a downstream
        pick-up that saw fewer than two tooth passages, all NaN); the
        upstream speed has at least one.

    Raises
    ------
    JudderError
        Unknown format, unreadable file, a channel that is not in the
        file, a unit that is missing, unknown or of the wrong kind.
    """
    path = Path(path)
    suffix = path.suffix.lower()
    if suffix not in FORMATS:
        raise JudderError(f"{path}: unknown acquisition format "
                          f"{suffix or '(no suffix)'!r}; allowed: "
                          f"{', '.join(FORMATS)}")
    specs = _specs(path, channels)
    if not path.is_file():
        raise JudderError(f"{path}: no such file")
    names, metadata, raws = _load(path, suffix,
                                  [spec.name for spec in specs.values()])
    read = {role: _channel(path, role, spec, names, raws.get(spec.name))
            for role, spec in specs.items()}
    for role in REQUIRED_ROLES:
        if not len(read[role].values):
            raise JudderError(f"{path}: {role} channel {specs[role].name!r} "
                              "has no finite samples")
    return Acquisition(path=path, format=suffix[1:], channels=read,
                       metadata=metadata)


def _load(path, suffix, wanted):
    """Names in the file, its metadata and the wanted channels found.

    Returns
    -------
    names : list of str
    metadata : dict
    raws : dict
        Name -> (time s, values, unit or None) for the wanted names in
        the file.
    """
    loader = {".mf4": _load_mdf, ".mdf": _load_mdf, ".csv": _load_csv,
              ".tdms": _load_tdms, ".mat": _load_mat}[suffix]
    try:
        return loader(path, wanted)
    except JudderError:
        raise
    except Exception as exc:   # whatever a corrupt file makes a library do
        raise JudderError(f"{path}: not a readable {FORMATS[suffix]} file "
                          f"({_one_line(exc)})") from None


def _one_line(exc, limit=200):
    text = " ".join(str(exc).split()) or type(exc).__name__
    return text if len(text) <= limit else text[:limit - 3] + "..."


def _listing(names):
    if not names:
        return "(none)"
    shown = ", ".join(repr(n) for n in names[:_LISTED])
    more = len(names) - _LISTED
    return shown + (f" and {more} more" if more > 0 else "")


def _channel(path, role, spec, names, raw):
    """One role's channel: found, unit known, in SI, NaN dropped."""
    where = f"{path}: {role} channel {spec.name!r}"
    if raw is None:
        raise JudderError(f"{path}: no channel {spec.name!r} (for {role}); "
                          f"channels in the file: {_listing(names)}")
    time, values, file_unit = raw
    unit = spec.unit if spec.unit is not None and str(spec.unit).strip() \
        else file_unit
    if unit is None or not str(unit).strip():
        raise JudderError(f"{where} has no unit in the file; give it with "
                          f"--channel {role}={spec.name}:UNIT (allowed: "
                          f"{_allowed_units(ROLES[role])})")
    kind_of_unit = ROLES[role]
    if kind_of_unit == "speed" and _is_angle_unit(unit):
        kind_of_unit = "angle"
    try:
        factor = angle_factor(unit) if kind_of_unit == "angle" \
            else unit_factor(unit, kind_of_unit)
    except JudderError as exc:
        raise JudderError(f"{where}: {exc}") from None
    time, values = _finite(where, time, values)
    values = values * factor
    if ROLES[role] != "speed":
        _plausible(where, ROLES[role], time, values)
        return Channel(time=time, values=values,
                       unit_in_file=str(unit).strip(), name=spec.name)
    kind = _speed_kind(where, spec, kind_of_unit, time, values)
    if kind != "angle":
        _plausible(where, "speed", time, values)
    return Channel(time=time, values=values, unit_in_file=str(unit).strip(),
                   name=spec.name, kind=kind)


#: An encoder's counts as an angle unit: ``counts/N`` (N counts a
#: revolution; also count, pulses, increments).
_COUNT_UNIT = re.compile(r"(?:counts?|pulses?|increments?)\s*/\s*(\d+)",
                         re.IGNORECASE)


def angle_factor(unit):
    """rad per ``unit`` of an angle channel: rad, deg, rev, or an
    encoder's ``counts/N``; None where ``unit`` is not one."""
    text = _normalise_unit(unit)
    factor = _lookup(ANGLE_UNITS, text)
    if factor is not None:
        return factor
    counts = _COUNT_UNIT.fullmatch(text)
    if counts and int(counts.group(1)) > 0:
        return 2.0 * math.pi / int(counts.group(1))
    return None


def _is_angle_unit(unit):
    return angle_factor(unit) is not None


def _speed_kind(where, spec, kind_of_unit, time, values):
    """What a speed channel's samples are: given, told by an angle unit,
    or detected from the time stamps."""
    if spec.kind is None:
        return "angle" if kind_of_unit == "angle" else \
            detect_speed_kind(time, values)
    if (spec.kind == "angle") != (kind_of_unit == "angle"):
        raise JudderError(f"{where}: kind {spec.kind!r} needs "
                          + ("an angle unit (rad, deg, rev, counts/N)"
                             if spec.kind == "angle" else "a speed unit")
                          + f", the channel is in {kind_of_unit} units")
    return spec.kind


def _plausible(where, kind, time, values):
    """Refuse values no bench records (a broken writer, a wrong unit):
    :data:`PLAUSIBLE` bounds the magnitude of each kind (SI)."""
    low, high, shown, unit = PLAUSIBLE[kind]
    bad = (values < low) | (values > high)
    if np.any(bad):
        first = int(np.argmax(bad))
        raise JudderError(
            f"{where}: {values[first] / shown:.3g} {unit} at "
            f"{time[first]:.6g} s is not a value a bench records; allowed: "
            f"{low / shown:g} to {high / shown:g} {unit} (check the "
            "channel's unit, or the file)")


def _finite(where, time, values):
    """Time and values as float arrays, NaN samples dropped, checked."""
    time = np.atleast_1d(np.asarray(time))
    values = np.atleast_1d(np.asarray(values))
    if values.dtype.kind not in "biuf" or values.ndim != 1:
        raise JudderError(f"{where} is not a 1-D numeric signal "
                          f"(dtype {values.dtype}, shape {values.shape})")
    time = time.astype(float)
    values = values.astype(float)
    if time.shape != values.shape:
        raise JudderError(f"{where}: {len(values)} samples but "
                          f"{time.size} time stamps; they must be as many")
    keep = np.isfinite(time) & np.isfinite(values)
    time, values = time[keep], values[keep]
    if np.any(np.diff(time) < 0):
        raise JudderError(f"{where}: time goes backwards at "
                          f"{time[np.argmax(np.diff(time) < 0)]:.9g} s; "
                          "time stamps must not decrease")
    return _merge_instants(time, values)


def _merge_instants(time, values):
    """Samples closer in time than :data:`SAME_INSTANT` as one, their
    mean: a DAQ that puts several channels on the union of their time
    bases writes stamps 1e-18 s apart (and a repeated stamp), which no
    sampling rate can be read from."""
    if len(time) < 2:
        return time, values
    first = np.r_[True, np.diff(time) > SAME_INSTANT]
    if first.all():
        return time, values
    group = np.cumsum(first) - 1
    return time[first], (np.bincount(group, weights=values)
                         / np.bincount(group))


def _plain(value):
    """A metadata value as plain Python (numpy scalars and arrays, dicts)."""
    if isinstance(value, dict):
        return {str(k): _plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if isinstance(value, np.ndarray):
        return _plain(value.tolist())
    if isinstance(value, np.datetime64):
        return str(value)
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, bytes):
        return value.decode("utf-8", "replace")
    return value


# --- CSV -------------------------------------------------------------------

def _load_csv(path, wanted):
    """CSV as :func:`pysim.export.write_csv` writes it, and as DAQ software
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
    header = [_split_header(cell) for cell in rows[0]]
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
    time = _csv_column(path, body, rows, time_column) * _column_factor(
        path, header[time_column], "time")
    raws = {}
    for name in wanted:
        if name in names and names.index(name) != time_column:
            column = names.index(name)
            raws[name] = (time, _csv_column(path, body, rows, column),
                          header[column][1])
    return [n for i, n in enumerate(names) if i != time_column], metadata, \
        raws


def _csv_header_row(path, rows, body):
    """Index of the row that names the columns: the first with a time
    column and as many fields as the data rows (a DAQ's header block,
    ``Time;14:03:22`` among its lines, may come before it)."""
    widths = [len(row) for row in rows]
    data_width = max(set(widths), key=widths.count)
    for index, row in enumerate(rows):
        if len(row) == data_width and any(
                _split_header(cell)[0].lower() in _TIME_NAMES
                for cell in row):
            return index
    names = [_split_header(cell)[0] for cell in rows[0]]
    raise JudderError(f"{path}: no time column; the line naming the "
                      "columns must name one 'time [s]' (or 'time' with a "
                      f"units row under it); columns of line {body[0][0]}: "
                      f"{_listing(names)}")


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


def _column_factor(path, column, kind):
    """Factor of the unit of a (name, unit) column; 1 when it has none."""
    name, unit = column
    if unit is None:
        return 1.0
    try:
        return unit_factor(unit, kind)
    except JudderError as exc:
        raise JudderError(f"{path}: column {name!r}: {exc}") from None


def _csv_lines(path):
    """The lines of a CSV file: UTF-8 (with or without BOM), else
    Windows-1252, the encoding European DAQ software writes (``°C``,
    ``µs``)."""
    data = path.read_bytes()
    try:
        return decode_text(data, str(path), "CSV").splitlines()
    except JudderError:
        try:
            text = data.decode("cp1252")
        except UnicodeDecodeError:
            text = None
        if text is None or "\0" in text:
            raise
        return text.splitlines()


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


def _split_header(cell):
    """``name [unit]`` -> (name, unit); a plain name has unit None."""
    match = re.fullmatch(r"\s*(.*?)\s*\[([^\[\]]*)\]\s*", cell)
    if match:
        return match.group(1), match.group(2).strip() or None
    return cell.strip(), None


def _csv_time_column(path, names):
    for index, name in enumerate(names):
        if name.lower() in _TIME_NAMES:
            return index
    raise JudderError(f"{path}: no time column; the first line of data "
                      f"must name one 'time [s]' (columns: "
                      f"{_listing(names)})")


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


# --- MDF -------------------------------------------------------------------

def _load_mdf(path, wanted):
    """ASAM MDF: each channel on the time base of its channel group."""
    try:
        from asammdf import MDF
    except ImportError:
        raise JudderError(f"{path}: reading MDF needs asammdf (pip "
                          "install asammdf)") from None
    with open(path, "rb") as stream:
        magic = stream.read(8)
    if magic not in _MDF_MAGIC:
        # asammdf would say so too, then complain again on collection
        raise ValueError(f"it starts with {magic!r}, not {_MDF_MAGIC[0]!r}")
    mdf = _open_mdf(MDF, path)
    try:
        where = _mdf_channels(mdf)
        raws = {}
        for name in wanted:
            found = _mdf_find(path, mdf, where, name)
            if found is not None:
                raws[name] = _mdf_signal(mdf, *found)
        listed = [name if len(places) == 1 else
                  f"{_mdf_group_label(mdf, group)}/{name}"
                  for name, places in where.items() for group, _ in places]
        return listed, _mdf_metadata(mdf.header), raws
    finally:
        mdf.close()


def _open_mdf(MDF, path):
    """``MDF(path)``; a file it cannot read raises ValueError, quietly.

    asammdf 8 leaves a half-built object whose ``__del__`` fails when its
    constructor fails; it is collected here with that one failure
    silenced, so that it does not print ``Exception ignored in ...``.
    """
    previous = sys.unraisablehook

    def hook(unraisable):
        if not getattr(unraisable.object, "__module__", "").startswith(
                "asammdf"):
            previous(unraisable)
    sys.unraisablehook = hook
    try:
        try:
            return MDF(str(path))
        except Exception as exc:
            message = _one_line(exc)
        gc.collect()
    finally:
        sys.unraisablehook = previous
    raise ValueError(message)


def _mdf_channels(mdf):
    """Name -> every (group, index) it occurs at, master channels left
    out."""
    masters = mdf.masters_db
    where = {}
    for name, places in mdf.channels_db.items():
        data = [(g, i) for g, i in places if masters.get(g) != i]
        if data:
            where[name] = data
    return where


def _mdf_group_label(mdf, group):
    """A channel group's name: its acquisition name, else its comment's
    first line, else its index."""
    channel_group = mdf.groups[group].channel_group
    for text in (getattr(channel_group, "acq_name", ""),
                 getattr(channel_group, "comment", "")):
        text = str(text or "").strip().splitlines()
        if text and "/" not in text[0]:
            return text[0].strip()
    return str(group)


def _mdf_find(path, mdf, where, name):
    """(group, index) of ``NAME`` (in one group only) or ``GROUP/NAME``
    (GROUP the group's name or index); None where there is none."""
    if name in where and len(where[name]) == 1:
        return where[name][0]
    group_name, slash, channel = name.rpartition("/")
    if name not in where and slash and channel in where:
        chosen = [(g, i) for g, i in where[channel]
                  if group_name in (_mdf_group_label(mdf, g), str(g))]
        if len(chosen) == 1:
            return chosen[0]
        name = channel
    if name not in where:
        return None
    choices = [f"{_mdf_group_label(mdf, g)}/{name} "
               f"({mdf.groups[g].channel_group.cycles_nr} samples)"
               for g, _ in where[name]]
    raise JudderError(f"{path}: channel {name!r} is in several groups; "
                      f"name one as GROUP/NAME (or the group's index, "
                      f"{where[name][-1][0]}/{name}): {', '.join(choices)}")


def _mdf_signal(mdf, group, index):
    signal = mdf.get(group=group, index=index)
    return signal.timestamps, signal.samples, (signal.unit or None)


def _mdf_metadata(header):
    """The header comment (JSON as :mod:`pysim.export` writes it, else
    text) and the header's author, department, project, subject."""
    metadata = {}
    for key in ("author", "department", "project", "subject"):
        value = getattr(header, key, "")
        if value:
            metadata[key] = str(value)
    text = getattr(header, "description", None)
    if text is None:
        text = getattr(header, "comment", "") or ""
    parsed = _comment_dict(text)
    if parsed is not None:
        metadata.update(parsed)
    elif text.strip():
        metadata["comment"] = text.strip()
    return metadata


def _comment_dict(text):
    """The JSON object of a comment: all of it, its ``<TX>``, or a line
    (MDF3 comments gather lines of history)."""
    for candidate in [text] + text.splitlines():
        try:
            parsed = json.loads(_xml_text(candidate.strip()))
        except ValueError:
            continue
        if isinstance(parsed, dict):
            return _plain(parsed)
    return None


def _xml_text(comment):
    """The ``<TX>`` of an MDF comment, or the comment itself."""
    comment = comment or ""
    try:
        element = ET.fromstring(comment).find(".//TX")
    except ET.ParseError:
        return comment
    if element is None:
        return comment
    return element.text or ""


# --- TDMS ------------------------------------------------------------------

def _load_tdms(path, wanted):
    """NI TDMS: waveform time tracks or a time channel of the group."""
    try:
        from nptdms import TdmsFile
    except ImportError:
        raise JudderError(f"{path}: reading TDMS needs npTDMS (pip install "
                          "npTDMS)") from None
    tdms = TdmsFile.read(str(path))
    names = [f"{g.name}/{c.name}" for g in tdms.groups()
             for c in g.channels()]
    raws = {}
    for name in wanted:
        found = _tdms_find(path, tdms, name)
        if found is not None:
            raws[name] = _tdms_signal(path, *found)
    return names, _plain(dict(tdms.properties)), raws


def _tdms_find(path, tdms, name):
    """(group, channel) named ``group/channel`` or ``channel``."""
    group_name, slash, channel_name = name.rpartition("/")
    matches = [(g, c) for g in tdms.groups() for c in g.channels()
               if (slash and g.name == group_name and c.name == channel_name)
               or c.name == name]
    if len(matches) > 1:
        paths = [f"{g.name}/{c.name}" for g, c in matches]
        raise JudderError(f"{path}: channel {name!r} is in several groups; "
                          f"name one of {_listing(paths)}")
    return matches[0] if matches else None


def _tdms_signal(path, group, channel):
    unit = channel.properties.get("unit_string") or None
    values = channel[:]
    if "wf_increment" in channel.properties:
        factor = _tdms_time_factor(path, channel, channel.properties.get(
            "wf_xunit_string") or "s")
        return channel.time_track() * factor, values, unit
    clock = _tdms_time_channel(group)
    if clock is None or clock is channel:
        raise JudderError(f"{path}: channel '{group.name}/{channel.name}' "
                          "has no time: no wf_increment property and no "
                          f"'time' channel in group {group.name!r}")
    factor = _tdms_time_factor(path, clock, clock.properties.get(
        "unit_string") or "s")
    return _seconds(clock[:]) * factor, values, unit


def _tdms_time_channel(group):
    for channel in group.channels():
        if _split_header(channel.name)[0].lower() in _TIME_NAMES:
            return channel
    return None


def _tdms_time_factor(path, channel, unit):
    return _column_factor(path, (channel.name, unit), "time")


def _seconds(time):
    """Time stamps as float s (datetime64: from the first one)."""
    time = np.asarray(time)
    if np.issubdtype(time.dtype, np.datetime64):
        return (time - time[0]) / np.timedelta64(1, "s")
    return time


# --- MAT -------------------------------------------------------------------

def _load_mat(path, wanted):
    """MATLAB MAT up to v7: variables or struct fields with time vectors."""
    import scipy.io
    try:
        data = scipy.io.loadmat(str(path), simplify_cells=True)
    except NotImplementedError:      # v7.3: an HDF5 file
        data = _load_mat73(path)
    top = {k: v for k, v in data.items() if not k.startswith("__")}
    signals = _mat_signals(top)
    raws = {}
    for name in wanted:
        scope = _mat_scope(path, signals, name)
        if scope is not None:
            raws[name] = _mat_signal(path, top, scope)
    return sorted(signals), _mat_metadata(top), raws


def _load_mat73(path):
    """A MAT v7.3 file (HDF5, h5py) as ``loadmat(simplify_cells=True)``
    gives a v7 one: structs as dicts, char arrays as text, vectors 1-D,
    scalars as numbers."""
    import h5py
    with h5py.File(path, "r") as top:
        return {key: _mat73_value(top[key]) for key in top
                if not key.startswith("#")}


def _mat73_value(node):
    import h5py
    kind = node.attrs.get("MATLAB_class", b"")
    kind = kind.decode() if isinstance(kind, bytes) else str(kind)
    if isinstance(node, h5py.Group):
        return {key: _mat73_value(node[key]) for key in node
                if not key.startswith("#")}
    values = np.asarray(node[()]).T       # MATLAB stores column-major
    if kind == "char":
        return "".join(map(chr, values.ravel()))
    values = np.squeeze(values)
    return values.item() if values.ndim == 0 else values


def _mat_signals(top, prefix=(), scopes=None):
    """Dotted name -> (path of struct names, key) of every numeric array."""
    scopes = {} if scopes is None else scopes
    node = _mat_node(top, prefix)
    for key, value in node.items():
        if isinstance(value, dict) and key not in ("units", "metadata"):
            _mat_signals(top, prefix + (key,), scopes)
        elif isinstance(value, np.ndarray) and value.dtype.kind in "biuf":
            scopes[".".join(prefix + (key,))] = (prefix, key)
    return scopes


def _mat_node(top, prefix):
    node = top
    for key in prefix:
        node = node[key]
    return node


def _mat_scope(path, signals, name):
    """(struct path, key) of ``name``: dotted, or a unique plain name."""
    if name in signals:
        return signals[name]
    matches = [dotted for dotted, (_, key) in signals.items() if key == name]
    if len(matches) > 1:
        raise JudderError(f"{path}: variable {name!r} is in several structs; "
                          f"name one of {_listing(sorted(matches))}")
    return signals[matches[0]] if matches else None


def _mat_signal(path, top, scope):
    """(time, values, unit) of one signal, looking for its time vector and
    unit in its struct, then in the structs around it."""
    prefix, key = scope
    nodes = [_mat_node(top, prefix[:i]) for i in range(len(prefix), -1, -1)]
    time = _first(nodes, [f"{key}_time", f"t_{key}"] + list(_TIME_NAMES))
    if time is None:
        name = ".".join(prefix + (key,))
        raise JudderError(f"{path}: variable {name!r} has no time vector; "
                          f"give one as {key}_time, t_{key}, time or t")
    units = [node["units"] for node in nodes
             if isinstance(node.get("units"), dict)]
    unit = _first(units, [key])
    if unit is not None:
        unit = str(unit).strip() or None
    return time, _mat_node(top, prefix)[key], unit


def _first(nodes, keys):
    """The first value of ``keys`` found in ``nodes`` (inner first)."""
    for node in nodes:
        for key in keys:
            if key in node and not isinstance(node[key], dict):
                return node[key]
    return None


def _mat_metadata(top):
    """The ``metadata`` struct and the scalar variables (numbers, text)."""
    metadata = {key: _plain(value) for key, value in top.items()
                if isinstance(value, (str, int, float, bool, np.generic))}
    if isinstance(top.get("metadata"), dict):
        metadata.update(_plain(top["metadata"]))
    return metadata
