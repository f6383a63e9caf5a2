"""Sensitivity of the tongues (Fig. 17, Fig. 18, section 4.3)."""

import numpy as np
import pytest

from sources import get_preset
from infra.errors import ParameterError
from stability.sensitivity import (paper_conclusions, sensitivity_study,
                                   tip_shifts)

BAR = 1e5


@pytest.fixture(scope="module")
def study():
    return sensitivity_study(get_preset("paper-4dof"),
                             ["k12", "k24", "J1", "J2", "J3", "J4", "mu_g"],
                             np.linspace(10.0, 220.0, 141), 1.5 * BAR)


def test_paper_conclusions_hold(study):
    verdicts = {c["statement"]: c for c in paper_conclusions(study)}
    for statement in [
            "stiffness up moves the tongues up in frequency (tongues at f_i, "
            "2 f_i and f_i + f_j)",
            "inertia up moves the tongues down in frequency (tongues at f_i, "
            "2 f_i and f_i + f_j)",
            "k12 acts mainly on the low-frequency tongues",
            "k24 acts mainly on the high-frequency single-period tongue",
            "J2 and J4 move the tongue near 105 Hz most, J1 little, J3 not "
            "at all",
            "lower mu_g shrinks the tongues (tips rise or vanish)"]:
        assert verdicts[statement]["holds"], verdicts[statement]["evidence"]


def test_difference_tongue_moves_against_k12(study):
    # f2 - f1 falls when k12 raises f1 more than f2: not the paper's rule
    verdict = next(c for c in paper_conclusions(study)
                   if c["statement"].startswith("tongue 5") and
                   "up" in c["statement"])
    assert not verdict["holds"]


def test_tip_shift_table(study):
    rows = tip_shifts(study)
    assert len(rows) == len(study.cases) * 6
    j3 = [r for r in rows if r["parameter"] == "J3" and r["tongue"] == 2]
    assert all(abs(r["d_freq_hz"]) < 1e-3 for r in j3)
    # halving mu_g doubles every tip amplitude exactly (mu_g p_f product)
    for r in rows:
        if r["parameter"] == "mu_g" and r["factor"] == 0.5:
            base = r["tip_p_f_bar"] - r["d_p_f_bar"]
            assert r["tip_p_f_bar"] == pytest.approx(2 * base, rel=1e-6)


def test_bad_variation_is_refused():
    with pytest.raises(ParameterError, match="J2"):
        sensitivity_study(get_preset("paper-4dof"), ["J2"], [100.0], BAR,
                          factors=(-1.0,))
