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

# 0: the handlers are in place and numpy, scipy and Dask are being
# imported (the whole import takes about 0.5 s); 0.2 s later: still
# importing, or parsing.
@pytest.mark.parametrize("sig, status, word", [
    (signal.SIGINT, 130, "interrupted"), (signal.SIGTERM, 143, "terminated")])
@pytest.mark.parametrize("after", [0.0, 0.2])
def test_signal_while_starting(tmp_path, sig, status, word, after, markers):
    out = tmp_path / "m.npz"
    proc = _start([*LONG_MAP, "--out", str(out)],
                  preexec_fn=markers.with_ctrl_c)
    markers.wait_for(lambda: markers.handles_signals(proc.pid),
                     "signal handlers")
    time.sleep(after)
    assert proc.poll() is None
    proc.send_signal(sig)
    _, stderr = proc.communicate(timeout=60)
    assert proc.returncode == status, stderr
    assert _one_line(stderr) == f"judder: {word}; no partial output was written"
    assert os.listdir(tmp_path) == []


def test_ctrl_c_during_a_map(tmp_path, markers):
    import psutil
    out = tmp_path / "m.npz"
    proc = _start([*LONG_MAP, "--out", str(out)],
                  preexec_fn=markers.with_ctrl_c)
    # in the map's middle: 3 s of CPU (the imports take about 1 s, the
    # map about 10 s)
    child = psutil.Process(proc.pid)
    markers.wait_for(lambda: markers.cpu_seconds(child) >= 3.0
                     or proc.poll() is not None, "3 s of the map")
    assert proc.poll() is None, "the map finished before Ctrl-C"
    proc.send_signal(signal.SIGINT)
    _, stderr = proc.communicate(timeout=60)
    assert proc.returncode == 130, stderr
    assert "interrupted" in _one_line(stderr)
    assert os.listdir(tmp_path) == []      # neither the file nor a .part


def test_ctrl_c_of_the_process_group_with_workers(tmp_path, markers):
    """A terminal's Ctrl-C reaches the Dask workers too: one line, the
    workers gone."""
    import psutil
    out = tmp_path / "s.csv"
    proc = _start(["sensitivity", "--params", "k12,k24,J2,J4,c12,mu_g", "--freq",
                   "20:220:2000", "--workers", "2", "--out", str(out)],
                  start_new_session=True, preexec_fn=markers.with_ctrl_c)
    markers.wait_for(lambda: markers.workers_computing(proc.pid),
                     "two workers computing")
    children = psutil.Process(proc.pid).children(recursive=True)
    assert proc.poll() is None
    os.killpg(proc.pid, signal.SIGINT)
    _, stderr = proc.communicate(timeout=60)
    assert proc.returncode == 130, stderr
    assert "interrupted" in _one_line(stderr)
    assert os.listdir(tmp_path) == []
    gone, alive = psutil.wait_procs(children, timeout=10)
    assert alive == []


def test_a_second_signal_does_not_wait_for_the_clean_up(tmp_path, markers):
    """Closing two Dask workers takes seconds; a second SIGTERM in them
    ends the command at once, saying a .part file may remain."""
    proc = _start(["sensitivity", "--params", "k12,k24,J2,J4,c12,mu_g",
                   "--freq", "20:220:2000", "--workers", "2", "--out",
                   str(tmp_path / "s.csv")])
    markers.wait_for(lambda: markers.workers_computing(proc.pid),
                     "two workers computing")
    start = time.monotonic()
    # SIGTERM again every 50 ms until it ends: two signals before the
    # first is handled count as one, so the second is the first that
    # finds the clean-up running, however loaded the machine
    while proc.poll() is None and time.monotonic() - start < 60:
        proc.send_signal(signal.SIGTERM)
        time.sleep(0.05)
    _, stderr = proc.communicate(timeout=60)
    assert time.monotonic() - start < 2.0
    assert proc.returncode == 143, stderr
    assert stderr.splitlines()[0] == (
        "judder: stopped again while cleaning up; a temporary "
        ".NAME.*.part file may remain")
    assert "Traceback" not in stderr


def test_in_process_calls_restore_the_handlers():
    from judder.cli import main
    before = signal.getsignal(signal.SIGINT), signal.getsignal(signal.SIGTERM)
    assert main(["params", "--json"]) == 0
    assert (signal.getsignal(signal.SIGINT),
            signal.getsignal(signal.SIGTERM)) == before


# -- a third-party FMU that crashes, hangs or returns NaN --------------

