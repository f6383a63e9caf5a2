"""Monodromy, Floquet multipliers and their classification (Eq. 6-13)."""

import numpy as np
import pytest
import scipy.linalg
from numpy.testing import assert_allclose

from sources import get_preset
from infra.errors import JudderError
from stability import KINDS, build_driveline, classify, floquet
from stability.monodromy import monodromy_dyson, monodromy_solve_ivp

BAR = 1e5

# Leading non-trivial multiplier inside the tongues of Fig. 14, computed
# independently from Eq. (6) and (10)-(12) with the Appendix A values,
# N_c R_m S = 6e-3 m^3 and mean_pressure_damping = 0 (the calibration of
# drivelines.registry), printed to 3-4 digits.
REFERENCE_TABLE = [
    (102.9, 0.3, 1.026 + 0j, "single-period"),       # tongue 2, Fig. 14
    (37.9, 0.5, -1.049 + 0j, "double-period"),       # tongue 3
    (84.0, 0.5, 0.164 + 1.025j, "combination"),      # tongue 5
    (60.0, 0.5, 0.9996 + 0j, "stable"),
]


def _match(a, b):
    """Pair the multisets a and b greedily; return the leftovers of a."""
    rest = list(a)
    for value in b:
        rest.pop(int(np.argmin(np.abs(np.array(rest) - value))))
    return np.array(rest)


@pytest.mark.parametrize("method", ["dyson", "solve_ivp"])
@pytest.mark.parametrize("freq, pf_bar, leading, kind", REFERENCE_TABLE)
def test_reference_table(paper4, method, freq, pf_bar, leading, kind):
    r = floquet(paper4, freq, pf_bar * BAR, method=method)
    # the table has 3-4 digits; its values to within 1e-4 after rounding
    # to the digits printed there
    digits = 4 if kind == "stable" else 3
    assert round(r.leading.real, digits) == pytest.approx(leading.real,
                                                          abs=1e-4)
    assert round(abs(r.leading.imag), digits) == pytest.approx(
        leading.imag, abs=1e-4)
    assert r.kind == kind
    assert r.growth_rate == pytest.approx(np.log(r.leading_abs) * freq)


def test_reference_table_moduli(paper4):
    # |multiplier| of the reference table: 1e-3 (printed digits), and the
    # stable point at 60 Hz to 1e-4
    expected = [1.026, 1.049, 1.038, 0.9996]
    got = [floquet(paper4, f, p * BAR).leading_abs
           for f, p, _, _ in REFERENCE_TABLE]
    assert_allclose(got, expected, atol=1e-3)
    assert_allclose(got[3], 0.9996, atol=1e-4)


@pytest.mark.parametrize("freq, pf_bar", [(102.9, 0.3), (84.0, 0.5),
                                          (37.9, 0.5)])
def test_full_and_augmented_forms_add_multipliers_at_one(paper4, freq,
                                                         pf_bar):
    reduced = floquet(paper4, freq, pf_bar * BAR).multipliers
    full = floquet(paper4, freq, pf_bar * BAR, form="full").multipliers
    augmented = floquet(paper4, freq, pf_bar * BAR,
                        form="augmented").multipliers
    # Eq. (6): the reduced multipliers plus two rigid-body angles at 1
    assert len(full) == len(reduced) + 2
    assert_allclose(_match(full, reduced), [1, 1], atol=1e-8)
    # Eq. (9): the forcing oscillator adds two more at exactly 1, and
    # leaves the others where they were (Eq. 9 is block-triangular)
    assert len(augmented) == len(full) + 2
    assert_allclose(_match(augmented, full), [1, 1], atol=1e-8)
    assert_allclose(np.sort(np.abs(_match(augmented, [1, 1, 1, 1]))),
                    np.sort(np.abs(reduced)), atol=1e-8)


def test_literal_mean_pressure_is_stable_in_dither_range():
    # Eq. (2)-(4) taken literally (the whole p_m in the damping): no
    # tongue at a few tenths of a bar as in Fig. 14; at 102.9 Hz the
    # driveline stays stable up to p_f = p_m = 10 bar and is unstable at
    # 20 bar, once the slip damping mu_g N_c R_m S p(t) changes sign for
    # part of the cycle
    literal = build_driveline(get_preset("paper-4dof").replace(
        mean_pressure_damping=1.0))
    assert floquet(literal, 102.9, 0.5 * BAR).kind == "stable"
    assert floquet(literal, 102.9, 10 * BAR).leading_abs < 1
    assert floquet(literal, 102.9, 20 * BAR).leading_abs > 1


