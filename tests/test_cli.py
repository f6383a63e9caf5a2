"""The ``judder`` command line, run as a user runs it (subprocess)."""

import cmath
import json
import math
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

BAR = 1e5


def judder(*args, check=True):
    """Run ``python -m judder ARGS``; return the CompletedProcess."""
    proc = subprocess.run([sys.executable, "-m", "judder", *args],
                          capture_output=True, text=True, timeout=120)
    if check:
        assert proc.returncode == 0, proc.stderr
    return proc


def judder_json(*args):
    return json.loads(judder(*args, "--json").stdout)


def test_eig_json():
    data = judder_json("eig")
    assert data["natural_frequencies_hz"] == pytest.approx([18.939, 102.884],
                                                           abs=5e-4)
    assert data["damping_factor_12"] == pytest.approx(0.0084, abs=5e-4)
    data = judder_json("eig", "--model", "3dof")
    assert data["natural_frequencies_hz"] == pytest.approx([18.047], abs=5e-4)


def test_eig_set_is_repeatable():
    data = judder_json("eig", "--set", "c12=10", "--set", "J2=0.231")
    assert data["damping_factor_12"] == pytest.approx(0.168, abs=5e-4)


def test_floquet_json():
    data = judder_json("floquet", "--freq", "102.9", "--pf", "0.3",
                       "--driveline", "chain")
    assert data["kind"] == "single-period"
    lead = data["leading"]
    assert (lead["re"], lead["im"], lead["abs"], lead["arg"]) == \
        pytest.approx((1.0261, 0.0, 1.0261, 0.0), abs=1e-4)
    assert data["leading_abs"] == pytest.approx(1.0261, abs=1e-4)
    assert len(data["multipliers"]) == 6
    # every complex number says what its numbers are; abs and arg agree
    # with re and im, and each exponent is ln(multiplier) / T (Eq. 12)
    period = data["period_s"]
    for m, e in zip(data["multipliers"], data["exponents_per_s"]):
        z = complex(m["re"], m["im"])
        assert (m["abs"], m["arg"]) == pytest.approx((abs(z), cmath.phase(z)))
        assert e["re"] == pytest.approx(math.log(m["abs"]) / period)
    literal = judder_json("floquet", "--freq", "102.9", "--pf", "0.5",
                          "--set", "mean_pressure_damping=1")
    assert literal["kind"] == "stable"


def test_map_writes_npz_and_plot(tmp_path):
    out, plot = tmp_path / "m.npz", tmp_path / "m.png"
    data = judder_json("map", "--freq", "80:110:7", "--pf", "0:1:3",
                       "--out", str(out), "--plot", str(plot))
    assert data["points"] == 21
    assert data["counts"]["single-period"] > 0
    with np.load(out) as npz:
        assert npz["kind"].shape == (7, 3)
        assert npz["p_f_bar"] == pytest.approx([0, 0.5, 1.0])
        assert npz["p_f_pa"] == pytest.approx([0, 0.5e5, 1e5])
        meta = json.loads(str(npz["parameters"]))
        assert meta["parameters"]["J4"] == 0.122
        assert list(npz["kind_names"])[1] == "single-period"
    assert plot.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert not list(tmp_path.glob(".*.part"))


def test_map_npz_holds_the_threshold_boundaries_and_tongues(tmp_path):
    # --out alone computes the exact boundaries and stores them, with the
    # judder-relevant rate the map was shaded with
    out = tmp_path / "m.npz"
    judder_json("map", "--driveline", "chain", "--freq", "10:220:40",
                "--pf", "0:1.5:4", "--out",
                str(out))
    tongues = judder_json("tongues", "--driveline", "chain", "--freq",
                          "10:220:40")["tongues"]
    with np.load(out) as npz:
        assert float(npz["min_growth_per_s"]) == 1.0
        assert list(npz["boundary_kinds"]) == ["single-period",
                                               "double-period", "combination"]
        assert npz["boundary_p_f_bar"].shape == (40, 3)
        assert npz["boundary_freq_hz"] == pytest.approx(
            np.linspace(10, 220, 40))
        # the same tongues, numbers and tips as `judder tongues` on that grid
        assert list(npz["tongue_number"]) == [t["number"] for t in tongues]
        assert list(npz["tongue_kind"]) == [t["kind"] for t in tongues]
        assert npz["tongue_tip_p_f_bar"] == pytest.approx(
            [t["tip_p_f_bar"] for t in tongues], rel=1e-9)
        # tongue 2's tip (paper-4dof): 102.9 Hz, 0.0275 bar
        two = list(npz["tongue_number"]).index(2)
        assert npz["tongue_tip_p_f_bar"][two] == pytest.approx(0.0275,
                                                              abs=5e-4)


