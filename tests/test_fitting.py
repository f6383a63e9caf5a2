"""Fitting the model boundary to a measured one (section 4.2)."""

import numpy as np
import pytest

from drivelines import get_preset
from infra.errors import JudderError
from judder.inputs import read_boundary_csv
from stability.fitting import fit_boundary, model_boundary

BAR = 1e5
FREQS = np.linspace(60.0, 200.0, 29)   # the bench's dither range


@pytest.fixture(scope="module")
def measured():
    # a boundary computed from known parameters (section 4.2's fitted set)
    return model_boundary(get_preset("paper-4dof-fitted"), FREQS, 1.5 * BAR)


def test_fit_recovers_known_parameters(measured):
    assert np.isnan(measured).sum() > 5      # censored points take part
    result = fit_boundary(get_preset("paper-4dof"), FREQS, measured,
                          1.5 * BAR)
    truth = get_preset("paper-4dof-fitted")
    assert result.success
    for name, value in zip(result.names, result.values):
        assert value == pytest.approx(truth[name], rel=1e-5), name
    assert result.residual_rms_bar < 1e-6
    assert np.all(np.isfinite(result.std))


def test_wrong_fixed_damping_leaves_a_residual(measured):
    # c12 held at the Appendix value: the boundary cannot be matched
    result = fit_boundary(get_preset("paper-4dof"), FREQS, measured,
                          1.5 * BAR, names=("mu_g", "k24"))
    assert result.residual_rms_bar > 0.05


def test_bounds_must_contain_the_start():
    with pytest.raises(JudderError, match="c12"):
        fit_boundary(get_preset("paper-4dof"), FREQS, np.full(29, BAR),
                     1.5 * BAR, names=("c12",), bounds={"c12": (1.0, 2.0)})


def test_read_boundary_csv():
    freqs, amps = read_boundary_csv(
        "freq_hz,p_f_bar\n60,0.7\n# comment\n150,\n100,0.2,extra\n")
    np.testing.assert_allclose(freqs, [60, 150, 100])
    assert amps[0] == pytest.approx(0.7e5) and np.isnan(amps[1])


@pytest.mark.parametrize("text, words", [
    ("freq_hz,p_f_bar\n60;0.7\n", ["line 2"]),
    ("60,-1\n", ["line 1", ">= 0"]),
    ("", ["no data"]),
])
def test_bad_boundary_csv(text, words):
    with pytest.raises(JudderError) as info:
        read_boundary_csv(text, source="b.csv")
    for word in words:
        assert word in str(info.value)


def test_a_boundary_without_judder_cannot_be_fitted():
    with pytest.raises(JudderError, match="no point with judder"):
        fit_boundary(get_preset("paper-4dof"), [100.0, 120.0],
                     [np.nan, np.nan], 1.5 * BAR, names=("mu_g",))
