"""A model whose Jacobian depends on the dither frequency beyond the
cosine (a valve's roll-off written with f_dither) is recognised, so that
no study linearised at one frequency is read at another."""

import numpy as np
import pytest
from numpy.testing import assert_allclose

from fmu.build import build_fmu
from sources.fmus import linearize_fmu
from sources.modelica import linearize

ROLLOFF = """within RollLib;
model Rolloff "An oscillator whose damping a dither modulates through a valve's lag"
  parameter Real p_f(min=0)=1 "Dither amplitude";
  parameter Real f_dither(min=0)=10 "Dither frequency";
  parameter Real tau(min=0)=0 "Time constant of the valve";
  Real x(start=1, fixed=true);
  Real v(start=0, fixed=true);
  Real phase = 2*3.141592653589793*f_dither*time;
equation
  der(x) = v;
  der(v) = -100*x - (1 + p_f/sqrt(1 + (2*3.141592653589793*f_dither*tau)^2)
                     *cos(phase))*v;
end Rolloff;
"""


@pytest.fixture(scope="module")
def library(tmp_path_factory):
    root = tmp_path_factory.mktemp("rolloff")
    (root / "RollLib").mkdir()
    (root / "RollLib" / "package.mo").write_text(
        "package RollLib\nend RollLib;\n")
    (root / "RollLib" / "Rolloff.mo").write_text(ROLLOFF)
    return root


def _modulation(tau, f):
    # closed form: B = -e2 e2^T / sqrt(1 + (2 pi f tau)^2)
    return -1 / np.sqrt(1 + (2 * np.pi * f * tau) ** 2)


@pytest.mark.parametrize("tau, dependent", [(0.0, False), (2e-3, True)])
def test_the_symbolic_path_tells_a_roll_off(library, tau, dependent):
    model = linearize("RollLib.Rolloff", str(library),
                      {"tau": tau, "f_dither": 37.7})
    assert model.frequency_dependent is dependent
    assert_allclose(model.B[1, 1], _modulation(tau, 37.7), rtol=1e-12)


@pytest.mark.parametrize("tau, dependent", [(0.0, False), (2e-3, True)])
def test_the_fmu_path_tells_a_roll_off(library, tmp_path, tau, dependent):
    path = build_fmu(library / "RollLib" / "Rolloff.mo", "RollLib.Rolloff",
                     tmp_path / "rolloff.fmu", roots=[library]).path
    model = linearize_fmu(path, {"tau": tau, "f_dither": 37.7})
    assert model.frequency_dependent is dependent
    assert_allclose(model.B[1, 1], _modulation(tau, 37.7), rtol=1e-9)


def test_a_study_reads_the_model_at_its_own_dither_frequency(library):
    # check at 3.2 Hz linearises the roll-off there, whatever f_dither the
    # class or the user's --set held; a map over frequencies has no one
    # linearisation and is refused, naming the parameter
    from infra.errors import JudderError
    from studies.check import check
    from studies.map import stability_map
    from studies.sensitivity import sensitivity
    from sources.modelica import ModelicaParameters
    params = ModelicaParameters("RollLib.Rolloff", str(library),
                                {"tau": 0.05})
    assert params["f_dither"] == 10.0
    checked = check([3.2], [2e-5], params, sensitivity=("tau",))
    given = check([3.2], [2e-5], params.replace(f_dither=3.2),
                  sensitivity=("tau",))
    point, reference = checked.checks[0].floquet, given.checks[0].floquet
    assert checked.params["f_dither"] == 3.2
    assert point.growth_rate == pytest.approx(reference.growth_rate,
                                              rel=1e-12)
    # held at the class's 10 Hz the valve's roll-off is 2.7 times stronger
    # (closed form above): another growth rate
    held = linearize("RollLib.Rolloff", str(library),
                     {"tau": 0.05, "f_dither": 10.0})
    moved = params.replace(f_dither=3.2).linear_model()
    assert held.B[1, 1] / moved.B[1, 1] == pytest.approx(
        _modulation(0.05, 10.0) / _modulation(0.05, 3.2), rel=1e-12)
    with pytest.raises(JudderError, match="f_dither"):
        sensitivity(("tau",), [3.0, 3.4], parameters=params)


def test_a_map_of_a_frequency_dependent_model_follows_its_frequency(library):
    # the issue's acceptance: the same map as a loop of --set f_dither
    from studies.map import stability_map
    from sources.modelica import ModelicaParameters
    params = ModelicaParameters("RollLib.Rolloff", str(library),
                                {"tau": 0.05})
    freqs, amplitudes = np.linspace(2.6, 3.8, 7), [0.0, 1e-5, 3e-5, 6e-5]
    followed = stability_map(freqs, amplitudes, params, exact=True)
    for i, f in enumerate(freqs):
        column = stability_map([f], amplitudes, params.replace(f_dither=f))
        assert_allclose(followed.map.leading[i], column.map.leading[0],
                        rtol=1e-12, atol=0)
    # held at one linearisation the map would differ: the roll-off at
    # 2.6 Hz is not that at 3.8 Hz
    held = stability_map(freqs, amplitudes, ModelicaParameters(
        "RollLib.Rolloff", str(library), {"tau": 0.0}))
    assert np.abs(held.map.leading - followed.map.leading).max() > 1e-3
    # the exact boundaries too, column by column
    assert followed.boundaries.amplitude.shape == (7, 3)
    # a model without the roll-off is studied over many frequencies
    flat = ModelicaParameters("RollLib.Rolloff", str(library), {"tau": 0.0})
    assert stability_map([3.0, 3.4], [0.0, 2e-5], flat).map.freq_hz.size == 2
