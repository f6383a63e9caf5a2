"""Friction-gradient threshold without dither (Fig. 19)."""

import numpy as np
import pytest

from sources import get_preset
from infra.errors import JudderError
from stability import build_driveline
from stability.threshold import (closed_form_threshold, constant_system,
                                 friction_threshold, max_real_part,
                                 threshold_study)

LITERAL = get_preset("paper-4dof").replace(mean_pressure_damping=1.0)


def _all_c(params, c):
    return params.replace(**{n: c for n in
                             params.driveline.external_damping_names()})


@pytest.mark.parametrize("c", [0.05, 0.1, 0.5, 1.0, 2.0])
def test_threshold_matches_hand_value_and_closed_form(c):
    # Fig. 19b: the rigid-chain slip mode (chain damping 3c against the
    # output body's c, in series 0.75 c) gives, with N_c R_m S p_m =
    # 6000 N m, mu_g* = -0.75 c / 6000 = -1.25e-4 c
    params = _all_c(LITERAL, c)
    threshold = friction_threshold(params)
    assert threshold == pytest.approx(-1.25e-4 * c, rel=1e-9)
    assert threshold == pytest.approx(closed_form_threshold(params),
                                      rel=1e-9)


def test_3dof_threshold_closed_form():
    params = get_preset("paper-3dof").replace(mean_pressure_damping=1.0)
    assert friction_threshold(params) == pytest.approx(
        closed_form_threshold(params), rel=1e-9)


def test_threshold_moves_to_negative_mu_g_as_damping_grows():
    study = threshold_study(LITERAL, np.linspace(-1e-3, 1e-3, 5),
                            np.linspace(0.0, 2.0, 9))
    assert np.all(np.diff(study.thresholds) < 0)
    assert study.thresholds[0] == pytest.approx(0.0, abs=1e-12)
    # Fig. 19a: unstable (positive real part) below the threshold only
    below = study.mu_g < study.threshold
    assert np.all(study.max_real_part[below] > 0)
    assert np.all(study.max_real_part[~below] < 0)


def test_poles_are_the_eigenvalues_of_the_reduced_system():
    driveline = build_driveline(LITERAL)
    poles = np.sort_complex(constant_system(driveline).poles())
    eig = np.sort_complex(np.linalg.eigvals(driveline.periodic_system().A0))
    np.testing.assert_allclose(poles, eig, atol=1e-8)


def test_rigid_body_zeros_do_not_decide():
    # Eq. (6) as printed has two zero eigenvalues, and with no external
    # damping a third: the verdict must come from the other modes
    free = _all_c(LITERAL, 0.0)
    full = build_driveline(free).state_matrix(0.0, 1.0, 0.0)
    assert np.max(np.linalg.eigvals(full).real) == pytest.approx(0, abs=1e-9)
    assert max_real_part(free.replace(mu_g=0.01)) < -1.0
    assert max_real_part(free.replace(mu_g=-0.01)) > 1.0


def test_threshold_needs_the_mean_pressure():
    with pytest.raises(JudderError, match="mean_pressure_damping"):
        friction_threshold(get_preset("paper-4dof"))