def test_params_save_load_and_no_overwrite(tmp_path):
    path = tmp_path / "mine.toml"
    judder("params", "--preset", "paper-4dof-fitted", "--save", str(path))
    assert "c12 = 10.0" in path.read_text()
    first = judder_json("eig", "--param-file", str(path))
    assert first["damping_factor_12"] == pytest.approx(0.168, abs=5e-4)
    before = path.read_text()
    refused = judder("params", "--save", str(path), check=False)
    assert refused.returncode == 2 and "exists" in refused.stderr
    assert path.read_text() == before


@pytest.mark.parametrize("args, words", [
    (["eig", "--set", "J1=-1"], ["J1", "-1", "> 0"]),
    (["eig", "--set", "J9=1"], ["--set 'J9=1'", "unknown"]),
    (["eig", "--preset", "nope"], ["nope", "paper-4dof"]),
    (["eig", "--model", "3dof", "--preset", "paper-4dof"], ["--model"]),
    (["floquet", "--freq", "0", "--pf", "1"], ["freq", "0"]),
    (["floquet", "--freq", "50", "--pf", "-1"], ["pf", "-1", "bar"]),
    (["floquet", "--freq", "nan", "--pf", "1"], ["freq", "nan"]),
    (["map", "--freq", "100:10:5"], ["--freq", "100:10:5", "START <= STOP"]),
    (["map", "--pf", "0:1:x"], ["--pf", "0:1:x"]),
    (["map", "--freq", "1:2:3000", "--pf", "0:1:3000"], ["points"]),
    (["eig", "--param-file", "/nonexistent/p.toml"], ["/nonexistent/p.toml"]),
])
def test_bad_input_gives_clear_error(args, words):
    proc = judder(*args, check=False)
    assert proc.returncode == 2
    assert "Traceback" not in proc.stderr
    for word in words:
        assert word in proc.stderr


def test_help_explains_units():
    text = judder("map", "--help").stdout
    assert "Hz" in text and "bar" in text and "SI" in text


def test_ctrl_c_leaves_no_partial_file(tmp_path, markers):
    out = tmp_path / "big.npz"
    proc = subprocess.Popen(
        [sys.executable, "-m", "judder", "map", "--freq", "1:250:40000",
         "--pf", "0:1:50", "--out", str(out)],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
        preexec_fn=markers.with_ctrl_c)
    import psutil
    child = psutil.Process(proc.pid)
    # in the map's middle: 3 s of CPU (imports about 1 s, the map 10 s)
    markers.wait_for(lambda: markers.cpu_seconds(child) >= 3.0
                     or proc.poll() is not None, "3 s of the map")
    assert proc.poll() is None, "the map finished before it was interrupted"
    proc.send_signal(signal.SIGINT)
    _, stderr = proc.communicate(timeout=60)
    assert proc.returncode == 130
    assert "interrupted" in stderr
    assert os.listdir(tmp_path) == []


