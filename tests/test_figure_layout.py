"""Each figure the README and the report make, drawn from a small
computation and read back as a reviewer would (issue 46): no two texts
overlap, nothing leaves the canvas, the legend lists exactly what is drawn,
and titles print engineering precision
(:func:`infra.plotstyle.layout_problems`)."""

from pathlib import Path

import matplotlib
import numpy as np
import pytest

from infra.plotstyle import layout_problems, significant_digits
from judder import api

matplotlib.use("Agg")

EXAMPLES = Path(__file__).parents[1] / "examples"
#: The title the commands give the example driveline
#: (judder.commands._model.model_title), with the file as a user may name
#: it: a long path (the check figure's title was clipped by one).
EXAMPLE_TITLE = f"4dof driveline, {EXAMPLES.resolve() / 'driveline.toml'}"


@pytest.fixture(scope="module")
def example():
    from studies.inputs import load_parameters
    return load_parameters(param_file=EXAMPLES / "driveline.toml")


@pytest.fixture(autouse=True)
def _rc():
    import matplotlib.pyplot as plt
    from threadpoolctl import threadpool_limits
    with matplotlib.rc_context({"font.family": "DejaVu Sans"}), \
            threadpool_limits(limits=1):
        yield
    plt.close("all")


# --- the figures, each as its command draws it ------------------------------

def _check(example):
    # README step 3 (105 Hz, 0.2 bar) and settings by tongues 2 and 5
    return api.check([105.0, 102.9, 86.0], [0.2, 0.3, 0.5],
                     parameters=example, sensitivity=(),
                     background=True).figure(title=EXAMPLE_TITLE)


def _check_six(example):
    # six settings on the paper preset, two close pairs (issue 46: their
    # margins collided, and the points looked like tongue 5's tip)
    return api.check([60.0, 84.0, 86.0, 102.9, 104.0, 150.0],
                     [0.2, 0.5, 0.45, 0.3, 0.3, 0.3], sensitivity=(),
                     background=True).figure(
        title="4dof driveline, paper preset")


def _map(example):
    return api.stability_map(np.linspace(5, 250, 60),
                             np.linspace(0, 1.5, 30), parameters=example,
                             exact=True).figure(title=EXAMPLE_TITLE)


def _map_judder(example):
    # the judder line and the grey from the exact boundaries of growth at
    # min_growth (issue 46), as `judder map` draws them
    result = api.stability_map(np.linspace(5, 250, 60),
                               np.linspace(0, 1.5, 30), parameters=example,
                               exact=True, min_growth=1.0)
    assert result.judder is not None
    return result.figure(title=EXAMPLE_TITLE)


def _tongues_over_map(example):
    result = api.tongues(np.linspace(10, 220, 60), parameters=example,
                         background=True)
    assert result.judder_boundaries is not None
    return result.figure(title=EXAMPLE_TITLE)


def _tongues(example):
    return api.tongues(np.linspace(10, 220, 60), parameters=example
                       ).figure(title=EXAMPLE_TITLE)


def _sensitivity(example):
    return api.sensitivity(["k12", "k24", "J2", "J4", "mu_g", "c12"],
                           np.linspace(10, 220, 40), parameters=example,
                           workers=1).figure(
        title="sensitivity of the stability boundary (Fig. 17, 18), "
              + EXAMPLE_TITLE)


def _floquet(example):
    return api.floquet(105.0, 0.2, parameters=example).figure(
        title=EXAMPLE_TITLE)


def _orbit_chart(example):
    return api.orbit(np.linspace(60, 200, 15), np.linspace(0.05, 0.7, 8),
                     parameters=example).figure(title=EXAMPLE_TITLE)


def _orbit_chart_fine(example):
    # 0.125 Hz apart: the judder points are shaded as a region, not
    # markers that merge into bars (issue 46)
    return api.orbit(np.linspace(100, 112, 97), np.linspace(0.1, 0.7, 7),
                     parameters=example).figure(title=EXAMPLE_TITLE)


def _orbit_branch(example):
    return api.orbit(206.0, np.linspace(0.01, 0.8, 12)).figure(
        title="4dof driveline, paper preset")


def _advice(example):
    return api.advise(example, bounds={"k24": (0.5, 4.0)},
                      background=True).figure(title=EXAMPLE_TITLE)


