"""The messages issue 34 found wanting: each names the file, option or
value and what is allowed, in one line on stderr."""

from pathlib import Path
import json
import subprocess
import sys
import zipfile

import pytest

from judder.cli import main
from facts import names

ROOT = Path(__file__).resolve().parents[1]


def run(argv, capsys):
    status = main(argv)
    out, err = capsys.readouterr()
    return status, out, err


def one_error(err):
    """The error line, after checking that stderr is one such line."""
    assert err.startswith("judder: error: ") and err.count("\n") == 1, err
    return err


def test_mixed_separators_are_named(capsys, tmp_path):
    path = tmp_path / "run.csv"
    path.write_text("time [s];speed [rpm]\n0,1000\n0.001;1000\n0.002,1001\n")
    status, out, err = run(["chart", str(path), "--channel",
                            "upstream_speed=speed", "--workers", "1"], capsys)
    assert status == 2 and out == ""
    # the file, both lines with their separators, what is allowed
    names(one_error(err), str(path), "line 1", "';'", "line 2", "','",
          "allowed", "tab")


def test_a_word_that_is_no_kind_lists_the_kinds(capsys):
    status, out, err = run(["chart", "x.csv", "--channel",
                            "upstream_speed=EngSpd_up:rpm:bogus"], capsys)
    assert status == 2
    names(one_error(err), "--channel", "upstream_speed=EngSpd_up:rpm:bogus",
          "'bogus'", "allowed", "passage", "sampled", "angle")


def test_a_long_refinement_names_refine(capsys):
    status, out, err = run(["envelope", "--ranges",
                            str(ROOT / "examples" / "ranges.toml"),
                            "--samples", "2", "--refine", "100000000"],
                           capsys)
    assert status == 2
    names(one_error(err), "--refine", "100000000", "3 parameters",
          "106 frequencies")


def test_a_users_file_as_checkpoint_is_no_pickle_advice(capsys, tmp_path):
    mine = tmp_path / "mine.npz"
    mine.write_bytes(b"my own data\n")
    status, out, err = run(["envelope", "--ranges",
                            str(ROOT / "examples" / "ranges.toml"),
                            "--samples", "2", "--checkpoint", str(mine)],
                           capsys)
    assert status == 2
    names(one_error(err), "checkpoint", str(mine), "allowed")
    assert "pickle" not in err and mine.read_bytes() == b"my own data\n"


@pytest.mark.parametrize("rows, facts", [
    ("p\n1\nnan\n3\n2\n", ["sample 2 of 4 is nan", "line 3",
                            "allowed: finite pressures, at least 4"]),
    ("p\n1\n3\n", ["at least 4 finite samples", "got 2"]),
    # issue 44, item 9: decimal commas were cut at the comma (1,49759 read
    # as 49759, exit 0): the cells of a ';' file are read with them, and a
    # file that cannot hold them is refused naming the line or the option
    ("p\n1,5\n1\n0,5\n1\n", ["line 2", "'1,5' has 2 cells",
                             "allowed: 1", "';' or tab"]),
    ("t;p\n0;1,5\n1;1\n2;0.5\n3;1\n", ["'0.5'", "line 4", "'1,5'"]),
])
def test_a_bad_period_file_is_named(capsys, tmp_path, rows, facts):
    period = tmp_path / "period.csv"
    period.write_text(rows)
    status, out, err = run(["floquet", "--freq", "100", "--pf", "0.2",
                            "--dither-wave", f"period:{period}"], capsys)
    assert status == 2
    names(one_error(err), f"--dither-wave period:{period}", *facts)


def test_a_period_of_decimal_commas_is_the_period_of_decimal_points(
        capsys, tmp_path):
    # issue 44, item 9: the same samples written with decimal commas (';'
    # separated, as a German Excel writes them) give the same multipliers
    import math
    samples = [1 + 0.5 * math.cos(2 * math.pi * i / 16)
               + 0.1 * math.cos(4 * math.pi * i / 16) for i in range(16)]
    point = tmp_path / "point.csv"
    point.write_text("t_s,p_bar\n" + "".join(
        f"{i / 1600:.6f},{p:.5f}\n" for i, p in enumerate(samples)))
    comma = tmp_path / "comma.csv"
    comma.write_text(point.read_text().replace(",", ";").replace(".", ","))
    outs = []
    for period, decimal in ((point, []), (comma, []), (comma,
                                                       ["--decimal", ","])):
        status, out, err = run(["floquet", "--freq", "100", "--pf", "0.2",
                                "--json", "--dither-wave",
                                f"period:{period}"] + decimal, capsys)
        assert status == 0, err
        outs.append(json.loads(out)["growth_rate_per_s"])
    assert outs[1] == outs[0] and outs[2] == outs[0]
    status, out, err = run(["floquet", "--freq", "100", "--pf", "0.2",
                            "--dither-wave", f"period:{point}",
                            "--decimal", ","], capsys)
    assert status == 2
    for fact in ("--decimal", "','", "';' or tab"):
        assert fact in err


