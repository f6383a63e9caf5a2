"""Channels of an acquisition: which file channel plays which role (the
``--channel`` option), and one file channel turned into a checked
:class:`~pysim.bench.acquisition.Channel` in SI.

Every channel keeps its own time base: a pick-up speed is sampled at tooth
passages (non-uniform), the pressure at its own rate. NaN samples are
dropped channel by channel, samples within :data:`SAME_INSTANT` of each
other are one (their mean), and values no bench records are refused
(:data:`PLAUSIBLE`).

Examples
--------
>>> parse_channel_option("pressure=PressEVEN:bar")
('pressure', ChannelSpec(name='PressEVEN', unit='bar', kind=None))
"""

import numpy as np

from infra.errors import JudderError
from infra.units import PA_PER_BAR, RAD_S_PER_RPM

from ._common import listing
from .acquisition import REQUIRED_ROLES, ROLES, Channel, ChannelSpec
from .speed_channels import SPEED_KINDS, detect_speed_kind
from .units import (allowed_units, angle_factor, is_angle_unit,
                    parse_scale, unit_factor)

__all__ = ["parse_channel_option", "checked_specs", "channel_in_si",
           "PLAUSIBLE", "SAME_INSTANT"]

#: Physical range of each kind (SI low, SI high, SI per unit shown, unit):
#: a driveline shaft below 100 000 rpm either way, a clutch pressure from
#: -1 bar (a sensor's offset) to 1000 bar.
PLAUSIBLE = {"speed": (-1e5 * RAD_S_PER_RPM, 1e5 * RAD_S_PER_RPM,
                       RAD_S_PER_RPM, "rpm"),
             "pressure": (-PA_PER_BAR, 1000 * PA_PER_BAR, PA_PER_BAR,
                          "bar")}
#: Time stamps closer than this (s) are one instant (a 1 MHz DAQ's step).
SAME_INSTANT = 1e-6


def parse_channel_option(text):
    """``ROLE=NAME``, ``ROLE=NAME:UNIT`` or ``ROLE=NAME:UNIT:KIND`` (the
    ``--channel`` option); KIND, for a speed, is a key of
    :data:`pysim.bench.speed_channels.SPEED_KINDS`. UNIT may be a
    sensor's linear scale, ``4..20mA=0..25bar``
    (:func:`pysim.bench.units.parse_scale`); ROLE ``time`` names a
    file's time column of another name.

    A name containing ``:`` needs its unit appended.

    Returns
    -------
    role : str
    spec : ChannelSpec
    """
    role, equals, rest = str(text).partition("=")
    role = role.strip()
    if not equals or not rest.strip():
        raise JudderError(f"`channels` {text!r}: give ROLE=NAME, "
                          f"ROLE=NAME:UNIT or ROLE=NAME:UNIT:KIND with ROLE "
                          f"one of {', '.join(ROLES)}")
    _check_role(role, f"`channels` {text!r}")
    kind = None
    head, colon, last = rest.rpartition(":")
    if colon and last.strip() in SPEED_KINDS:
        if ROLES[role] != "speed":
            raise JudderError(f"`channels` {text!r}: a kind is for a speed "
                              f"channel, not the {role}")
        rest, kind = head, last.strip()
    name, colon, unit = rest.rpartition(":")
    if not colon:
        if kind is not None:
            raise JudderError(f"`channels` {text!r}: give the unit before "
                              f"the kind (ROLE=NAME:UNIT:{kind})")
        return role, ChannelSpec(rest.strip())
    try:
        scale = parse_scale(unit)
        unit_of_role = unit if scale is None else scale.unit
        if not (ROLES[role] == "speed" and is_angle_unit(unit_of_role)):
            unit_factor(unit_of_role, ROLES[role])
    except JudderError as exc:
        if ROLES[role] == "speed" and kind is None and ":" in name:
            # NAME:UNIT:WORD, WORD neither a unit nor a kind
            raise JudderError(
                f"`channels` {text!r}: {unit.strip()!r} is neither a "
                f"speed unit nor a kind of speed channel; allowed "
                f"kinds: {', '.join(SPEED_KINDS)} "
                f"(ROLE=NAME:UNIT:KIND)") from None
        raise JudderError(f"`channels` {text!r}: {exc}") from None
    return role, ChannelSpec(name.strip(), unit.strip(), kind)


