"""Reading bench acquisitions: one reader per file format, chosen by suffix.

The experimental stability charts of section 3.2 are drawn from bench
time histories: the speeds upstream and downstream of the EVEN clutch and
its actuation pressure. :func:`read_acquisition` reads them from the file
formats benches write, by the channel names of the user's file, through
the reader :data:`READERS` holds for the file's suffix:

* ``.mf4`` / ``.mdf``: ASAM MDF 4 (and 3) with asammdf; every channel
  keeps the time base of its channel group, its unit is the file's; a
  name in several groups is named ``GROUP/NAME`` (the group's
  acquisition name or index) (:mod:`pysim.bench._mdf`);
* ``.csv``: a ``time [s]`` (or ``time``, ``t``, ``Zeit``, ``timestamp``)
  column, headers ``name [unit]`` or plain names with a units row under
  them, ``# key: json-value`` metadata lines (what
  :func:`pysim.simulation.export.write_csv` writes) or a DAQ's header block of
  ``key;value`` lines before the names; ``,``, ``;`` or tab between
  fields; decimal and thousands separators decided from all the cells
  read, never cell by cell, or given by the caller (``decimal``)
  (:mod:`pysim.bench._numbers`); a time
  column of numbers or date-times; a BOM (:mod:`pysim.bench._csv`);
* ``.tdms``: NI TDMS with npTDMS; a waveform channel
  (``wf_increment``, ``wf_start_offset``) has its time track, any other
  takes the ``time`` channel of its group; channels whose clocks record
  their start (``wf_start_time``, date-time time channels) are laid on one
  time base, and a file where some do and others do not is refused;
  units from ``unit_string``; a channel is named ``channel`` or
  ``group/channel`` (:mod:`pysim.bench._tdms`);
* ``.mat``: MATLAB with scipy (up to v7) or h5py (v7.3, HDF5); each
  signal is a variable (or a field of a struct, ``struct.field``) with a
  time vector ``NAME_time``, ``t_NAME`` or a shared ``time`` / ``t``;
  units from a ``units`` struct (:mod:`pysim.bench._mat`).

A reader returns the raw channels; :mod:`pysim.bench.channels` turns
each into SI on its own time base, and checks it.

Every bad input raises :class:`infra.errors.JudderError` with a one-line
message naming the file, what is wrong and what is allowed; a corrupt
file does too.
"""

from functools import partial
from pathlib import Path

from infra.errors import JudderError

from . import _csv, _mat, _mdf, _tdms
from ._common import one_line
from .acquisition import REQUIRED_ROLES, Acquisition
from .channels import channel_in_si, checked_specs

__all__ = ["read_acquisition", "read_cost", "READERS", "FORMATS",
           "TEXT_SUFFIXES"]

#: File suffix -> reader. ``reader(path, wanted, time)`` returns the
#: channel names in the file (list of str), its metadata (dict) and the
#: wanted names found in it: name -> (time s, values, unit or None);
#: ``time`` is the ``time`` role's ChannelSpec (the file's time of another
#: name), or None.
READERS = {".mf4": _mdf.read, ".mdf": _mdf.read, ".csv": _csv.read,
           ".tdms": _tdms.read, ".mat": _mat.read}
#: Suffixes of text formats whose reader takes the decimal separator
#: (``reader(path, wanted, time, decimal=)``).
TEXT_SUFFIXES = (".csv",)
#: What the files of each suffix are, for messages.
FORMATS = {".mf4": "ASAM MDF4", ".mdf": "ASAM MDF", ".csv": "CSV",
           ".tdms": "NI TDMS", ".mat": "MATLAB MAT"}


#: Peak memory of reading and analysing one acquisition, bytes per byte
#: of the file: 17.4 for a 27 MB CSV (+470 MB resident) and 14 for the
#: same samples as a 25.6 MB MF4 (+350 MB) of 800 000 samples (the
#: analysis's arrays hold most of it).
MEMORY_PER_BYTE = 18
#: CPU seconds of reading and analysing one byte of an acquisition: 0.47
#: us for that CSV (12.8 s), 0.35 us for the MF4 (8.9 s).
SECONDS_PER_BYTE = 5e-7


def read_cost(path):
    """Memory (bytes) and CPU time (s) of reading and analysing an
    acquisition, from its size (an uncompressed file; a compressed MF4
    or MAT v7.3 holds more samples per byte)."""
    size = Path(path).stat().st_size if Path(path).is_file() else 0
    return size * MEMORY_PER_BYTE, size * SECONDS_PER_BYTE


def read_acquisition(path, channels, decimal=None):
    """Read the channels of a bench acquisition file, in SI units.

    Parameters
    ----------
    path : str or pathlib.Path
        ``.mf4``, ``.mdf``, ``.csv``, ``.tdms`` or ``.mat`` (a key of
        :data:`READERS`).
    channels : dict
        Role (``upstream_speed`` required, ``pressure`` and
        ``downstream_speed`` optional; ``time`` the file's time column,
        channel or vector where it has another name than those of
        :data:`pysim.bench._common.TIME_NAMES`) ->
        :class:`~pysim.bench.acquisition.ChannelSpec` (or a channel
        name).
    decimal : {'.', ','}, optional
        The decimal separator of a text file (CSV) whose cells cannot
        tell it (integers with ``1,000``); the thousands separator
        follows (:mod:`pysim.bench._numbers`). Default: decided from
        the file's cells. Binary formats store numbers and ignore it.

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
        file, a unit that is missing, unknown or of the wrong kind, a
        number that is not written as ``decimal`` says.
    """
    path = Path(path)
    suffix = path.suffix.lower()
    if suffix not in READERS:
        raise JudderError(f"{path}: unknown acquisition format "
                          f"{suffix or '(no suffix)'!r}; allowed: "
                          f"{', '.join(READERS)}")
    specs = checked_specs(path, channels)
    time = specs.pop("time", None)
    if not path.is_file():
        raise JudderError(f"{path}: no such file")
    names, metadata, raws = _load(path, suffix,
                                  [spec.name for spec in specs.values()],
                                  time, decimal)
    read = {role: channel_in_si(path, role, spec, names,
                                raws.get(spec.name))
            for role, spec in specs.items()}
    for role in REQUIRED_ROLES:
        if not len(read[role].values):
            raise JudderError(f"{path}: {role} channel {specs[role].name!r} "
                              "has no finite samples")
    return Acquisition(path=path, format=suffix[1:], channels=read,
                       metadata=metadata)


def _load(path, suffix, wanted, time, decimal):
    """What the reader of ``suffix`` returns; whatever else a corrupt
    file makes its library raise becomes one JudderError."""
    reader = READERS[suffix]
    if suffix in TEXT_SUFFIXES:
        reader = partial(reader, decimal=decimal)
    try:
        return reader(path, wanted, time)
    except JudderError:
        raise
    except Exception as exc:   # whatever a corrupt file makes a library do
        raise JudderError(f"{path}: not a readable {FORMATS[suffix]} file "
                          f"({one_line(exc)})") from None
