"""Conversion factors: SI inside, bar and rpm where engineers read them.

Examples
--------
>>> 0.3 * PA_PER_BAR
30000.0
>>> round(1000 * RAD_S_PER_RPM, 6)
104.719755
"""

import math

__all__ = ["PA_PER_BAR", "RPM_PER_RAD_S", "RAD_S_PER_RPM"]

#: Pascal per bar.
PA_PER_BAR = 1e5
#: Revolutions per minute per rad/s.
RPM_PER_RAD_S = 60.0 / (2.0 * math.pi)
#: rad/s per revolution per minute.
RAD_S_PER_RPM = 2.0 * math.pi / 60.0
