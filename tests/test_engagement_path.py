"""An engagement's path through the map (:mod:`stability.engagement_path`).

References: the closed form of a held slip (a constant exponent sigma:
the accumulated growth is sigma t, the gain exp(sigma t)); the Floquet
exponent of check's linearisation at the same slip; the bench FMU's run
of an engagement whose slip falls through a tongue (the amplitude of
its double-period motion at f/2, read by a Hann window, grows by the
path's predicted gain within a factor 1.5, as benchmarks/
engagement_path.py measures over 45 engagements).
"""

import numpy as np
import pytest

from infra.spectrum import hann_amplitude
from infra.units import PA_PER_BAR
from sources import get_preset
from stability.bench import linearisation_at
from stability.engagement_path import (EngagementPath, engagement_path,
                                       mean_slip)
from stability.multipliers import floquet
from studies.inputs import friction_of

PAPER = get_preset("paper-4dof")
#: A characteristic whose slope 0.0028 s/rad lasts from 60 to 90 rad/s.
TABLE = "slip_rad_s,mu\n0,0.018\n60,0.02\n90,0.105\n120,0.108\n300,0.11\n"


def test_a_held_slip_has_the_exponent_of_check_and_grows_exponentially():
    at = linearisation_at(PAPER)
    time = np.linspace(0.6, 4.0, 200)
    slip = np.full_like(time, 84.72)
    path = engagement_path(at, 205.0, 0.4 * PA_PER_BAR, time, slip)
    sigma = floquet(at(84.72), 205.0, 0.4 * PA_PER_BAR).growth_rate
    assert path.growth_per_s == pytest.approx(np.full(200, sigma), rel=1e-12)
    assert path.accumulated == pytest.approx(sigma * (time - 0.6), rel=1e-9)
    assert path.gain(1.0, 2.0) == pytest.approx(np.exp(sigma), rel=1e-9)
    assert set(path.kind) == {"double-period"}


def test_spans_are_where_the_exponent_exceeds_the_growth():
    time = np.arange(0.0, 1.0, 0.1)
    growth = np.array([0, 2, 3, 2, 0, 0, 5, 5, 0, 0], dtype=float)
    path = EngagementPath(time=time, slip=100 - 10 * time,
                          growth_per_s=growth, kind=np.array(["x"] * 10),
                          accumulated=np.concatenate([[0], np.cumsum(
                              0.5 * (growth[1:] + growth[:-1]) * 0.1)]))
    spans = path.spans(1.0)
    assert [(round(a, 2), round(b, 2)) for a, b, *_ in spans] == \
        [(0.1, 0.3), (0.6, 0.7)]
    assert spans[0][5] == pytest.approx(0.5)      # trapezoids of 2, 3, 2


def test_mean_slip_removes_the_dither_and_keeps_the_drift():
    time = np.arange(0.0, 1.0, 1e-4)
    slip = 80.0 - 5.0 * time + 0.7 * np.sin(2 * np.pi * 100.0 * time)
    mean = mean_slip(time, slip, 100.0)
    inside = (time > 0.05) & (time < 0.95)
    assert mean[inside] == pytest.approx(80.0 - 5.0 * time[inside],
                                         abs=2e-3)


def test_the_path_predicts_the_bench_runs_gain_through_a_tongue(tmp_path):
    from judder import api
    table = tmp_path / "table.csv"
    table.write_text(TABLE)
    values = friction_of(PAPER, str(table))
    result = api.simulate(206.0, 2.0, parameters=values,
                          bench={"load_share": 0.8})
    run, path, summary = result.runs[0][1], result.paths[0], \
        result.summaries[0]
    # the slip falls through the table's slope: a double-period span
    (start, stop, slip_start, slip_stop, kind, efolds), = \
        summary_spans = path.spans(1.0)
    assert kind == "double-period" and slip_start > 70 > 62 > slip_stop
    assert summary["path_spans"][0]["efolds"] == pytest.approx(efolds)
    assert summary_spans

    def amplitude(centre):
        keep = np.abs(run.time - centre) <= 0.06
        t, w = run.time[keep], run["slip"][keep]
        return hann_amplitude(t, w - np.polyval(np.polyfit(t, w, 1), t),
                              [103.0])[0]
    first = result.start + 0.06
    last = float(path.time[np.argmax(path.accumulated)])
    measured = amplitude(last) / amplitude(first)
    assert 1 / 1.5 <= path.gain(first, last) / measured <= 1.5
    assert measured > 3            # it did grow, by the run itself


def test_a_burst_through_a_tongue_is_judder_of_the_engagement(tmp_path):
    """The slip crosses tongue 4 in about 1.3 s: the double-period motion
    grows past the limit for a few tenths of a second, which the whole
    run's spectrum averages below it. The engagement judders, when and
    where the path says it grows."""
    from judder import api
    table = tmp_path / "table.csv"
    table.write_text(TABLE)
    values = friction_of(PAPER, str(table))
    result = api.simulate(205.5, 2.6, parameters=values,
                          bench={"load_share": 0.87})
    summary, path = result.summaries[0], result.paths[0]
    assert result.run_kind == "falling_slip"
    assert summary["judder"] and summary["judder_in_burst"]
    assert summary["mechanism"] == "parametric"
    assert summary["judder_kind"] == "double-period"
    assert summary["envelope_peak_hz"] == pytest.approx(205.5 / 2)
    assert summary["oscillation_rpm"] > summary["judder_limit_rpm"] > \
        summary["spectrum_oscillation_rpm"]
    # the motion grows while the path is inside the tongue and peaks
    # after it leaves: the burst starts inside the span
    (start, stop, *_), = path.spans(1.0)
    assert start < summary["judder_from_s"] < stop < \
        summary["envelope_peak_s"]


def test_a_held_slip_is_not_judged_by_its_envelope():
    from judder import api
    summary = api.simulate(205.0, 0.4, parameters=PAPER).summaries[0]
    assert summary["envelope_peak_rpm"] is None
    assert not summary.get("judder_in_burst")