FOUR = "Judder.Examples.Driveline4DOF"
_DD = "fmi2Status fmi2GetDirectionalDerivative("
#: C edits of the FMU's own fmi2.c: (text after which to insert, code).
SABOTAGE = {
    # a segfault in fmi2GetDirectionalDerivative
    "crashdd": (None, "*(volatile int *)0 = 0;"),
    # a segfault while the binary is loaded (dlopen runs constructors)
    "crashload": ("#include \"instance.h\"\n",
                  "#include <signal.h>\n__attribute__((constructor)) static "
                  "void judder_boom(void) { raise(SIGSEGV); }\n"),
    # fmi2GetDirectionalDerivative never returns
    "hangdd": (None, "for (volatile int spin = 1; spin;) {}"),
    # fmi2GetDirectionalDerivative writes NaN after its result
    "nandd": (None, "dz[0] = 0.0 / 0.0; return fmi2OK;"),
}


def _sabotaged(tmp_path, kind):
    """A copy of the 4-DOF FMU whose binary is compiled from its own
    sources with one edit of fmi2.c (see SABOTAGE)."""
    import zipfile
    from fmu.build import fmi_headers
    from fmu.description import SOURCES
    from fmu.store import ensure_fmu
    source = ensure_fmu(FOUR)
    work = tmp_path / kind
    with zipfile.ZipFile(source) as z:
        z.extractall(work)
    wrapper = work / "sources" / "fmi2.c"
    text = wrapper.read_text()
    after, code = SABOTAGE[kind]
    if after is None:       # at the top of fmi2GetDirectionalDerivative
        start = text.index(_DD)
        brace = text.index("{", start) + 1
        if kind == "nandd":     # after the model's own result
            code = ""
            text = text.replace(
                "    return STATUS(instance_directional(CORE(c), z, nz, v, nv, "
                "dv, dz, 0));",
                "    fmi2Status status = STATUS(instance_directional(CORE(c), "
                "z, nz, v, nv, dv, dz, 0));\n    dz[0] = 0.0 / 0.0;\n"
                "    return status;", 1)
            assert "dz[0] = 0.0 / 0.0" in text
        else:
            text = text[:brace] + code + text[brace:]
    else:
        assert after in text
        text = text.replace(after, after + code, 1)
    wrapper.write_text(text)
    library = next((work / "binaries" / "linux64").glob("*.so"))
    sources = work / "sources"
    subprocess.run(["gcc", "-shared", "-fPIC", "-O2", "-fvisibility=hidden",
                    "-std=c99", f"-I{sources}", f"-I{fmi_headers()}",
                    *[str(sources / name) for name in SOURCES["2.0"]],
                    "-o", str(library), "-lm"], check=True)
    target = tmp_path / f"{kind}.fmu"
    with zipfile.ZipFile(target, "w") as z:
        for item in sorted(work.rglob("*")):
            if item.is_file():
                z.write(item, item.relative_to(work).as_posix())
    return target


def _scratch(tmp_path):
    """A temporary folder of the child's own (``TMPDIR``), so that what it
    leaves behind is told apart from the folders of the tests beside it,
    and the environment that gives it."""
    scratch = tmp_path / "scratch"
    scratch.mkdir()
    return scratch, {**os.environ, "TMPDIR": str(scratch)}


def _left_in(scratch, prefixes=("judder-fmu-", "tmp")):
    """The FMU folders left in ``scratch``."""
    return [p.name for p in scratch.iterdir() if p.name.startswith(prefixes)]


@pytest.mark.parametrize("kind, command, words", [
    ("crashdd", ["map", "--freq", "100:110:3", "--pf", "0:0.3:3"],
     ["crashed (SIGSEGV)", "fmi2GetDirectionalDerivative at t = 0 s"]),
    ("crashdd", ["check", "--freq", "105", "--pf", "0.2"],
     ["crashed (SIGSEGV)", "fmi2GetDirectionalDerivative"]),
    ("crashload", ["map", "--freq", "100:110:3", "--pf", "0:0.3:3"],
     ["crashed (SIGSEGV)", "loading the binary"]),
    ("nandd", ["check", "--freq", "105", "--pf", "0.2"],
     ["the FMU's Jacobian has a non-finite value"]),
])
def test_a_crashing_fmu_is_one_line(tmp_path, kind, command, words):
    fmu = _sabotaged(tmp_path, kind)
    scratch, env = _scratch(tmp_path)
    done = subprocess.run([sys.executable, "-m", "judder", *command,
                           "--fmu", str(fmu)], capture_output=True,
                          text=True, timeout=120, env=env)
    assert done.returncode == 2, done.stderr
    line = _one_line(done.stderr)
    assert line.startswith(f"judder: error: --fmu {fmu}: "), line
    for word in words:
        assert word in line, line
    assert not _left_in(scratch)


