"""What a bench acquisition is once read: channels on their own time bases,
in SI, under the roles the analysis reads them by.

Examples
--------
>>> ChannelSpec("PressEVEN", "bar")
ChannelSpec(name='PressEVEN', unit='bar', kind=None)
"""

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .speed_channels import interval_means

__all__ = ["ChannelSpec", "Channel", "Acquisition", "ROLES",
           "REQUIRED_ROLES"]

#: Roles a channel plays, and the kind of quantity of each; ``time``
#: names the time column, channel or vector of a file whose time is not
#: called one of :data:`pysim.bench._common.TIME_NAMES` (catman's
#: ``Zeit  1 - Standardmessrate``), and is no channel of the acquisition.
ROLES = {"upstream_speed": "speed", "pressure": "pressure",
         "downstream_speed": "speed", "time": "time"}
#: The one role every acquisition must give.
REQUIRED_ROLES = ("upstream_speed",)


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
        needed where the file has none. Or a linear sensor scale
        ``LOW..HIGH UNIT=LOW..HIGH UNIT`` (``4..20mA=0..25bar``: a
        transmitter's current for its pressure range;
        :func:`pysim.bench.units.parse_scale`).
    kind : str, optional
        For a speed: what its samples are, a key of
        :data:`pysim.bench.speed_channels.SPEED_KINDS`; default:
        ``angle`` for an angle unit, else told from the time stamps.
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
        :data:`pysim.bench.speed_channels.SPEED_KINDS`): ``values``
        are rad for ``angle``; :meth:`interval_means` gives the speed as the
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
        (:func:`pysim.bench.speed_channels.interval_means`)."""
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
        ``engine_speed_rpm`` in files of :mod:`pysim.simulation.campaigns`).
    """

    path: Path
    format: str
    channels: dict
    metadata: dict
