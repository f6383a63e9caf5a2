r"""Fitting the model's stability boundary to a measured one (section 4.2).

The paper compares the judder region measured on the bench (Fig. 10) with
the model's tongues and adjusts the parameters that cannot be measured
(the clutch-damper damping ``c12``, the friction gradient ``mu_g`` and the
stiffness ``k24``) until the model boundary follows the measured one: the
dotted (first attempt) and solid (fitted) lines of Fig. 16a. This module
does that adjustment by bounded least squares and says how far the result
can be trusted.

Measured boundary
-----------------
A list of dither frequencies with, for each, the lowest amplitude at
which judder was seen, or none (no judder up to the largest amplitude
tried, ``p_max``: a *censored* point). A point may carry the kind of
judder seen (single-period, double-period, combination), or the tongue it
belongs to (its number as in Fig. 14, or its resonance label such as
``'f2'`` or ``'f1+f2'``).

Which model boundary
--------------------
A chart's verdict calls a run judder when it grows at ``min_growth`` or
faster (``judder chart --min-growth``), so its boundary is the model's
boundary of judder growing at that rate, not the stability boundary; and
a bench is not the driveline alone: its motor's speed control damps body
1 (``c1 + d_control``). ``fit_boundary(min_growth=, added=)`` compares
with that model; the fitted values stay the driveline's. The round trip
(emulated campaign -> chart -> fit) is measured in docs/roundtrip.md.

This package is the facade: import from ``stability.fit``. The fit has
its parts in private modules (as ``scipy.optimize._lsq``):

* ``_fitting``: :func:`fit_boundary`, the steps put together;
* ``_common``: what every step shares: the problem, the model's
  boundaries at trial parameters, the residuals, the nearest kind of each
  point, one bounded least-squares run, the progress count;
* ``_model``: the model boundary a measurement is compared with, and the
  start and fitted curves of Fig. 16a;
* ``_matching``: matching each measured point to a kind of tongue;
* ``_starts``: the local fits from several starts;
* ``_uncertainty``: standard uncertainties and 95 % intervals (Jacobian,
  profile likelihood, bootstrap);
* ``_identifiability``: what the data can determine (enough onsets,
  parameters that move the measured boundary, flat directions);
* ``_result``: :class:`FitResult` and the sentences saying what went
  wrong.
"""

from ._fitting import DEFAULT_FIT, ERROR_MODELS, fit_boundary
from ._identifiability import FLAT_CORRELATION, MIN_DOF, flat_pairs
from ._matching import parse_kind
from ._model import fit_curves, model_boundary
from ._result import FitResult
from ._uncertainty import CONFIDENCE, UNCERTAINTY_METHODS

__all__ = ["fit_boundary", "model_boundary", "fit_curves", "FitResult",
           "parse_kind", "flat_pairs", "DEFAULT_FIT", "ERROR_MODELS",
           "CONFIDENCE", "UNCERTAINTY_METHODS", "FLAT_CORRELATION",
           "MIN_DOF"]
