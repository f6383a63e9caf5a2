"""``judder envelope``: ranges and samples (closed forms), the broadest
region containing held-back samples, resuming from a checkpoint, the
command line. The Dask run equal to the serial one: tests/test_parallel.py."""

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from numpy.testing import assert_allclose, assert_array_equal
from scipy.stats import norm

from sources import get_preset
from infra.errors import JudderError
from judder import api
from studies.envelope import read_ranges
from stability.uncertainty import (Correlated, Normal, Ranges, Uniform,
                                   build_envelope, design_points,
                                   sample_boundary)

ROOT = Path(__file__).resolve().parents[1]
FITTED = get_preset("paper-4dof-fitted")
# around the f2 single-period tongue of the fitted set (section 4.2): the
# three parameters the paper calls hard to estimate
RANGES = Ranges((Uniform("c12", 8.0, 12.0),
                 Uniform("k24", 0.97 * FITTED["k24"], 1.03 * FITTED["k24"]),
                 Normal("mu_g", 0.022, 0.001)))
FREQ = np.array([100.0, 104.0, 108.0, 112.0])
P_MAX_BAR = 0.6
SMALL = dict(samples=4, parameters=FITTED, refine=4, min_growth=1.0)


# --- ranges and samples -----------------------------------------------------

def test_ends_of_the_ranges_are_the_intervals_and_coverage_quantiles():
    values = RANGES.values(np.array([[0, 0, 0], [1, 1, 1], [0.5, 0.5, 0.5]]))
    z = norm.ppf(0.975)                       # coverage 0.95
    assert_allclose(values[0], [8.0, 0.97 * FITTED["k24"], 0.022 - z * 1e-3])
    assert_allclose(values[1], [12.0, 1.03 * FITTED["k24"], 0.022 + z * 1e-3])
    assert_allclose(values[2], [10.0, FITTED["k24"], 0.022])


@pytest.fixture(autouse=True)
def _chain(chain_by_default):
    """This module pins the chain's envelope."""



def test_design_is_the_vertices_then_a_sobol_sample():
    unit, vertex = design_points(RANGES, 5, seed=3)
    assert unit.shape == (13, 3) and vertex.sum() == 8
    assert {tuple(u) for u in unit[vertex]} == {
        (a, b, c) for a in (0, 1) for b in (0, 1) for c in (0, 1)}
    inside = unit[~vertex]
    assert np.all((inside > 0) & (inside < 1))
    assert_array_equal(design_points(RANGES, 5, seed=3)[0], unit)
    with pytest.raises(JudderError, match="sampler 'grid' is unknown"):
        design_points(RANGES, 5, sampler="grid")


def test_a_fit_covariance_is_reproduced_by_its_sample():
    # correlated normal (coverage near 1): the sample covariance of 4096
    # Sobol points is the given one
    cov = np.array([[4.0, 1.2], [1.2, 1.0]])
    ranges = Ranges((Correlated(("c12", "k24"), np.array([10.0, 5.0]), cov),),
                    coverage=0.999999)
    unit, _ = design_points(ranges, 4096, vertices=False)
    values = ranges.values(unit)
    assert_allclose(values.mean(axis=0), [10.0, 5.0], atol=0.01)
    assert_allclose(np.cov(values.T), cov, rtol=0.02, atol=0.02)


def test_probability_union_and_convergence_of_given_boundaries():
    # three random samples at two frequencies, boundaries in Pa; kinds in
    # the last axis (NaN: none)
    nan = np.nan
    amplitude = np.array([[[3e4, nan, nan], [nan, nan, nan]],
                          [[2e4, 5e4, nan], [4e4, nan, nan]],
                          [[nan, nan, 1e4], [nan, nan, nan]]])
    e = build_envelope([100.0, 110.0], 1e5, ["c12"], np.zeros((3, 1)),
                       np.zeros(3, bool), amplitude, np.ones(3, bool),
                       amplitude[0], amplitudes=11)
    assert_allclose(e.broadest, [1e4, 4e4])
    # at 100 Hz: unstable from 1e4 (one), 2e4 (two), 3e4 (all three)
    assert_allclose(e.probability[0, [0, 1, 2, 3]], [0, 1 / 3, 2 / 3, 1])
    assert_allclose(e.probability[1, [3, 4, 10]], [0, 1 / 3, 1 / 3])
    c = e.convergence
    # the last sample (10 % of 3, rounded up) lowered 100 Hz from 2e4 to 1e4
    assert c["last"] == 1 and c["max_drop_bar"] == pytest.approx(0.1)
    # trapezoid over 10 Hz: heights 0.9 and 0.6 bar, before 0.8 and 0.6
    assert c["area_bar_hz"] == pytest.approx(7.5)
    assert c["added_area_bar_hz"] == pytest.approx(0.5)