@pytest.mark.parametrize("method", ["dyson", "solve_ivp"])
@pytest.mark.parametrize("preset", ["paper-4dof", "paper-3dof"])
def test_no_dither_is_matrix_exponential(method, preset):
    # closed form: with p_f = 0 the monodromy is expm(A0 T)
    system = build_driveline(get_preset(preset)).periodic_system()
    freq = 37.0
    got = {"dyson": monodromy_dyson,
           "solve_ivp": monodromy_solve_ivp}[method](system, freq, [0.0])[0]
    assert_allclose(got, scipy.linalg.expm(system.A0 / freq), atol=1e-9)


@pytest.mark.parametrize("preset, overrides, freq, pf_bar", [
    ("paper-4dof", {}, 5.0, 1.5),      # long period, many sub-intervals
    ("paper-4dof", {}, 250.0, 1.5),
    ("paper-4dof", {}, 18.9, 0.05),
    ("paper-4dof", {"mean_pressure_damping": 1.0}, 102.9, 20.0),
    ("paper-4dof-fitted", {}, 121.8, 3.0),
    ("paper-3dof", {}, 36.1, 1.0),
    ("paper-4dof", {"mu_g": -0.02}, 60.0, 0.5),
])
def test_dyson_matches_tight_solve_ivp(preset, overrides, freq, pf_bar):
    system = build_driveline(get_preset(preset).replace(**overrides)) \
        .periodic_system()
    amplitudes = np.array([0.0, 0.5, 1.0]) * pf_bar * BAR
    fast = monodromy_dyson(system, freq, amplitudes)
    reference = monodromy_solve_ivp(system, freq, amplitudes, rtol=1e-12,
                                    atol=1e-14)
    scale = np.abs(reference).max()
    assert_allclose(fast, reference, atol=1e-9 * scale)


@pytest.mark.parametrize("freq, kind", [
    (18.047, "single-period"),       # its eigenfrequency, Fig. 12
    (2 * 18.047, "double-period"),   # twice it
    (27.0, "stable"),
])
def test_3dof_tongues(paper3, freq, kind):
    assert floquet(paper3, freq, 1.0 * BAR).kind == kind


@pytest.mark.parametrize("multiplier, kind", [
    (0.999, "stable"), (1.0, "stable"), (1.01, "single-period"),
    (-1.01, "double-period"), (0.3 + 1.0j, "combination"),
    (-0.5 - 0.8j, "stable"), (1.2 + 1e-13j, "single-period"),
])
def test_classify(multiplier, kind):
    assert KINDS[classify(multiplier)] == kind


@pytest.mark.parametrize("freq, pf", [(0.0, 1.0), (-5.0, 1.0),
                                      (np.nan, 1.0), (10.0, -1.0),
                                      (10.0, np.inf)])
def test_bad_point_is_refused_at_the_api(freq, pf):
    # validated once, at the API (the kernels trust their inputs)
    from judder import api
    with pytest.raises(JudderError, match="allowed"):
        api.floquet(freq, pf)


def test_dyson_refuses_augmented_form(paper4):
    with pytest.raises(JudderError, match="solve_ivp"):
        floquet(paper4, 50.0, 1e4, method="dyson", form="augmented")


def test_unknown_method_lists_options(paper4):
    with pytest.raises(JudderError, match="dyson, solve_ivp"):
        floquet(paper4, 50.0, 1e4, method="rk4")


def test_dyson_refuses_a_period_too_long_for_its_memory(paper4):
    # 0.001 Hz would need about 160 000 sub-intervals (GBs of coefficients)
    with pytest.raises(JudderError, match="solve_ivp"):
        floquet(paper4, 1e-3, 1e4)


@pytest.mark.parametrize("t, freq, p_f", [(0.0, 102.9, 0.3e5),
                                          (1.3e-3, 60.0, 1.2e5)])
def test_full_system_is_eq6(paper4, t, freq, p_f):
    # the full form's rank-one split A0 + p_f cos(w t) u v^T is Eq. (6)
    # as written by state_matrix, and Eq. (9) borders it
    matrix = paper4.full_system().matrix(t, 2 * np.pi * freq, p_f)
    expected = paper4.state_matrix(t, freq, p_f)
    assert np.abs(matrix - expected).max() <= 1e-12 * np.abs(expected).max()
    augmented = paper4.augmented_system().matrix(t, 2 * np.pi * freq, p_f)
    assert np.array_equal(augmented[:8, :8], matrix)
    assert augmented[9, 8] == -(2 * np.pi * freq) ** 2