def _check_role(role, where):
    if role not in ROLES:
        raise JudderError(f"{where}: role {role!r} is unknown; allowed: "
                          f"{', '.join(ROLES)}")


def checked_specs(path, channels):
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
                          f"it as `channels` {missing[0]}=NAME[:UNIT]")
    return specs


def channel_in_si(path, role, spec, names, raw):
    """One role's channel: found, unit known, in SI, NaN dropped."""
    where = f"{path}: {role} channel {spec.name!r}"
    if raw is None:
        raise JudderError(f"{path}: no channel {spec.name!r} (for {role}); "
                          f"channels in the file: {listing(names)}")
    time, values, file_unit = raw
    unit = spec.unit if spec.unit is not None and str(spec.unit).strip() \
        else file_unit
    try:
        scale = parse_scale(unit) if unit is not None else None
    except JudderError as exc:
        raise JudderError(f"{where}: {exc}") from None
    if scale is not None:
        time, values, unit = _scaled(where, scale, file_unit, time, values)
    if unit is None or not str(unit).strip():
        raise JudderError(f"{where} has no unit in the file; give it with "
                          f"`channels` {role}={spec.name}:UNIT (allowed: "
                          f"{allowed_units(ROLES[role])})")
    kind_of_unit = ROLES[role]
    if kind_of_unit == "speed" and is_angle_unit(unit):
        kind_of_unit = "angle"
    try:
        factor = angle_factor(unit) if kind_of_unit == "angle" \
            else unit_factor(unit, kind_of_unit)
    except JudderError as exc:
        raise JudderError(f"{where}: {exc}") from None
    time, values = _finite(where, time, values)
    values = values * factor
    unit_in_file = str(unit if scale is None else scale.raw_unit).strip()
    if ROLES[role] != "speed":
        _plausible(where, ROLES[role], time, values)
        return Channel(time=time, values=values,
                       unit_in_file=unit_in_file, name=spec.name)
    kind = _speed_kind(where, spec, kind_of_unit, time, values)
    if kind == "angle":
        _plausible_angle(where, unit, time, values)
    else:
        _plausible(where, "speed", time, values)
    return Channel(time=time, values=values, unit_in_file=unit_in_file,
                   name=spec.name, kind=kind)


def _scaled(where, scale, file_unit, time, values):
    """A channel's raw readings through a sensor's linear scale: (time,
    values in the scale's unit, that unit). A file that gives the raw
    readings' unit must give the scale's."""
    if file_unit is not None and str(file_unit).strip() and \
            str(file_unit).strip() != scale.raw_unit:
        raise JudderError(f"{where} is in {str(file_unit).strip()!r}, the "
                          f"scale is for {scale.raw_unit!r}; allowed: a "
                          f"scale from the file's unit, such as 4..20"
                          f"{str(file_unit).strip()}=0..25bar")
    values = np.atleast_1d(np.asarray(values))
    if values.dtype.kind not in "biuf":
        return time, values, scale.unit       # _finite refuses it
    return time, scale(values.astype(float)), scale.unit


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


#: Least share of its path an encoder's angle travels one way: a shaft
#: turns one way through an engagement (judder modulates its speed by a
#: small share), a speed or a noisy level read as an angle goes back and
#: forth (an rpm column given ``rad``: 2 % of its path).
ONE_WAY_SHARE = 0.5


def _plausible_angle(where, unit, time, values):
    """Refuse an angle channel (rad, SI) that is no shaft's angle: one
    that goes back and forth (a speed given an angle unit), or whose
    speed no bench records (:data:`PLAUSIBLE`)."""
    if len(time) < 2:
        return
    steps = np.diff(np.unwrap(values))
    path = float(np.sum(np.abs(steps)))
    net = abs(float(np.sum(steps)))
    if path > 0 and net < ONE_WAY_SHARE * path:
        raise JudderError(
            f"{where}: read as an angle in {unit}, it does not turn one "
            f"way: it travels {path:.3g} rad back and forth for a net "
            f"{net:.3g} rad ({net / path:.0%}); allowed: an encoder's "
            f"accumulated angle (if it is a speed, give its speed unit, "
            f"e.g. rpm)")
    _plausible(where, "speed", time[1:], steps / np.diff(time))


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