# --- exact boundaries -------------------------------------------------------

@pytest.fixture(scope="module")
def serial():
    return api.envelope(RANGES, FREQ, P_MAX_BAR, workers=1, driveline="chain",
                        **SMALL)


def test_held_back_samples_lie_inside_the_broadest_region(serial):
    e = serial.envelope
    assert not serial.failures and e.ok.all()
    assert np.isfinite(e.broadest).sum() >= 3
    assert np.all(e.edge <= e.sampled)
    unit, _ = design_points(RANGES, 6, seed=11, vertices=False)
    for row in RANGES.values(unit):
        tongue = sample_boundary((FITTED, RANGES.names, row, FREQ,
                                  P_MAX_BAR * 1e5, "dyson", 1.0))
        assert e.contains(tongue, tolerance=1e-3), row     # 1e-3 Pa


def test_the_drawn_bands_follow_each_samples_boundary(serial):
    # the figure's bands (issue 46: stair-stepped before) come from each
    # sample's boundary, linear between the study's frequencies: at those
    # frequencies they are the grid's probability, halfway between two
    # they count the samples whose two neighbouring values average below
    e = serial.envelope
    p = e.p_f
    assert np.allclose(e.probability_at(e.freq_hz, p), e.probability)
    low = e.lowest[e.random]
    i = int(np.argmax(np.isfinite(low).all(axis=0)[:-1]
                      & np.isfinite(low).all(axis=0)[1:]))
    assert np.isfinite(low[:, i:i + 2]).all()     # a pair was found
    middle = 0.5 * (e.freq_hz[i] + e.freq_hz[i + 1])
    expected = (0.5 * (low[:, i] + low[:, i + 1])[:, None]
                <= p[None, :]).mean(axis=0)
    assert np.allclose(e.probability_at([middle], p)[0], expected)
    assert np.allclose(e.quantile_at(e.freq_hz, 0.5),
                       e.quantile_boundary(0.5), equal_nan=True)


def test_an_interrupted_envelope_resumes_from_its_checkpoint(tmp_path,
                                                              serial):
    checkpoint = tmp_path / "e.checkpoint.npz"
    calls = []

    def stop_after_three(done, total):
        calls.append(done)
        if done >= 3:
            raise KeyboardInterrupt
    with pytest.raises(KeyboardInterrupt):
        api.envelope(RANGES, FREQ, P_MAX_BAR, workers=1, refine=0,
                     checkpoint=checkpoint, progress=stop_after_three,
                     **{k: v for k, v in SMALL.items() if k != "refine"})
    assert checkpoint.exists()
    again = api.envelope(RANGES, FREQ, P_MAX_BAR, workers=1, refine=0,
                         checkpoint=checkpoint,
                         **{k: v for k, v in SMALL.items() if k != "refine"})
    assert again.resumed == 3
    assert_array_equal(again.envelope.amplitude, serial.envelope.amplitude)
    with pytest.raises(JudderError, match="belongs to another envelope"):
        api.envelope(RANGES, FREQ[:2], P_MAX_BAR, workers=1, refine=0,
                     checkpoint=checkpoint,
                     **{k: v for k, v in SMALL.items() if k != "refine"})


# --- files and command line -------------------------------------------------

def test_ranges_file_with_a_fit_covariance(tmp_path):
    fit = {"fitted": {"c12": {"value": 10.0, "std": 2.0},
                      "k24": {"value": 1.2e5, "std": 3e3}},
           "covariance": {"names": ["c12", "k24"],
                          "matrix": [[4.0, 3e3], [3e3, 9e6]]}}
    (tmp_path / "fit.json").write_text(json.dumps(fit))
    (tmp_path / "r.toml").write_text(
        'coverage = 0.9\n[parameters]\nmu_g = [0.02, 0.024]\n'
        'J2 = { relative = [0.9, 1.1] }\n[fit]\nfile = "fit.json"\n')
    ranges = read_ranges(tmp_path / "r.toml", FITTED)
    assert ranges.names == ("mu_g", "J2", "c12", "k24")
    assert ranges.coverage == 0.9
    assert ranges.items[1].low == pytest.approx(0.9 * FITTED["J2"])
    assert_allclose(ranges.items[2].covariance, [[4.0, 3e3], [3e3, 9e6]])