def test_a_hanging_fmu_is_stopped(tmp_path):
    fmu = _sabotaged(tmp_path, "hangdd")
    scratch, env = _scratch(tmp_path)
    start = time.monotonic()
    done = subprocess.run([sys.executable, "-m", "judder", "check", "--freq",
                           "105", "--pf", "0.2", "--fmu", str(fmu)],
                          capture_output=True, text=True, timeout=120,
                          env={**env, "JUDDER_FMU_TIMEOUT": "3"})
    assert time.monotonic() - start < 30
    assert done.returncode == 2, done.stderr
    line = _one_line(done.stderr)
    assert "no answer within 3 s" in line, line
    assert "fmi2GetDirectionalDerivative at t = 0 s" in line, line
    assert "JUDDER_FMU_TIMEOUT" in line
    assert not _left_in(scratch)


def test_the_fmu_child_is_killed_with_its_command(tmp_path):
    """SIGTERM while a hung FMU's child runs: the command ends with 143,
    the child and the extracted folder go with it."""
    import psutil
    fmu = _sabotaged(tmp_path, "hangdd")
    scratch, env = _scratch(tmp_path)
    proc = _start(["check", "--freq", "105", "--pf", "0.2", "--fmu",
                   str(fmu)], env=env)
    deadline = time.monotonic() + 60
    children = []
    while time.monotonic() < deadline and not children:
        time.sleep(0.2)
        children = [c for c in psutil.Process(proc.pid).children()
                    if "sources.fmu_host" in " ".join(c.cmdline())]
    assert children
    proc.send_signal(signal.SIGTERM)
    _, stderr = proc.communicate(timeout=60)
    assert proc.returncode == 143, stderr
    assert "terminated" in _one_line(stderr)
    gone, alive = psutil.wait_procs(children, timeout=10)
    assert alive == []
    assert not _left_in(scratch, ("judder-fmu-",))


# -- a scheduler that is not one ---------------------------------------

def _serve(sock, mode):
    import socket
    held = []
    while True:
        try:
            conn, _ = sock.accept()
        except OSError:
            return
        held.append(conn)          # kept open: a silent peer
        if mode == "garbage":
            try:
                conn.sendall(b"HTTP/1.1 200 OK\r\n\r\nnot dask\r\n" * 8)
            except OSError:
                pass


@pytest.fixture(scope="module")
def fake_schedulers():
    """Addresses: one that accepts and says nothing, one that answers
    garbage, one where nothing listens."""
    import socket
    import threading
    addresses, sockets = {}, []
    for mode in ("silent", "garbage"):
        sock = socket.socket()
        sock.bind(("127.0.0.1", 0))
        sock.listen(16)
        sockets.append(sock)
        threading.Thread(target=_serve, args=(sock, mode),
                         daemon=True).start()
        addresses[mode] = f"127.0.0.1:{sock.getsockname()[1]}"
    closed = socket.socket()
    closed.bind(("127.0.0.1", 0))
    addresses["refused"] = f"127.0.0.1:{closed.getsockname()[1]}"
    closed.close()
    yield addresses
    for sock in sockets:
        sock.close()


EXAMPLES = os.path.join(os.path.dirname(__file__), "..", "examples")
CHANNELS = ["--channel", "upstream_speed=EngSpd_up", "--channel",
            "pressure=PressEVEN:bar", "--channel", "downstream_speed=OutSpd"]
#: Every command that takes --scheduler, with arguments that pass.
SCHEDULED = {
    "sensitivity": ["sensitivity", "--params", "k12", "--freq", "20:120:20"],
    "fit": ["fit", "--boundary", f"{EXAMPLES}/measured_boundary.csv"],
    "crosscheck": ["crosscheck", "--freq", "100", "--pf", "0.1"],
    "campaign": ["campaign", "--freq", "40:60:3", "--pf", "0.5", "--out",
                 "{tmp}/campaign"],
    "chart": ["chart", "--index", f"{EXAMPLES}/bench/runs.csv", *CHANNELS],
    "report": ["report", "--out", "{tmp}/report.html"],
    "envelope": ["envelope", "--ranges", f"{EXAMPLES}/ranges.toml",
                 "--freq", "60:200:11", "--samples", "4"],
}


def _in_process(argv, capsys):
    from judder.cli import main
    try:
        status = main(argv)
    except SystemExit as exc:
        status = exc.code
    return status, capsys.readouterr().err


@pytest.mark.parametrize("command", sorted(SCHEDULED))
def test_a_garbage_scheduler_is_refused_by_every_command(
        command, fake_schedulers, tmp_path, capsys):
    address = fake_schedulers["garbage"]
    argv = [a.replace("{tmp}", str(tmp_path)) for a in SCHEDULED[command]]
    start = time.monotonic()
    status, err = _in_process([*argv, "--scheduler", address], capsys)
    assert time.monotonic() - start < 10
    assert status == 2, err
    assert _one_line(err) == (
        f"judder: error: --scheduler {address}: it does not speak the Dask "
        "protocol; allowed: the address of a running Dask scheduler")
    assert os.listdir(tmp_path) == []


