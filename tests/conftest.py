"""Shared fixtures: the paper's drivelines, and a user's Modelica class
that is not a driveline. The tests' own helpers (``facts``: what a
message must name) are importable from here on."""

from pathlib import Path
import signal
import sys
import time

import pytest

from sources import get_preset
from stability import build_driveline

# --import-mode=importlib puts no test folder on sys.path: the helpers
sys.path.insert(0, str(Path(__file__).resolve().parent))


@pytest.fixture(scope="session")
def paper4():
    """4-DOF Appendix A values with N_c R_m S = 6e-3 m^3 (the calibration
    of drivelines.registry)."""
    return build_driveline(get_preset("paper-4dof"))


@pytest.fixture(scope="session")
def paper3():
    return build_driveline(get_preset("paper-3dof"))


@pytest.fixture(scope="session")
def oscillator_library(tmp_path_factory):
    """A user's library folder with ``MyLib.Oscillator``: a Mathieu-like
    oscillator whose dither is the cosine (s = q = 0), a sine (s = 1) or
    also quadratic in the amplitude (q = 1); none of the paper's names."""
    root = tmp_path_factory.mktemp("oscillator")
    package = root / "MyLib"
    package.mkdir()
    (package / "package.mo").write_text("package MyLib\nend MyLib;\n")
    (package / "Oscillator.mo").write_text("""within MyLib;
model Oscillator "One body on a spring, damping modulated by a dither"
  parameter Real p_f(min=0)=1 "Dither amplitude";
  parameter Real f_dither(min=0)=10 "Dither frequency";
  parameter Real s=0 "Share of the sine";
  parameter Real q=0 "Quadratic part";
  Real x(start=1, fixed=true) "Position";
  Real v(start=0, fixed=true) "Speed";
  Real phase = 2*3.141592653589793*f_dither*time;
equation
  der(x) = v;
  der(v) = -100*x - (1 + p_f*((1 - s)*cos(phase) + s*sin(phase))
                     + q*p_f^2*cos(phase))*v;
end Oscillator;
""")
    return root


class ChildMarkers:
    """Ready markers of a child process: a test that signals a child
    waits for one of these, never a fixed delay (a loaded machine is
    slower)."""

    @staticmethod
    def with_ctrl_c():
        """``preexec_fn`` of a child that a test sends Ctrl-C: SIGINT as
        a terminal's process has it. A test run started in the background
        (``make test &``, nohup, a CI job) has it ignored, and a child
        inherits that: the tool then keeps it ignored, as it should."""
        signal.signal(signal.SIGINT, signal.SIG_DFL)

    @staticmethod
    def wait_for(condition, what, timeout=120):
        """Poll ``condition()`` until true: tests wait for a ready marker of
        the child, never a fixed delay (a loaded machine is slower)."""
        deadline = time.monotonic() + timeout
        while not condition():
            assert time.monotonic() < deadline, \
                f"no {what} within {timeout} s"
            time.sleep(0.01)

    @staticmethod
    def handles_signals(pid):
        """The child's ready marker for signals: its SIGTERM handler is in
        place (bit 15 of ``SigCgt`` in /proc/PID/status; Python catches only
        SIGINT by itself), i.e. the tool's first line has run."""
        try:
            with open(f"/proc/{pid}/status") as stream:
                caught = next(int(line.split()[1], 16) for line in stream
                              if line.startswith("SigCgt:"))
        except (OSError, StopIteration):
            return False
        return bool(caught >> (signal.SIGTERM - 1) & 1)

    @staticmethod
    def cpu_seconds(process):
        """CPU seconds a process (psutil) has used, 0 when it is gone."""
        import psutil
        try:
            times = process.cpu_times()
        except psutil.Error:
            return 0.0
        return times.user + times.system

    @staticmethod
    def workers(pid):
        """The Dask worker processes under ``pid`` (not the resource
        tracker)."""
        import psutil
        found = []
        for child in psutil.Process(pid).children(recursive=True):
            try:
                if "spawn_main" in " ".join(child.cmdline()):
                    found.append(child)
            except psutil.Error:
                pass
        return found

    @staticmethod
    def workers_computing(pid, count=2, seconds=3.0):
        """Ready marker of a Dask command: ``count`` workers, each past its
        start (about 0.6 s of CPU) and its imports, computing jobs."""
        found = ChildMarkers.workers(pid)
        return len(found) >= count and all(
            ChildMarkers.cpu_seconds(w) >= seconds for w in found)


@pytest.fixture
def markers():
    """:class:`ChildMarkers`."""
    return ChildMarkers


@pytest.fixture
def judder_here(capsys):
    """``judder ARGS`` in this process: ``(status, stdout, stderr)``.

    For tests of what a command computes, which need not pay an
    interpreter's start-up and imports (about 1.5 s each); tests of the
    process itself (signals, exit on a crash) start one."""
    from judder.cli import main

    def run(*args):
        status = main([str(arg) for arg in args])
        out, err = capsys.readouterr()
        return status, out, err
    return run


@pytest.fixture
def chain_by_default(monkeypatch):
    """The views judge a preset's chain alone unless told (Eq. 6, free:
    the paper's Fig. 12, 14-18 and the numbers its tests pin), where the
    tool judges the preset on its test bench; for the in-process API and
    ``main`` of a test module whose numbers are the chain's."""
    monkeypatch.setattr("stability.bench.default_driveline",
                        lambda values: "chain")
