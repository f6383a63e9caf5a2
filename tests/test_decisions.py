"""Decisions: fast Hill boundaries, judder relevance, check margins, advice.

Reference values are independent computations: the per-frequency 'scan'
solver (Hill + Brent on the Dyson monodromy), solve_ivp monodromies, Floquet
growth rates at the reported points, natural frequencies (Eq. 15), and the
paper's ranking (section 4.3, section 5).
"""

import json
from pathlib import Path
import subprocess
import sys

import numpy as np
import pytest
from numpy.testing import assert_allclose

from sources import get_preset
from infra.criteria import DEFAULT_MIN_GROWTH_PER_S
from infra.errors import JudderError
from judder import api
from stability import build_driveline, floquet, natural_frequencies
from stability.decisions.advice import (CLEARANCE, PRUNE_BELOW,
                                        OperatingRange, _clear,
                                        window_boundary)
from stability.decisions.margins import search_grid, setting_margin
from stability.decisions.relevance import is_judder_relevant
from stability.hill import combination_boundaries, modal_transfer
from stability.monodromy import monodromy_solve_ivp
from stability.tongues import lowest_boundaries
from facts import names

EXAMPLES = Path(__file__).parents[1] / "examples"

BAR = 1e5
#: Frequencies through all six tongues of Fig. 14 and between them.
FREQS = np.array([17.0, 19.0, 21.0, 37.0, 38.5, 81.0, 83.5, 86.0, 99.0,
                  102.5, 106.0, 119.0, 121.5, 124.0, 203.0, 207.0, 60.0])


@pytest.fixture(autouse=True)
def _chain(chain_by_default):
    """This module pins the paper chain's and the example chain's
    numbers (the tool judges a preset on its bench unless told)."""



@pytest.mark.parametrize("preset", ["paper-4dof", "paper-4dof-fitted"])
def test_hill_solver_equals_the_scan_solver(preset):
    # every kind, every frequency: same points found, same amplitudes
    system = build_driveline(get_preset(preset)).periodic_system()
    fast = lowest_boundaries(system, FREQS, 1.5 * BAR, solver="hill")
    scan = lowest_boundaries(system, FREQS, 1.5 * BAR, solver="scan")
    assert np.array_equal(np.isfinite(fast), np.isfinite(scan))
    assert np.isfinite(fast[:, 2]).sum() >= 4     # combination points present
    # Brent on the monodromy stops at xtol = 1e-9 p_max
    assert_allclose(fast[np.isfinite(fast)], scan[np.isfinite(scan)],
                    rtol=1e-7)


def test_hill_solver_finds_the_narrow_combination_tongue_of_the_geared_5dof():
    # the f3 - f1 = 95.6 Hz tongue sits next to a mode damped 5e-3 1/s;
    # Newton from the first-order seed alone missed 94, 94.5, 96, 97 Hz
    from sources.modelica import ModelicaParameters
    system = build_driveline(ModelicaParameters(
        "Judder.Examples.Driveline5DOFGeared",
        values={"w_slip": 2.6})).periodic_system()
    freqs = np.linspace(80.0, 110.0, 61)
    fast = lowest_boundaries(system, freqs, 1.5 * BAR, solver="hill")
    scan = lowest_boundaries(system, freqs, 1.5 * BAR, solver="scan")
    assert np.array_equal(np.isfinite(fast), np.isfinite(scan))
    assert np.isfinite(fast[(freqs >= 94) & (freqs <= 97), 2]).all()
    assert_allclose(fast[np.isfinite(fast)], scan[np.isfinite(scan)],
                    rtol=1e-8)


@pytest.mark.parametrize("freq", [83.0, 84.5, 121.0, 122.5])
def test_combination_boundary_is_a_complex_pair_on_the_unit_circle(paper4,
                                                                   freq):
    system = paper4.periodic_system()
    p, nu = combination_boundaries(modal_transfer(system), [freq], 1.5 * BAR)
    lam = np.linalg.eigvals(monodromy_solve_ivp(system, freq, [p[0]],
                                                rtol=1e-12, atol=1e-14)[0])
    pair = lam[np.abs(lam.imag) > 1e-6]
    assert np.abs(np.abs(pair) - 1).min() < 1e-7
    # the argument of the pair is nu T (mod 2 pi, up to sign)
    angle = np.abs(np.angle(pair[np.argmin(np.abs(np.abs(pair) - 1))]))
    assert angle == pytest.approx(nu[0] / freq, rel=1e-6)