@pytest.mark.parametrize("mode, words", [
    ("silent", "no Dask answer within 5 s"),
    ("refused", "cannot connect (Connection refused)")])
@pytest.mark.parametrize("command", ["sensitivity", "chart", "fit"])
def test_a_dead_scheduler_is_refused_within_seconds(
        command, mode, words, fake_schedulers, tmp_path, capsys):
    address = fake_schedulers[mode]
    start = time.monotonic()
    status, err = _in_process([*SCHEDULED[command], "--scheduler", address],
                              capsys)
    assert time.monotonic() - start < 10
    assert status == 2, err
    line = _one_line(err)
    assert line.startswith(f"judder: error: --scheduler {address}: ")
    assert words in line


# -- values at the boundary: ranges, units, files ----------------------

F2 = '"fitted": {"c12": {"value": 10, "std": 1}, "mu_g": {"value": 0.02, "std": 0.001}}'
BOUNDARY_FILES = {
    "table_1e9.csv": "freq_hz,p_f_bar\n105,0.2\n1e9,0.2\n",
    "ranges_list.toml": "parameters = [1, 2]\n",
    "ranges_std.toml": '[parameters]\nmu_g = { distribution = "normal", '
                       'mean = 0.022, std = "big" }\n',
    "fit_size.json": "{" + F2 + ', "covariance": {"names": ["c12", "mu_g"],'
                     ' "matrix": [[1, 0, 0], [0, 1, 0], [0, 0, 1]]}}',
    "fit_names.json": "{" + F2 + ', "covariance": {"names": ["c12", "zz"], '
                      '"matrix": [[1, 0], [0, 1]]}}',
    "fit_std.json": '{"fitted": {"c12": {"value": 10, "std": "big"}}}',
    "fit_value.json": '{"fitted": {"c12": {"std": 1}}}',
    "ranges_fit_size.toml": '[fit]\nfile = "fit_size.json"\n',
    "ranges_fit_names.toml": '[fit]\nfile = "fit_names.json"\n',
    "ranges_fit_std.toml": '[fit]\nfile = "fit_std.json"\n',
    "ranges_fit_value.toml": '[fit]\nfile = "fit_value.json"\n',
    "NoClutch/package.mo": "package NoClutch\nend NoClutch;\n",
    "NoClutch/Chain.mo": (
        "within NoClutch;\nmodel Chain\n"
        "  Judder.Components.Inertia J1(J = 0.1);\n"
        "  Judder.Components.Inertia J2(J = 0.2);\n"
        "  Judder.Components.SpringDamper s(c = 1000, d = 1);\n"
        "  parameter Real p_f = 0;\n  parameter Real f_dither = 100;\n"
        "equation\n  connect(J1.flange_b, s.flange_a);\n"
        "  connect(s.flange_b, J2.flange_a);\nend Chain;\n"),
}

ENVELOPE = ["envelope", "--freq", "60:200:11", "--samples", "2", "--ranges"]
CHECK = ["check", "--freq", "105", "--pf", "0.2"]

