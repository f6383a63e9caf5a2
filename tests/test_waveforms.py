"""Dither waveforms beyond the cosine (stability.waveforms): closed forms,
the engines against a direct integration, and the tongue a square wave's
third harmonic opens at f2/3."""

import numpy as np
import pytest
from numpy.testing import assert_allclose
from scipy.integrate import quad, solve_ivp

from infra.errors import JudderError
from stability import floquet, natural_frequencies
from stability.hill import modal_transfer, real_boundaries
from stability.monodromy import DysonPropagator
from stability.waveforms import (Dithered, FilteredSquare, FourierSeries,
                                 from_samples, with_waveform)

TAU = 0.5e-3          # valve time constant, s


def _lowest(system, freq, harmonics=None):
    """Lowest single-period boundary by Hill's method, Pa."""
    return real_boundaries(modal_transfer(system), [freq], 1,
                           harmonics)[0, 0]


def _direct(system, freq, p_f, breaks=(0.25, 0.75)):
    """Monodromy by solve_ivp, restarted at the waveform's kinks."""
    omega, period = 2 * np.pi * freq, 1.0 / freq
    size = len(system.A0)
    y = np.eye(size)
    edges = [0.0, *(b * period for b in breaks), period]
    for a, b in zip(edges[:-1], edges[1:]):
        # one-sided limits of the shape at the ends of each piece
        def rhs(t, x, a=a, b=b):
            t = min(max(t, a + 1e-12 * period), b - 1e-12 * period)
            return (system.matrix(t, omega, p_f)
                    @ x.reshape(size, size)).ravel()
        sol = solve_ivp(rhs, (a, b), y.ravel(), method="DOP853", rtol=1e-12,
                        atol=1e-14)
        y = sol.y[:, -1].reshape(size, size)
    return y


@pytest.mark.parametrize("tau", [0.0, TAU, 5 * TAU])
def test_filtered_square_coefficients_are_its_fourier_series(tau):
    wave, freq = FilteredSquare(tau), 34.3
    c = wave.coefficients(7, freq)
    for n in range(8):
        # integrate each half period separately (kinks at +-pi/2)
        parts = [quad(lambda x: wave.values(x, freq) * np.cos(n * x),
                      a, b, epsabs=1e-13)[0]
                 - 1j * quad(lambda x: wave.values(x, freq) * np.sin(n * x),
                             a, b, epsabs=1e-13)[0]
                 for a, b in ((-np.pi / 2, np.pi / 2),
                              (np.pi / 2, 3 * np.pi / 2))]
        assert abs(sum(parts) / (2 * np.pi) - c[n]) < 1e-12
    # the lag's steady state is continuous at the switching instants
    if tau > 0:
        left, right = wave.values(np.pi / 2 - 1e-12, freq), \
            wave.values(np.pi / 2 + 1e-12, freq)
        assert left == pytest.approx(right, abs=1e-8)


def test_measured_period_and_series_round_trip():
    series = FourierSeries(cos=(1.0, 0.0, 0.3), sin=(0.0, 0.1))
    theta = np.linspace(0, 2 * np.pi, 64, endpoint=False)
    samples = 2e5 + 0.4e5 * series.values(theta, 100.0)   # Pa, with a mean
    measured = from_samples(samples)
    assert_allclose(measured.coefficients(4, 100.0),
                    series.coefficients(4, 100.0), atol=1e-14)


def test_cosine_waveform_is_the_default(paper4):
    system = paper4.periodic_system()
    cosine = with_waveform(system, FourierSeries(cos=(1.0,)))
    assert_allclose(DysonPropagator(cosine, 60.0, 1e5).monodromy([1e5]),
                    DysonPropagator(system, 60.0, 1e5).monodromy([1e5]),
                    atol=1e-13)
    # the lowest boundary (the higher ones, near 460 bar, are truncation's)
    assert _lowest(cosine, 102.9) == pytest.approx(_lowest(system, 102.9),
                                                   rel=1e-12)


@pytest.mark.parametrize("freq, p_f, tau", [
    (34.29, 0.07e5, TAU), (102.9, 0.3e5, TAU), (60.0, 0.5e5, TAU),
    (34.29, 0.07e5, 0.0)])     # the square wave itself: jumps at T/4, 3T/4
def test_dyson_with_a_square_wave_equals_direct_integration(paper4, freq,
                                                            p_f, tau):
    system = Dithered(paper4, FilteredSquare(tau)).periodic_system()
    assert_allclose(DysonPropagator(system, freq, p_f).monodromy([p_f])[0],
                    _direct(system, freq, p_f), atol=1e-9)


def test_square_wave_third_harmonic_excites_the_f2_tongue_at_f2_over_3(
        paper4):
    # issue 12 acceptance: the harmonic 3f of a square-wave dither at
    # f = f2/3 sits on the resonance of tongue 2 (Fig. 14), so a tongue
    # opens at f2/3 where the cosine has none below 2 bar
    f2 = natural_frequencies(paper4)[1]
    wave = FilteredSquare(TAU)
    square = Dithered(paper4, wave).periodic_system()
    cosine = paper4.periodic_system()
    freq = f2 / 3
    p_star = _lowest(square, freq, harmonics=24)
    assert _lowest(cosine, freq) > 2e5
    # Hill's boundary is a multiplier at +1 of the directly integrated
    # monodromy; just above it the square wave is unstable, single-period
    lam = np.linalg.eigvals(_direct(square, freq, p_star))
    assert np.abs(lam - 1).min() < 1e-6
    above = np.linalg.eigvals(_direct(square, freq, 1.02 * p_star))
    lead = above[np.argmax(np.abs(above))]
    assert abs(lead) > 1 and abs(lead.imag) < 1e-9 and lead.real > 0
    below = np.linalg.eigvals(_direct(cosine, freq, 1.02 * p_star))
    assert np.abs(below).max() < 1
    # as the harmonics predict: the cosine's tip of tongue 2 at f2 scaled
    # by c_1 = 1/2 over the square wave's third harmonic |c_3| at f2/3
    tip_cosine = _lowest(cosine, f2)
    c3 = abs(wave.coefficients(3, freq)[3])
    assert p_star == pytest.approx(tip_cosine * 0.5 / c3, rel=5e-3)
    # and the lowest boundary around f2/3 dips there
    nearby = [_lowest(square, freq * (1 + d))
              for d in (-0.01, 0.01)]
    assert min(nearby) > p_star