@pytest.mark.parametrize("freq, column", [(102.9, 0), (121.8, 2), (37.9, 1)])
def test_boundary_of_a_growth_rate_grows_at_that_rate(paper4, freq, column):
    rate = 2.0
    system = paper4.periodic_system().shifted(rate)
    p = lowest_boundaries(system, [freq], 3 * BAR)[0, column]
    assert floquet(paper4, freq, p).growth_rate == pytest.approx(rate,
                                                                 rel=1e-7)


def test_judder_relevance_rule():
    assert DEFAULT_MIN_GROWTH_PER_S == 1.0      # one e-fold per 1 s engagement
    assert is_judder_relevant([0.02, 0.99, 1.01, np.nan]).tolist() == \
        [False, False, True, False]
    with pytest.raises(JudderError, match="min_growth"):
        is_judder_relevant([1.0], -1.0)


def test_map_counts_only_judder_relevant_growth():
    # the slow slip-speed dome of a stiffly damped clutch damper (README)
    slow = api.stability_map([60.0], [1.2], changes={"c12": 10.0},
                             min_growth=1.0)
    assert slow.map.kind[0, 0] == 1 and 0 < slow.map.growth_rate[0, 0] < 0.1
    assert slow.as_dict()["judder_relevant_points"] == 0
    assert api.stability_map([60.0], [1.2], changes={"c12": 10.0},
                             min_growth=0.0).judder_relevant_points() == 1


def test_map_text_names_unstable_and_judder_points_and_its_times():
    from judder.commands.map import count_words, time_words
    result = api.stability_map(np.linspace(60, 130, 15),
                               np.linspace(0, 1.2, 7), changes={"c12": 10.0},
                               min_growth=1.0, exact=True)
    counts = result.map.counts()
    unstable = int(np.count_nonzero(result.map.kind > 0))
    judder = result.judder_relevant_points()
    assert 0 < judder < unstable      # the slow dome of c12 = 10
    # every count, with the threshold it was counted at: the points, the
    # unstable ones by kind, the judder ones, the forced ones above the
    # limit and the union
    names(count_words(result), "105 points", f"{counts['stable']} stable",
          f"{unstable} unstable", "|lambda| > 1",
          *[f"{k} {v}" for k, v in counts.items() if k != "stable"],
          f"{judder} judder", ">= 1 1/s", "30 rpm",
          f"{int((result.forced_amplitude_rpm() > 30).sum())}",
          f"{int(result.judder_points().sum())}")
    names(time_words(result, 9.5), f"{result.seconds:.2f} s", "9.50 s")


@pytest.mark.parametrize("freq, p_bar, inside", [(102.9, 0.3, True),
                                                  (101.5, 0.3, False),
                                                  (83.0, 0.3, False)])
def test_margins_are_exact_points_of_the_growth_boundary(paper4, freq, p_bar,
                                                         inside):
    rate = 1.0
    system = paper4.periodic_system().shifted(rate)
    m = setting_margin(system, freq, p_bar * BAR, 1.5 * BAR,
                       search_grid([freq]))
    assert m.inside is inside
    assert np.sign(m.margin_hz) == np.sign(m.margin_p_f) == \
        (-1 if inside else 1)
    # at the bar margin and at the Hz margin the response grows at `rate`
    at_bar = floquet(paper4, freq, m.boundary_p_f).growth_rate
    at_hz = floquet(paper4, m.crossing_hz, p_bar * BAR).growth_rate
    assert at_bar == pytest.approx(rate, rel=1e-6)
    assert at_hz == pytest.approx(rate, rel=1e-6)


