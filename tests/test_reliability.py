"""Reliability (issue 24): signals at any moment, a third-party FMU that
crashes or hangs, a scheduler that is not one, values out of their
documented range, memory a typo would take, outputs on one path, bench
channels that cannot be right. Every case ends in one line naming what
to change, a known exit status, no traceback and no partial file.

CLI cases run through a subprocess where the process itself is at stake
(signals, crashes, hangs), in-process otherwise.
"""

import os
import signal
import subprocess
import sys
import time

import pytest

#: A map long enough to be interrupted in its middle (about 10 s here).
LONG_MAP = ["map", "--freq", "1:250:40000", "--pf", "0:1:50"]


def _start(args, **kw):
    return subprocess.Popen([sys.executable, "-m", "judder", *args],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True, **kw)


def _one_line(stderr):
    lines = [line for line in stderr.splitlines() if line.strip()]
    assert len(lines) == 1, stderr
    assert "Traceback" not in stderr
    return lines[0]


# -- signals -----------------------------------------------------------

# 0.1 s: numpy, scipy and Dask are being imported (the whole import takes
# about 0.5 s); 0.3 s: still importing on a loaded machine, or parsing.
@pytest.mark.parametrize("sig, status, word", [
    (signal.SIGINT, 130, "interrupted"), (signal.SIGTERM, 143, "terminated")])
@pytest.mark.parametrize("delay", [0.1, 0.3])
def test_signal_while_starting(tmp_path, sig, status, word, delay):
    out = tmp_path / "m.npz"
    proc = _start([*LONG_MAP, "--out", str(out)])
    time.sleep(delay)
    assert proc.poll() is None
    proc.send_signal(sig)
    _, stderr = proc.communicate(timeout=60)
    assert proc.returncode == status, stderr
    assert _one_line(stderr) == f"judder: {word}; no partial output was written"
    assert os.listdir(tmp_path) == []


def test_ctrl_c_during_a_map(tmp_path):
    out = tmp_path / "m.npz"
    proc = _start([*LONG_MAP, "--out", str(out)])
    time.sleep(3.0)
    assert proc.poll() is None, "the map finished before Ctrl-C"
    proc.send_signal(signal.SIGINT)
    _, stderr = proc.communicate(timeout=60)
    assert proc.returncode == 130, stderr
    assert "interrupted" in _one_line(stderr)
    assert os.listdir(tmp_path) == []      # neither the file nor a .part


def test_ctrl_c_of_the_process_group_with_workers(tmp_path):
    """A terminal's Ctrl-C reaches the Dask workers too: one line, the
    workers gone."""
    import psutil
    out = tmp_path / "s.csv"
    proc = _start(["sensitivity", "--params", "k12,k24,J2,J4,c12,mu_g", "--freq",
                   "20:220:2000", "--workers", "2", "--out", str(out)],
                  start_new_session=True)
    deadline = time.monotonic() + 60
    children = []
    while time.monotonic() < deadline and len(children) < 2:
        time.sleep(0.5)
        children = psutil.Process(proc.pid).children(recursive=True)
    assert proc.poll() is None and len(children) >= 2
    time.sleep(5.0)             # the workers are up and computing
    os.killpg(proc.pid, signal.SIGINT)
    _, stderr = proc.communicate(timeout=60)
    assert proc.returncode == 130, stderr
    assert "interrupted" in _one_line(stderr)
    assert os.listdir(tmp_path) == []
    gone, alive = psutil.wait_procs(children, timeout=10)
    assert alive == []


def test_in_process_calls_restore_the_handlers():
    from judder.cli import main
    before = signal.getsignal(signal.SIGINT), signal.getsignal(signal.SIGTERM)
    assert main(["params", "--json"]) == 0
    assert (signal.getsignal(signal.SIGINT),
            signal.getsignal(signal.SIGTERM)) == before
