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

from infra.plotstyle import KIND_COLORS
from judder import api
from stability import floquet
from stability.plots import (boundary_curve, multipliers_figure,
                             tongues_figure)

matplotlib.use("Agg")

GOLDEN = Path(__file__).parent / "golden"
EXAMPLES = Path(__file__).parents[1] / "examples"
TOLERANCE = 1.0
BAR = 1e5


@pytest.fixture(autouse=True)
def _chain(chain_by_default):
    """This module pins the paper's figures, of the chain."""



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


def test_map_legend_lists_only_the_kinds_drawn(rc):
    # 90-115 Hz up to 0.5 bar holds tongue 2 alone (single-period): no
    # double-period or combination patch or boundary in the legend
    # (issue 33); with tongue 4 (2 f2 = 205.8 Hz) the double-period too
    import matplotlib.pyplot as plt

    def legend(freq):
        result = api.stability_map(freq, np.linspace(0, 0.5, 20),
                                   exact=True)
        fig = result.figure()
        texts = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
        plt.close(fig)
        return texts
    alone = legend(np.linspace(90, 115, 40))
    assert "single-period" in alone
    assert not any(k in text for text in alone
                   for k in ("double-period", "combination"))
    both = legend(np.r_[np.linspace(90, 115, 40), np.linspace(200, 212, 30)])
    assert "double-period" in both and "combination" not in both


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


# --- colours that survive greyscale and colour-vision deficiency ---------

#: Machado, Oliveira & Fernandes (2009), severity 1: linear-RGB matrices
#: simulating protanopia, deuteranopia and tritanopia.
DICHROMACY = {
    "protanopia": [[0.152286, 1.052583, -0.204868],
                   [0.114503, 0.786281, 0.099216],
                   [-0.003882, -0.048116, 1.051998]],
    "deuteranopia": [[0.367322, 0.860646, -0.227968],
                     [0.280085, 0.672501, 0.047413],
                     [-0.011820, 0.042940, 0.968881]],
    "tritanopia": [[1.255528, -0.076749, -0.178779],
                   [-0.078411, 0.930809, 0.147602],
                   [0.004733, 0.691367, 0.303900]]}


def _fill_colours():
    """Every fill of a map: the kinds (stable white first) and the grey of
    slow growth, as 8-bit RGB."""
    from matplotlib.colors import to_rgb
    from infra.plotstyle import SLOW_COLOR
    return np.array([np.round(255 * np.array(to_rgb(c)))
                     for c in (*KIND_COLORS, SLOW_COLOR)], dtype=np.uint8)


def _greyscale(rgb8):
    """Grey levels (0-255) as an image converter makes them: PIL's
    ``convert('L')``, ITU-R 601-2 luma."""
    from PIL import Image
    image = Image.fromarray(rgb8.reshape(1, -1, 3), "RGB").convert("L")
    return np.asarray(image, dtype=float).ravel()


def test_kind_colours_stay_apart_in_greyscale():
    grey = _greyscale(_fill_colours())
    # every pair of fills (white, three kinds, slow grey) at least 15 % of
    # the grey range apart, so a greyscale print tells them apart
    gaps = np.abs(grey[:, None] - grey[None, :])[np.triu_indices(len(grey),
                                                                 1)]
    assert gaps.min() >= 0.15 * 255, grey


@pytest.mark.parametrize("kind", sorted(DICHROMACY))
def test_kind_colours_stay_apart_for_colour_blind_readers(kind):
    srgb = _fill_colours() / 255.0
    linear = np.where(srgb <= 0.04045, srgb / 12.92,
                      ((srgb + 0.055) / 1.055) ** 2.4)
    seen = np.clip(linear @ np.array(DICHROMACY[kind]).T, 0, 1)
    back = np.where(seen <= 0.0031308, 12.92 * seen,
                    1.055 * seen ** (1 / 2.4) - 0.055)
    grey = _greyscale(np.round(255 * back).astype(np.uint8))
    gaps = np.abs(grey[:, None] - grey[None, :])[np.triu_indices(len(grey),
                                                                 1)]
    assert gaps.min() >= 0.10 * 255, (kind, grey)


# --- no clipped or colliding text -----------------------------------------

def _text_problems(fig):
    """What :func:`infra.plotstyle.layout_problems` finds in ``fig``:
    texts that leave the figure or overlap another (tick labels, titles,
    axis labels, legends, annotations without their leaders, colour-bar
    labels), legends that do not list what is drawn, titles in more than
    engineering precision (empty: none)."""
    from infra.plotstyle import layout_problems
    return layout_problems(fig)


@pytest.fixture(scope="module")
def small_map():
    return api.stability_map(np.linspace(5, 250, 60), np.linspace(0, 1.5, 30),
                             exact=True, min_growth=1.0, driveline="chain")