def test_check_reports_verdict_margins_and_the_strongest_parameters():
    result = api.check([102.9, 60.0], [0.3, 0.3],
                       sensitivity=["J1", "J3", "J4", "k24"])
    inside, outside = result.records()
    assert inside["verdict"] == "JUDDER"
    assert inside["margin_hz_tongue"]["number"] == 2
    assert inside["e_folding_time_s"] == pytest.approx(
        1 / inside["growth_rate_per_s"])
    assert outside["verdict"] == "STABLE" and outside["margin_hz"] > 20
    # tongue 2 grows from f2: its edge moves with f2 (Eq. 15) under k24,
    # J1 and J3 hardly move it (section 4.3)
    sens = {r["parameter"]: r["margin_hz_per_unit_log"]
            for r in inside["sensitivity"]}
    params = get_preset("paper-4dof")
    step = 1e-3
    f2 = [natural_frequencies(build_driveline(params.replace(
        k24=params["k24"] * (1 + s))))[1] for s in (step, -step)]
    elasticity = np.log(f2[0] / f2[1]) / np.log((1 + step) / (1 - step))
    # inside, the margin is minus the distance to the edge above f0
    assert -sens["k24"] == pytest.approx(inside["crossing_hz"] * elasticity,
                                         rel=0.05)
    assert [r["parameter"] for r in inside["sensitivity"]][:2] == ["k24",
                                                                  "J4"]
    assert abs(sens["J3"]) < 1e-2 * abs(sens["k24"])
    assert abs(sens["J1"]) < 1e-2 * abs(sens["k24"])


def test_check_speaks_one_vocabulary_with_fields_that_say_what_they_mean():
    from infra.criteria import VERDICTS
    # the growth's words apart from the forced response's: a limit no
    # forced oscillation here reaches (the chain's resonance forces 102.9
    # Hz, 0.05 bar to judder at the default 30 rpm, below)
    result = api.check([102.9, 60.0, 102.9], [0.3, 0.3, 0.05],
                       sensitivity=["J4", "k24"], judder_limit_rpm=1000)
    records = result.records()
    judder, stable, slow = records
    assert [r["verdict"] for r in (judder, slow, stable)] == list(VERDICTS)
    forced = api.check([102.9], [0.05], sensitivity=()).records()[0]
    assert forced["settled_amplitude_rpm"] > 30
    assert (forced["verdict"], forced["mechanism"]) == ("JUDDER", "forced")
    # 102.9 Hz, 0.05 bar: inside tongue 2 (|lambda| > 1) but growing at
    # 0.0947 1/s, slower than the judder-relevant 1 1/s
    assert slow["inside_stability_tongue"] and not slow["judder_relevant"]
    assert slow["tongue"]["number"] == 2
    assert judder["inside_stability_tongue"] and judder["judder_relevant"]
    assert not stable["inside_stability_tongue"] and stable["tongue"] is None
    driveline, *lines = result.summary().splitlines()
    assert "chain" in driveline
    for record, line in zip(records, lines):
        assert line.split(": ")[1].startswith(record["verdict"])
    # the text line shows the parameters that move the margin most, in
    # the JSON's order, per +10 % (0.1 of the per-unit-log value)
    top = judder["sensitivity"][0]
    assert top["parameter"] == "k24"
    assert (f"margin per +10 %: k24 "
            f"{0.1 * top['margin_hz_per_unit_log']:+.2f} Hz, J4") in lines[0]
    # no frequency reaches judder at 0.05 bar: said in words, with the
    # range searched, and true at every frequency of that range
    low, high = slow["frequency_search_hz"]
    assert (low, high) == pytest.approx((60.0 / 4, 102.9 * 4))
    assert slow["margin_hz"] is None
    names(lines[2], "0.05 bar", f"{low:.3g} to {high:.3g} Hz")
    paper4 = build_driveline(get_preset("paper-4dof"))
    rates = [floquet(paper4, f, 0.05e5).growth_rate
             for f in np.geomspace(low, high, 400)]
    assert max(rates) < DEFAULT_MIN_GROWTH_PER_S
    assert "no tongue edge" not in result.summary()
    # both thresholds, named: judder (>= 1 1/s) for the margin, and where
    # the setting's frequency becomes unstable (|lambda| = 1, growth 0)
    onset = slow["unstable_boundary_p_f_bar"]
    assert floquet(paper4, 102.9, onset * BAR).growth_rate == pytest.approx(
        0.0, abs=1e-9)
    assert onset < 0.05 < slow["boundary_p_f_bar"]
    names(lines[2], "0.098 bar below judder", ">= 1 1/s", "tongue 2",
          "|lambda| > 1", f"102.9 Hz from {onset:.3f} bar")


