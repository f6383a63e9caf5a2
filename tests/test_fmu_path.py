"""The FMU path (sources.fmus): a driveline read from an FMU's
directional derivatives against the symbolic path (sources.modelica)
on the project's own FMUs, and FMUs it must refuse."""

import json
import re
import subprocess
import sys
import zipfile

import numpy as np
import pytest
from numpy.testing import assert_allclose

from sources.fmus import FmuError, FmuParameters, linearize_fmu
from sources.modelica import linearize
from fmu.build import build_fmu
from infra.errors import ParameterError
from fmu.store import ensure_fmu
from stability import LinearDriveline, build_driveline, floquet

BAR = 1e5
FOUR = "Judder.Examples.Driveline4DOF"
TWO_CLUTCHES = "Judder.Examples.Driveline4DOFTwoClutches"


@pytest.fixture(scope="module")
def four_fmu():
    return ensure_fmu(FOUR)


def _same_system(ours, theirs):
    assert ours.state_names == theirs.state_names
    assert ours.values == theirs.values
    mine, yours = (LinearDriveline.from_model(m).reduction
                   for m in (ours, theirs))
    pairs = [(ours.A0, theirs.A0), (ours.B, theirs.B),
             (ours.omega2, theirs.omega2), (mine.A0, yours.A0),
             (mine.basis, yours.basis)]
    for a, b in pairs:
        assert_allclose(a, b, rtol=0, atol=1e-14 * max(np.abs(b).max(), 1))
    assert_allclose(mine.U @ mine.V.T, yours.U @ yours.V.T, rtol=0,
                    atol=1e-14 * np.abs(yours.U @ yours.V.T).max())


@pytest.mark.parametrize("values", [{}, {"c12": 10.0, "mu_g": 0.03,
                                         "p_f": 0.5 * BAR}])
def test_the_fmu_gives_the_symbolic_system(four_fmu, values):
    ours = linearize_fmu(four_fmu, values)
    theirs = linearize(FOUR, values=values)
    _same_system(ours, theirs)
    fmu_line = LinearDriveline.from_model(ours)
    assert fmu_line.reduction.rigid.shape[1] == 2
    assert fmu_line.reduction.rank == 1
    symbolic = LinearDriveline.from_model(theirs)
    for freq, p_f in [(102.9, 0.3 * BAR), (38.0, 1.2 * BAR),
                      (150.0, 0.05 * BAR)]:
        a = floquet(fmu_line, freq, p_f).multipliers
        b = floquet(symbolic, freq, p_f).multipliers
        assert np.abs(np.sort_complex(a) - np.sort_complex(b)).max() < 1e-10


def test_rank_two_fmu_and_the_parameter_set():
    path = ensure_fmu(TWO_CLUTCHES)
    params = FmuParameters(str(path)).with_overrides(["c12=2"])
    assert params.model == TWO_CLUTCHES and params["c12"] == 2.0
    ours = build_driveline(params)
    theirs = LinearDriveline.from_model(linearize(TWO_CLUTCHES,
                                                  values={"c12": 2.0}))
    assert ours.reduction.rank == 2
    a = floquet(ours, 102.9, 0.4 * BAR).multipliers
    b = floquet(theirs, 102.9, 0.4 * BAR).multipliers
    assert np.abs(np.sort_complex(a) - np.sort_complex(b)).max() < 1e-10
    with pytest.raises(ParameterError, match="'k99' is not a tunable"):
        params.with_overrides(["k99=1"])
    with pytest.raises(ParameterError, match=">= 0"):
        params.replace(c12=-1.0)


def _rewritten(source, target, edit):
    """A copy of an FMU with its modelDescription.xml edited."""
    with zipfile.ZipFile(source) as old, \
            zipfile.ZipFile(target, "w", zipfile.ZIP_DEFLATED) as new:
        for item in old.infolist():
            data = old.read(item)
            if item.filename == "modelDescription.xml":
                data = edit(data.decode()).encode()
            new.writestr(item, data)
    return target


def _close_system(ours, theirs, rtol):
    """``ours`` read by central differences: the symbolic system within
    their truncation error."""
    assert ours.state_names == theirs.state_names
    for a, b in ((ours.A0, theirs.A0), (ours.B, theirs.B)):
        assert_allclose(a, b, rtol=0, atol=rtol * np.abs(b).max())


def _same_multipliers(ours, theirs, tolerance):
    for freq, p_f in [(102.9, 0.3 * BAR), (38.0, 1.2 * BAR)]:
        a = floquet(LinearDriveline.from_model(ours), freq, p_f).multipliers
        b = floquet(LinearDriveline.from_model(theirs), freq,
                    p_f).multipliers
        assert np.abs(np.sort_complex(a) - np.sort_complex(b)).max() \
            < tolerance


@pytest.mark.parametrize("model", [FOUR, TWO_CLUTCHES])
def test_an_fmu_without_directional_derivatives_is_read_by_differences(
        tmp_path, model):
    # the Reference FMUs and many exporters declare none: the Jacobian is
    # then read by central differences of fmi2GetDerivatives
    plain = _rewritten(ensure_fmu(model), tmp_path / "plain.fmu",
                       lambda xml: xml.replace(
                           'providesDirectionalDerivative="true"', ""))
    values = {"c12": 2.0, "p_f": 0.4 * BAR}
    ours, theirs = linearize_fmu(plain, values), linearize(model,
                                                          values=values)
    _close_system(ours, theirs, 1e-8)
    _same_multipliers(ours, theirs, 1e-8)


