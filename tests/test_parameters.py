"""Parameter presets, overrides, validation and TOML files."""

import math

import pytest

from drivelines import SPECS
from sources import dumps_toml, get_preset, load_toml
from infra.errors import ParameterError


@pytest.mark.parametrize("preset, name, value", [
    # Appendix A, 4 DOFs model
    ("paper-4dof", "J1", 1.12), ("paper-4dof", "J2", 0.231),
    ("paper-4dof", "J3", 4.07), ("paper-4dof", "J4", 0.122),
    ("paper-4dof", "k12", 3856.0), ("paper-4dof", "k24", 32885.0),
    ("paper-4dof", "c12", 0.5), ("paper-4dof", "c24", 0.1),
    ("paper-4dof", "c3", 0.1), ("paper-4dof", "mu0", 0.09),
    ("paper-4dof", "mu_g", 0.017),
    # Appendix A, 3 DOFs model
    ("paper-3dof", "J24", 0.353), ("paper-3dof", "k", 3451.0),
    ("paper-3dof", "c", 0.5),
    # section 4.2: c12 = 10, mu_g = 0.022, k24 about 6 % higher
    ("paper-4dof-fitted", "c12", 10.0), ("paper-4dof-fitted", "mu_g", 0.022),
    ("paper-4dof-fitted", "k24", 32885.0 * 1.06),
])
def test_preset_values(preset, name, value):
    assert get_preset(preset)[name] == pytest.approx(value, rel=1e-12)


def test_clutch_product_and_default_option():
    p = get_preset("paper-4dof")
    assert p.clutch_factor == pytest.approx(6e-3, rel=1e-12)
    assert p["mean_pressure_damping"] == 0.0
    assert p["p_m"] == 1e6  # about 10 bar on the EVEN clutch, section 2.2


def test_overrides_apply_and_validate():
    p = get_preset("paper-4dof").with_overrides(["c12=10", " mu_g = -0.01 "])
    assert (p["c12"], p["mu_g"]) == (10.0, -0.01)


@pytest.mark.parametrize("assignment, words", [
    ("J1=-1", ["J1", "-1", "> 0"]),
    ("J1=0", ["J1", "> 0"]),
    ("c12=nan", ["c12", "nan"]),
    ("k24=inf", ["k24", "inf"]),
    ("mean_pressure_damping=1.5", ["mean_pressure_damping", "<= 1"]),
    ("N_c=2.5", ["N_c", "integer"]),
    ("J5=1", ["J5", "unknown", "J1"]),
    ("c12", ["NAME=VALUE"]),
    ("c12=ten", ["c12", "not a number"]),
])
def test_bad_overrides_name_the_parameter(assignment, words):
    with pytest.raises(ParameterError) as info:
        get_preset("paper-4dof").with_overrides([assignment])
    for word in words:
        assert word in str(info.value)


def test_3dof_names_are_refused_on_4dof():
    with pytest.raises(ParameterError, match="J24"):
        get_preset("paper-4dof").replace(J24=1.0)


def test_unknown_preset_lists_presets():
    with pytest.raises(ParameterError, match="paper-4dof-fitted"):
        get_preset("paper-5dof")


@pytest.mark.parametrize("preset", ["paper-3dof", "paper-4dof",
                                    "paper-4dof-fitted"])
def test_toml_round_trip(preset):
    p = get_preset(preset).with_overrides(["mu_g=0.0123"])
    back = load_toml(dumps_toml(p))
    assert back.model == p.model
    assert back.as_dict() == p.as_dict()


def test_toml_partial_file_uses_paper_values():
    p = load_toml('model = "4dof"\n[parameters]\nc12 = 10.0\n')
    assert p["c12"] == 10.0 and p["J4"] == 0.122


@pytest.mark.parametrize("text, words", [
    ('model = "4dof"\n[parameters]\nJ4 = -0.1\n', ["my.toml", "J4"]),
    ('model = "5dof"\n', ["my.toml", "5dof"]),
    ("model = \n", ["my.toml", "TOML"]),
    # a misspelt table would otherwise be ignored and the paper's values used
    ('model = "4dof"\n[parameter]\nc12 = 10.0\n', ["my.toml", "parameter"]),
])
def test_toml_errors_name_the_file(text, words):
    with pytest.raises(ParameterError) as info:
        load_toml(text, source="my.toml")
    for word in words:
        assert word in str(info.value)


def test_every_spec_has_unit_and_description():
    for specs in SPECS.values():
        for spec in specs.values():
            assert spec.unit and spec.description
            assert not math.isnan(spec.lower)
