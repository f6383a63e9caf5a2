"""Figures against golden images, and what each figure must show.

The golden PNGs under ``tests/golden/`` were drawn by this code (Agg, 72
dpi, matplotlib's bundled DejaVu fonts, the pinned matplotlib) and looked
at against the paper's figures; ``compare_images`` allows an RMS
difference of :data:`TOLERANCE` grey levels. After a matplotlib upgrade,
regenerate them with ``JUDDER_UPDATE_GOLDEN=1`` and look at them again.
"""

import os
from pathlib import Path

import matplotlib
import numpy as np
import pytest
from matplotlib.testing.compare import compare_images

from judder import api
from stability import floquet
from stability.plotting import (KIND_COLORS, boundary_curve,
                                multipliers_figure, tongues_figure)

matplotlib.use("Agg")

GOLDEN = Path(__file__).parent / "golden"
TOLERANCE = 1.0
BAR = 1e5


def _check(fig, name, tmp_path):
    import matplotlib.pyplot as plt
    actual = tmp_path / f"{name}.png"
    fig.savefig(actual, dpi=72)
    plt.close(fig)
    golden = GOLDEN / f"{name}.png"
    if os.environ.get("JUDDER_UPDATE_GOLDEN"):
        golden.parent.mkdir(exist_ok=True)
        golden.write_bytes(actual.read_bytes())
    assert golden.exists(), f"no golden image {golden}"
    problem = compare_images(str(golden), str(actual), tol=TOLERANCE)
    assert problem is None, problem


@pytest.fixture(scope="module")
def rc():
    # one BLAS thread, as the command line runs: the kernels work on many
    # tiny matrices, where threads only contend
    from threadpoolctl import threadpool_limits
    with matplotlib.rc_context({"font.family": "DejaVu Sans"}), \
            threadpool_limits(limits=1):
        yield


def test_fig15_multipliers_by_kind(rc, paper4, tmp_path):
    # the points of the reference notes: single-period 102.9 Hz 0.3 bar,
    # double-period 37.9 Hz 0.5 bar, combination 84 Hz 0.5 bar
    results = [floquet(paper4, f, p * BAR) for f, p in
               ((102.9, 0.3), (37.9, 0.5), (84.0, 0.5))]
    assert [r.kind for r in results] == ["single-period", "double-period",
                                         "combination"]
    fig = multipliers_figure(results, title="Fig. 15")
    # each leading multiplier in the colour of its kind
    for column, code in enumerate((1, 2, 3)):
        ax = fig.axes[column]
        lead = [line for line in ax.lines if line.get_marker() == "D"]
        assert matplotlib.colors.same_color(lead[0].get_color(),
                                            KIND_COLORS[code])
    _check(fig, "fig15", tmp_path)


def test_fig14_map_with_exact_boundaries(rc, tmp_path):
    result = api.stability_map(np.linspace(5, 250, 60),
                               np.linspace(0, 1.5, 30), exact=True)
    numbers = sorted(t.number for t in result.tongues if t.number)
    assert numbers == [1, 2, 3, 4, 5, 6]
    fig = result.figure(title="4dof, paper preset")
    left = fig.axes[0]
    # the numbers are drawn at the exact tips, not at grid cells
    labels = {a.get_text(): a.xy for a in left.texts}
    assert labels["2"][1] == pytest.approx(0.0275, abs=5e-4)
    assert labels["1"][1] == pytest.approx(0.0376, abs=5e-4)
    # the legend is outside the axes
    box = left.get_legend().get_window_extent(fig.canvas.get_renderer())
    assert box.x0 > left.get_window_extent().x1
    _check(fig, "fig14", tmp_path)


def test_tongues_without_map(rc, paper4, tmp_path):
    from stability.tongues import find_tongues, tongue_boundaries
    b = tongue_boundaries(paper4, np.linspace(10, 220, 80), 1.5 * BAR)
    fig = tongues_figure(b, find_tongues(paper4, b), title="tongues")
    _check(fig, "tongues", tmp_path)


def test_boundary_curve_inserts_tips_and_closes_tongues():
    f = np.array([1.0, 2.0, 3.0, 4.0, 5.0])
    a = np.array([np.nan, 0.5, 0.2, 0.6, np.nan])
    x, y = boundary_curve(f, a, tips=[(2.6, 0.1)], p_max_bar=1.0)
    # up from p_max at 2, down to the exact tip, back up to p_max at 4
    np.testing.assert_allclose(x, [2.0, 2.0, 2.6, 3.0, 4.0, 4.0])
    np.testing.assert_allclose(y, [1.0, 0.5, 0.1, 0.2, 0.6, 1.0])
    # a tongue at the edge of the grid stays open there
    x, y = boundary_curve(f, np.array([0.3, 0.4, np.nan, 0.5, 0.6]),
                          p_max_bar=1.0)
    np.testing.assert_allclose(x, [1, 2, 2, np.nan, 4, 4, 5])
    np.testing.assert_allclose(y, [0.3, 0.4, 1, np.nan, 1, 0.5, 0.6])
