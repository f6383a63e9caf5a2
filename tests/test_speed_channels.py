"""What a speed channel's samples are, and the angle they carry
(pysim.bench.speed_channels), against closed forms."""

import numpy as np
import pytest
from numpy.testing import assert_allclose

from pysim.simulation.campaigns import pickup_samples
from pysim.bench.speed_channels import detect_speed_kind, interval_means

#: A shaft at 1000 rpm with a 20 rpm oscillation at 103 Hz, rad and s.
OMEGA, AMPLITUDE, NU = 1000 * np.pi / 30, 20 * np.pi / 30, 2 * np.pi * 103


def _angle(t):
    return OMEGA * t + AMPLITUDE / NU * np.sin(NU * t)


def _rebuilt(time, speed):
    """The angle the analysis rebuilds: the sum of mean speed x interval."""
    return np.concatenate([[0.0], np.cumsum(speed[1:] * np.diff(time))])


@pytest.mark.parametrize("lost", [[500], list(range(0, 1300, 3))])
def test_lost_tooth_passages_keep_the_angle(lost):
    # a 41-tooth pick-up: the angle at its passages is a whole number of
    # pitches; with passages lost (a dropped sample, NaN removed) the
    # interval spans several while the speed there is that of one
    fine = np.arange(0.0, 2.0, 1e-6)
    t, rpm = pickup_samples(fine, _angle(fine), 41)
    keep = np.ones(len(t), bool)
    keep[lost] = False
    t, speed = t[keep], rpm[keep] * np.pi / 30
    assert detect_speed_kind(t, speed) == "passage"
    _, means = interval_means(t, speed, "passage")
    exact = _angle(t) - _angle(t[0])
    assert_allclose(_rebuilt(t, means), exact, atol=2e-3 * 2 * np.pi / 41)
    # read as they are, an interval over lost teeth counts the speed of
    # the one before its end: off by per cent of a pitch each time
    assert np.abs(_rebuilt(t, speed) - exact).max() > 0.01 * 2 * np.pi / 41


def test_sampled_speed_integrates_to_its_angle():
    # a DAQ's 2 kHz samples of the speed, 2 % lost: the spline's integral
    t = np.arange(0.0, 1.0, 5e-4)
    keep = np.random.default_rng(3).random(len(t)) > 0.02
    t = t[keep]
    speed = OMEGA + AMPLITUDE * np.cos(NU * t)
    assert detect_speed_kind(t, speed) == "sampled"
    end, means = interval_means(t, speed, "sampled")
    assert_allclose(end, t[1:])
    assert_allclose(_rebuilt(t, np.r_[0.0, means]), _angle(t) - _angle(0.0),
                    atol=1e-5)


def test_encoder_angle_gives_its_differences():
    t = np.arange(0.0, 0.5, 5e-4)
    wrapped = np.mod(_angle(t), 2 * np.pi)        # an angle within a turn
    _, means = interval_means(t, wrapped, "angle")
    assert_allclose(means, np.diff(_angle(t)) / np.diff(t), rtol=1e-9)
