"""Size and work of every input a user supplies, estimated before any
work (issue 34): acquisitions of ``chart``, the points of ``fit
--boundary``, the grids of ``threshold``; ``--workers`` cut to the jobs,
cores and memory with the reason said."""

import os
from pathlib import Path
import resource
import subprocess
import sys
import time

import pytest

from infra.parallel import WORKER_BYTES, worker_count
from judder.cli import main
from facts import names

ROOT = Path(__file__).resolve().parents[1]
BENCH = ROOT / "examples" / "bench"


def run(argv, capsys):
    status = main(argv)
    out, err = capsys.readouterr()
    return status, out, err


def test_an_acquisition_beyond_the_memory_is_refused_before_reading(
        tmp_path):
    # a 2 GiB sparse file (the issue's: read to 6.4 GB before "not a text
    # file") under a 3 GiB address space: refused from its size
    sparse = tmp_path / "run.csv"
    with open(sparse, "wb") as stream:
        stream.truncate(2 * 2**30)

    def limit():
        resource.setrlimit(resource.RLIMIT_AS, (3 * 2**30, 3 * 2**30))
    started = time.monotonic()
    done = subprocess.run(
        [sys.executable, "-m", "judder", "chart", str(sparse),
         "--channel", "upstream_speed=speed", "--workers", "1"],
        capture_output=True, text=True, preexec_fn=limit, timeout=120)
    assert done.returncode == 2, done.stderr
    assert done.stderr.startswith("judder: error: ")
    names(done.stderr, str(sparse), "36 GiB", "2048 MB", "x 18",
          "available", "allowed")
    assert time.monotonic() - started < 60


def test_a_binary_file_named_csv_is_refused_from_its_first_block(capsys,
                                                                  tmp_path):
    sparse = tmp_path / "run.csv"
    with open(sparse, "wb") as stream:
        stream.truncate(50 * 2**20)
    status, out, err = run(["chart", str(sparse), "--channel",
                            "upstream_speed=speed", "--workers", "1"],
                           capsys)
    assert status == 2
    assert err.startswith("judder: error: ") and err.count("\n") == 1
    names(err, str(sparse), "NUL", "allowed", "UTF-8")


def test_the_acquisitions_work_is_estimated_from_their_sizes(capsys,
                                                             monkeypatch):
    # 9 runs of about 100 kB: 0.5 us a byte, a few tenths of a second
    size = sum((BENCH / f"run0{i}.csv").stat().st_size for i in range(1, 10))
    seconds = size * 5e-7
    monkeypatch.setenv("JUDDER_MAX_HOURS", f"{seconds / 2 / 3600:.9f}")
    status, out, err = run(["chart", "--index", str(BENCH / "runs.csv"),
                            "--channel", "upstream_speed=EngSpd_up",
                            "--workers", "1"], capsys)
    assert status == 2 and out == ""
    assert err.startswith("judder: error: ")
    names(err, f"{seconds:.3g} s", "9 acquisitions",
          f"{size / 2**20:.4g} MB", "limit")


def test_a_large_boundary_is_refused_beyond_the_time_limit(capsys, tmp_path,
                                                           monkeypatch):
    boundary = tmp_path / "b.csv"
    boundary.write_text("freq_hz,p_f_bar\n" + "".join(
        f"{60 + 0.0014 * i:.6f},0.3\n" for i in range(100_000)))
    monkeypatch.setenv("JUDDER_MAX_HOURS", "1")
    started = time.monotonic()
    status, out, err = run(["fit", "--boundary", str(boundary),
                            "--fit", "mu_g"], capsys)
    assert status == 2
    # 0.5 s + 100 000 points x 3 starts x 0.1 s
    # the estimate and what drives it, the limit, the options to change
    assert err.startswith("judder: error: ") and err.count("\n") == 1
    names(err, "8.33 h", "100000 measured points", "3 local fits", "60 min",
          "allowed", "--boundary", "--starts", "JUDDER_MAX_HOURS")
    assert time.monotonic() - started < 30


def test_a_threshold_grid_follows_the_time_limit(capsys, monkeypatch):
    monkeypatch.setenv("JUDDER_MAX_HOURS", "0.01")
    status, out, err = run(["threshold", "--mu-g=-0.001:0.001:100000",
                            "--c-ext", "0:2:100000"], capsys)
    assert status == 2
    # 1e5 x 0.26 ms + 1e5 x 4.4 ms
    assert err.startswith("judder: error: ")
    names(err, "7.77 min", "100000 mu_g", "100000 c_i", "36 s")