def test_a_schema_error_of_an_fmu_is_given_whole(capsys, tmp_path):
    fmu = tmp_path / "v1.fmu"
    with zipfile.ZipFile(fmu, "w") as archive:
        archive.writestr("modelDescription.xml", (
            '<?xml version="1.0" encoding="UTF-8"?>\n<fmiModelDescription '
            'fmiVersion="1.0" modelName="M" modelIdentifier="M" guid="{1}" '
            'numberOfContinuousStates="1" numberOfEventIndicators="0" '
            'bogus="1">\n<ModelVariables/>\n</fmiModelDescription>\n'))
    status, out, err = run(["eig", "--fmu", str(fmu)], capsys)
    assert status == 2
    # the option, the file, and the validator's own words whole
    names(one_error(err), f"--fmu {fmu}", "modelDescription.xml", "line 2",
          "attribute 'bogus'")


def test_a_class_without_parameters_says_so(capsys, tmp_path):
    (tmp_path / "NoPar.mo").write_text(
        "model NoPar\n  Real x(start=1, fixed=true);\nequation\n"
        "  der(x) = -x;\nend NoPar;\n")
    status, out, err = run(["params", "--modelica", "NoPar", "--library",
                            str(tmp_path), "--set", "k=1"], capsys)
    assert status == 2
    names(one_error(err), "'k'", "allowed", "no tunable parameter")
    # a study needs the dither's amplitude: refused from the source first
    status, out, err = run(["eig", "--modelica", "NoPar", "--library",
                            str(tmp_path), "--set", "k=1"], capsys)
    assert status == 2
    names(err, "NoPar.mo:1", "--dither-amplitude", "'p_f'", "NoPar")


@pytest.mark.parametrize("value, words", [
    # 10 is plausible as bar: the slip is named, with both ways to write it
    ("10", ("p_m=10bar", "p_m=10Pa")),
    # 1e4 is no plausible bar: the range allowed, and how to keep it
    ("1e4", ("allowed", "100000 to 1e+08 Pa", "p_m=1e4Pa")),
])
def test_a_plain_mean_pressure_suggests_bar_only_where_plausible(
        capsys, value, words):
    status, out, err = run(["eig", "--set", f"p_m={value}"], capsys)
    assert status == 2
    names(one_error(err), "p_m", *words)
    assert "1e+09" not in err
    assert ("10bar" in err) == (value == "10")    # bar only where plausible


def test_a_negligible_external_damping_is_as_none(capsys):
    # c_i = 1e-300 once said "widen the range" where 0 works
    thresholds = []
    for c in ("0", "1e-300"):
        import json
        status, out, err = run(["threshold", "--c-ext", f"{c}:{c}:1",
                                "--mu-g=-0.001:0.001:3", "--json"], capsys)
        assert status == 0, err
        thresholds.append(json.loads(out)["mu_g_thresholds"][0])
    assert thresholds[0] == thresholds[1]
    assert abs(thresholds[0]) < 1e-15     # the closed form's 0


def test_an_empty_model_is_refused_for_fmi_2(tmp_path):
    (tmp_path / "Empty.mo").write_text("model Empty\nend Empty;\n")
    done = subprocess.run(
        [sys.executable, "-m", "fmu", "Empty", "--library", str(tmp_path),
         "--out", str(tmp_path / "out"), "--fmi", "2.0"],
        capture_output=True, text=True, timeout=300, cwd=ROOT)
    assert done.returncode == 2
    assert done.stderr.startswith("fmu: error: ")
    names(done.stderr, "Empty", "FMI 2.0", "allowed", "FMI 3.0")
    assert not (tmp_path / "out").exists()
