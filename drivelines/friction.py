"""A clutch's friction characteristic as data: ``mu(|w|)`` as a table.

The paper linearises the friction of the wet clutch about an operating
slip (Eq. 5: ``mu = mu0 + mu_g w``). A clutch has a characteristic of its
own, measured on a friction rig (SAE No. 2, mu-v), a property of the
lining and the oil, not of the operating point. :class:`FrictionTable`
holds one: the coefficient at increasing absolute slip speeds,
interpolated linearly with its end values held outside, as
``Judder.Interfaces.PartialFrictionTable`` (and MSL's ``Clutch`` with
``mu_pos``) interpolate it, so that the FMU, the periodic orbit and the
linearisation read one law. Its value and slope at a slip (the slope of
the segment there) are the ``mu0`` and ``mu_g`` of the stability model
linearised at that slip (:meth:`FrictionTable.at`).

The share of the clamping load that feels the characteristic (``m``,
``mean_pressure_damping``) stays a parameter of the driveline.
"""

from dataclasses import dataclass

import numpy as np

from infra.errors import JudderError

__all__ = ["FrictionTable", "straight_line", "FMU_ROWS", "BUILT_INS"]

#: Rows of the bench FMU's table (``Judder.Examples.TestBenchTable``):
#: a shorter table is continued flat past its last slip.
FMU_ROWS = 64

#: The named characteristics: ``bounded`` (the bench's bounded rising
#: curve, ``Judder.Components.CurveWetClutch``: the default) and
#: ``straight`` (the straight line of Eq. 5 through ``mu0`` at the
#: operating slip with the slope ``mu_g``).
BUILT_INS = ("bounded", "straight")


