"""Faults: signals mid-run, a full disk, a file the user owns, the umask,
concurrent campaigns into one folder. Nothing may be lost or left half
written, and every exit says why in one line."""

import csv
import os
import resource
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from sources import get_preset
from infra.errors import JudderError
from infra.files import MARK, save_npz, write_text, written_by_us
from infra.provenance import Provenance, recorded, tool_version
from judder.cli import main
from pysim.simulation.campaigns import Campaign, run_campaign

BIG_MAP = ["map", "--freq", "1:250:40000", "--pf", "0:1:50"]


def judder(*args, **kw):
    return subprocess.run([sys.executable, "-m", "judder", *args],
                          capture_output=True, text=True, timeout=300, **kw)


def test_sigterm_like_ctrl_c(tmp_path, markers):
    out = tmp_path / "big.npz"
    proc = subprocess.Popen([sys.executable, "-m", "judder", *BIG_MAP,
                             "--out", str(out)], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)
    import psutil
    child = psutil.Process(proc.pid)
    # in the map's middle: 3 s of CPU (imports about 1 s)
    markers.wait_for(lambda: markers.cpu_seconds(child) >= 3.0
                     or proc.poll() is not None, "3 s of the map")
    assert proc.poll() is None, "the map finished before SIGTERM"
    proc.send_signal(signal.SIGTERM)
    _, stderr = proc.communicate(timeout=60)
    assert proc.returncode == 143
    assert "terminated" in stderr and "Traceback" not in stderr
    assert os.listdir(tmp_path) == []


def test_broken_pipe_is_quiet():
    proc = subprocess.run(
        f"{sys.executable} -m judder params --json | head -1",
        shell=True, capture_output=True, text=True, timeout=60)
    assert proc.stdout == "{\n"
    assert proc.stderr == ""


def test_full_disk_leaves_nothing(tmp_path):
    """RLIMIT_FSIZE stands for a full disk (no tmpfs without root)."""
    def limit():
        resource.setrlimit(resource.RLIMIT_FSIZE, (2000, 2000))
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
    out = tmp_path / "m.npz"
    proc = subprocess.run(
        [sys.executable, "-m", "judder", "map", "--freq", "10:200:40",
         "--pf", "0:1:40", "--out", str(out)], capture_output=True,
        text=True, timeout=120, preexec_fn=limit)
    assert proc.returncode == 2, proc.stderr
    assert "cannot write" in proc.stderr and "Traceback" not in proc.stderr
    assert os.listdir(tmp_path) == []


def test_internal_error_says_so(monkeypatch, capsys):
    from judder.commands import eig
    def broken(*args, **kw):
        raise RuntimeError("kaboom")
    monkeypatch.setattr(eig, "eig", broken)
    assert main(["eig"]) == 1
    err = capsys.readouterr().err
    assert "internal error" in err and "kaboom" in err and "report" in err
    assert len(err.splitlines()) == 1


def test_overwrite_rule_and_umask(tmp_path, capsys):
    user = tmp_path / "m.npz"
    user.write_text("mine")
    argv = ["map", "--freq", "100:110:2", "--pf", "0:0.3:2", "--out",
            str(user)]
    assert main(argv) == 2
    assert user.read_text() == "mine"
    assert main(argv + ["--force"]) == 0
    assert written_by_us(user)
    assert main(argv) == 0           # judder's own file: replaced
    old = os.umask(0o027)
    try:
        assert main(argv + ["--plot", str(tmp_path / "m.png")]) == 0
    finally:
        os.umask(old)
    assert (user.stat().st_mode & 0o777) == 0o640
    assert written_by_us(tmp_path / "m.png")
    capsys.readouterr()


@pytest.mark.parametrize("suffix", ["png", "svg", "pdf", "eps"])
def test_figures_carry_the_mark(tmp_path, suffix, capsys):
    path = tmp_path / f"t.{suffix}"
    assert main(["threshold", "--mu-g", "-0.001:0.001:5", "--c-ext",
                 "0:1:2", "--plot", str(path)]) == 0
    assert written_by_us(path)
    capsys.readouterr()


