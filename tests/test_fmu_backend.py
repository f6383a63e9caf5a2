"""Modelica -> ODE: rumoca front end and the project's structural back end.

The ODE is generated from the .mo source alone; it must reduce the
acausal models to their minimal states and reproduce Eq. (1) as the
stability layer writes it, and it must follow edits to the source.
"""

import shutil
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from sources import get_preset
from stability import build_driveline

pytest.importorskip("rumoca")
pytest.importorskip("casadi")

from fmu.backend import to_ode  # noqa: E402
from fmu.frontend import FrontEndError, load_flat_model  # noqa: E402

LIBRARY = Path(__file__).resolve().parents[1] / "modelica"
W_IN = 1000 * 2 * np.pi / 60


def _ode(name, library=LIBRARY):
    flat = load_flat_model(library / "Judder" / "Examples" / f"{name}.mo",
                           f"Judder.Examples.{name}", roots=[library])
    return to_ode(flat)


def _simulate(ode, t_end=1.0, **parameters):
    f, outputs, start = ode.functions()
    p = ode.parameter_vector(**parameters)
    sol = solve_ivp(lambda t, x: np.asarray(f(t, x, p)).ravel(), (0, t_end),
                    np.asarray(start(p)).ravel(), method="DOP853",
                    rtol=1e-12, atol=1e-12, dense_output=True)
    return sol, outputs, p


@pytest.mark.parametrize("name, states", [
    ("Driveline4DOF", ["inertia1.phi", "inertia1.w", "inertia2.phi",
                       "inertia2.w", "inertia4.phi", "inertia4.w",
                       "inertia3.phi", "inertia3.w"]),
    ("Driveline3DOF", ["inertia1.phi", "inertia1.w", "inertia24.phi",
                       "inertia24.w", "inertia3.phi", "inertia3.w"]),
    ("TestBenchEngagement", ["inertia1.phi", "inertia1.w", "inertia2.phi",
                             "inertia2.w", "inertia4.phi", "inertia4.w",
                             "inertia3.phi", "inertia3.w"]),
])
def test_index_reduction_keeps_the_minimal_states(name, states):
    # rumoca keeps 15, 11 and 17 states (relative angles, motor angle)
    assert [s.name for s in _ode(name).states] == states


def test_4dof_ode_is_eq1():
    ode = _ode("Driveline4DOF")
    sol, _, _ = _simulate(ode, f_dither=60.0)
    params = get_preset("paper-4dof")
    driveline = build_driveline(params)
    torque = params["mu0"] * params.clutch_factor * params["p_m"]
    x0 = [0, -torque / 3856, -torque / 3856 - torque / 32885, 0,
          W_IN, W_IN, W_IN, 0]
    reference = solve_ivp(
        lambda t, x: driveline.state_matrix(t, 60.0, 0.3e5) @ x
        + driveline.state_forcing(t, 60.0, 0.3e5, engine_torque=torque,
                                  resistant_torque=torque),
        (0, 1), x0, method="DOP853", rtol=1e-12, atol=1e-12,
        dense_output=True)
    t = np.linspace(0, 1, 501)
    got, want = sol.sol(t), reference.sol(t)
    # ODE order: (phi, w) per body 1, 2, 4, 3; Eq. (6): angles then speeds
    for row, column in zip(range(8), [0, 4, 1, 5, 2, 6, 3, 7]):
        scale = np.abs(want[column]).max()
        assert np.abs(got[row] - want[column]).max() < 1e-9 * scale


def test_outputs_follow_the_source():
    ode = _ode("Driveline4DOF")
    names = [o.name for o in ode.outputs]
    f, outputs, start = ode.functions()
    p = ode.parameter_vector()
    x0 = np.asarray(start(p)).ravel()
    y = dict(zip(names, np.asarray(outputs(0.0, x0, p)).ravel()))
    assert y["slip"] == pytest.approx(W_IN)
    assert y["actuation_pressure"] == pytest.approx(1e6 + 0.3e5)
    # friction torque of the clutch at t = 0: mu0 N_c R_m S p plus the
    # dither part of mu_g slip N_c R_m S p (mean_pressure_damping = 0)
    nrs = 8 * 0.075 * 0.01
    assert y["clutch_torque"] == pytest.approx(
        nrs * (0.09 * 1.03e6 + 0.017 * W_IN * 0.3e5), rel=1e-12)


def test_a_changed_source_changes_the_ode(tmp_path):
    # a temporary copy of the library with one parameter default changed,
    # in the record of Appendix A the example extends
    copy = tmp_path / "modelica"
    shutil.copytree(LIBRARY, copy)
    path = copy / "Judder" / "Data" / "Driveline4DOFData.mo"
    path.write_text(path.read_text().replace(
        "parameter Units.Inertia J4=0.122", "parameter Units.Inertia J4=0.244"))
    changed = _ode("Driveline4DOF", library=copy)
    assert dict((q.name, q.start) for q in changed.parameters)["J4"] == 0.244
    # at rest with the shaft 2-4 twisted and no clutch pressure, body 4
    # accelerates by k24 * twist / J4: half as much with J4 doubled
    x = np.array([0, 0, 0.0, 0, 0.01, 0, 0, 0])
    accelerations = []
    for ode in (_ode("Driveline4DOF"), changed):
        f, _, _ = ode.functions()
        p = ode.parameter_vector(p_m=0.0, p_f=0.0)
        accelerations.append(np.asarray(f(0.0, x, p)).ravel()[5])
    assert accelerations[0] == pytest.approx(-32885 * 0.01 / 0.122,
                                             rel=1e-12)
    assert accelerations[1] == pytest.approx(accelerations[0] / 2, rel=1e-12)


def test_syntax_error_names_the_file(tmp_path):
    copy = tmp_path / "modelica"
    shutil.copytree(LIBRARY, copy)
    path = copy / "Judder" / "Examples" / "Driveline3DOF.mo"
    path.write_text(path.read_text().replace("equation", "equaton", 1))
    with pytest.raises(FrontEndError, match="Driveline3DOF"):
        _ode("Driveline3DOF", library=copy)
