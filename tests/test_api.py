"""The Python API: one function per command, the same numbers as the
command line, the engine registry through every study."""

import json
import subprocess
import sys

import numpy as np
import pytest
from numpy.testing import assert_allclose

from drivelines import get_model
from sources import get_preset
from infra.errors import JudderError
from judder import api
from judder.cli import build_parser
from stability.monodromy import METHODS

BAR = 1e5


@pytest.fixture(autouse=True)
def _chain(chain_by_default):
    """This module pins the chain's numbers."""



def _cli_json(*args):
    proc = subprocess.run([sys.executable, "-m", "judder", *args, "--json"],
                          capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    return json.loads(proc.stdout)


def _commands():
    parser = build_parser()
    sub = next(a for a in parser._actions if a.dest == "command")
    return set(sub.choices)


def test_every_command_has_one_api_function():
    names = {"map": "stability_map"}
    for command in _commands():
        assert callable(getattr(api, names.get(command, command)))
    assert len(_commands()) == len(api.__all__)


def test_api_gives_the_numbers_of_the_command_line():
    # tongue tips of Fig. 14 (tongue 2 at f2 = 102.9 Hz), by both routes
    freqs = np.linspace(80.0, 130.0, 26)
    result = api.tongues(freqs, 1.5).as_dict()
    cli = _cli_json("tongues", "--freq", "80:130:26", "--driveline", "chain")
    assert [t["number"] for t in result["tongues"]] == \
        [t["number"] for t in cli["tongues"]]
    assert_allclose([t["tip_p_f_bar"] for t in result["tongues"]],
                    [t["tip_p_f_bar"] for t in cli["tongues"]], rtol=1e-12)
    two = next(t for t in result["tongues"] if t["number"] == 2)
    assert two["tip_freq_hz"] == pytest.approx(102.88, rel=5e-3)


def test_changes_are_applied_on_top_of_the_parameters():
    # Eq. (16): c12 = 10 gives the 16.8 % of section 4.2
    result = api.eig(get_preset("paper-4dof"), {"c12": 10.0})
    assert result.damping_factor_12 == pytest.approx(0.168, abs=5e-4)
    assert result.params["c12"] == 10.0


def test_threshold_takes_the_mean_pressure_unless_changed():
    assert api.threshold([0.0], [0.1]).params["mean_pressure_damping"] == 1
    half = api.threshold([0.0], [0.1],
                         changes={"mean_pressure_damping": 0.5})
    assert half.params["mean_pressure_damping"] == 0.5
    # the threshold scales with 1 / (mean_pressure_damping p_m)
    assert half.study.threshold == pytest.approx(-2.5e-5, rel=1e-9)


@pytest.mark.parametrize("method", sorted(METHODS))
def test_tongues_with_every_engine(method):
    # combination tongue 5 (f2 - f1 = 83.9 Hz) and single-period tongue 2:
    # every engine gives the same boundaries
    freqs = [83.0, 84.0, 102.9]
    result = api.tongues(freqs, 1.0, method=method)
    reference = api.tongues(freqs, 1.0, method="dyson")
    assert result.boundaries.method == method
    assert_allclose(result.boundaries.amplitude,
                    reference.boundaries.amplitude, rtol=1e-7)
    assert result.boundaries.max_multiplier_error < 1e-6


def test_sensitivity_and_fit_take_the_engine():
    freqs = np.array([100.0, 102.9, 106.0])
    study = api.sensitivity(["k24"], freqs, 1.0, factors=[1.06],
                            method="solve_ivp", workers=1)
    assert study.method == "solve_ivp"
    assert study.study.nominal.boundaries.method == "solve_ivp"
    measured = api.tongues(freqs, 1.0).boundaries.stability_boundary
    report = api.fit(freqs, measured / BAR, 1.0, names=["mu_g"],
                     method="solve_ivp", min_growth=0.0)
    assert report.fit.success
    assert report.fit.values[0] == pytest.approx(0.017, rel=1e-5)


def test_unknown_engine_lists_the_engines():
    with pytest.raises(JudderError, match="dyson, solve_ivp"):
        api.tongues([100.0], 1.0, method="euler")


def test_crosscheck_takes_the_engine():
    # inside tongue 2: both views say unstable, with either engine
    result = api.crosscheck([102.9], [0.3], duration=2.0,
                            method="solve_ivp", workers=1)
    point = result.check.points[0]
    assert result.method == "solve_ivp"
    assert point.floquet_unstable and point.time_unstable
    assert point.floquet_rate == pytest.approx(2.652, abs=1e-3)


def test_run_fmu_refuses_a_parameter_the_fmu_lacks():
    from fmu.store import ensure_fmu
    from pysim.simulation.runs import run_fmu
    fmu = ensure_fmu(get_model("4dof").modelica_class)
    with pytest.raises(JudderError, match="J24"):
        run_fmu(fmu, 100.0, 0.0, params=get_preset("paper-3dof"),
                duration=0.01)


def test_simulate_needs_a_driveline_with_a_bench_model():
    with pytest.raises(JudderError, match="bench"):
        api.simulate(100.0, 0.1, parameters=get_preset("paper-3dof"))


@pytest.mark.parametrize("call, words", [
    (lambda: api.floquet(2e5, 0.3), "freq_hz = 200000 Hz"),
    (lambda: api.stability_map([10.0, -1.0], [0.0, 0.3]), "freq_hz = -1 Hz"),
    (lambda: api.tongues([100.0], 0.0), "p_max_bar = 0 bar"),
    (lambda: api.sensitivity(["c12"], [100.0], np.nan), "p_max_bar = nan"),
    (lambda: api.check([100.0], [-0.1]), "p_f_bar = -0.1 bar"),
    (lambda: api.crosscheck([100.0], [np.inf]), "p_f_bar = inf bar"),
])
def test_the_api_validates_its_values_once(call, words):
    # the same rule as the command line's (judder.commands._values), at
    # the API; the kernels below trust their inputs
    with pytest.raises(JudderError, match=words.replace("(", r"\(")):
        call()