def test_marks_of_text_and_npz(tmp_path):
    write_text(tmp_path / "a.csv", "x\n1\n")
    # outside a command: the version alone, after the rows
    assert (tmp_path / "a.csv").read_text() == (
        f"x\n1\n# {MARK} {tool_version()}\n")
    with recorded(Provenance("0.1.0", "ab" * 32)):
        write_text(tmp_path / "a.toml", "x = 1\n")
    assert (tmp_path / "a.toml").read_text() == (
        f"# {MARK} 0.1.0, inputs sha256:{'ab' * 32}\nx = 1\n")
    save_npz(tmp_path / "a.npz", {"x": np.arange(3)})
    assert written_by_us(tmp_path / "a.npz")
    (tmp_path / "b.csv").write_text("x\n1\n")
    assert not written_by_us(tmp_path / "b.csv")


def _index(folder):
    with open(folder / "index.csv", newline="") as stream:
        return list(csv.DictReader(stream))


def test_campaign_identity_and_resume(tmp_path):
    params = get_preset("paper-4dof")
    close = Campaign(freq_hz=(100.0, 100.0 + 1e-9), p_f_bar=(0.05,),
                     duration=0.3, formats=("csv",))
    rows = run_campaign(close, params, tmp_path, workers=1)
    assert len({r["run_id"] for r in rows}) == 2       # no collision
    again = Campaign(freq_hz=(100.0,), p_f_bar=(0.05,), duration=0.3,
                     formats=("csv",), seed=7)
    other = run_campaign(again, params, tmp_path, workers=1)
    assert other[0]["run_id"] not in {r["run_id"] for r in rows}
    changed = run_campaign(close, params.replace(c12=2.0), tmp_path,
                           workers=1)
    assert not {r["run_id"] for r in changed} & {r["run_id"] for r in rows}
    ids = [r["run_id"] for r in _index(tmp_path)]
    assert len(ids) == len(set(ids)) == 5              # nothing lost
    for row in _index(tmp_path):
        assert (tmp_path / row["files"]).exists()
    assert not list(tmp_path.glob(".*.part"))


def test_concurrent_campaigns_into_one_folder(tmp_path):
    args = ["campaign", "--out", str(tmp_path), "--pf", "0.05",
            "--duration", "0.3", "--format", "csv", "--workers", "1"]
    procs = [subprocess.Popen([sys.executable, "-m", "judder", *args,
                               "--freq", freq], stdout=subprocess.PIPE,
                              stderr=subprocess.PIPE, text=True)
             for freq in ("60:100:3", "80:120:3")]
    for proc in procs:
        _, err = proc.communicate(timeout=300)
        assert proc.returncode == 0, err
    rows = _index(tmp_path)
    ids = [r["run_id"] for r in rows]
    assert len(ids) == len(set(ids)) == 4    # 80 and 100 Hz in both grids
    assert all(r["status"] == "ok" for r in rows)
    assert not list(tmp_path.glob(".*.part"))


def test_campaign_refuses_foreign_index(tmp_path):
    (tmp_path / "index.csv").write_bytes(b"\xff\xfe")
    with pytest.raises(JudderError, match="index"):
        run_campaign(Campaign(freq_hz=(100.0,), p_f_bar=(0.05,),
                              duration=0.3), get_preset("paper-4dof"),
                     tmp_path, workers=1)