def test_tongues_json_and_csv(tmp_path):
    out = tmp_path / "b.csv"
    data = judder_json("tongues", "--driveline", "chain", "--freq",
                       "10:220:106", "--out", str(out))
    numbers = {t["number"]: t for t in data["tongues"]}
    assert set(numbers) == {1, 2, 3, 4, 5, 6}
    assert numbers[2]["tip_freq_hz"] == pytest.approx(102.88, rel=5e-3)
    assert numbers[2]["kind"] == "single-period"
    assert abs(numbers[5]["tip_offset_percent"]) < 0.5
    assert data["max_boundary_multiplier_error"] < 1e-6
    lines = out.read_text().splitlines()
    header, first, growth, mark = lines[0], lines[1], lines[-2], lines[-1]
    provenance = data["provenance"]
    assert mark == (f"# written by judder {provenance['judder_version']}, "
                    f"inputs sha256:{provenance['input_sha256']}")
    # the growth rate these are the boundaries of (fit --boundary reads it)
    assert growth == "# min_growth_per_s: 0"
    assert header.startswith("freq_hz,p_f_bar,single_period_bar")
    assert first.startswith("10,")
    assert len(lines) == 106 + 3


def test_compare_puts_two_sets_side_by_side(tmp_path):
    paper = tmp_path / "paper.toml"
    judder("params", "--preset", "paper-4dof", "--save", str(paper))
    fitted = str(Path(__file__).parents[1] / "examples" / "driveline.toml")
    plot = tmp_path / "compare.png"
    data = judder_json("compare", "--driveline", "chain", fitted,
                       str(paper), "--freq", "105",
                       "--pf", "0.2", "--grid", "10:220:106", "--plot",
                       str(plot))
    a, b = data["sets"]
    assert (a["file"], b["file"]) == (fitted, str(paper))
    # the same numbers as the single commands give for each set
    for side, source in ((a, ["--param-file", fitted]),
                         (b, ["--preset", "paper-4dof"])):
        eig = judder_json("eig", *source, "--driveline", "chain")
        assert side["natural_frequencies_hz"] == pytest.approx(
            eig["natural_frequencies_hz"], rel=1e-12)
        tips = judder_json("tongues", *source, "--freq", "10:220:106",
                           "--driveline", "chain")
        assert [t["tip_p_f_bar"] for t in side["tongues"]] == pytest.approx(
            [t["tip_p_f_bar"] for t in tips["tongues"]], rel=1e-9)
        assert [t["judder_tip_p_f_bar"] for t in side["tongues"]] == \
            pytest.approx([t["judder_tip_p_f_bar"] for t in tips["tongues"]],
                          rel=1e-9)
    # README: 105 Hz, 0.2 bar is slow growth at 0.563 1/s with the fitted
    # set; the paper's tongue 2 (f2 = 102.9 Hz) is narrower: stable there
    assert a["settings"][0]["verdict"] == "SLOW GROWTH"
    assert a["settings"][0]["growth_rate_per_s"] == pytest.approx(0.563,
                                                                  abs=5e-4)
    assert b["settings"][0]["verdict"] == "STABLE"
    # the paper's driveline has fewer safe windows at 0.7 bar
    full = [[w for w in s["safe_windows"] if w["full_range"]] for s in (a, b)]
    assert len(full[0]) == 2 and len(full[1]) == 4
    assert plot.stat().st_size > 0
    text = judder("compare", "--driveline", "chain", fitted, str(paper),
                  "--freq", "105", "--pf", "0.2", "--grid",
                  "10:220:106").stdout
    assert "SLOW GROWTH (+0.563 1/s)" in text and "STABLE" in text
    assert "tongue 2 (f2) unstable from" in text
    assert "judder (>= 1 1/s) from" in text
    one = judder("compare", fitted, check=False)
    assert one.returncode == 2


def test_sensitivity_json_c12_study():
    data = judder_json("sensitivity", "--params", "c12", "--values", "0.5,10",
                       "--freq", "10:220:106", "--workers", "1")
    rows = [r for r in data["tip_shifts"] if r["value"] == 10.0]
    gone = {r["tongue"] for r in rows if not r["present"]}
    assert gone == {3}


def test_threshold_json():
    data = judder_json("threshold", "--c-ext", "0:1:3")
    assert data["mean_pressure_damping"] == 1.0
    assert data["mu_g_threshold"] == pytest.approx(-1.25e-5, rel=1e-6)
    assert data["mu_g_thresholds"] == pytest.approx([0, -6.25e-5, -1.25e-4],
                                                    abs=1e-10)


