"""NI TDMS acquisitions with npTDMS, imported when a file is read."""

import numpy as np

from infra.errors import JudderError

from ._common import (column_factor, is_time_name, listing, on_one_clock,
                      plain, time_unit)

__all__ = ["read"]


#: The TDMS time stamp 0 (1904-01-01 UTC): LabVIEW's "no start time".
_TDMS_EPOCH = np.datetime64("1904-01-01T00:00:00", "ns")


def read(path, wanted, time=None):
    """NI TDMS: waveform time tracks or a time channel of the group, laid
    on one time base where the channels record when their clocks started
    (``wf_start_time``, a date-time time channel):
    :func:`pysim.bench._common.on_one_clock`."""
    try:
        from nptdms import TdmsFile
    except ImportError:
        raise JudderError(f"{path}: reading TDMS needs npTDMS (pip install "
                          "npTDMS)") from None
    tdms = TdmsFile.read(str(path))
    names = [f"{g.name}/{c.name}" for g in tdms.groups()
             for c in g.channels()]
    raws, starts = {}, {}
    for name in wanted:
        found = _tdms_find(path, tdms, name)
        if found is not None:
            *raws[name], starts[name] = _tdms_signal(path, *found, time)
    raws = on_one_clock(path, {n: tuple(r) for n, r in raws.items()},
                        starts, "wf_start_time or a date-time time channel")
    return names, plain(dict(tdms.properties)), raws


def _tdms_find(path, tdms, name):
    """(group, channel) named ``group/channel`` or ``channel``."""
    group_name, slash, channel_name = name.rpartition("/")
    matches = [(g, c) for g in tdms.groups() for c in g.channels()
               if (slash and g.name == group_name and c.name == channel_name)
               or c.name == name]
    if len(matches) > 1:
        paths = [f"{g.name}/{c.name}" for g, c in matches]
        raise JudderError(f"{path}: channel {name!r} is in several groups; "
                          f"name one of {listing(paths)}")
    return matches[0] if matches else None


def _tdms_signal(path, group, channel, time):
    """(time s, values, unit, the clock's start or None)."""
    unit = channel.properties.get("unit_string") or None
    values = channel[:]
    if "wf_increment" in channel.properties:
        factor = _tdms_time_factor(path, channel, channel.properties.get(
            "wf_xunit_string") or "s")
        return (channel.time_track() * factor, values, unit,
                _instant(channel.properties.get("wf_start_time")))
    clock = next((c for c in group.channels()
                  if is_time_name(c.name, time)), None)
    if clock is None or clock is channel:
        raise JudderError(f"{path}: channel '{group.name}/{channel.name}' "
                          "has no time: no wf_increment property and no "
                          f"{time.name if time else 'time'!r} channel in "
                          f"group {group.name!r}"
                          + ("" if time else "; name another with "
                             "`channels` time=NAME[:UNIT]"))
    stamps = clock[:]
    if np.issubdtype(np.asarray(stamps).dtype, np.datetime64):
        # date-time stamps: s from the first, which is the clock's start
        return _seconds(stamps), values, unit, _instant(stamps[0])
    factor = _tdms_time_factor(path, clock, time_unit(
        time, clock.properties.get("unit_string")) or "s")
    return stamps * factor, values, unit, None


def _tdms_time_factor(path, channel, unit):
    return column_factor(path, (channel.name, unit), "time")


def _seconds(time):
    """Date-time stamps as float s from the first one."""
    time = np.asarray(time)
    return (time - time[0]) / np.timedelta64(1, "s")


def _instant(value):
    """A TDMS time stamp as ``numpy.datetime64`` (ns), or None for none or
    LabVIEW's zero time stamp."""
    if value is None:
        return None
    instant = np.datetime64(value, "ns")
    return None if instant == _TDMS_EPOCH else instant