def test_the_threshold_estimate_is_within_a_factor_3_of_the_work():
    from studies._preflight import (THRESHOLD_DAMPING_S,
                                            THRESHOLD_MU_S)
    from studies.threshold import threshold
    import numpy as np
    threshold([0.0], [1.0])          # imports and caches out of the clock
    started = time.process_time()
    threshold(np.linspace(-1e-3, 1e-3, 400), np.linspace(0, 2, 60))
    spent = time.process_time() - started
    estimate = 400 * THRESHOLD_MU_S + 60 * THRESHOLD_DAMPING_S
    assert estimate / 3 < spent < 3 * estimate


def test_workers_are_cut_to_the_jobs_cores_and_memory(monkeypatch):
    import infra.memory
    cores = os.cpu_count()
    monkeypatch.setattr(infra.memory, "available_memory", lambda: 64 * 2**30)
    assert worker_count(48, 9) == (
        min(9, cores), f"`workers` 48 reduced to {min(9, cores)}: "
        + ("9 jobs" if cores >= 9 else f"{cores} cores"))
    assert worker_count(None, 9) == (min(9, cores), "")
    assert worker_count(1, 9) == (1, "")
    assert worker_count(2, 1) == (1, "`workers` 2 reduced to 1: 1 job")
    # 1 GiB: 80 % holds 5 workers of 150 MB, 2 with 200 MB runs
    monkeypatch.setattr(infra.memory, "available_memory", lambda: 2**30)
    count, reason = worker_count(8, 100, job_bytes=200 * 2**20)
    assert count == min(2, cores)
    assert reason.endswith("memory for 2 (1 GiB available, 350 MB each)") \
        or cores < 2
    assert worker_count(8, 100)[0] == min(5, cores)
    assert WORKER_BYTES == 150 * 2**20


@pytest.mark.skipif((os.cpu_count() or 1) > 8, reason="needs <= 8 cores")
def test_a_chart_with_48_workers_starts_no_more_than_the_cores(tmp_path):
    done = subprocess.run(
        [sys.executable, "-m", "judder", "chart", "--index",
         str(BENCH / "runs.csv"), "--channel", "upstream_speed=EngSpd_up",
         "--channel", "pressure=PressEVEN:bar",
         "--channel", "downstream_speed=OutSpd", "--workers", "48"],
        capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    cores = os.cpu_count()
    # one warning line: the option, what it was cut to and why
    assert done.stderr.startswith("judder: warning: ")
    assert done.stderr.count("\n") == 1
    names(done.stderr, "--workers 48", f"{cores}: {cores} cores")
    assert "9 runs" in done.stdout


def test_an_orbit_grid_is_refused_before_it_is_made(capsys):
    # 1e10 orbits once ended in a MemoryError after allocating
    started = time.monotonic()
    status, out, err = run(["orbit", "--freq", "60:200:100000",
                            "--pf", "0.05:0.7:100000"], capsys)
    assert status == 2
    assert err.strip() == (
        "judder: error: the work is estimated at 3.33e+03 h (100000 "
        "frequencies x 100000 amplitudes), above the limit of 24 h; "
        "allowed: fewer --freq or --pf values, or raise the limit with "
        "JUDDER_MAX_HOURS=HOURS")
    assert time.monotonic() - started < 30


def test_a_check_on_the_bench_is_estimated_at_the_benchs_cost(capsys,
                                                              monkeypatch):
    # 36 s allowed: 200 settings cost 9 s on the chain (0.045 s each) but
    # 42 s on the preset's bench (0.21 s each: its orbits and the safe
    # band's walk), where it is refused before the work
    monkeypatch.setenv("JUDDER_MAX_HOURS", "0.01")
    grid = ["--freq", "60:200:20", "--pf", "0.05:0.5:10", "--params", "none"]
    status, out, err = run(["check", *grid], capsys)
    assert status == 2
    names(err, "42 s", "200 settings")
    from studies._preflight import check_settings_time
    assert check_settings_time(200, 0) == pytest.approx(9.0)
