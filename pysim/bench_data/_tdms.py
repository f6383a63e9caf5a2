"""NI TDMS acquisitions with npTDMS, imported when a file is read."""

import numpy as np

from infra.errors import JudderError

from ._common import TIME_NAMES, column_factor, listing, plain, split_header

__all__ = ["read"]


def read(path, wanted):
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
        if split_header(channel.name)[0].lower() in TIME_NAMES:
            return channel
    return None


def _tdms_time_factor(path, channel, unit):
    return column_factor(path, (channel.name, unit), "time")


def _seconds(time):
    """Time stamps as float s (datetime64: from the first one)."""
    time = np.asarray(time)
    if np.issubdtype(time.dtype, np.datetime64):
        return (time - time[0]) / np.timedelta64(1, "s")
    return time