def test_an_fmi3_fmu_gives_the_symbolic_system(tmp_path):
    from sources.modelica import LIBRARY
    source = LIBRARY.joinpath(*FOUR.split(".")).with_suffix(".mo")
    path = build_fmu(source, FOUR, tmp_path / "four3.fmu", version="3.0",
                     roots=[LIBRARY]).path
    ours, theirs = linearize_fmu(path), linearize(FOUR)
    _close_system(ours, theirs, 1e-8)
    _same_multipliers(ours, theirs, 1e-8)


@pytest.mark.parametrize("edit, message", [
    (lambda xml: re.sub(r"<ModelExchange.*?</ModelExchange>", "", xml,
                        flags=re.S), "Co-Simulation only")])
def test_an_fmu_without_what_is_needed_is_refused_in_one_line(
        four_fmu, tmp_path, edit, message):
    bad = _rewritten(four_fmu, tmp_path / "bad.fmu", edit)
    with pytest.raises(FmuError, match=message):
        linearize_fmu(bad)
    proc = _cli("floquet", "--fmu", str(bad), "--freq", "100", "--pf", "0.1")
    assert proc.returncode == 2, proc.stderr
    assert message in proc.stderr and len(proc.stderr.splitlines()) == 1


@pytest.fixture(scope="module")
def oscillator(oscillator_library):
    """The FMU of conftest's oscillator class."""
    root = oscillator_library
    return build_fmu(root / "MyLib" / "Oscillator.mo", "MyLib.Oscillator",
                     root / "Oscillator.fmu", roots=[root]).path


def test_the_form_of_the_dither_is_checked(oscillator):
    linear = linearize_fmu(oscillator, {"p_f": 0.5})
    # closed form: A0 = [[0, 1], [-100, -1]], B = -e2 e2^T
    assert_allclose(linear.A0, [[0, 1], [-100, -1]], rtol=1e-15)
    assert_allclose(linear.B, [[0, 0], [0, -1]], rtol=1e-15)
    assert LinearDriveline.from_model(linear).reduction.rigid.shape[1] == 0
    with pytest.raises(FmuError, match="does not enter as p_f"):
        linearize_fmu(oscillator, {"s": 1.0})
    with pytest.raises(FmuError, match="not affine in p_f"):
        linearize_fmu(oscillator, {"q": 1.0})
    with pytest.raises(FmuError, match="`amplitude` 'a'"):
        linearize_fmu(oscillator, amplitude="a")


def _cli(*args):
    return subprocess.run([sys.executable, "-m", "judder", *args],
                          capture_output=True, text=True, timeout=120)


def test_cli_fmu_equals_cli_modelica(four_fmu):
    common = ("--freq", "102.9", "--pf", "0.3", "--set", "c12=10", "--json")
    ours = _cli("floquet", "--fmu", str(four_fmu), *common)
    theirs = _cli("floquet", "--modelica", FOUR, *common)
    assert ours.returncode == theirs.returncode == 0, ours.stderr
    ours, theirs = json.loads(ours.stdout), json.loads(theirs.stdout)
    assert ours["model"] == FOUR and set(ours) == set(theirs)
    assert abs(ours["leading_abs"] - theirs["leading_abs"]) < 1e-10
    proc = _cli("map", "--fmu", str(four_fmu), "--modelica", FOUR)
    assert proc.returncode == 2
    assert "replaces --modelica" in proc.stderr
    assert "Traceback" not in proc.stderr


def test_cli_map_of_a_rank_two_fmu():
    # the map's memory check sized the series by the rank-one factor u
    path = ensure_fmu(TWO_CLUTCHES)
    proc = _cli("map", "--fmu", str(path), "--freq", "90:110:5", "--pf",
                "0:1:4", "--json")
    assert proc.returncode == 0, proc.stderr
    data = json.loads(proc.stdout)
    symbolic = LinearDriveline.from_model(linearize(TWO_CLUTCHES))
    lead = max(np.abs(floquet(symbolic, f, p * BAR).multipliers).max()
               for f in np.linspace(90, 110, 5) for p in np.linspace(0, 1, 4))
    assert abs(data["max_leading_abs"] - lead) < 1e-10


def test_sensitivity_through_the_fmu_equals_the_symbolic_path(four_fmu):
    from sources.modelica import ModelicaParameters
    from judder import api
    freq = np.linspace(95.0, 110.0, 6)
    ours, theirs = (api.sensitivity(["c12"], freq, parameters=params,
                                    workers=1).tip_shifts
                    for params in (FmuParameters(str(four_fmu)),
                                   ModelicaParameters(FOUR)))
    assert len(ours) == len(theirs) > 0
    for a, b in zip(ours, theirs):
        for key, value in b.items():
            if isinstance(value, float):
                assert a[key] == pytest.approx(value, rel=1e-9, abs=1e-9)
            else:
                assert a[key] == value