def test_floquet_names_the_threshold_its_point_passes():
    from studies.inputs import load_parameters
    example = load_parameters(param_file=EXAMPLES / "driveline.toml")
    slow = api.floquet(105, 0.2, example)      # README: growing at 0.56 1/s
    assert slow.result.growth_rate == pytest.approx(0.5625, abs=5e-5)
    assert slow.verdict() == "SLOW GROWTH"
    assert slow.as_dict()["verdict"] == "SLOW GROWTH"
    names(slow.verdict_words(), "|lambda| > 1", "0.5625 1/s", ">= 1 1/s")
    assert api.floquet(105, 0.2, example, min_growth=0.5).verdict() == \
        "JUDDER"
    assert api.floquet(102.9, 0.3).verdict() == "JUDDER"
    assert api.floquet(60, 0.3).verdict() == "STABLE"


def test_tongues_give_where_each_tongue_becomes_unstable_and_judder():
    from studies.inputs import load_parameters
    example = load_parameters(param_file=EXAMPLES / "driveline.toml")
    result = api.tongues(np.linspace(10, 220, 211), parameters=example)
    data = result.as_dict()
    assert data["min_growth_per_s"] == 0.0
    assert data["judder_min_growth_per_s"] == DEFAULT_MIN_GROWTH_PER_S
    two = next(t for t in data["tongues"] if t["number"] == 2)
    # README: tongue 2 unstable from 0.054 bar at 105.8 Hz
    assert two["tip_freq_hz"] == pytest.approx(105.8, abs=0.05)
    assert two["tip_p_f_bar"] == pytest.approx(0.054, abs=5e-4)
    driveline = build_driveline(example)
    assert floquet(driveline, two["tip_freq_hz"], two["tip_p_f_bar"] * BAR
                   ).growth_rate == pytest.approx(0.0, abs=1e-6)
    # judder from the tip of the 1 1/s boundary, above the unstable one
    late = floquet(driveline, two["judder_tip_freq_hz"],
                   two["judder_tip_p_f_bar"] * BAR).growth_rate
    assert late == pytest.approx(DEFAULT_MIN_GROWTH_PER_S, rel=1e-6)
    assert two["judder_tip_p_f_bar"] > 4 * two["tip_p_f_bar"]
    from judder.commands.tongues import tip_table
    text = "\n".join(tip_table(data))
    assert "unstable from" in text and "judder (>= 1 1/s) from" in text
    assert (f"{two['tip_p_f_bar']:.4f} bar at {two['tip_freq_hz']:.3f} Hz"
            in text)
    assert (f"{two['judder_tip_p_f_bar']:.4f} bar at "
            f"{two['judder_tip_freq_hz']:.3f} Hz") in text


def test_tongues_check_floquet_and_sensitivity_agree_between_thresholds():
    """Acceptance of issue 33: a setting between tongue 2's two tips (at
    its tip frequency, above where it becomes unstable and below where it
    judders) is SLOW GROWTH to check and floquet and inside the tongue
    whose unstable tip tongues and sensitivity give; above the judder tip
    both say JUDDER, below the unstable tip STABLE. check's tongue tip is
    the judder tip of tongues, named so in both JSONs."""
    from studies.inputs import load_parameters
    example = load_parameters(param_file=EXAMPLES / "driveline.toml")
    freqs = np.linspace(10, 220, 211)
    tips = api.tongues(freqs, parameters=example).as_dict()
    two = next(t for t in tips["tongues"] if t["number"] == 2)
    unstable, judder = two["tip_p_f_bar"], two["judder_tip_p_f_bar"]
    assert unstable < judder           # 0.0542 and 0.2327 bar
    f = two["tip_freq_hz"]
    settings = [0.5 * unstable, 0.5 * (unstable + judder), 1.2 * judder]
    records = api.check([f] * 3, settings, example,
                        sensitivity=()).records()
    assert [r["verdict"] for r in records] == \
        ["STABLE", "SLOW GROWTH", "JUDDER"]
    assert [api.floquet(f, p, example).verdict() for p in settings] == \
        ["STABLE", "SLOW GROWTH", "JUDDER"]
    between = records[1]
    assert 0 < between["growth_rate_per_s"] < DEFAULT_MIN_GROWTH_PER_S
    # check's two boundaries at the tip frequency are the tips of tongues
    assert between["unstable_boundary_p_f_bar"] == pytest.approx(unstable,
                                                                 rel=2e-3)
    assert between["boundary_p_f_bar"] == pytest.approx(judder, rel=2e-3)
    assert between["tongue"]["judder_tip_p_f_bar"] == pytest.approx(
        judder, rel=1e-6)
    assert "tip_p_f_bar" not in between["tongue"]
    # sensitivity's nominal tips are the unstable ones of tongues
    sens = api.sensitivity(["c12"], freqs, 1.5, values=[10.0],
                           parameters=example, workers=1).as_dict()
    nominal = next(t for t in sens["nominal_tongues"] if t["number"] == 2)
    assert nominal["tip_p_f_bar"] == pytest.approx(unstable, rel=1e-9)