@pytest.mark.parametrize("sig", [signal.SIGTERM, signal.SIGKILL])
def test_campaign_workers_die_with_their_parent(tmp_path, sig, markers):
    proc = subprocess.Popen(
        [sys.executable, "-m", "judder", "campaign", "--out", str(tmp_path),
         "--freq", "60:200:15", "--pf", "0.05:0.3:4", "--duration", "0.3",
         "--format", "csv", "--workers", "2"], stdout=subprocess.PIPE,
        stderr=subprocess.PIPE, text=True)
    index = tmp_path / "index.csv"
    deadline = time.time() + 300
    while not index.exists() or len(index.read_text().splitlines()) < 3:
        assert proc.poll() is None and time.time() < deadline
        time.sleep(0.1)
    # the workers may be started from any thread (Dask's nannies run in
    # its event-loop thread): the children of every task of the process
    children = " ".join(
        (task / "children").read_text()
        for task in Path(f"/proc/{proc.pid}/task").iterdir())
    assert children.split(), "no worker processes"
    proc.send_signal(sig)
    _, err = proc.communicate(timeout=60)
    assert proc.returncode == (143 if sig == signal.SIGTERM else -9)
    assert "Traceback" not in err

    def left():
        # a pid may be reused: only a judder process counts
        alive = []
        for pid in children.split():
            try:
                with open(f"/proc/{pid}/cmdline") as stream:
                    if "judder" in stream.read():
                        alive.append(pid)
            except OSError:
                pass
        return alive
    markers.wait_for(lambda: not left(), "the workers' end", timeout=30)
    if sig == signal.SIGTERM:
        assert not list(tmp_path.glob(".*.part"))
    # SIGKILL cannot be caught: a write cut short may leave its ``.part``
    # (the next run into the folder removes it), never a half index
    rows = _index(tmp_path)
    assert rows and all((tmp_path / name).exists() for r in rows
                        for name in r["files"].split())


def test_resume_removes_parts_of_a_killed_run_only(tmp_path):
    old, young = tmp_path / ".index.csv.killed.part", tmp_path / ".r.live.part"
    old.write_text("cut short")
    young.write_text("being written")
    hour_ago = time.time() - 3600
    os.utime(old, (hour_ago, hour_ago))
    run_campaign(Campaign(freq_hz=(100.0,), p_f_bar=(0.05,), duration=0.3,
                          formats=("csv",)), get_preset("paper-4dof"),
                 tmp_path, workers=1)
    assert not old.exists() and young.exists()


def test_fmu_command_contract(tmp_path):
    """``python -m fmu``: bad input exits 2 in one line; a model whose
    parameters are all literal builds, and its FMU gives x(1) = exp(-k)."""
    def fmu(*args):
        return subprocess.run([sys.executable, "-m", "fmu", *args],
                              capture_output=True, text=True, timeout=300)
    for args, word in ((["--tolerance", "-1"], "--tolerance"),
                       (["--tolerance", "nan"], "--tolerance"),
                       (["Judder.Nope", "--out", str(tmp_path)], "Nope")):
        proc = fmu(*args)
        assert proc.returncode == 2 and word in proc.stderr
        assert len(proc.stderr.splitlines()) == 1, proc.stderr
    (tmp_path / "Tiny.mo").write_text(
        "model Tiny\n  parameter Real k = 2;\n"
        "  Real x(start=1, fixed=true);\nequation\n  der(x) = -k*x;\n"
        "end Tiny;\n")
    proc = fmu("Tiny", "--library", str(tmp_path), "--out", str(tmp_path),
               "--fmi", "2.0")
    assert proc.returncode == 0, proc.stderr
    from fmpy import simulate_fmu
    result = simulate_fmu(str(tmp_path / "Tiny.fmu"), stop_time=1.0,
                          output=["x"], start_values={"k": 3.0},
                          fmi_type="ModelExchange")
    assert result["x"][-1] == pytest.approx(np.exp(-3.0), rel=1e-6)


def test_api_save_keeps_a_file_judder_did_not_write(tmp_path):
    from judder import api
    result = api.tongues(np.linspace(90, 110, 5), 0.5)
    mine = tmp_path / "mine.csv"
    mine.write_text("freq,my notes\n")
    with pytest.raises(JudderError, match="judder did not write it"):
        result.save(mine)
    assert mine.read_text() == "freq,my notes\n"
    result.save(mine, force=True)
    assert written_by_us(mine)
    result.save(mine)                   # its own file: replaced anyway