def _compare(example):
    from sources import get_preset
    return api.compare(get_preset("paper-4dof"), example,
                       labels=("paper-4dof", "driveline.toml"),
                       freq_hz=np.linspace(10, 220, 60),
                       settings=[(105.0, 0.2)], maps=True).figure(
        title="paper-4dof against examples/driveline.toml")


def _fit(example):
    from studies.inputs import read_boundary_csv
    freq, onset = read_boundary_csv(
        (EXAMPLES / "measured_boundary.csv").read_text())
    return api.fit(freq, onset / 1e5, 1.0, names=["mu_g"], starts=1,
                   changes={"c12": 10.0}).figure()


def _envelope(example):
    from sources import get_preset
    from stability.uncertainty.ranges import Normal, Ranges, Uniform
    fitted = get_preset("paper-4dof-fitted")
    ranges = Ranges((Uniform("c12", 8.0, 12.0),
                     Normal("mu_g", 0.022, 0.001)))
    return api.envelope(ranges, np.linspace(96, 116, 6), 0.6, samples=4,
                        refine=0, parameters=fitted, workers=1,
                        driveline="chain", min_growth=1.0).figure(
        title="4dof driveline, paper-4dof-fitted")


def _threshold(example):
    return api.threshold(np.linspace(-1e-3, 1e-3, 21),
                         np.linspace(0, 2, 11)).figure(
        title="4dof driveline, paper preset")


def _engagement_path(example):
    # a falling slip: the run, its spectrum and its path through the map
    from sources import get_preset
    return api.simulate(205.0, 0.4, parameters=get_preset("paper-4dof"),
                        bench={"load_share": 0.99}).figure(
        title="4dof driveline, paper preset, load_share 0.99")


FIGURES = {"check": _check, "check-six": _check_six, "map": _map,
           "map-judder": _map_judder, "tongues": _tongues,
           "tongues-over-map": _tongues_over_map,
           "sensitivity": _sensitivity, "floquet": _floquet,
           "orbit-chart": _orbit_chart,
           "orbit-chart-fine": _orbit_chart_fine, "orbit-branch": _orbit_branch,
           "advice": _advice, "compare": _compare, "fit": _fit,
           "envelope": _envelope, "threshold": _threshold,
           "engagement-path": _engagement_path}


#: Figures the checker still flags, and why (issue 46).
KNOWN = {}


@pytest.mark.parametrize("name", [
    pytest.param(name, marks=pytest.mark.xfail(reason=KNOWN[name],
                                               strict=True))
    if name in KNOWN else name for name in sorted(FIGURES)])
def test_figure_layout(name, example):
    fig = FIGURES[name](example)
    assert layout_problems(fig) == []


# --- the checker can fail ----------------------------------------------------

def test_the_checker_finds_what_a_reviewer_would():
    import matplotlib.pyplot as plt
    from matplotlib.lines import Line2D
    fig, ax = plt.subplots(figsize=(4, 3), dpi=100)
    ax.plot([0, 1], [0, 1], color="C0", label="drawn, not listed")
    ax.plot([0, 1], [1, 0], color="C1", label="listed")
    ghost = Line2D([], [], color="C2", linestyle="--", label="not drawn")
    ax.legend(handles=[ax.lines[1], ghost], loc="lower left")
    ax.annotate("one note", (0.5, 0.5))
    ax.annotate("on another", (0.52, 0.5))
    ax.set_title("p_f = 0.0812726 bar, f = 105 Hz")
    ax.set_xlabel("a label that runs far beyond the right edge of the "
                  "canvas, clipped")
    problems = layout_problems(fig)
    assert any("'one note' overlaps 'on another'" in p for p in problems)
    assert any("leaves the canvas" in p and "clipped" in p
               for p in problems)
    assert "'drawn, not listed' is drawn but not in a legend" in problems
    assert "legend entry 'not drawn' is not drawn" in problems
    assert any("0.0812726" in p for p in problems)
    # what is right is not flagged: the listed line, 105 Hz
    assert not any("'listed'" in p or "105 " in p for p in problems)
    assert len(problems) == 5, problems


@pytest.mark.parametrize("number, digits", [
    ("0.0812726", 6), ("0.081", 2), ("34860", 4), ("1.50", 3),
    ("102.9", 4), ("104.45", 5), ("+21.46", 4), ("0", 1)])
def test_significant_digits(number, digits):
    assert significant_digits(number) == digits
