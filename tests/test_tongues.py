"""Tongue boundaries (Hill's method, monodromy) and tips (Fig. 14, 16)."""

import numpy as np
import pytest
from numpy.testing import assert_allclose

from sources import get_preset
from infra.errors import JudderError
from stability import KINDS, build_driveline, floquet, natural_frequencies
from stability.monodromy import monodromy_solve_ivp
from stability.hill import modal_transfer, real_boundaries
from stability.kinds import Kind
from stability.tongues import find_tongues, resonance_of, tongue_boundaries

BAR = 1e5
GRID = np.linspace(10.0, 220.0, 211)


@pytest.fixture(scope="module")
def paper_tongues(paper4):
    boundaries = tongue_boundaries(paper4, GRID, 1.5 * BAR)
    return boundaries, find_tongues(paper4, boundaries)


@pytest.mark.parametrize("freq, multiplier", [
    (100.0, 1), (102.9, 1), (110.0, 1), (20.0, 1),
    (37.9, -1), (205.8, -1), (39.5, -1)])
def test_hill_boundary_is_a_multiplier_on_the_unit_circle(paper4, freq,
                                                          multiplier):
    # independent check: a tight solve_ivp monodromy at the Hill amplitude
    system = paper4.periodic_system()
    p = real_boundaries(modal_transfer(system), [freq], multiplier)[0, 0]
    lam = np.linalg.eigvals(monodromy_solve_ivp(system, freq, [p],
                                                rtol=1e-12, atol=1e-14)[0])
    assert np.abs(lam - multiplier).min() < 1e-6


@pytest.mark.parametrize("freq, multiplier, exact_bar", [
    # the lowest root of det(M(p_f) - multiplier I) by Brent's method on
    # a solve_ivp monodromy (rtol 1e-13), to 10 digits
    (20.0, 1, 0.2173594551), (100.0, 1, 0.3641545256),
    (130.0, 1, 3.4040183125), (200.0, 1, 10.9737812939),
    (45.0, -1, 3.1715192139), (200.0, -1, 1.3934439216)])
def test_hill_boundary_is_the_exact_floquet_boundary(paper4, freq,
                                                     multiplier, exact_bar):
    system = paper4.periodic_system()
    p = real_boundaries(modal_transfer(system), [freq], multiplier)[0, 0]
    assert p / BAR == pytest.approx(exact_bar, rel=1e-9)
    # and the monodromy's det(M - multiplier I) changes sign across it
    below, above = monodromy_solve_ivp(system, freq,
                                       [p * (1 - 1e-9), p * (1 + 1e-9)],
                                       rtol=1e-13, atol=1e-15)
    eye = np.eye(len(system.A0))
    assert (np.linalg.det(below - multiplier * eye)
            * np.linalg.det(above - multiplier * eye)) < 0


def test_hill_truncation_is_converged(paper4):
    g = modal_transfer(paper4.periodic_system())
    for freq, mult in [(102.9, 1), (60.0, 1), (205.8, -1)]:
        few = real_boundaries(g, [freq], mult, harmonics=6)[0, 0]
        many = real_boundaries(g, [freq], mult, harmonics=30)[0, 0]
        assert few == pytest.approx(many, rel=1e-10)


def test_every_boundary_point_checked_against_monodromy(paper_tongues):
    boundaries, _ = paper_tongues
    # the six tongues span about 74 Hz at 1.5 bar: 72 points of a 1 Hz grid
    assert np.isfinite(boundaries.amplitude).sum() > 60
    assert boundaries.max_multiplier_error < 1e-6


def test_boundary_separates_stable_from_unstable(paper4, paper_tongues):
    boundaries, _ = paper_tongues
    for i in [9, 93, 28, 74, 112, 196]:   # inside tongues 1, 2, 3, 5, 6, 4
        column = int(np.nanargmin(boundaries.amplitude[i]))
        p = boundaries.amplitude[i, column]
        above = floquet(paper4, GRID[i], p * (1 + 1e-4))
        below = floquet(paper4, GRID[i], p * (1 - 1e-4))
        assert above.kind == KINDS[column + 1]
        assert below.kind == "stable"


# Tips of Fig. 14 within 0.5 % in frequency of Eq. (15) and its combinations
@pytest.mark.parametrize("number, kind, resonance", [
    (1, "single-period", lambda f1, f2: f1),
    (2, "single-period", lambda f1, f2: f2),
    (3, "double-period", lambda f1, f2: 2 * f1),
    (4, "double-period", lambda f1, f2: 2 * f2),
    (5, "combination", lambda f1, f2: f2 - f1),
    (6, "combination", lambda f1, f2: f1 + f2),
])
def test_tongue_tips_at_the_resonances(paper4, paper_tongues, number, kind,
                                       resonance):
    _, tongues = paper_tongues
    tongue = next(t for t in tongues if t.number == number)
    expected = resonance(*natural_frequencies(paper4))
    assert tongue.kind == kind
    assert tongue.tip_freq_hz == pytest.approx(expected, rel=5e-3)
    assert tongue.tip_multiplier_error < 1e-6
    assert 0 < tongue.tip_p_f < 0.3 * BAR   # a few tenths of a bar at most
    assert not tongue.tip_at_edge


def test_tips_are_refined_below_the_grid(paper4, paper_tongues):
    boundaries, tongues = paper_tongues
    tip = next(t for t in tongues if t.number == 2)
    assert tip.tip_p_f <= np.nanmin(boundaries.amplitude[:, 0])


