"""Shared fixtures: the paper's drivelines."""

import pytest

from drivelines import get_preset
from stability import build_driveline


@pytest.fixture(scope="session")
def paper4():
    """4-DOF Appendix A values with N_c R_m S = 6e-3 m^3 (the calibration
    of drivelines.registry)."""
    return build_driveline(get_preset("paper-4dof"))


@pytest.fixture(scope="session")
def paper3():
    return build_driveline(get_preset("paper-3dof"))
