"""ASAM MDF acquisitions (MF4, MDF 3) with asammdf, imported when a file
is read."""

import gc
import json
import sys
import xml.etree.ElementTree as ET

from infra.errors import JudderError

from ._common import one_line, plain

__all__ = ["read"]

#: First 8 bytes of an MDF file (finalised, unfinalised).
_MDF_MAGIC = (b"MDF     ", b"UnFinMF ")


def read(path, wanted, time=None):
    """ASAM MDF: each channel on the time base of its channel group (its
    master channel: a ``time`` role is refused, as MDF names none)."""
    if time is not None:
        raise JudderError(f"{path}: `channels` time={time.name} is not "
                          "allowed for an MDF file: each channel group has "
                          "its master channel as its time; allowed: no "
                          "time role")
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
            message = one_line(exc)
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
    """The header comment (JSON as :mod:`pysim.simulation.export` writes it, else
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
            return plain(parsed)
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
