"""The bench's parameters come from its model: names, units, ranges and
defaults as its ``Judder.Data`` records declare them, which are the ones
the bench FMU's model description declares."""

import math

import pytest

from infra.errors import JudderError
from judder.commands._model import parse_bench
from stability.bench import bench_parameters, check_bench
from sources import get_preset

PAPER = get_preset("paper-4dof")


def test_the_bench_parameters_are_the_bench_class_own():
    parameters = bench_parameters(PAPER)
    # the records TestBenchData and BoundedCurveData declare these,
    # besides the driveline's Appendix A values and the dither's
    assert set(parameters) == {"t_engage", "t_ramp", "N_c_load", "p_load",
                               "load_share", "w_motor", "w_gearbox",
                               "d_control", "tau_max", "delta_mu", "w_op"}
    assert parameters["w_motor"].unit == "rad/s"
    assert parameters["w_motor"].default == pytest.approx(1000 * math.pi / 30)
    assert parameters["d_control"].unit == "N m s/rad"
    assert parameters["d_control"].default == 2000.0
    assert parameters["p_load"].unit == "Pa"
    assert parameters["N_c_load"].unit == "1"
    assert parameters["N_c_load"].low == 1.0
    assert parameters["delta_mu"].low == 1e-6
    # a time of the bench starts at the run's start at the earliest:
    # t_engage = -1 was run from -0.5 s (issue 44)
    assert parameters["t_engage"].low == 0.0


def test_the_records_are_what_the_bench_fmu_declares():
    """The bench's records (read without a compiler) and the FMU the
    compiler builds from the class that extends them declare the same
    parameters, units, ranges, defaults and run length; the orbit's
    clutch regularisation is the curve clutch's."""
    from fmu.store import model_description, parameter_default
    from fmu.units import base_exponents
    from infra.units import UNITS
    from stability.orbit import EngagementModel
    from studies.bench import bench_fmu
    fmu = bench_fmu(PAPER)[1]
    description = model_description(fmu)
    declared = {v.name: v for v in description.modelVariables}
    for name, parameter in bench_parameters(PAPER).items():
        variable = declared[name]
        assert variable.causality == "parameter"
        exponents, factor = base_exponents(variable.unit or "1")
        assert (UNITS[parameter.unit].dimension, UNITS[parameter.unit].factor
                ) == (exponents, factor), name
        assert float(variable.start) == parameter.default, name
        assert (-math.inf if variable.min is None else float(variable.min)
                ) == parameter.low, name
        assert (math.inf if variable.max is None else float(variable.max)
                ) == parameter.high, name
        assert variable.description == parameter.description, name
    assert float(parameter_default(fmu, "clutch.w_small")) == \
        EngagementModel.w_small
    from drivelines.records import experiment_stop_time
    assert experiment_stop_time(PAPER.driveline.bench_class) == \
        float(description.defaultExperiment.stopTime)


def test_the_bench_views_build_no_fmu(monkeypatch):
    """The orbit and the Floquet view of the bench read its records:
    no FMU is built or unpacked for them."""
    def refused(*args, **kwargs):
        raise AssertionError("an FMU was asked for")
    monkeypatch.setattr("fmu.store.ensure_fmu", refused)
    monkeypatch.setattr("fmu.store.model_description", refused)
    from judder import api
    result = api.orbit([105.0], [0.2], parameters=PAPER)
    assert len(result.rows()) == 1
    assert len(api.check([105.0], [0.2], parameters=PAPER).records()) == 1


def test_text_is_read_in_the_declared_unit():
    bench = parse_bench(["w_motor=1500rpm", "p_load = 9.8bar",
                         "t_ramp=200ms"], PAPER)
    assert bench == pytest.approx({"w_motor": 1500 * math.pi / 30,
                                   "p_load": 9.8e5, "t_ramp": 0.2})


@pytest.mark.parametrize("bench, words", [
    ({"w_gearbox": -1.0}, ["w_gearbox", "at least 0 rad/s"]),
    ({"N_c_load": 0.5}, ["N_c_load", "at least 1"]),
    ({"delta_mu": float("nan")}, ["delta_mu", "nan"]),
    ({"w_moter": 1.0}, ["'w_moter'", "w_motor"]),
])
def test_values_outside_the_declared_range_are_refused(bench, words):
    with pytest.raises(JudderError) as error:
        check_bench(PAPER, bench)
    for word in words:
        assert word in str(error.value)


def test_a_class_without_a_bench_takes_no_bench_parameter():
    from sources.modelica import ModelicaParameters
    values = ModelicaParameters("Judder.Examples.Driveline4DOF")
    # the study's words (`bench`), which the command line says as --bench
    with pytest.raises(JudderError, match="`bench` w_motor is not allowed "
                                          "with the class"):
        parse_bench(["w_motor=100"], values)
