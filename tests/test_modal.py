"""Natural frequencies (Eq. 14-15) and damping factor (Eq. 16)."""

import numpy as np
import pytest
from numpy.testing import assert_allclose

from sources import get_preset
from stability import (build_driveline, clutch_damper_damping_factor,
                       closed_form_frequencies, natural_frequencies)


@pytest.mark.parametrize("preset, expected_hz", [
    ("paper-4dof", [18.939, 102.884]),  # Eq. (15); paper: 18.9 and 102.9 Hz
    ("paper-3dof", [18.047]),  # "close to 20 Hz"; sqrt(k (J1+J24)/(J1 J24))/2pi
])
def test_natural_frequencies(preset, expected_hz):
    params = get_preset(preset)
    freqs = natural_frequencies(build_driveline(params))
    assert_allclose(freqs, expected_hz, atol=5e-4)
    # the general eigenproblem and the closed form agree
    assert_allclose(closed_form_frequencies(params), freqs, rtol=1e-12)


@pytest.mark.parametrize("c12, expected", [
    (0.5, 0.0084),   # Appendix value; paper rounds to 0.9 %
    (10.0, 0.168),   # fitted value of section 4.2; paper: 17 %
])
def test_damping_factor_eq16(c12, expected):
    params = get_preset("paper-4dof").replace(c12=c12)
    assert clutch_damper_damping_factor(params) == pytest.approx(expected,
                                                                 abs=5e-4)


def test_eq15_follows_stiffness_changes():
    # Eq. (15) against the eigenproblem away from the Appendix values
    params = get_preset("paper-4dof").replace(k24=2 * 32885.0, J2=0.5)
    assert_allclose(closed_form_frequencies(params),
                    natural_frequencies(build_driveline(params)), rtol=1e-12)


def test_rigid_body_modes_are_dropped(paper4):
    w2 = np.linalg.eigvals(np.linalg.solve(paper4.mass_matrix(),
                                           paper4.stiffness_matrix()))
    assert np.sum(np.abs(w2) < 1e-6) == 2
    assert len(natural_frequencies(paper4)) == 2
