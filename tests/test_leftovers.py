"""Nothing left behind (issue 34): no Dask scratch after a run, nor after
a SIGKILL once the next cluster starts; no empty folder from a failed
FMU build; a command's outputs written all or none."""

import os
from pathlib import Path
import resource
import select
import signal
import subprocess
import sys

ROOT = Path(__file__).resolve().parents[1]
BENCH = ROOT / "examples" / "bench"

#: A cluster of two workers; 'ready' once it runs, then jobs that never
#: end (until killed).
_ENDLESS = ("import time\n"
            "from infra.parallel import cluster, parallel_map\n"
            "if __name__ == '__main__':\n"
            "    with cluster(2):\n"
            "        list(parallel_map(abs, [1, 2], workers=2))\n"
            "        print('ready', flush=True)\n"
            "        list(parallel_map(time.sleep, [600] * 4))\n")

_ONCE = ("import math\n"
         "from infra.parallel import parallel_map\n"
         "if __name__ == '__main__':\n"
         "    print(list(parallel_map(math.sqrt, [0.0, 4.0, 9.0], "
         "workers=2)))\n")


def _python(script, tmp, **kw):
    return subprocess.Popen(
        [sys.executable, "-c", script], cwd=ROOT, text=True,
        stdout=subprocess.PIPE, stderr=subprocess.PIPE,
        env={**os.environ, "TMPDIR": str(tmp)}, **kw)


def test_a_dask_run_leaves_no_scratch(tmp_path):
    scratch = tmp_path / "tmp"
    scratch.mkdir()
    out, err = _python(_ONCE, scratch).communicate(timeout=300)
    assert out == "[0.0, 2.0, 3.0]\n", err
    # no dask-scratch-space/global.lock, purge.lock, no judder-dask-*
    assert list(scratch.iterdir()) == []


def test_the_scratch_of_a_killed_cluster_goes_with_the_next_one(tmp_path):
    scratch = tmp_path / "tmp"
    scratch.mkdir()
    proc = _python(_ENDLESS, scratch)
    try:
        ready, _, _ = select.select([proc.stdout], [], [], 300)
        assert ready and proc.stdout.readline() == "ready\n"
    finally:
        proc.kill()
        proc.communicate(timeout=60)
    left = [p.name for p in scratch.iterdir()]
    assert [n for n in left if n.startswith(f"judder-dask-{proc.pid}-")]
    # a folder of a living process stays
    alive = scratch / f"judder-dask-{os.getpid()}-mine"
    alive.mkdir()
    out, err = _python(_ONCE, scratch).communicate(timeout=300)
    assert out == "[0.0, 2.0, 3.0]\n", err
    assert [p.name for p in scratch.iterdir()] == [alive.name]


def test_a_failed_fmu_build_leaves_no_folder(tmp_path):
    (tmp_path / "Bad.mo").write_text(
        "model Bad\n  Real x;\nequation\n  der(x) = -y;\nend Bad;\n")
    out = tmp_path / "fmus" / "here"
    done = subprocess.run(
        [sys.executable, "-m", "fmu", "Bad", "--library", str(tmp_path),
         "--out", str(out)], capture_output=True, text=True, timeout=300,
        cwd=ROOT)
    assert done.returncode == 2, done.stderr
    assert "unresolved component reference: 'y'" in done.stderr
    assert not (tmp_path / "fmus").exists()


def test_a_chart_on_a_full_disk_writes_none_of_its_outputs(tmp_path):
    """RLIMIT_FSIZE stands for a full disk: the NPZ (5 kB) fits, the PNG
    (60 kB) does not; neither is left, nor the boundary."""
    def limit():
        resource.setrlimit(resource.RLIMIT_FSIZE, (20_000, 20_000))
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
    out = tmp_path / "out"
    out.mkdir()
    done = subprocess.run(
        [sys.executable, "-m", "judder", "chart", "--index",
         str(BENCH / "runs.csv"), "--channel", "upstream_speed=EngSpd_up",
         "--channel", "pressure=PressEVEN:bar",
         "--channel", "downstream_speed=OutSpd", "--workers", "1",
         "--out", str(out / "c.npz"), "--plot", str(out / "c.png"),
         "--boundary", str(out / "c.csv")],
        capture_output=True, text=True, timeout=300, preexec_fn=limit)
    assert done.returncode == 2, done.stderr
    assert done.stderr.startswith(f"judder: error: cannot write "
                                  f"{out / 'c.png'}: File too large")
    assert list(out.iterdir()) == []


def test_outputs_written_together_replace_nothing_on_failure(tmp_path):
    import pytest

    from infra.errors import JudderError
    from infra.files import all_or_none, write_text
    first, second = tmp_path / "a.csv", tmp_path / "b.csv"
    write_text(first, "# written by judder\nold\n")
    with pytest.raises(JudderError, match="late"):
        with all_or_none():
            write_text(first, "# written by judder\nnew\n")
            assert "old" in first.read_text().splitlines()   # not yet
            raise JudderError("late")
    assert "old" in first.read_text().splitlines()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.csv"]
    with all_or_none():
        write_text(first, "# written by judder\nnew\n")
        write_text(second, "# written by judder\nb\n")
    assert "new" in first.read_text().splitlines()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.csv", "b.csv"]