BOUNDARY_CASES = [
    # the documented frequency range, 0.001 Hz to 100 kHz
    (["check", "--freq", "1e9", "--pf", "0.2"], 2,
     ["--freq 1e9", "<= 100000 Hz"]),
    (["check", "--freq", "105,1e9", "--pf", "0.2"], 2, ["--freq 1e9"]),
    (["check", "--table", "{d}/table_1e9.csv"], 2,
     ["line 3: column 'freq_hz' = 1e+09 Hz", "0.001 to 100000 Hz"]),
    (["advise", "--no-design", "--freq-range=60:1e9"], 2,
     ["--freq-range 1e9", "<= 100000 Hz"]),
    (["advise", "--no-design", "--freq-range", "120:90"], 2,
     ["--freq-range 120:90", "LOW < HIGH"]),
    # growth thresholds
    (["report", "--min-growth", "nan", "--out", "{d}/r.html"], 2,
     ["--min-growth nan", ">= 0 1/s"]),
    (["report", "--min-growth", "-1", "--out", "{d}/r.html"], 2,
     ["--min-growth -1", ">= 0 1/s"]),
    (["check", "--freq", "105", "--pf", "0.2", "--min-growth", "inf"], 2,
     ["--min-growth inf"]),
    # empty names of a driveline
    ([*CHECK, "--modelica", ""], 2, ["--modelica ''", "full class name"]),
    ([*CHECK, "--fmu", ""], 2, ["--fmu ''", ".fmu file"]),
    # ranges and covariance files
    ([*ENVELOPE, "{d}/ranges_list.toml"], 2,
     ["parameters = [1, 2] is not allowed", "[parameters] table"]),
    ([*ENVELOPE, "{d}/ranges_std.toml"], 2,
     ["parameters.mu_g.std = 'big'", "finite number"]),
    ([*ENVELOPE, "{d}/ranges_fit_size.toml"], 2,
     ["covariance: the matrix is not 2 x 2"]),
    ([*ENVELOPE, "{d}/ranges_fit_names.toml"], 2,
     ["covariance has no row for 'mu_g'"]),
    ([*ENVELOPE, "{d}/ranges_fit_std.toml"], 2,
     ["fitted.c12.std = 'big'", "finite number"]),
    ([*ENVELOPE, "{d}/ranges_fit_value.toml"], 2, ["fitted.c12 has no value"]),
    # a chart NPZ cut short (its zip directory is at the end)
    (["fit", "--chart", "{d}/truncated.npz", "--fit", "mu_g"], 2,
     ["--chart", "truncated.npz", "a truncated or damaged NPZ file"]),
    (["report", "--chart", "{d}/truncated.npz", "--out", "{d}/r.html"], 2,
     ["--chart", "a truncated or damaged NPZ file"]),
    # --group of a chart charted without --group-by ('allowed:' and nothing)
    (["fit", "--chart", "{d}/whole.npz", "--group", "65-70", "--fit",
      "mu_g"], 2, ["--group '65-70'", "one group", "allowed: no --group"]),
    # a Modelica driveline without a clutch
    (["map", "--modelica", "NoClutch.Chain", "--library", "{d}", "--freq",
      "100:110:3", "--pf", "0:0.3:3"], 2,
     ["NoClutch.Chain", "p_f does not enter", "clutch"]),
    # units where the README promises them
    (["check", "--freq", "105Hz", "--pf", "200mbar", "--json"], 0, []),
    (["check", "--freq", "0.105kHz,110", "--pf", "200mbar", "--json"], 0, []),
]