def _figures(paper4, small_map):
    """One of each figure the commands draw, from small computations."""
    from studies.figures.check import check_figure
    yield "map", small_map.figure(title="stability map (Fig. 14), 4dof "
                                  "driveline, paper preset, c12=0.5")
    yield "tongues", tongues_figure(small_map.boundaries, small_map.tongues,
                                    small_map.map, title="tongues",
                                    min_growth=1.0)
    # two tips half a hertz apart (tongues 13 and 14 of BenchLib's
    # Driveline6DOF were): their numbers must not run together
    from dataclasses import replace
    first, second = small_map.tongues[:2]
    close = [replace(first, tip_freq_hz=88.0, tip_p_f=0.2 * BAR, number=13),
             replace(second, tip_freq_hz=88.5, tip_p_f=0.2 * BAR, number=14)]
    yield "close tips", tongues_figure(small_map.boundaries, close,
                                       title="close tips")
    yield "fig15", multipliers_figure(
        [floquet(paper4, f, p * BAR) for f, p in
         ((102.9, 0.3), (37.9, 0.5), (84.0, 0.5))], title="Fig. 15")
    yield "multipliers", multipliers_figure([floquet(paper4, 102.9, 0.3 * BAR)],
                                            title="one setting")
    check = api.check([102.9, 104.0, 60.0], [0.3, 0.3, 0.2],
                      sensitivity=())
    yield "check", check_figure(check.records(), small_map.map,
                                min_growth=1.0, title="check")
    sens = api.sensitivity(["c12"], np.linspace(10, 220, 40), 1.5,
                           values=[0.5, 2, 5, 10], workers=1)
    # the titles the commands give (judder/commands/*.py)
    yield "sensitivity-c12", sens.figure(
        title="sensitivity of the stability boundary (Fig. 17, 18), 4dof "
              "driveline, paper preset")
    yield "threshold", api.threshold(np.linspace(-1e-3, 1e-3, 21),
                                     np.linspace(0, 2, 11)).figure(
        title="4dof driveline, paper preset")
    yield "advice", api.advise(bounds={"k24": (0.5, 4.0)},
                               background=True).figure(
        title="4dof driveline, paper preset")
    from sources import get_preset
    yield "compare", api.compare(
        get_preset("paper-4dof"), get_preset("paper-4dof-fitted"),
        labels=("paper-4dof", "paper-4dof-fitted"),
        freq_hz=np.linspace(10, 220, 60), maps=True).figure(
        title="two presets")
    bench = Path(__file__).parents[1] / "examples" / "bench"
    yield "chart", api.chart([], index=bench / "runs.csv", channels={
        "upstream_speed": "EngSpd_up", "pressure": "PressEVEN:bar",
        "downstream_speed": "OutSpd"}, workers=1).figure(
        title="experimental stability chart")


def test_no_figure_text_is_clipped_or_collides(rc, paper4, small_map):
    import matplotlib.pyplot as plt
    found = {}
    for name, fig in _figures(paper4, small_map):
        problems = _text_problems(fig)
        plt.close(fig)
        if problems:
            found[name] = problems
    assert not found, found


def test_advice_legend_lists_only_the_kinds_its_map_draws(rc):
    # the example driveline advised over 90-120 Hz up to 0.5 bar: its wide
    # view (45-180 Hz up to 1 bar) holds tongues 1 and 2 (single-period)
    # only; tongue 4 (211.6 Hz) lies outside it and tongues 5, 6 above it
    # (1.13 and 1.12 bar, `judder tongues`): no double-period or
    # combination patch or boundary in the legend (issue 33)
    import matplotlib.pyplot as plt
    from studies.inputs import load_parameters
    example = load_parameters(param_file=EXAMPLES / "driveline.toml")
    advice = api.advise(example, freq_range=(90, 120), valve_max_bar=0.5,
                        background=True)
    assert advice.advice.success
    fig = advice.figure()
    texts = [t.get_text() for t in fig.axes[1].get_legend().get_texts()]
    plt.close(fig)
    assert "single-period" in texts
    assert "single-period boundary ($|\\lambda| = 1$)" in texts
    assert not any(kind in text for text in texts
                   for kind in ("double-period", "combination"))


def test_tongue_numbers_that_touch_are_set_apart(rc):
    # BenchLib.Driveline6DOF with J4=0.2 (README, step 6): tongue 13's
    # number ended 0.9 px past where 14's began, under the 1 px overlap
    # allowed, and the two read "1314" (issue 33); here the second number
    # starts 0.5 px before the first ends
    import matplotlib.pyplot as plt
    from infra.plotstyle import LABEL_GAP_PT, LABEL_GID, settle_labels
    fig, ax = plt.subplots(figsize=(6, 3), dpi=150)
    ax.set_xlim(0, 100)
    ax.set_ylim(0, 1)

    def number(text, x):
        return ax.annotate(text, (x, 0.5), textcoords="offset points",
                           xytext=(4, 1), fontsize=8, fontweight="bold",
                           gid=LABEL_GID)
    first = number("13", 50)
    fig.draw_without_rendering()
    renderer = fig.canvas.get_renderer()
    box = first.get_window_extent(renderer)
    hz_per_px = 100 / ax.get_window_extent(renderer).width
    second = number("14", 50 + (box.width - 0.5) * hz_per_px)
    fig.draw_without_rendering()
    assert second.get_window_extent(renderer).x0 < box.x1
    settle_labels(fig)
    one, two = (t.get_window_extent(renderer) for t in (first, second))
    gap = max(two.x0 - one.x1, two.y0 - one.y1)
    plt.close(fig)
    assert gap >= LABEL_GAP_PT * 150 / 72 - 1e-9


