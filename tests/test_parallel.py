"""The Dask executor: failures reported with their inputs and never lost,
results equal to a serial run on a scheduler and workers started as
separate processes, and no worker left behind after Ctrl-C or SIGTERM."""

import json
import math
import os
import select
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import psutil
import pytest
from numpy.testing import assert_array_equal

from sources import get_preset

from infra.errors import JudderError
from infra.parallel import (TaskFailure, TaskFailures, TaskInputErrors,
                            cluster, parallel_map)
from judder import api
from stability.uncertainty import Normal, Ranges, Uniform

ROOT = Path(__file__).resolve().parents[1]
DASK = Path(sys.executable).parent / "dask"


# jobs for math.sqrt (importable on every worker, unlike a function of a
# test module): job 3 fails
JOBS = [0.0, 1.0, 2.0, -1.0, 4.0, 5.0, 6.0, 7.0]
DOMAIN = "ValueError: math domain error"


@pytest.fixture(scope="module")
def scheduler(tmp_path_factory):
    """A Dask scheduler and two single-threaded workers, each its own
    process on localhost, as on a real cluster."""
    folder = tmp_path_factory.mktemp("dask")
    file = folder / "scheduler.json"
    quiet = {"stdout": subprocess.DEVNULL, "stderr": subprocess.DEVNULL,
             "cwd": ROOT}
    procs = [subprocess.Popen(
        [str(DASK), "scheduler", "--host", "127.0.0.1", "--port", "0",
         "--no-dashboard", "--scheduler-file", str(file)], **quiet)]
    try:
        deadline = time.monotonic() + 60
        address = None
        while address is None and time.monotonic() < deadline:
            time.sleep(0.1)
            try:
                address = json.loads(file.read_text())["address"]
            except (OSError, ValueError, KeyError):
                pass
        procs += [subprocess.Popen(
            [str(DASK), "worker", address, "--nthreads", "1",
             "--nworkers", "1", "--no-dashboard",
             "--local-directory", str(folder)], **quiet) for _ in range(2)]
        from distributed import Client
        with Client(address, timeout=30) as client:
            client.wait_for_workers(2, timeout=60)
        yield address
    finally:
        for proc in reversed(procs):
            proc.terminate()
        for proc in procs:
            proc.wait(timeout=30)


def test_serial_failures_are_reported_and_the_others_go_on():
    with pytest.raises(TaskFailures) as caught:
        done = []
        for value in parallel_map(math.sqrt, JOBS[:6], workers=1):
            done.append(value)
    assert done == [0.0, 1.0, math.sqrt(2), 2.0, math.sqrt(5)]
    (failure,) = caught.value.failures
    assert failure == TaskFailure(3, "-1.0", DOMAIN)
    # a ValueError inside a job is a bug (exit 1), not an input error
    assert not isinstance(caught.value, JudderError)
    assert f"1 of 6 jobs failed: job 3 (-1.0): {DOMAIN}" in str(caught.value)


def _refuse_negative(x):
    if x < 0:
        raise JudderError(f"x = {x:g} is not allowed; allowed: x >= 0")
    return x


def test_jobs_failing_on_their_input_are_an_input_error():
    with pytest.raises(TaskInputErrors) as caught:
        list(parallel_map(_refuse_negative, JOBS[:6], workers=1))
    assert isinstance(caught.value, JudderError)     # exit status 2
    assert str(caught.value) == ("1 of 6 jobs failed: job 3 (-1.0): x = -1 "
                                 "is not allowed; allowed: x >= 0")
    assert caught.value.failures[0].input_error


def test_one_bug_among_input_errors_makes_the_whole_a_bug():
    jobs = [-1.0, "text"]
    with pytest.raises(TaskFailures) as caught:
        list(parallel_map(_refuse_negative, jobs, workers=1))
    assert not isinstance(caught.value, JudderError)
    assert [f.input_error for f in caught.value.failures] == [True, False]
    assert "job 1 ('text'): TypeError" in str(caught.value)


def test_existing_cluster_equals_serial_and_keeps_failures(scheduler):
    serial = list(parallel_map(math.sqrt, JOBS, workers=1, failures="yield"))
    with cluster(scheduler=scheduler):
        remote = list(parallel_map(math.sqrt, JOBS, failures="yield",
                                   describe=lambda x: f"x = {x}"))
        with pytest.raises(TaskFailures, match="job 3 \\(-1.0\\)"):
            list(parallel_map(math.sqrt, JOBS))
    assert remote[:3] == serial[:3] and remote[4:] == serial[4:]
    assert remote[3] == TaskFailure(3, "x = -1.0", DOMAIN)
    assert serial[3].message == DOMAIN