def test_cli_dither_wave():
    import json
    import subprocess
    import sys

    def floquet(*extra):
        proc = subprocess.run(
            [sys.executable, "-m", "judder", "floquet", "--freq", "34.2946",
             "--pf", "0.07", "--driveline", "chain", "--json", *extra],
            capture_output=True, text=True, timeout=120)
        assert proc.returncode == 0, proc.stderr
        return json.loads(proc.stdout)
    # 0.07 bar is just above the square wave's tongue tip at f2/3
    assert floquet("--dither-wave", "square:0.5")["kind"] == "single-period"
    assert floquet()["kind"] == "stable"
    bad = subprocess.run([sys.executable, "-m", "judder", "floquet", "--freq",
                          "34", "--pf", "0.07", "--dither-wave", "triangle"],
                         capture_output=True, text=True, timeout=120)
    assert bad.returncode == 2 and "allowed: cosine" in bad.stderr


def test_hill_solver_defers_to_scan_for_another_waveform(paper4):
    """The batched Hill solver assumes the cosine of Eq. (4); with a square
    wave the default solver must give the per-frequency Hill result (the
    f2/3 tongue of the third harmonic included), not the cosine's."""
    from stability.tongues import lowest_boundaries
    square = Dithered(paper4, FilteredSquare(1.0e-3)).periodic_system()
    freqs = np.array([34.0, 34.3, 60.0, 102.9])
    assert_allclose(lowest_boundaries(square, freqs, 1.5e5, "hill"),
                    lowest_boundaries(square, freqs, 1.5e5, "scan"),
                    rtol=1e-12, equal_nan=True)
    cosine = lowest_boundaries(paper4.periodic_system(), freqs, 1.5e5, "hill")
    assert np.isnan(cosine[1, 0]) and np.isfinite(
        lowest_boundaries(square, freqs, 1.5e5, "hill")[1, 0])


#: Every form with the engines that take it: the Dyson engine needs
#: ``A0 + p_f c(w t) U V^T``, which Eq. (9)'s forcing column p_f D is not.
FORMS_AND_ENGINES = [("reduced", "dyson"), ("reduced", "solve_ivp"),
                     ("full", "dyson"), ("full", "solve_ivp"),
                     ("augmented", "solve_ivp")]
#: A harmonic-rich smooth shape: 2nd harmonic in sine, 3rd in cosine.
FOURIER = FourierSeries(cos=(1.0, 0.0, 0.3), sin=(0.0, 0.2))


@pytest.mark.parametrize("wave, expected", [
    # issue 22: the full form used to give the cosine's 1.026103 here
    (FilteredSquare(0.0), 1.035197),
    (FOURIER, 1.026751)])
def test_every_form_and_engine_takes_the_waveform(paper4, wave, expected):
    # inside tongue 2 near its tip (Fig. 14): the leading multiplier of
    # the reduced Eq. (6), the full Eq. (6) and the augmented Eq. (9) is
    # the waveform's, by every engine, to 1e-7 (the engines' tolerance)
    dithered = Dithered(paper4, wave)
    leading = {(form, engine): floquet(dithered, 102.9, 0.3e5, method=engine,
                                       form=form).leading_abs
               for form, engine in FORMS_AND_ENGINES}
    assert leading[("reduced", "dyson")] == pytest.approx(expected, abs=1e-6)
    assert_allclose(list(leading.values()), leading[("reduced", "dyson")],
                    rtol=0, atol=1e-7)
    # Hill's method (on the reduced form, the one without a pole at
    # s = 0) gives the single-period boundary below: there every form and
    # engine has its leading multiplier on the unit circle
    p_star = _lowest(dithered.periodic_system(), 102.9)
    assert p_star < 0.3e5
    for form, engine in FORMS_AND_ENGINES:
        at_boundary = floquet(dithered, 102.9, p_star, method=engine,
                              form=form).leading_abs
        assert at_boundary == pytest.approx(1.0, abs=1e-7), (form, engine)


def test_a_linearised_model_has_no_augmented_form():
    from sources.modelica import LinearPeriodicModel
    from sources.kinds import SourceKind
    from stability.linear import LinearDriveline
    # Mathieu-like oscillator: A0 = [[0, 1], [-100, -1]], B = -e2 e2^T
    model = LinearPeriodicModel(
        "Oscillator", ("x", "v"), np.array([[0.0, 1.0], [-100.0, -1.0]]),
        np.array([[0.0, 0.0], [0.0, -1.0]]), np.array([100.0]), {}, "p_f",
        "f_dither", SourceKind.MODELICA)
    square = Dithered(LinearDriveline.from_model(model), FilteredSquare(0.0))
    with pytest.raises(JudderError, match="allowed: form = 'reduced' or "
                                          "'full'"):
        floquet(square, 3.2, 0.5, form="augmented")
    assert floquet(square, 3.2, 0.5, form="full").leading_abs == \
        pytest.approx(floquet(square, 3.2, 0.5).leading_abs, abs=1e-9)