def test_fig19_says_how_far_off_the_scale_the_driveline_lies(rc):
    # the paper's mu_g = 0.017 s/rad is 17 times the axes' end (1e-3):
    # each panel's arrow points along its own mu_g axis (right on the
    # left panel, up on the right one) and says so (issue 33: the left
    # one pointed up into the corner, "(above)")
    import matplotlib.pyplot as plt
    fig = api.threshold(np.linspace(-1e-3, 1e-3, 21),
                        np.linspace(0, 2, 11)).figure()
    left, right = fig.axes[:2]
    notes = {ax: [t for t in ax.texts if "this driveline" in t.get_text()]
             for ax in (left, right)}
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    for ax, (note,) in notes.items():
        assert "off the scale" in note.get_text()
        assert "17 times the axis' end" in note.get_text()
        arrow = note.arrow_patch.get_window_extent(renderer)
        # where it points, in pixels: its y is a fraction of the axes
        tip_y = ax.transAxes.transform((0, note.xy[1]))[1]
        if ax is left:       # mu_g runs along x: the arrow points right
            tip_x = ax.transAxes.transform(note.xy)[0]
            assert arrow.x1 == pytest.approx(tip_x, abs=6)   # shrunk 2 pt
            assert arrow.x1 - arrow.x0 > 20 and arrow.height < 5
        else:                # along y: it points up, to the top
            assert arrow.y1 == pytest.approx(tip_y, abs=6)
            assert tip_y > ax.transAxes.transform((0, 0.95))[1]
            assert arrow.y1 - arrow.y0 > 10
    plt.close(fig)


def test_a_boundary_is_drawn_only_where_it_separates_stable_from_unstable():
    """Issue 33 (the geared 5-DOF map: tongues 9 and 10 drawn through
    tongue 3): a single-period tongue |f - 100| / 10 bar and a
    combination tongue 0.15 + |f - 95| / 2 bar overlap; each line stops
    where it enters the other tongue, at the crossings of the two V's
    (closed form), and is drawn everywhere else."""
    import matplotlib.pyplot as plt
    from stability.plots import plot_boundaries
    from stability.tongues import Boundaries
    freqs = np.linspace(80, 120, 401)
    single = np.abs(freqs - 100) / 10
    combination = 0.15 + np.abs(freqs - 95) / 2
    amplitude = np.full((len(freqs), 3), np.nan)
    amplitude[:, 0] = single * BAR
    amplitude[:, 2] = np.where(combination < 1.5, combination, np.nan) * BAR
    boundaries = Boundaries(freq_hz=freqs, p_max=1.5 * BAR,
                            amplitude=amplitude,
                            multiplier_error=np.zeros_like(amplitude),
                            natural_frequencies_hz=np.array([50.0]))
    fig, ax = plt.subplots()
    solid, dotted = plot_boundaries(boundaries, ax=ax, numbers=False)
    for line, own, other in ((solid, single, combination),
                             (dotted, combination, single)):
        x, y = line.get_xdata(), line.get_ydata()
        drawn = np.isfinite(y)
        low = np.interp(x, freqs, other)
        # nothing drawn inside the other tongue, everything outside it
        assert np.all(y[drawn] <= low[drawn] + 1.5 / 1000 + 1e-12)
        on_curve = np.isfinite(x) & (np.abs(np.interp(x, freqs, own) - y)
                                     < 1e-9)
        assert np.all(drawn[on_curve & (y < low - 0.01)])
        assert not np.any(drawn[on_curve & (y > low + 0.01)])
    # the combination tongue's right flank enters the single-period one
    # at 0.15 + (f - 95) / 2 = (100 - f) / 10: f = 95.583 Hz, 0.4417 bar;
    # its left flank at 0.15 + (95 - f) / 2 = (100 - f) / 10: f = 94.125
    # Hz, 0.5875 bar; the dotted line ends there
    x, y = dotted.get_xdata(), dotted.get_ydata()
    right = np.isfinite(y) & (x > 95)
    assert y[right].max() == pytest.approx(0.4417, abs=2e-3)
    assert x[right][np.argmax(y[right])] == pytest.approx(95.583, abs=0.02)
    left = np.isfinite(y) & (x < 95)
    assert y[left].max() == pytest.approx(0.5875, abs=2e-3)
    assert x[left][np.argmax(y[left])] == pytest.approx(94.125, abs=0.02)
    plt.close(fig)
