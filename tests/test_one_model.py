"""One model in every view: the bench's maps, the check's verdict and the
orbit rest on the bench FMU's equations (issue 41)."""

import numpy as np
import pytest

from judder import api
from sources import get_preset
from stability.friction import forced_upstream_amplitude
from stability.modal import damped_modes
from stability.source import build_driveline

PRESET = "paper-4dof"


def test_bench_tip_1_is_the_bench_resonance_not_the_chains():
    # the bench's speed control (d_control on body 1) moves f1 from the
    # free chain's 18.94 Hz to 16.52 Hz; tongue 1's tip follows it
    from judder.bench import driveline_view
    params = get_preset(PRESET)
    bench = driveline_view(params, "bench")
    f1 = damped_modes(build_driveline(bench))[0][0]
    assert f1 == pytest.approx(16.52, abs=0.01)
    found = api.tongues(np.linspace(10, 30, 201), 1.0, params,
                        driveline="bench")
    tip_1 = next(t for t in found.tongues if t.number == 1)
    assert tip_1.tip_freq_hz == pytest.approx(f1, abs=0.1)
    chain = api.tongues(np.linspace(10, 30, 201), 1.0, params)
    assert next(t for t in chain.tongues
                if t.number == 1).tip_freq_hz == pytest.approx(18.94,
                                                               abs=0.1)
    assert found.as_dict()["driveline"] == "bench"


@pytest.mark.parametrize("freq_hz, p_f_bar", [
    (86.5, 0.5), (119.5, 0.6), (16.5, 0.3), (33.0, 0.75), (103.0, 0.3),
    (60.0, 0.3), (150.0, 0.5)])
def test_check_of_the_bench_gives_simulates_verdict(freq_hz, p_f_bar):
    # the verdict and mechanism of `check --driveline bench` (its orbit)
    # against the bench FMU's run judged as `simulate` judges it
    params = get_preset(PRESET)
    record = api.check([freq_hz], [p_f_bar], params, sensitivity=(),
                       driveline="bench").records()[0]
    run = api.simulate(freq_hz, p_f_bar, parameters=params).summaries[0]
    assert (record["verdict"] == "JUDDER") == run["judder"]
    if run["judder"]:
        assert record["mechanism"] == run["mechanism"]


def test_check_names_the_settled_oscillation_and_the_driveline():
    params = get_preset(PRESET)
    result = api.check([103.0], [0.3], params, sensitivity=())
    record = result.records()[0]
    # the chain's linear forced response, in closed form (Eq. 6 with D)
    expected = forced_upstream_amplitude(build_driveline(params), 103.0,
                                         0.3e5) * 30 / np.pi
    assert record["settled_amplitude_rpm"] == pytest.approx(expected,
                                                            rel=1e-12)
    assert record["verdict"] == "JUDDER"
    assert record["mechanism"] == "both"
    assert result.as_dict()["driveline"] == "chain"
    assert "chain" in result.summary().splitlines()[0]
    bench = api.check([103.0], [0.3], params, sensitivity=(),
                      driveline="bench")
    # forced: the orbit is stable (257 rpm) though the steady slip's
    # linearisation grows (+1.08 1/s)
    row = bench.records()[0]
    assert row["mechanism"] == "forced"
    assert row["settled_amplitude_rpm"] == pytest.approx(257, rel=0.02)
    assert "test bench" in bench.summary().splitlines()[0]


def test_a_driveline_outside_the_list_is_refused():
    with pytest.raises(Exception) as error:
        api.check([100.0], [0.2], get_preset(PRESET), driveline="rig")
    assert "'rig'" in str(error.value) and "bench" in str(error.value)
