"""Writing runs as files a bench engineer opens: CSV and ASAM MDF4.

Both carry the time histories in SI units with their units, and the run's
metadata (dither frequency and amplitude, parameters). Files are written
atomically (:func:`infra.files.atomic_write`).
"""

import io
import json

import numpy as np

from infra.errors import JudderError
from infra.files import atomic_write, mark_line

__all__ = ["write_run", "write_csv", "write_mdf"]


def write_csv(path, time, signals, units, metadata):
    """CSV: a header ``name [unit]`` on the first line (as a spreadsheet
    expects), the samples, then ``# key: value`` metadata lines and the
    mark (:func:`infra.files.mark_line`); an empty cell where a channel
    has no sample (NaN: e.g. a pick-up before its shaft turns one
    tooth)."""
    buffer = io.StringIO()
    names = list(signals)
    buffer.write(",".join(["time [s]"] + [f"{n} [{units[n]}]"
                                          for n in names]) + "\n")
    for i, t in enumerate(time):
        buffer.write(",".join([f"{t:.9g}"] + [_cell(signals[n][i])
                                              for n in names]) + "\n")
    buffer.write("# an empty cell is no sample of that channel at that "
                 "time\n")
    for key, value in metadata.items():
        buffer.write(f"# {key}: {json.dumps(value)}\n")
    buffer.write(mark_line() + "\n")
    atomic_write(path, lambda stream: stream.write(buffer.getvalue().encode()))


def _cell(value):
    return f"{value:.9g}" if np.isfinite(value) else ""


def write_mdf(path, channels, metadata):
    """ASAM MDF 4.10; one channel group per time base.

    Parameters
    ----------
    channels : sequence of (name, unit, timestamps, samples)
    metadata : dict
        Written as JSON into the file comment.
    """
    try:
        from asammdf import MDF, Signal
    except ImportError:
        raise JudderError("writing .mf4 needs asammdf (pip install "
                          "asammdf)") from None
    mdf = MDF(version="4.10")
    groups = {}
    for name, unit, timestamps, samples in channels:
        key = (len(timestamps), float(timestamps[0]) if len(timestamps) else 0)
        groups.setdefault(key, []).append(
            Signal(samples=np.asarray(samples, dtype=float),
                   timestamps=np.asarray(timestamps, dtype=float), name=name,
                   unit=unit))
    for signals in groups.values():
        mdf.append(signals, comment=json.dumps(metadata))
    mdf.header.comment = json.dumps(metadata)
    mdf.header.author = mark_line().removeprefix("# ")

    def write(stream):
        buffer = io.BytesIO()
        mdf.save(buffer, overwrite=True)
        stream.write(buffer.getvalue())
    atomic_write(path, write)


def write_run(path, time, signals, units, metadata):
    """CSV or MF4 by the file suffix."""
    suffix = str(path).lower().rsplit(".", 1)[-1]
    if suffix == "csv":
        write_csv(path, time, signals, units, metadata)
    elif suffix == "mf4":
        write_mdf(path, [(n, units[n], time, signals[n]) for n in signals],
                  metadata)
    else:
        raise JudderError(f"{path}: allowed suffixes: .csv, .mf4")