def test_advise_reproduces_the_paper_and_clears_the_window():
    """Acceptance: section 4.3/5 ranking, and a design whose recomputed map
    has no judder-relevant point in 60-200 Hz x 0-0.7 bar (k24 may triple:
    the default bounds, halved to doubled, hold no design, below)."""
    result = api.advise(bounds={"k24": (0.5, 4.0)})
    ranking = [name for name, _, _ in result.ranking]
    assert set(ranking[:3]) == {"J2", "J4", "k24"}
    assert result.advice.success
    assert result.judder_points == 0
    assert result.verification.kind.size == 141 * 36
    factors = dict(zip(result.advice.names, result.advice.factors))
    assert factors["k24"] > 1 and factors["J4"] < 1   # tongues moved up
    # smallest along its ray: 90 % of the change does not clear it
    x = np.log(result.advice.factors)
    operating = OperatingRange()
    assert not _clear([result.params], result.advice.names, 0.9 * x,
                      operating, 1.0, 1.6 * BAR)
    assert _clear([result.params], result.advice.names, x, operating, 1.0,
                  1.6 * BAR)
    # k24 tripled moves f2 above the window: nothing is unstable there
    assert result.unstable == []
    assert "the advised design is stable" in result.summary()


#: The README's two advice commands on the fitted example: the default
#: bounds, and J4 held to -20 %..+25 % with c12 up to x5.
README_BOUNDS = {"default": {}, "J4 and c12 bounded": {"J4": (0.8, 1.25),
                                                       "c12": (0.5, 5.0)}}


@pytest.fixture(scope="module")
def example_advice():
    """``{case: AdviceResult}`` of :data:`README_BOUNDS`, each computed
    once for the tests below."""
    from studies.inputs import load_parameters
    example = load_parameters(param_file=EXAMPLES / "driveline.toml")
    return {case: api.advise(example, bounds=bounds, driveline="chain")
            for case, bounds in README_BOUNDS.items()}


def test_advise_within_bounds_or_says_there_is_none(example_advice):
    # the paper's driveline: within a factor 2 nothing clears 60-200 Hz
    nothing = api.advise(bounds={})
    assert not nothing.advice.success
    assert nothing.as_dict()["design"]["bounds"]["k24"] == [0.5, 2.0]
    design = next(line for line in nothing.summary().splitlines()
                  if line.startswith("design:"))
    names(design, "none", "J2 x0.5-2")
    # the fitted example with J4 held to -20 %..+25 % (and c12 up to x5)
    result = example_advice["J4 and c12 bounded"]
    example = result.params
    assert result.advice.success and result.judder_points == 0
    bounds = result.as_dict()["design"]["bounds"]
    for name, factor in zip(result.advice.names, result.advice.factors):
        low, high = bounds[name]
        assert low - 1e-12 <= factor <= high + 1e-12
    assert bounds["J4"] == [0.8, 1.25] and bounds["J2"] == [0.5, 2.0]
    # the change in the parameter's own unit beside the factor
    advised = result.advised_params()
    j4 = dict(zip(result.advice.names, result.advice.factors))["J4"]
    assert (f"J4 {example['J4']:.4g} -> {advised['J4']:.4g} kg m^2 "
            f"(x{j4:.3f})") in result.summary()
    # clear of judder, but tongue 2 is still unstable below 0.7 bar,
    # growing slower than 1 1/s: the advice says where, and it is so
    region = max(result.unstable, key=lambda r: r.freq_hz[1] - r.freq_hz[0])
    assert region.freq_hz[0] < 105 < region.freq_hz[1]
    driveline = build_driveline(advised)
    above = floquet(driveline, region.lowest_at_hz,
                    1.02 * region.lowest_p_f).growth_rate
    below = floquet(driveline, region.lowest_at_hz,
                    0.98 * region.lowest_p_f).growth_rate
    assert 0 < above < 1.0 and below < 0
    assert "still unstable (|lambda| > 1) but not judder" in result.summary()


