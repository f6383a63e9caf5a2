"""Inputs once misread without a word, and bugs once reported as input
errors (issue 34): each is refused with the file, channel or value named,
or reported as a bug (exit 1) naming the job."""

from pathlib import Path

import pytest

from judder.cli import main
from facts import names

BENCH = Path(__file__).resolve().parents[1] / "examples" / "bench"
CHANNELS = ["--channel", "upstream_speed=EngSpd_up",
            "--channel", "pressure=PressEVEN:bar",
            "--channel", "downstream_speed=OutSpd"]


def run(argv, capsys):
    status = main(argv)
    out, err = capsys.readouterr()
    return status, out, err


def test_a_role_given_twice_is_refused_naming_both(capsys):
    status, out, err = run(
        ["chart", "--index", str(BENCH / "runs.csv"),
         "--channel", "upstream_speed=OutSpd",
         "--channel", "upstream_speed=EngSpd_up"], capsys)
    assert status == 2 and out == ""
    # both options as given, the role, what is allowed
    assert err.startswith("judder: error: ") and err.count("\n") == 1
    names(err, "--channel upstream_speed=OutSpd",
          "--channel upstream_speed=EngSpd_up", "allowed", "one channel")


def test_an_rpm_column_given_an_angle_unit_is_refused(capsys, tmp_path):
    status, out, err = run(
        ["chart", str(BENCH / "run01.csv"),
         "--channel", "upstream_speed=EngSpd_up:rad",
         "--channel", "pressure=PressEVEN:bar", "--workers", "1",
         "--plot", str(tmp_path / "c.png")], capsys)
    assert status == 2
    assert "amplitude" not in out
    # the rpm values (about 1000) read as rad go back and forth: 2 % of
    # their path is net travel
    names(err, "upstream_speed", "'EngSpd_up'", "rad", "(2%)",
          "speed unit")
    assert err.count(str(BENCH / "run01.csv")) == 1
    assert list(tmp_path.iterdir()) == []


def test_an_encoder_angle_still_reads(tmp_path):
    import numpy as np

    from pysim.bench.acquisition import ChannelSpec
    from pysim.bench.readers import read_acquisition
    t = np.arange(0, 1, 1e-3)
    # 1000 rpm with a 5 % judder at 30 Hz, as degrees
    angle = np.degrees(104.72 * t + 0.05 * 104.72 / (2 * np.pi * 30)
                       * np.sin(2 * np.pi * 30 * t))
    path = tmp_path / "encoder.csv"
    path.write_text("time [s],phi [deg]\n" + "".join(
        f"{a:.9g},{b:.9g}\n" for a, b in zip(t, angle)))
    read = read_acquisition(path, {"upstream_speed": ChannelSpec("phi")})
    speed = read.channels["upstream_speed"]
    assert speed.kind == "angle"
    assert np.allclose(speed.values, np.radians(angle))


def test_a_nan_onset_in_a_boundary_is_refused_naming_file_and_line(
        capsys, tmp_path):
    boundary = tmp_path / "b.csv"
    boundary.write_text("freq_hz,p_f_bar\n100,0.3\n110,nan\n120,0.4\n")
    status, out, err = run(["fit", "--boundary", str(boundary),
                            "--fit", "mu_g"], capsys)
    assert status == 2
    assert err.startswith("judder: error: ") and err.count("\n") == 1
    names(err, str(boundary), "line 3", "p_f_bar", "'nan'", "allowed",
          ">= 0 bar", "empty")


def _head(tmp_path, name, rows, header=None):
    lines = (BENCH / "run01.csv").read_text().splitlines()
    path = tmp_path / name
    path.write_text("\n".join([header or lines[0]] + lines[1:rows + 1])
                    + "\n")
    return path


@pytest.mark.parametrize("rows, header, lasts, samples", [
    (20, None, "0.0279", 20),                       # a 20-sample file
    (2042, "time [ms],EngSpd_up [rpm],OutSpd [rpm],PressEVEN",
     "0.003", 2042),                                # seconds labelled ms
])
def test_a_run_too_short_to_read_is_an_input_error(capsys, tmp_path, rows,
                                                    header, lasts, samples):
    path = _head(tmp_path, "short.csv", rows, header)
    status, out, err = run(["chart", str(path), *CHANNELS, "--workers", "1",
                            "--out", str(tmp_path / "c.npz")], capsys)
    assert status == 2 and out == ""
    assert err.startswith("judder: error: ") and err.count("\n") == 1
    names(err, str(path), f"{lasts} s", f"{samples} samples", "allowed",
          "0.2 s", "unit")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["short.csv"]


def test_unreadable_runs_give_every_reason_on_stderr(capsys, tmp_path):
    short = _head(tmp_path, "a.csv", 20)
    empty = tmp_path / "b.csv"
    empty.write_text("")
    status, out, err = run(["chart", str(short), str(empty), *CHANNELS,
                            "--workers", "1"], capsys)
    assert status == 2 and out == ""
    assert err.startswith("judder: error: ") and err.count("\n") == 1
    names(err, "2 runs", f"{short}: ", "0.0279 s", f"{empty}: ")


def test_a_bug_in_a_job_is_a_bug_naming_the_job(capsys, monkeypatch):
    import pysim.bench.charts as charts

    def broken(*args, **kwargs):
        raise ValueError("operands could not be broadcast together")
    monkeypatch.setattr(charts, "analyse_run", broken)
    status, out, err = run(["chart", str(BENCH / "run01.csv"), *CHANNELS,
                            "--workers", "1"], capsys)
    assert status == 1
    assert err.startswith("judder: internal error: ")
    # the job and its input, the exception whole, that it is a bug
    names(err, "1 of 1", "job 0", str(BENCH / "run01.csv"),
          "ValueError: operands could not be broadcast together", "bug")
