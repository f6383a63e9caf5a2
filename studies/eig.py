"""``judder eig``: natural frequencies and damping factor."""

from dataclasses import dataclass

import numpy as np

from sources.dither_modes import linearised_mode
from stability import modal
from stability.source import build_driveline

from ._common import resolve


def eig(parameters=None, changes=None, driveline=None):
    """``judder eig``: natural frequencies (Eq. 14-15) and the
    clutch-damper damping factor (Eq. 16), and the damped modes without
    dither.

    For a Modelica class or an FMU the natural frequencies are those of
    its Jacobian's stiffness part and the damped modes those of its
    system without dither, rigid-body angles removed; the closed forms
    (Eq. 15) and the clutch-damper factor (Eq. 16) belong to the paper's
    chains, so they are None there.

    ``driveline='bench'``: of the driveline on its test bench
    (:func:`stability.bench.driveline_view`), whose first damped mode is its
    resonance (16.5 Hz for the paper's set, 18.9 Hz on the free chain).

    Returns
    -------
    EigResult

    Examples
    --------
    >>> eig().natural_frequencies_hz.round(3)
    array([ 18.939, 102.884])
    """
    from stability.bench import driveline_view
    values, view = driveline_view(resolve(parameters, changes), driveline)
    driveline = build_driveline(values)
    damped_hz, ratio = modal.damped_modes(driveline)
    paper = values.source_kind.is_chain
    return EigResult(
        params=values,
        natural_frequencies_hz=modal.natural_frequencies(driveline),
        closed_form_frequencies_hz=(modal.closed_form_frequencies(values)
                                    if paper else None),
        damping_factor_12=(float(modal.clutch_damper_damping_factor(values))
                           if paper else None),
        damped_frequencies_hz=damped_hz, damping_ratio=ratio,
        driveline=view)


@dataclass(frozen=True)
class EigResult:
    """``judder eig``: natural frequencies (Eq. 15) and damping (Eq. 16).

    Frequencies in Hz; ``damping_factor_12`` and ``damping_ratio`` as
    fractions. ``closed_form_frequencies_hz`` and ``damping_factor_12``
    are None for a Modelica class or an FMU (they are the paper's
    formulas for its chains).
    """

    params: object
    natural_frequencies_hz: np.ndarray
    closed_form_frequencies_hz: np.ndarray
    damping_factor_12: float
    damped_frequencies_hz: np.ndarray
    damping_ratio: np.ndarray
    driveline: str = "chain"

    @property
    def frequencies_from(self):
        """Where the natural frequencies come from: the stiffness and
        inertias of a registry chain (Eq. 14; Eq. 15 is their closed form
        for the paper's 4-DOF chain), else a Jacobian's stiffness part."""
        return ("stiffnesses and inertias, Eq. 14"
                if self.closed_form_frequencies_hz is not None
                else "the Jacobian's stiffness part")

    def as_dict(self):
        mode = linearised_mode(self.params)
        from stability.bench import driveline_words
        return {"model": self.params.model, "driveline": self.driveline,
                "driveline_description": driveline_words(self.params,
                                                         self.driveline),
                **({"mode": mode} if mode else {}),
                "natural_frequencies_hz": self.natural_frequencies_hz,
                "natural_frequencies_from": self.frequencies_from,
                "closed_form_frequencies_hz": self.closed_form_frequencies_hz,
                "damping_factor_12": self.damping_factor_12,
                "damping_factor_12_percent": (
                    None if self.damping_factor_12 is None
                    else 100 * self.damping_factor_12),
                "damped_modes": [{"frequency_hz": f, "damping_ratio": r}
                                 for f, r in zip(self.damped_frequencies_hz,
                                                 self.damping_ratio)]}
