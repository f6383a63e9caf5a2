"""Time estimated before work (issue 9): a request estimated above the
limit is refused at once with the estimate, what drives it and what to
change; an ordinary one runs; the estimate follows the engine's counts
and its measured time.

Refusals run in-process through ``judder.cli.main`` like
tests/test_hostile.py; ``JUDDER_MAX_HOURS`` lowers the limit for the
commands whose real refusals would need a huge request.
"""

import math
import time
from pathlib import Path

import numpy as np
import pytest
from threadpoolctl import threadpool_limits

from sources import get_preset
from judder import api
from judder.cli import main
from studies import _preflight as estimates
from stability import build_driveline
from stability.maps import stability_map
from stability.monodromy import DysonPropagator

ROOT = Path(__file__).resolve().parents[1]
RANGES = str(ROOT / "examples" / "ranges.toml")

#: (argv, JUDDER_MAX_HOURS or None, words of the one error line)
REFUSED = [
    # real: 50000 frequencies at 0.01-0.02 Hz, ~11000 sub-intervals each,
    # about 35 h; its memory (2 amplitudes) is small
    (["map", "--freq", "0.01:0.02:50000", "--pf", "0:1:2"], None,
     ["35.", " h ", "50000 frequencies", "sub-intervals", "--freq",
      "JUDDER_MAX_HOURS"]),
    (["sensitivity", "--params", "c12", "--values",
      ",".join(["1"] * 5000), "--freq", "5:250:50000", "--workers", "1"],
     None, ["5001 cases x 50000 frequencies", "--factors"]),
    (["crosscheck", "--freq", "50:100:300", "--pf", "0:1:100",
      "--duration", "3000", "--workers", "1"], None,
     ["60000 FMU runs", "--duration"]),
    # a lowered limit (0.36 s)
    (["floquet", "--freq", "0.01", "--pf", "0.1"], "0.0001",
     ["sub-intervals per period at 0.01 Hz", "higher --freq"]),
    (["tongues", "--freq", "5:250:1000"], "0.0001",
     ["1000 frequencies"]),
    (["campaign", "--out", "{d}/c", "--freq", "40:60:10", "--pf", "0.5",
      "--workers", "1"], "0.0001", ["10 runs", "--duration"]),
    (["envelope", "--ranges", RANGES, "--preset", "paper-4dof-fitted",
      "--freq", "5:250:300", "--workers", "1"], "0.0001",
     ["samples x 300 frequencies", "--samples"]),
    (["map", "--freq", "100:110:2", "--pf", "0:0.3:2"], "abc",
     ["JUDDER_MAX_HOURS", "'abc'", "hours > 0"]),
]


def run(argv, capsys):
    try:
        status = main(argv)
    except SystemExit as exc:
        status = exc.code
    return (status, *capsys.readouterr())


@pytest.mark.parametrize("argv, hours, words", REFUSED,
                         ids=[" ".join(c[0])[:50] for c in REFUSED])
def test_refused_before_work_with_the_estimate(argv, hours, words, tmp_path,
                                               capsys, monkeypatch):
    if hours is None:
        monkeypatch.delenv("JUDDER_MAX_HOURS", raising=False)
    else:
        monkeypatch.setenv("JUDDER_MAX_HOURS", hours)
    argv = [a.replace("{d}", str(tmp_path)) for a in argv]
    started = time.perf_counter()
    status, out, err = run(argv, capsys)
    # the refusal costs the estimate only (the work would take hours)
    assert time.perf_counter() - started < 30
    assert status == 2, err
    assert "Traceback" not in err
    errors = [line for line in err.splitlines() if "error:" in line]
    assert len(errors) == 1, err
    for word in words:
        assert word in errors[0], err
    assert not list(tmp_path.iterdir())


def test_an_ordinary_map_runs_without_a_word(capsys, monkeypatch):
    monkeypatch.delenv("JUDDER_MAX_HOURS", raising=False)
    status, out, err = run(["map", "--freq", "100:110:2", "--pf",
                            "0:0.3:2"], capsys)
    assert status == 0, err
    assert "estimated" not in err


def test_the_limit_variable_raises_the_limit(monkeypatch):
    params = get_preset("paper-4dof")
    freqs, amplitudes = np.linspace(0.01, 0.02, 50000), np.linspace(0, 1, 2)
    monkeypatch.setenv("JUDDER_MAX_HOURS", "100")
    wall = estimates.check_map(params, freqs, amplitudes, "dyson")
    assert 24 * 3600 < wall < 100 * 3600
    # the reference engine is not estimated
    monkeypatch.delenv("JUDDER_MAX_HOURS")
    assert estimates.check_map(params, freqs, amplitudes,
                               "solve_ivp") is None


def test_long_work_is_announced_on_a_terminal(capsys, monkeypatch):
    monkeypatch.setattr(estimates, "_terminal", lambda: True)
    estimates.check_time(3 * estimates.ANNOUNCE_S, "7 things", "fewer")
    assert "estimated time 30 s (7 things)" in capsys.readouterr().err
    estimates.check_time(estimates.ANNOUNCE_S / 2, "7 things", "fewer")
    assert capsys.readouterr().err == ""
    # shared by workers
    assert estimates.check_time(40.0, "x", "y", workers=4) == 10.0
    capsys.readouterr()
    # not in a pipe or a log (one error line stays one line)
    monkeypatch.setattr(estimates, "_terminal", lambda: False)
    estimates.check_time(3 * estimates.ANNOUNCE_S, "7 things", "fewer")
    assert capsys.readouterr().err == ""


@pytest.mark.parametrize("freq", [0.3, 1.0, 7.0, 100.0])
def test_subintervals_are_the_engines(freq):
    # at a small amplitude the engine takes exactly the sub-intervals the
    # fastest eigenvalue asks for (a strong one may add more)
    params = get_preset("paper-4dof")
    system = build_driveline(params).periodic_system()
    steps, size = estimates.subintervals(params, [freq])
    engine = DysonPropagator(system, freq, 1e3)._coefficients[0].shape[0]
    assert steps[0] == engine and size == len(system.A0) == 6
    radius = np.abs(np.linalg.eigvals(system.A0)).max()
    assert steps[0] == math.ceil((2 * radius + 2 * math.pi * freq)
                                 / freq / 8)


def test_a_small_map_takes_about_its_estimate():
    # CPU time of one thread, as calibrated: robust to a loaded machine
    params = get_preset("paper-4dof")
    driveline = build_driveline(params)
    freqs, amplitudes = np.linspace(1.0, 5.0, 12), np.linspace(0, 1.5, 40)
    with threadpool_limits(1):
        stability_map(driveline, freqs[:1], amplitudes * 1e5)   # warm up
        started = time.process_time()
        stability_map(driveline, freqs, amplitudes * 1e5)
        seconds = time.process_time() - started
    estimate = estimates.map_seconds(params, freqs, amplitudes)
    assert estimate / 3 < seconds < 3 * estimate, (seconds, estimate)


def test_tongues_take_about_their_estimate():
    params = get_preset("paper-4dof")
    freqs = np.linspace(10.0, 220.0, 100)
    with threadpool_limits(1):
        api.tongues(freqs[:6])                                 # warm up
        started = time.process_time()
        api.tongues(freqs)
        seconds = time.process_time() - started
    estimate = estimates.tongues_seconds(params, freqs)
    assert estimate / 3 < seconds < 3 * estimate, (seconds, estimate)