@pytest.mark.parametrize("case", README_BOUNDS)
def test_advised_design_is_safe_over_the_whole_window_it_claims(
        example_advice, case):
    """The advice never contradicts itself: the design it says clears the
    window has the whole operating range, 60-200 Hz, as its safe window at
    the valve's highest amplitude (0.7 bar) in its own report, and its
    exact judder boundary, on a 0.05 Hz grid (ten times the safe windows'
    0.5 Hz), lies at or above 0.7 + 0.1 bar everywhere in 55-205 Hz, with
    at least half of the clearance (0.1 %) the search keeps on the 0.5 Hz
    grid (until this version the bounded case gave 0.79993 bar at 109 Hz
    and a safe window with a gap at 103.5-114.5 Hz)."""
    result = example_advice[case]
    assert result.advice.success
    design = result.as_dict()["design"]
    full = [w for w in design["safe_windows"] if w["full_range"]]
    assert full == [{"freq_hz": [60.0, 200.0], "max_p_f_bar": 0.7,
                     "full_range": True}]
    freqs = np.linspace(55, 205, 3001)
    boundary = window_boundary([result.advised_params()], freqs,
                               DEFAULT_MIN_GROWTH_PER_S, 1.6 * BAR)
    assert boundary.min() >= (1 + 0.5 * CLEARANCE) * 0.8 * BAR


def test_advise_lists_only_the_changes_the_design_needs(example_advice):
    """The README's example: the search ends with k12 x1.005 beside the
    changes that matter; it is dropped, as the window stays clear without
    it, and the design the advice lists still clears it."""
    result = example_advice["default"]
    example = result.params
    advice = result.advice
    assert advice.success
    factors = dict(zip(advice.names, advice.factors))
    # what was dropped was small, and is back at its nominal value
    assert set(advice.dropped) >= {"k12"}
    for name, factor in advice.dropped.items():
        assert 0 < abs(factor - 1) < PRUNE_BELOW
        assert factors[name] == 1.0
    # every change still listed is at least 3 %
    listed = {n: f for n, f in factors.items() if f != 1.0}
    assert listed and all(abs(f - 1) >= PRUNE_BELOW for f in listed.values())
    text = result.summary()
    assert "dropped as unnecessary" in text
    # one item dropped: 'without it', not 'without them'
    assert ("without it)" in text) == (len(advice.dropped) == 1)
    design_line = next(line for line in text.splitlines()
                       if line.startswith("design: "))
    assert "k12" not in design_line
    # the listed design clears the window: its exact judder boundary lies
    # above 0.7 + 0.1 bar over 55-205 Hz, and its recomputed map has no
    # point growing at 1 1/s or faster
    advised = result.advised_params()
    operating = OperatingRange()
    freqs = np.linspace(55, 205, 301)
    boundary = window_boundary([advised], freqs, DEFAULT_MIN_GROWTH_PER_S,
                               1.6 * BAR)
    assert boundary.min() >= 0.8 * BAR
    assert result.judder_points == 0
    growth = result.verification.growth_rate
    assert np.nanmax(growth) < DEFAULT_MIN_GROWTH_PER_S
    assert _clear([example], advice.names, np.log(advice.factors),
                  operating, DEFAULT_MIN_GROWTH_PER_S, 1.6 * BAR)
    # and it needs what is left: without its smallest change it does not
    smallest = min(listed, key=lambda n: abs(np.log(listed[n])))
    without = np.log([1.0 if n == smallest else f
                      for n, f in factors.items()])
    assert not _clear([example], advice.names, without, operating,
                      DEFAULT_MIN_GROWTH_PER_S, 1.6 * BAR)


