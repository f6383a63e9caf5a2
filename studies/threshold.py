"""``judder threshold``: friction-gradient threshold without dither (Fig. 19).
"""

from dataclasses import dataclass

import numpy as np

from drivelines.specs import MEAN_PRESSURE_DAMPING
from infra.errors import JudderError
from infra.files import keeps_foreign_files, write_text
from stability.source import build_driveline

from ._common import resolve


def threshold(mu_g, c_ext, parameters=None, changes=None, progress=None):
    """``judder threshold``: the friction-gradient threshold without
    dither (Fig. 19).

    Fig. 19 needs the mean pressure in the slip damping, so
    ``mean_pressure_damping`` is 1 here unless ``changes`` sets it.

    Parameters
    ----------
    mu_g : array_like
        Friction gradients for Fig. 19a, s/rad.
    c_ext : array_like
        Values of every external damping c_i for Fig. 19b, N m s/rad.

    Returns
    -------
    ThresholdResult

    Examples
    --------
    With every c_i = 0.1 N m s/rad the threshold is -1.25e-4 c_i:

    >>> r = threshold([0.0], [0.1])
    >>> round(float(r.study.threshold), 10)
    -1.25e-05
    """
    from stability.threshold import threshold_study
    changes = dict(changes or {})
    base = resolve(parameters, {})
    if not base.source_kind.is_chain:
        raise JudderError(f"threshold of {base.model} is not possible: "
                          "Fig. 19 varies mu_g and the external dampings "
                          "of the paper's chains by their roles; allowed: "
                          "a preset or a parameter file of one")
    changes.setdefault(MEAN_PRESSURE_DAMPING, 1.0)
    values = resolve(parameters, changes)
    study = threshold_study(values, mu_g, c_ext, callback=progress)
    own = (float(np.mean(build_driveline(values).external_damping)),
           float(values["mu_g"]))
    return ThresholdResult(params=values, study=study, own=own)


@dataclass(frozen=True)
class ThresholdResult:
    """``judder threshold``: Fig. 19.

    ``study`` is the :class:`stability.threshold.ThresholdStudy`; ``own``
    the driveline's own point on Fig. 19b: (mean external damping c_i,
    N m s/rad; mu_g, s/rad).
    """

    params: object
    study: object
    own: tuple

    @property
    def slope(self):
        """Slope of the threshold against c_i, s/rad per N m s/rad (None
        with one c_i)."""
        s = self.study
        if len(s.external_damping) < 2:
            return None
        return float(np.polyfit(s.external_damping, s.thresholds, 1)[0])

    def as_dict(self):
        s = self.study
        return {"model": self.params.model,
                "mean_pressure_damping":
                    self.params["mean_pressure_damping"],
                "mu_g": s.mu_g, "max_real_part_per_s": s.max_real_part,
                "mu_g_threshold": s.threshold,
                "external_damping": s.external_damping,
                "mu_g_thresholds": s.thresholds,
                "mu_g_thresholds_closed_form": s.closed_form,
                "slope": self.slope}

    @keeps_foreign_files
    def save(self, path):
        s = self.study
        lines = ["c_ext,mu_g_threshold,mu_g_threshold_closed_form"] + [
            f"{c:.9g},{m:.9g},{k:.9g}" for c, m, k in
            zip(s.external_damping, s.thresholds, s.closed_form)]
        write_text(path, "\n".join(lines) + "\n")

    def figure(self, title=None, stacked=False):
        from .figures.threshold import threshold_figure
        return threshold_figure(self, title=title, stacked=stacked)