@pytest.fixture(scope="module")
def boundary_folder(tmp_path_factory):
    import numpy as np
    d = tmp_path_factory.mktemp("boundary")
    for name, text in BOUNDARY_FILES.items():
        (d / name).parent.mkdir(exist_ok=True)
        (d / name).write_text(text)
    np.savez(d / "whole.npz", boundary_group=np.array([""]),
             boundary_freq_hz=np.array([100.0]),
             boundary_p_f_bar=np.array([0.2]),
             boundary_tried_bar=np.array([1.0]))
    data = (d / "whole.npz").read_bytes()
    (d / "truncated.npz").write_bytes(data[:len(data) // 2])
    return d


@pytest.mark.parametrize("argv, status, words", BOUNDARY_CASES,
                         ids=[" ".join(c[0])[:60] for c in BOUNDARY_CASES])
def test_values_at_the_boundary(argv, status, words, boundary_folder, capsys):
    argv = [a.replace("{d}", str(boundary_folder)) for a in argv]
    got, err = _in_process(argv, capsys)
    assert "Traceback" not in err and "internal error" not in err, err
    assert got == status, err
    if status:
        line = _one_line(err)
        assert line.startswith("judder: error: ")
        for word in words:
            assert word in line, line


def test_units_mean_what_they_say(capsys):
    """--freq 105Hz --pf 200mbar is --freq 105 --pf 0.2 (check, report);
    --freq-range 90Hz:120Hz is 90:120 (advise)."""
    import json
    from judder.cli import main
    results = []
    for argv in (["check", "--freq", "105Hz", "--pf", "200mbar"],
                 ["check", "--freq", "105", "--pf", "0.2"]):
        assert main([*argv, "--params", "none", "--json"]) == 0
        out = json.loads(capsys.readouterr().out)
        out.pop("seconds", None)
        results.append(out)
    assert results[0] == results[1]
    for argv in (["advise", "--no-design", "--freq-range", "90Hz:120Hz"],
                 ["advise", "--no-design", "--freq-range", "90:120"]):
        assert main([*argv, "--json"]) == 0
        out = json.loads(capsys.readouterr().out)
        out.pop("seconds", None)
        results.append(out)
    assert results[2] == results[3]
    assert results[2]["operating_range"]["freq_hz"] == [90.0, 120.0]
    # report --freq 105Hz --pf 200mbar: the configured setting in Hz, bar
    from judder.cli import build_parser
    args = build_parser().parse_args(["report", "--out", "r.html", "--freq",
                                      "105Hz", "--pf", "200mbar"])
    assert (args.freq, args.pf) == (105.0, pytest.approx(0.2, rel=1e-15))


# -- memory and work a typo would take ---------------------------------

@pytest.mark.parametrize("hours, argv, words", [
    # 199 901 frequencies 0.5 Hz apart; grew to 23 GB with 60:1e9 before
    (None, ["advise", "--no-design", "--freq-range=60:100000"],
     ["--freq-range 60:100000 makes 199901 frequencies", "at most 100000"]),
    # 1e10 settings: the list of pairs alone would not fit
    (None, ["check", "--freq", "60:200:100000", "--pf", "0:1:100000"],
     ["10000000000 settings", "fewer --freq x --pf settings"]),
    # ... also when the time limit is raised
    ("1e9", ["check", "--freq", "60:200:100000", "--pf", "0:1:100000"],
     ["--freq x --pf asks for 1e+10 settings", "at most 100000"]),
])
def test_a_typo_cannot_take_the_machine(hours, argv, words, capsys,
                                        monkeypatch):
    if hours is not None:
        monkeypatch.setenv("JUDDER_MAX_HOURS", hours)
    import resource
    before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    start = time.monotonic()
    status, err = _in_process(argv, capsys)
    assert time.monotonic() - start < 10
    assert status == 2, err
    line = _one_line(err)
    for word in words:
        assert word in line, line
    # refused before any allocation of that size (ru_maxrss in kB)
    assert resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - before \
        < 200_000


def test_advise_memory_estimate_names_the_option(monkeypatch, capsys):
    """20 000 Hz at 0.5 Hz steps: 39 901 frequencies x 12.5 kB = 0.465 GiB,
    refused when only 0.5 GiB is left (80 % of it is the bound)."""
    from studies import _preflight
    monkeypatch.setattr(_preflight, "available_memory", lambda: 2 ** 29)
    status, err = _in_process(["advise", "--no-design",
                               "--freq-range=60:20000"], capsys)
    assert status == 2
    line = _one_line(err)
    assert "--freq-range 60:20000 needs about 0.465 GiB (39901 frequencies" \
        in line, line
    assert "0.5 GiB are available" in line


def test_available_memory_follows_ulimit():
    """``ulimit -v`` is what a batch system sets: the estimate uses what
    is left of it."""
    script = ("import resource; from studies._preflight "
              "import available_memory as a; print(a())")
    done = subprocess.run(
        ["bash", "-c", f"ulimit -v 3000000; {sys.executable} -c '{script}'"],
        capture_output=True, text=True, timeout=60,
        cwd=os.path.join(os.path.dirname(__file__), ".."))
    left = int(done.stdout)
    assert 0 < left < 3000000 * 1024


# -- the overwrite rule ------------------------------------------------

REPORT = ["report", "--map-freq", "90:120:10", "--map-pf", "0:1:10",
          "--grid", "90:120:20", "--sensitivity", "k24"]


@pytest.mark.skipif(not __import__("shutil").which("chromium"),
                    reason="--pdf needs Chromium")
def test_report_pdf_twice(tmp_path):
    """The second run recognises the first run's PDF and replaces it; a
    PDF of the user's is kept."""
    argv = [*REPORT, "--out", str(tmp_path / "r.html"), "--pdf",
            str(tmp_path / "r.pdf")]
    for _ in range(2):
        done = subprocess.run([sys.executable, "-m", "judder", *argv],
                              capture_output=True, text=True, timeout=600)
        assert done.returncode == 0, done.stderr
    from infra.files import written_by_us
    assert written_by_us(tmp_path / "r.pdf")
    _check_pdf_update((tmp_path / "r.pdf").read_bytes())
    mine = tmp_path / "mine.pdf"
    mine.write_bytes(b"%PDF-1.4\n% the user's\n")
    done = subprocess.run([sys.executable, "-m", "judder", *REPORT, "--out",
                           str(tmp_path / "s.html"), "--pdf", str(mine)],
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 2
    assert "--pdf" in _one_line(done.stderr) and "--force" in done.stderr
    assert mine.read_bytes() == b"%PDF-1.4\n% the user's\n"
    assert not (tmp_path / "s.html").exists()


def _check_pdf_update(data):
    """The last cross-reference section is where startxref says, and its
    one entry points at the information dictionary, whose Creator is the
    mark; the previous section is where /Prev says."""
    import re
    start = int(re.findall(rb"startxref\s+(\d+)", data)[-1])
    assert data[start:start + 5] == b"xref\n"
    entry = re.match(rb"xref\n(\d+) 1\n(\d{10}) (\d{5}) n \n", data[start:])
    number, offset = int(entry.group(1)), int(entry.group(2))
    assert data[offset:].startswith(b"%d 0 obj" % number)
    assert b"/Creator (written by judder " in data[offset:start]
    trailer = data[start:]
    assert b"/Info %d 0 R" % number in trailer
    previous = int(re.search(rb"/Prev (\d+)", trailer).group(1))
    assert data[previous:previous + 4] == b"xref"


def test_mark_pdf_keeps_the_title_and_the_rest():
    from infra.files import mark_pdf
    body = (b"%PDF-1.4\n1 0 obj\n<</Title (a \\(b\\))\n/Creator (Chrome \\(X\\) "
            b"x)>>\nendobj\n2 0 obj\n<</Type /Catalog>>\nendobj\n")
    xref = len(body)
    original = body + (b"xref\n0 3\n0000000000 65535 f \n0000000009 00000 n "
                       b"\n%010d 00000 n \ntrailer\n<</Size 3\n/Root 2 0 R\n"
                       b"/Info 1 0 R>>\nstartxref\n%d\n%%%%EOF\n"
                       % (body.index(b"2 0 obj"), xref))
    marked = mark_pdf(original)
    assert marked.startswith(original)
    _check_pdf_update(marked)
    update = marked[len(original):]
    assert b"/Title (a \\(b\\))" in update and b"Chrome" not in update
    assert b"/Prev %d" % xref in update


def test_checkpoint_on_the_output_is_refused_before_work(tmp_path, capsys):
    out = tmp_path / "e.npz"
    start = time.monotonic()
    status, err = _in_process(
        ["envelope", "--ranges", f"{EXAMPLES}/ranges.toml", "--freq",
         "60:200:11", "--samples", "2", "--out", str(out), "--checkpoint",
         str(out)], capsys)
    assert time.monotonic() - start < 5
    assert status == 2
    assert _one_line(err) == (
        f"judder: error: --checkpoint {out} is also given as --out; allowed: "
        "a different file for the checkpoint and each output")
    assert os.listdir(tmp_path) == []


# -- bench channels that cannot be right -------------------------------

def _bench_copy(tmp_path, edits):
    """The example bench with some runs' CSV rows edited:
    ``edits[name](rows)`` changes the rows (header first) in place."""
    import csv
    import shutil
    folder = tmp_path / "bench"
    shutil.copytree(os.path.join(EXAMPLES, "bench"), folder)
    for name, edit in edits.items():
        with open(folder / name, newline="") as stream:
            rows = list(csv.reader(stream))
        edit(rows)
        with open(folder / name, "w", newline="") as stream:
            csv.writer(stream).writerows(rows)
    return folder


def _one_huge_sample(rows):
    rows[500][1] = "1e300"


def _every_third_nan(rows):
    for row in rows[1::3]:
        row[1] = "nan"


def test_implausible_bench_samples_are_refused_per_run(tmp_path, capsys):
    """One speed sample of 1e300 rpm, or every third sample NaN: that run
    is refused with its reason, never folded into the chart; the other
    runs keep their verdicts."""
    import json
    from judder.cli import main
    clean = _bench_copy(tmp_path / "clean", {})
    assert main(["chart", "--index", str(clean / "runs.csv"), *CHANNELS,
                 "--workers", "1", "--json"]) == 0
    before = {os.path.basename(r["file"]): r
              for r in json.loads(capsys.readouterr().out)["runs"]}
    folder = _bench_copy(tmp_path, {"run01.csv": _one_huge_sample,
                                    "run02.csv": _every_third_nan})
    assert main(["chart", "--index", str(folder / "runs.csv"), *CHANNELS,
                 "--workers", "1", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    runs = {os.path.basename(r["file"]): r for r in data["runs"]}
    failed = {os.path.basename(f["file"]): f["message"]
              for f in data["failed"]}
    assert set(failed) == {"run01.csv", "run02.csv"}
    assert "1e+300 rpm at 0.735818 s is not a value a bench records" in \
        failed["run01.csv"]
    assert "run02.csv" in failed
    assert set(runs) == set(before) - {"run01.csv", "run02.csv"}
    for name, run in runs.items():
        assert run["judder"] == before[name]["judder"]
        assert run["amplitude_rpm"] == before[name]["amplitude_rpm"]


@pytest.mark.parametrize("rows", [1, "same"])
def test_a_run_without_a_time_base_is_one_line(tmp_path, rows, capsys):
    """A one-sample CSV, or one whose time stamps are all equal: the run
    is refused naming the file and channel (it was a TypeError in a job,
    reported with the job's Python repr)."""
    import csv
    with open(os.path.join(EXAMPLES, "bench", "run01.csv"),
              newline="") as stream:
        table = list(csv.reader(stream))
    if rows == 1:
        table = table[:2]
    else:
        table = [table[0]] + [["1.0", *row[1:]] for row in table[1:]]
    with open(tmp_path / "run.csv", "w", newline="") as stream:
        csv.writer(stream).writerows(table)
    (tmp_path / "runs.csv").write_text("file,freq_hz,p_f_bar\nrun.csv,210,"
                                       "0.4\n")
    from judder.cli import main
    status = main(["chart", "--index", str(tmp_path / "runs.csv"),
                   *CHANNELS])
    out, err = capsys.readouterr()
    assert status == 2
    assert "Traceback" not in err + out and "RunSource" not in err + out
    # nothing is written, and the one line says why, naming the file
    line = _one_line(err)
    assert line.startswith(f"judder: error: no run could be read: "
                           f"{tmp_path / 'run.csv'}: "), line
    assert "upstream_speed channel 'EngSpd_up' has 1 distinct time " \
        "stamp(s)" in line and not out


def test_a_flat_measured_period_says_so(tmp_path, capsys):
    (tmp_path / "flat.csv").write_text("1\n1\n1\n1\n1\n1\n")
    status, err = _in_process(["floquet", "--freq", "100", "--pf", "0.2",
                               "--dither-wave",
                               f"period:{tmp_path / 'flat.csv'}"], capsys)
    assert status == 2
    assert "np.float64" not in err
    assert _one_line(err) == (f"judder: error: --dither-wave period:"
                              f"{tmp_path / 'flat.csv'}: the measured period "
                              "has no fundamental (its first harmonic is 0, "
                              "e.g. a constant); allowed: a period with a "
                              "fundamental")


@pytest.mark.parametrize("make, argv, facts", [
    # a folder as a parameter file: the digest walked all of /usr first,
    # no answer in 60 s (issue 44, item 10)
    (lambda tmp: tmp, ["eig", "--param-file"], ["--param-file", "folder",
                                                "64 MiB"]),
    (lambda tmp: tmp, ["check", "--table"], ["--table", "folder"]),
    # a sparse 16 GB file: hashed in full before its size was checked
    ("sparse", ["fit", "--fit", "mu_g", "--boundary"],
     ["--boundary", "16384 MiB", "64 MiB"]),
    ("sparse", ["report", "--out", "r.html", "--boundary"],
     ["--boundary", "16384 MiB"]),
    ("sparse", ["map", "--freq", "100:110:3", "--pf", "0.1:0.3:3",
                "--dither-wave"], ["--dither-wave period:", "16384 MiB"]),
])
def test_an_input_is_checked_by_size_and_type_before_it_is_hashed(
        tmp_path, capsys, monkeypatch, make, argv, facts):
    import infra.provenance
    from judder.cli import main

    def hashed(path):
        raise AssertionError(f"{path} hashed before it was checked")
    monkeypatch.setattr(infra.provenance, "_bytes_digest", hashed)
    monkeypatch.chdir(tmp_path)
    if make == "sparse":
        path = tmp_path / "huge.csv"
        with open(path, "wb") as stream:
            stream.truncate(16 * 2**30)
    else:
        path = make(tmp_path / "folder")
        path.mkdir()
    value = (f"period:{path}" if argv[-1] == "--dither-wave" else str(path))
    started = time.perf_counter()
    assert main(argv + [value]) == 2
    assert time.perf_counter() - started < 30
    err = capsys.readouterr().err
    assert "internal error" not in err
    for fact in facts + [str(path)]:
        assert fact in err


@pytest.mark.parametrize("argv, facts", [
    # check --table and report --boundary of 1e5 rows ran for an hour
    # (issue 44, item 12): estimated before any work, refused above the
    # limit naming the file to shorten (not --freq x --pf, not --starts)
    (["check", "--table"], ["8.17 h", "100000 settings", "fewer rows in "
                            "--table", "JUDDER_MAX_HOURS"]),
    (["report", "--out", "r.html", "--boundary"],
     ["2.78 h", "100000 measured points", "fewer points in --boundary",
      "JUDDER_MAX_HOURS"]),
])
def test_a_long_table_is_estimated_before_any_work(tmp_path, capsys,
                                                   monkeypatch, argv, facts):
    from judder.cli import main
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("JUDDER_MAX_HOURS", "0.5")
    table = tmp_path / "t.csv"
    table.write_text("freq_hz,p_f_bar,tried_bar\n" + "".join(
        f"{50 + i * 0.0015:.4f},{0.3 + (i % 7) * 0.1:.1f},1.5\n"
        for i in range(100_000)))
    started = time.perf_counter()
    assert main(argv + [str(table)]) == 2
    assert time.perf_counter() - started < 120
    err = capsys.readouterr().err
    for fact in facts:
        assert fact in err
    assert "--starts" not in err and "--freq x --pf" not in err
    assert not (tmp_path / "r.html").exists()