@pytest.mark.parametrize("bound, words", [
    ("J4=2x:3x", "LOW <= 1x <= HIGH"), ("J4", "NAME=LOW:HIGH"),
    ("J4=0.8x:x", "followed by x"), ("mu_g=0.5x:2x", "--params"),
    ("J4=1x:1x", "LOW < HIGH"), ("J4=0.1:0.2", "LOW <= 1x <= HIGH")])
def test_advise_refuses_bad_bounds(bound, words):
    proc = _judder("advise", "--bounds", bound, "--no-design")
    assert proc.returncode == 2
    error = proc.stderr.splitlines()[-1]
    assert words in error and "--bounds" in error


def test_advise_bounds_are_values_or_factors_as_in_fit(capsys):
    # J4 = 0.122 kg m^2 nominal: 0.8x:1.25x and the same range in kg m^2
    # (with its unit: a plain number in advise is still the former factor
    # for this release, with a warning naming the new spelling) are one
    # range; fit reads the same text alike
    from judder.commands.advise import _factors
    from judder.commands._values import parse_bounds
    values = get_preset("paper-4dof")
    given = ("J4=0.8x:1.25x", "J4=0.0976kg*m^2:0.1525kg*m^2", "J4=0.8:1.25")
    factors = [_factors([text], values)["J4"] for text in given]
    assert factors[0] == pytest.approx((0.8, 1.25), rel=1e-12)
    assert factors[1] == pytest.approx((0.8, 1.25), rel=1e-12)
    assert factors[2] == pytest.approx((0.8, 1.25), rel=1e-12)
    assert "J4=0.8x:1.25x" in capsys.readouterr().err
    fitted = parse_bounds([given[0]], values, ["J4"], "--fit")
    assert fitted["J4"] == pytest.approx((0.8 * 0.122, 1.25 * 0.122))
    # in fit a plain number was and is a value, kg m^2
    assert parse_bounds([given[2]], values, ["J4"], "--fit")["J4"] == (
        0.8, 1.25)


def _judder(*args):
    return subprocess.run([sys.executable, "-m", "judder", *args],
                          capture_output=True, text=True, timeout=120)


def test_check_command_line(tmp_path):
    table = tmp_path / "dither.csv"
    table.write_text("freq_hz,p_f_bar\n60,0.2\n102.9,0.3\n")
    proc = _judder("check", "--table", str(table), "--params", "k24",
                   "--json", "--out", str(tmp_path / "c.csv"))
    assert proc.returncode == 0, proc.stderr
    data = json.loads(proc.stdout)
    assert [s["verdict"] for s in data["settings"]] == ["STABLE", "JUDDER"]
    text = (tmp_path / "c.csv").read_text()
    assert text.startswith("freq_hz,p_f_bar")
    assert text.splitlines()[-1].startswith("# written by judder ")
    summary = _judder("check", "--freq", "102.9", "--pf", "0.3", "--params",
                      "none")
    # the driveline judged (a preset: on its test bench), then one line
    # a setting
    assert summary.stdout.count("\n") == 2 and "JUDDER" in summary.stdout
    assert "test bench" in summary.stdout.splitlines()[0]
    proc = _judder("check", "--freq", "60", "--pf", "-1")
    assert proc.returncode == 2 and "--pf -1" in proc.stderr
    assert proc.stderr.count("\n") == 1


@pytest.mark.parametrize("text, words", [
    # a German table with a comment line: the line as the file numbers it
    ("freq_hz;p_f_bar\n60;0,2\n# second setting\n102,9;\n",
     "--table {path}, line 4: column 'p_f_bar' is empty; allowed: a "
     "dither amplitude >= 0 bar (every row is a setting to check)"),
    ("freq_hz,p_f_bar\n60,0.2\n,0.3\n",
     "--table {path}, line 3: column 'freq_hz' is empty; allowed: a "
     "frequency > 0 Hz"),
    ("freq_hz,p_f_bar\n# a comment\n60,0.2\n1e9,0.3\n",
     "--table {path}, line 4: column 'freq_hz' = 1e+09 Hz is not allowed; "
     "allowed: 0.001 to 100000 Hz")])