def test_an_envelope_on_the_cluster_equals_the_serial_one(scheduler):
    # samples and the refinement between them, on the two worker processes
    fitted = get_preset("paper-4dof-fitted")
    ranges = Ranges((Uniform("c12", 8.0, 12.0),
                     Normal("mu_g", 0.022, 0.001)))
    run = dict(ranges=ranges, freq_hz=[104.0, 110.0], p_max_bar=0.6,
               samples=2, refine=2, parameters=fitted)
    serial = api.envelope(workers=1, **run).envelope
    with cluster(scheduler=scheduler):
        remote = api.envelope(**run).envelope
    assert np.isfinite(serial.broadest).any()
    for name in ("amplitude", "nominal", "refined", "refined_values",
                 "probability", "broadest"):
        assert_array_equal(getattr(remote, name), getattr(serial, name))


def test_workers_and_scheduler_together_are_refused():
    # the library names its arguments; the command line says its options
    with pytest.raises(JudderError, match="`workers` 2 is not allowed with "
                                          "`scheduler`"):
        with cluster(workers=2, scheduler="tcp://127.0.0.1:1"):
            pass
    with pytest.raises(JudderError, match="`workers` 0"):
        with cluster(workers=0):
            pass


#: Jobs that never end on two local workers, after a line 'ready' once the
#: cluster runs (while it starts, Ctrl-C is ignored: infra.parallel);
#: Ctrl-C exits 130.
_ENDLESS = ("import sys, time\n"
            "from infra.parallel import cluster, parallel_map\n"
            "if __name__ == '__main__':\n"
            "    try:\n"
            "        with cluster(2):\n"
            "            list(parallel_map(abs, [1, 2], workers=2))\n"
            "            print('ready', flush=True)\n"
            "            list(parallel_map(time.sleep, [600] * 4))\n"
            "    except KeyboardInterrupt:\n"
            "        sys.exit(130)\n")


@pytest.mark.parametrize("signum, status", [(signal.SIGINT, 130),
                                            (signal.SIGTERM, 143)])
def test_a_signal_closes_the_local_cluster(tmp_path, signum, status,
                                          markers):
    # a signal to the command alone, while its two workers run: they must
    # go with it, quietly
    script = tmp_path / "endless.py"
    script.write_text(_ENDLESS)
    proc = subprocess.Popen([sys.executable, str(script)], cwd=ROOT,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True, preexec_fn=markers.with_ctrl_c)
    try:
        ready, _, _ = select.select([proc.stdout], [], [], 120)
        assert ready and proc.stdout.readline() == "ready\n", \
            "the cluster did not start"
        markers.wait_for(lambda: len(markers.workers(proc.pid)) == 2,
                         "two Dask workers")
        workers = markers.workers(proc.pid)
        os.kill(proc.pid, signum)
        _, err = proc.communicate(timeout=60)
    finally:
        if proc.poll() is None:
            proc.kill()
    assert proc.returncode == status, err
    gone, alive = psutil.wait_procs(workers, timeout=10)
    assert not alive, f"worker processes left: {alive}"
    assert err == "", err


def test_a_plain_script_without_a_main_guard_runs_once(tmp_path):
    # worker processes import their parent's __main__ from its file: an
    # unguarded script ran its calls again in each worker and died with
    # "RuntimeError: Nanny failed to start" (the README's snippet did)
    script = tmp_path / "unguarded.py"
    script.write_text(
        "import numpy as np\n"
        "from judder import api\n"
        "print('body', flush=True)\n"
        "r = api.sensitivity(['k24'], np.linspace(80, 130, 12), 1.0,\n"
        "                    workers=2)\n"
        "print('cases', r.cases)\n")
    root = Path(__file__).resolve().parents[1]
    proc = subprocess.run([sys.executable, str(script)], cwd=tmp_path,
                          capture_output=True, text=True, timeout=600,
                          env={**os.environ, "PYTHONPATH": str(root)})
    assert proc.returncode == 0, proc.stderr[-2000:]
    assert proc.stdout.split() == ["body", "cases", "3"]
    assert "Nanny" not in proc.stderr