@dataclass(frozen=True)
class FrictionTable:
    """A friction characteristic ``mu(|w|)``, interpolated linearly.

    Attributes
    ----------
    slip : tuple of float
        Absolute slip speeds, rad/s, increasing, at least 0.
    mu : tuple of float
        Friction coefficients at those slips, 1 (positive).
    source : str
        Where it comes from, as outputs name it (a file, ``'straight'``).
    oil_temperature_c : float or None
        The oil temperature ``mu`` is at, C (None: one temperature).
    family : tuple of (float, tuple of float)
        ``mu(w, T)``: the coefficients at each measured oil temperature,
        C, increasing (empty: one temperature);
        :meth:`at_oil_temperature` interpolates between them.
    """

    slip: tuple
    mu: tuple
    source: str
    oil_temperature_c: object = None
    family: tuple = ()

    def __post_init__(self):
        slip = np.asarray(self.slip, dtype=float)
        mu = np.asarray(self.mu, dtype=float)
        where = f"friction table {self.source}"
        if slip.ndim != 1 or slip.shape != mu.shape or len(slip) < 2:
            raise JudderError(f"{where}: {len(slip)} slips and {len(mu)} "
                              "friction coefficients; allowed: two columns "
                              "of the same length, at least 2 rows")
        if not (np.all(np.isfinite(slip)) and np.all(np.isfinite(mu))):
            raise JudderError(f"{where}: a value is not a finite number; "
                              "allowed: finite numbers only")
        if slip[0] < 0 or np.any(np.diff(slip) <= 0):
            raise JudderError(f"{where}: the slips are not increasing from "
                              "0 or more; allowed: increasing absolute slip "
                              "speeds")
        if np.any(mu <= 0):
            low = int(np.argmin(mu))
            raise JudderError(f"{where}: friction coefficient {mu[low]:g} at "
                              f"{slip[low]:g} rad/s is not allowed; allowed: "
                              "> 0")
        if len(slip) > FMU_ROWS:
            raise JudderError(f"{where}: {len(slip)} rows; allowed: at most "
                              f"{FMU_ROWS} (the bench FMU's table); give the "
                              "rig's curve at fewer slips")
        temperatures = [t for t, _ in self.family]
        if np.any(np.diff(temperatures) <= 0) or any(
                len(column) != len(slip) for _, column in self.family):
            raise JudderError(f"{where}: oil temperatures "
                              f"{temperatures} with columns of "
                              f"{[len(c) for _, c in self.family]} rows; "
                              "allowed: increasing temperatures, a "
                              "coefficient at every slip")
        object.__setattr__(self, "slip", tuple(slip.tolist()))
        object.__setattr__(self, "mu", tuple(mu.tolist()))

    def at_oil_temperature(self, temperature_c):
        """The characteristic at the oil temperature ``temperature_c``
        (C), interpolated linearly between the two measured temperatures
        around it.

        Raises
        ------
        JudderError
            Outside the measured temperatures, or for a table of one
            temperature.
        """
        temperatures = [t for t, _ in self.family]
        if not temperatures:
            raise JudderError(f"`oil_temperature_c` {temperature_c:g} C is not "
                              f"allowed: the friction table {self.source} "
                              "has one temperature; allowed: a table with "
                              "a column per oil temperature")
        if not temperatures[0] <= temperature_c <= temperatures[-1]:
            raise JudderError(f"`oil_temperature_c` {temperature_c:g} C is not "
                              f"allowed; allowed: {temperatures[0]:g} to "
                              f"{temperatures[-1]:g} C (the friction table "
                              f"{self.source}'s temperatures)")
        columns = np.array([mu for _, mu in self.family])
        mu = [np.interp(temperature_c, temperatures, columns[:, row])
              for row in range(columns.shape[1])]
        return FrictionTable(self.slip, tuple(mu), self.source,
                             float(temperature_c), self.family)

    def curve(self, slip):
        """Value and slope of the characteristic at many slips.

        Parameters
        ----------
        slip : array_like
            Slip speeds ``w``, rad/s, any shape (either sign).

        Returns
        -------
        mu : ndarray
            Friction coefficient at ``|w|``, 1.
        slope : ndarray
            ``d mu / d|w|``, s/rad: the slope of the segment holding
            ``|w|`` (a segment starts at its knot, as the Modelica
            interpolation's ``>=``), 0 outside the table.

        Examples
        --------
        >>> table = FrictionTable((0.0, 50.0, 100.0), (0.1, 0.12, 0.11), "x")
        >>> mu, slope = table.curve([25.0, -75.0, 200.0])
        >>> mu.round(4).tolist(), slope.round(5).tolist()
        ([0.11, 0.115, 0.11], [0.0004, -0.0002, 0.0])
        """
        w = np.abs(np.asarray(slip, dtype=float))
        knots, values = np.asarray(self.slip), np.asarray(self.mu)
        segment = np.clip(np.searchsorted(knots, w, side="right") - 1,
                          0, len(knots) - 2)
        slopes = np.diff(values) / np.diff(knots)
        inside = (w >= knots[0]) & (w < knots[-1])
        return (np.interp(w, knots, values),
                np.where(inside, slopes[segment], 0.0))

    def at(self, slip):
        """``(mu, slope)`` at one slip, floats: the ``mu0`` and ``mu_g``
        of the linearisation at ``slip`` (Eq. 5 about it)."""
        mu, slope = self.curve(slip)
        return float(mu), float(slope)

    def linear_range(self, slip):
        """Slip offset from ``slip`` over which the characteristic keeps
        its slope there, rad/s: the distance to the nearer end of its
        segment (infinite past the table's ends, where it is flat)."""
        w = abs(float(slip))
        knots = np.asarray(self.slip)
        if w < knots[0]:
            return float(knots[0] - w)
        if w >= knots[-1]:
            return float("inf")
        right = int(np.searchsorted(knots, w, side="right"))
        return float(min(w - knots[right - 1], knots[right] - w))

    def padded(self, rows=FMU_ROWS):
        """The table as the bench FMU's ``rows`` x 2 array: continued
        flat past its last slip (each added knot 1000 rad/s further), so
        that the FMU interpolates the same characteristic."""
        extra = rows - len(self.slip)
        slip = np.concatenate([self.slip, self.slip[-1]
                               + 1000.0 * np.arange(1, extra + 1)])
        mu = np.concatenate([self.mu, np.full(extra, self.mu[-1])])
        return np.column_stack([slip, mu])

    def start_values(self, name="friction_table"):
        """The FMU start values of the bench's table parameter ``name``
        (``friction_table[i,j]``, 1-based) from :meth:`padded`."""
        return {f"{name}[{row + 1},{column + 1}]": float(value)
                for (row, column), value in np.ndenumerate(self.padded())}

    def words(self):
        """What the characteristic is, in words."""
        temperature = ("" if self.oil_temperature_c is None else
                       f" at {self.oil_temperature_c:g} C oil")
        return (f"friction table {self.source}{temperature} "
                f"({len(self.slip)} points, {self.slip[0]:g} to "
                f"{self.slip[-1]:g} rad/s)")


def straight_line(mu0, mu_g, w_op):
    """The straight line of Eq. 5 through ``mu0`` at the operating slip
    ``w_op`` with the slope ``mu_g``, as a table (held outside) over the
    slips where it stays between ``mu0/2`` and ``3 mu0/2`` (at most
    ``w_op/2`` either side): the law the paper linearises, where it
    keeps a positive friction coefficient.

    Examples
    --------
    >>> line = straight_line(0.09, 0.017, 84.72)
    >>> [round(w, 3) for w in line.slip], line.at(84.72)
    ([82.073, 87.367], (0.09, 0.017))
    """
    half = 0.5 * w_op if mu_g == 0 else min(0.5 * w_op,
                                             0.5 * mu0 / abs(mu_g))
    low, high = w_op - half, w_op + half
    return FrictionTable((low, high), (mu0 + mu_g * (low - w_op),
                                       mu0 + mu_g * (high - w_op)),
                         "straight (Eq. 5)")