def test_check_names_the_line_and_column_of_an_empty_cell(tmp_path, capsys,
                                                          text, words):
    """Review of issue 31: an empty cell of --table is worded one way
    whichever column it is in and wherever it is found (the frequency's
    said neither the option nor the same "allowed"), and a frequency out
    of range names its line as the file numbers it (it said "row 3" for
    the fourth line of a file with a comment)."""
    from judder.cli import main
    table = tmp_path / "dither.csv"
    table.write_text(text)
    assert main(["check", "--table", str(table), "--params", "none"]) == 2
    assert capsys.readouterr().err.strip() == \
        "judder: error: " + words.format(path=table)


@pytest.mark.parametrize("kwargs, word", [
    ({"min_growth": float("nan")}, "min_growth"),
    ({"sensitivity": ["J9"]}, "J9"),
    ({"p_max_bar": 0.1}, "p_max")])
def test_check_refuses_bad_input(kwargs, word):
    with pytest.raises(JudderError, match=word):
        api.check([60.0], [0.2], **kwargs)


def test_windows_over_an_envelope_are_safe_for_every_set():
    # section 4.2: the broadest region over the uncertain parameters
    from stability.decisions.advice import safe_windows, window_boundary
    nominal = get_preset("paper-4dof")
    stiffer = nominal.replace(k24=1.06 * nominal["k24"], mu_g=0.022)
    operating = OperatingRange()
    grid = np.linspace(55.0, 205.0, 301)
    safe = {}
    for name, sets in [("nominal", [nominal]), ("stiffer", [stiffer]),
                       ("both", [nominal, stiffer])]:
        boundary = window_boundary(sets, grid, 1.0, 1.6 * BAR)
        safe[name], windows = safe_windows(grid, boundary, operating)
        if name == "nominal":
            # nothing safe at full amplitude next to f2 (tongue 2)
            assert not any(w.freq_hz[0] <= 102.9 <= w.freq_hz[1]
                           for w in windows if w.full_range)
        if name == "both":
            robust = [w for w in windows if w.full_range]
    assert_allclose(safe["both"], np.minimum(safe["nominal"],
                                             safe["stiffer"]))
    assert np.any(safe["both"] < safe["nominal"])
    assert robust
    assert floquet(build_driveline(nominal), 102.9, 0.7 * BAR).growth_rate > 1
    for window in robust:
        for f in window.freq_hz:
            for params in (nominal, stiffer):
                assert floquet(build_driveline(params), f,
                               0.8 * BAR).growth_rate < 1.0


def test_check_far_inside_a_tongue_answers():
    # 5 bar at 105 Hz: the batched boundaries on the search grid follow a
    # combination branch that a cold single-frequency solve misses; the
    # crossing is then known to the grid step (was a ValueError of brentq)
    from judder import api
    record = api.check([105.0], [5.0], sensitivity=()).records()[0]
    assert record["verdict"] == "JUDDER"
    assert record["margin_bar"] == pytest.approx(
        record["boundary_p_f_bar"] - 5.0)
    assert record["margin_hz"] < 0 and abs(record["margin_hz"]) < 50
    # how well that crossing is known: 0 (Brent's root) or half a step of
    # the 1200-point log grid (0.45 % of the frequency)
    assert 0 <= record["crossing_tolerance_hz"] < 3e-3 * record["crossing_hz"]
    exact = api.check([105.0], [0.2], sensitivity=()).records()[0]
    assert exact["crossing_tolerance_hz"] == 0.0


def test_advice_for_a_design_already_clear_says_none_is_needed(
        example_advice):
    """The advised design given back to advise: no change is needed, and
    the text says so (it printed "design: ; unchanged: ...")."""
    advice = next(iter(example_advice.values()))
    again = api.advise(advice.advised_params())
    assert again.advice.success
    assert all(abs(f - 1) <= 5e-4 for f in again.advice.factors)
    design = next(line for line in again.summary().splitlines()
                  if line.startswith("design:"))
    assert design.startswith(
        "design: none needed: the window is already clear; unchanged: ")
