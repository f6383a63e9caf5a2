"""Shared fixtures: the paper's drivelines, and a user's Modelica class
that is not a driveline."""

import pytest

from sources import get_preset
from stability import build_driveline


@pytest.fixture(scope="session")
def paper4():
    """4-DOF Appendix A values with N_c R_m S = 6e-3 m^3 (the calibration
    of drivelines.registry)."""
    return build_driveline(get_preset("paper-4dof"))


@pytest.fixture(scope="session")
def paper3():
    return build_driveline(get_preset("paper-3dof"))


@pytest.fixture(scope="session")
def oscillator_library(tmp_path_factory):
    """A user's library folder with ``MyLib.Oscillator``: a Mathieu-like
    oscillator whose dither is the cosine (s = q = 0), a sine (s = 1) or
    also quadratic in the amplitude (q = 1); none of the paper's names."""
    root = tmp_path_factory.mktemp("oscillator")
    package = root / "MyLib"
    package.mkdir()
    (package / "package.mo").write_text("package MyLib\nend MyLib;\n")
    (package / "Oscillator.mo").write_text("""within MyLib;
model Oscillator "One body on a spring, damping modulated by a dither"
  parameter Real p_f(min=0)=1 "Dither amplitude";
  parameter Real f_dither(min=0)=10 "Dither frequency";
  parameter Real s=0 "Share of the sine";
  parameter Real q=0 "Quadratic part";
  Real x(start=1, fixed=true) "Position";
  Real v(start=0, fixed=true) "Speed";
  Real phase = 2*3.141592653589793*f_dither*time;
equation
  der(x) = v;
  der(v) = -100*x - (1 + p_f*((1 - s)*cos(phase) + s*sin(phase))
                     + q*p_f^2*cos(phase))*v;
end Oscillator;
""")
    return root
