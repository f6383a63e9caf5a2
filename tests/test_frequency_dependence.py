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
