"""Stability maps: pointwise agreement and tongue positions (Fig. 14)."""

import numpy as np
import pytest
from numpy.testing import assert_allclose

from stability import KINDS, floquet, natural_frequencies, stability_map

BAR = 1e5


def test_map_equals_pointwise_floquet(paper4):
    freqs, amps = [20.0, 84.0, 150.0], [0.0, 0.4 * BAR, 1.2 * BAR]
    m = stability_map(paper4, freqs, amps)
    for i, f in enumerate(freqs):
        for j, p in enumerate(amps):
            r = floquet(paper4, f, p, method="solve_ivp")
            assert m.leading_abs[i, j] == pytest.approx(r.leading_abs,
                                                        abs=1e-9)
            assert KINDS[m.kind[i, j]] == r.kind


def test_six_tongues_at_the_paper_frequencies(paper4):
    # Fig. 14 / section 4.2: single-period at f1, f2; double-period at 2 f1,
    # 2 f2; combination at f2 - f1, f1 + f2
    f1, f2 = natural_frequencies(paper4)
    expected = {f1: "single-period", f2: "single-period",
                2 * f1: "double-period", 2 * f2: "double-period",
                f2 - f1: "combination", f1 + f2: "combination"}
    m = stability_map(paper4, sorted(expected), [1.0 * BAR])
    for freq, code in zip(m.freq_hz, m.kind[:, 0]):
        assert KINDS[code] == expected[freq], freq
    # and between tongues the driveline is stable
    between = stability_map(paper4, [10.0, 60.0, 160.0, 240.0], [1.0 * BAR])
    assert np.all(between.kind == 0)


def test_growth_rate_and_counts(paper4):
    m = stability_map(paper4, [102.9, 60.0], [0.3 * BAR])
    assert_allclose(m.growth_rate[:, 0],
                    np.log(m.leading_abs[:, 0]) * np.array([102.9, 60.0]))
    assert m.counts() == {"stable": 1, "single-period": 1,
                          "double-period": 0, "combination": 0}


def test_callback_reports_each_frequency(paper4):
    calls = []
    stability_map(paper4, [50.0, 60.0, 70.0], [0.0],
                  callback=lambda done, total: calls.append((done, total)))
    assert calls == [(1, 3), (2, 3), (3, 3)]