def test_fit_from_tongues_csv(tmp_path):
    boundary = tmp_path / "measured.csv"
    judder("tongues", "--driveline", "chain", "--preset",
           "paper-4dof-fitted", "--freq", "70:140:8",
           "--out", str(boundary))
    saved = tmp_path / "fitted.toml"
    saved.write_text("# written by judder\nan older fit\n")
    # the outputs rule: the fit.toml judder wrote is replaced, no --force
    data = judder_json("fit", "--boundary", str(boundary), "--fit",
                       "mu_g,k24", "--set", "c12=10", "--save-params",
                       str(saved))
    assert data["fitted"]["mu_g"]["value"] == pytest.approx(0.022, rel=1e-4)
    assert data["fitted"]["k24"]["value"] == pytest.approx(34858.1, rel=1e-4)
    assert "mu_g = 0.022" in saved.read_text()
    assert "an older fit" not in saved.read_text()


def test_fit_from_a_german_boundary_file(tmp_path):
    """The tongues CSV of test_fit_from_tongues_csv as a German
    spreadsheet saves it (';' between fields, decimal commas), fitted
    with --decimal ',': the same values."""
    boundary = tmp_path / "measured.csv"
    judder("tongues", "--driveline", "chain", "--preset",
           "paper-4dof-fitted", "--freq", "70:140:8",
           "--out", str(boundary))
    german = tmp_path / "gemessen.csv"
    german.write_text("".join(
        line if line.startswith("#") else
        line.replace(",", ";").replace(".", ",")
        for line in boundary.read_text().splitlines(keepends=True)))
    assert "0,754003501;" in german.read_text()
    data = judder_json("fit", "--boundary", str(german), "--decimal", ",",
                       "--fit", "mu_g,k24", "--set", "c12=10")
    assert data["fitted"]["mu_g"]["value"] == pytest.approx(0.022, rel=1e-4)
    assert data["fitted"]["k24"]["value"] == pytest.approx(34858.1, rel=1e-4)


@pytest.mark.parametrize("command", [["fit"], ["report", "--out",
                                               "report.html"]])
def test_an_ambiguous_boundary_file_is_refused_with_the_way_round(
        tmp_path, command):
    boundary = tmp_path / "b.csv"
    boundary.write_text("freq_hz;p_f_bar;tried_bar\n105;1,250;1,500\n"
                        "60;;1,500\n")
    command = [c.replace("report.html", str(tmp_path / "r.html"))
               for c in command]
    proc = judder(*command, "--boundary", str(boundary), check=False)
    assert proc.returncode == 2, proc.stderr
    for word in (str(boundary), "column 'p_f_bar'", "'1,250'", "line 2",
                 "--decimal '.' or ','"):
        assert word in proc.stderr
    assert "`" not in proc.stderr and "Traceback" not in proc.stderr
    proc = judder(*command, "--chart", str(tmp_path / "c.npz"),
                  "--decimal", ",", check=False)
    assert proc.returncode == 2
    assert "--decimal is for a --boundary file" in proc.stderr


@pytest.mark.parametrize("args, words", [
    (["tongues", "--pf-max", "0"], ["--pf-max", "> 0 bar"]),
    (["sensitivity", "--params", "k99"], ["k99", "unknown"]),
    (["sensitivity", "--params", "k12", "--factors", "0,2"], ["--factors"]),
    (["threshold", "--c-ext", "-1:1:3"], ["--c-ext"]),
    (["fit", "--boundary", "/nonexistent.csv"], ["/nonexistent.csv"]),
])
def test_study_commands_refuse_bad_input(args, words):
    proc = judder(*args, check=False)
    assert proc.returncode == 2, proc.stderr
    assert "Traceback" not in proc.stderr
    for word in words:
        assert word in proc.stderr


def test_version_is_pyprojects():
    import tomllib
    from pathlib import Path
    project = tomllib.loads((Path(__file__).parents[1] / "pyproject.toml")
                            .read_text())["project"]
    assert judder("--version").stdout.strip() == \
        f"judder {project['version']}"