@pytest.mark.parametrize("text, words", [
    ("[parameters]\nc13 = [1, 2]\n", ["c13", "allowed names"]),
    ("[parameters]\nc12 = [3, 2]\n", ["c12", "low < high"]),
    ("[parameters]\nc12 = { distribution = \"beta\" }\n", ["beta", "normal"]),
    ("[parameters]\nmu_g = { distribution = \"normal\", mean = 0.02 }\n",
     ["mu_g", "std is missing"]),
    ("colour = 1\n", ["colour"]),
])
def test_bad_ranges_are_refused_naming_the_key(tmp_path, text, words):
    (tmp_path / "r.toml").write_text(text)
    with pytest.raises(JudderError) as caught:
        read_ranges(tmp_path / "r.toml", FITTED)
    for word in words:
        assert word in str(caught.value)


def test_the_command_refuses_a_range_the_model_does_not_allow(tmp_path):
    (tmp_path / "r.toml").write_text("[parameters]\nc12 = [-5, 2]\n")
    proc = subprocess.run(
        [sys.executable, "-m", "judder", "envelope", "--ranges",
         str(tmp_path / "r.toml"), "--freq", "100:110:2", "--workers", "1"],
        capture_output=True, text=True, cwd=ROOT, timeout=120)
    assert proc.returncode == 2, proc.stderr
    assert "Traceback" not in proc.stderr
    assert proc.stderr.count("\n") == 1
    assert "c12" in proc.stderr and "-5" in proc.stderr


def test_the_command_writes_npz_csv_plot_and_json(tmp_path):
    out, table, plot = (tmp_path / "e.npz", tmp_path / "e.csv",
                        tmp_path / "e.png")
    proc = subprocess.run(
        [sys.executable, "-m", "judder", "envelope", "--ranges",
         str(ROOT / "examples" / "ranges.toml"), "--preset",
         "paper-4dof-fitted", "--freq", "104:108:2", "--pf-max", "0.6",
         "--samples", "2", "--refine", "0", "--workers", "1", "--out",
         str(out), "--csv", str(table), "--plot", str(plot), "--json"],
        capture_output=True, text=True, cwd=ROOT, timeout=300)
    assert proc.returncode == 0, proc.stderr
    data = json.loads(proc.stdout)
    assert data["samples"] == 8 + 2 and data["vertices"] == 8
    assert data["min_growth_per_s"] == 1.0
    with np.load(out) as arrays:
        assert arrays["amplitude_bar"].shape == (10, 2, 3)
        # every axis named, and the kinds of the last one
        assert list(arrays["amplitude_bar_axes"]) == ["sample", "freq_hz",
                                                      "kind"]
        assert list(arrays["kind_columns"]) == [
            "single-period", "double-period", "combination"]
        # the broadest edge is the lowest of every kind of every sample
        # (refine 0: nothing between the samples)
        ok = arrays["ok"]
        assert_allclose(np.nanmin(arrays["amplitude_bar"][ok], axis=(0, 2)),
                        arrays["broadest_bar"])
        assert_allclose(arrays["broadest_bar"], data["broadest_p_f_bar"])
    lines = table.read_text().splitlines()
    assert lines[0].startswith("freq_hz,nominal_p_f_bar,broadest_p_f_bar")
    # the overwrite rule's mark, last (the header first, for a spreadsheet)
    assert lines[-1].startswith("# written by judder ")
    assert len(lines) == 4
    assert plot.read_bytes()[:4] == b"\x89PNG"
    assert not (tmp_path / "e.npz.checkpoint.npz").exists()


def test_envelope_edges_close_on_the_top_of_the_axes():
    # each stretch of finite edge joins the top at its neighbouring
    # frequencies (where the edge rose above p_max), so the drawn region
    # is closed and holds the shading (issue 33: it was open at the top)
    from stability.plots.envelope import closed_edge
    nan = np.nan
    f, p = closed_edge(np.arange(6.0), [nan, 0.5, 0.4, nan, nan, 0.3], 1.0)
    assert_allclose(f, [0, 1, 2, 3, nan, 4, 5, 5])
    assert_allclose(p, [1, 0.5, 0.4, 1, nan, 1, 0.3, 1])
    f, p = closed_edge(np.arange(3.0), [nan, nan, nan], 1.0)
    assert f.size == 0 and p.size == 0