def test_boundaries_scale_exactly_with_mu_g(paper4):
    # mu_g only multiplies p_f when the mean pressure is left out
    doubled = build_driveline(get_preset("paper-4dof").replace(mu_g=0.034))
    freqs = [18.0, 37.9, 84.0, 102.9]
    base = tongue_boundaries(paper4, freqs, 2 * BAR).amplitude
    scaled = tongue_boundaries(doubled, freqs, 1 * BAR).amplitude
    finite = np.isfinite(scaled)
    assert finite.sum() >= 4
    assert_allclose(scaled[finite], base[finite] / 2, rtol=1e-7)


def _tips(preset, **changes):
    driveline = build_driveline(get_preset(preset).replace(**changes))
    boundaries = tongue_boundaries(driveline, GRID, 1.5 * BAR)
    return {t.number: t for t in find_tongues(driveline, boundaries)
            if t.number}


def test_clutch_damper_damping_study(paper_tongues):
    # Fig. 16b / 18b, c12 from 0.5 to 10 N m s/rad
    _, tongues = paper_tongues
    low = {t.number: t for t in tongues}
    high = _tips("paper-4dof", c12=10.0)
    assert 3 not in high                                  # tongue 3 vanishes
    for n in (5, 6):                                      # combination tongues
        assert high[n].tip_p_f > 0.7 * BAR                # above 0.7 bar
    for n in (1, 4):                                      # contract strongly
        assert high[n].tip_p_f > 3 * low[n].tip_p_f
    # tongue 2 barely moves: same frequency, tip still far below 0.7 bar
    assert high[2].tip_freq_hz == pytest.approx(low[2].tip_freq_hz, rel=2e-3)
    assert high[2].tip_p_f < 0.1 * BAR


def test_3dof_has_one_single_and_one_double_period_tongue():
    tips = _tips("paper-3dof")
    assert set(tips) == {1, 2}
    assert tips[1].kind == "single-period"
    assert tips[1].tip_freq_hz == pytest.approx(18.047, rel=5e-3)
    assert tips[2].kind == "double-period"
    assert tips[2].tip_freq_hz == pytest.approx(2 * 18.047, rel=5e-3)


def test_free_rotation_is_refused():
    free = build_driveline(get_preset("paper-4dof").replace(
        c1=0.0, c2=0.0, c3=0.0, c4=0.0))
    with pytest.raises(JudderError, match="c_i"):
        modal_transfer(free.periodic_system())


def test_tongue_reaching_the_grid_edges(paper4):
    # tongue 2 spans the whole 95-110 Hz grid below 1.5 bar
    freqs = np.linspace(95.0, 110.0, 20)
    boundaries = tongue_boundaries(paper4, freqs, 1.5 * BAR)
    tongues = find_tongues(paper4, boundaries)
    tongue2 = next(t for t in tongues if t.number == 2)
    assert tongue2.freq_range_hz == (95.0, 110.0)
    assert not tongue2.tip_at_edge


def test_tongue_range_is_where_the_boundary_exists(paper_tongues):
    boundaries, tongues = paper_tongues
    for tongue in tongues:
        low, high = tongue.freq_range_hz
        inside = (GRID >= low) & (GRID <= high)
        column = KINDS.index(tongue.kind) - 1
        assert np.all(np.isfinite(boundaries.amplitude[inside, column]))


@pytest.mark.parametrize("growth", [1.0, 2.0])
def test_growth_boundary_is_where_the_exponent_reaches_the_rate(paper4,
                                                                 growth):
    # the boundary of the shifted system exp(-g t) z: on it the Floquet
    # exponent ln|lambda|/T of the driveline equals g (Eq. 12-13)
    freqs = [102.5, 102.9, 103.3]
    b = tongue_boundaries(paper4, freqs, 1.5e5, min_growth=growth)
    assert b.min_growth == growth
    for f, p in zip(freqs, b.amplitude[:, 0]):
        assert floquet(paper4, f, p).growth_rate == pytest.approx(
            growth, abs=1e-6)
    stable = tongue_boundaries(paper4, freqs, 1.5e5)
    assert np.all(b.amplitude[:, 0] > stable.amplitude[:, 0])


def test_a_tongue_of_higher_order_is_labelled(paper4):
    # up to 3 bar the paper's 4-DOF driveline has a double-period tongue
    # at 2 f2 / 3 (68.6 Hz, Mathieu's third tongue of mode 2): labelled,
    # without a number of Fig. 14
    freqs = np.linspace(64.0, 72.0, 33)
    boundaries = tongue_boundaries(paper4, freqs, 3 * BAR)
    tongue, = find_tongues(paper4, boundaries)
    f2 = natural_frequencies(paper4)[1]
    assert tongue.kind == "double-period"
    assert tongue.resonance == "2f2/3" and tongue.number is None
    assert tongue.resonance_hz == pytest.approx(2 * f2 / 3, rel=1e-12)
    assert tongue.tip_freq_hz == pytest.approx(2 * f2 / 3, rel=0.03)


def test_the_nearest_resonance_of_the_kind_names_a_tongue():
    # f1 = 30, f2 = 100 Hz: a combination tongue tipped at 65.2 Hz grows
    # from (f1 + f2) / 2 = 65 Hz, not from f2 - f1 = 70 Hz (7 % away, once
    # taken for it); one at 69.5 Hz from f2 - f1, tongue 5 of Fig. 14
    assert resonance_of(65.2, Kind.COMBINATION, [30.0, 100.0])[:3] == \
        (None, "(f1+f2)/2", 65.0)
    assert resonance_of(69.5, Kind.COMBINATION, [30.0, 100.0])[:3] == \
        (5, "f2-f1", 70.0)
    assert resonance_of(20.0, Kind.SINGLE_PERIOD, [30.0, 100.0])[1] is None
