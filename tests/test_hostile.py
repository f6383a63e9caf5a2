"""Hostile input: every command, every option class, one table.

Each case is (argv, exit status, words the one-line message holds). Run
in-process through ``judder.cli.main``; a case fails on a traceback, on
a message of more than one line, or on exit 0 where an error is due.
``{d}`` in an argument is the folder of the fixture files.
"""

import json
import os

import pytest

from judder.cli import main

BAD_UTF8 = b"\xff\xfe\x00bad"
FILES = {
    "bool.toml": 'model = "4dof"\n[parameters]\nJ1 = true\n',
    "string.toml": 'model = "4dof"\n[parameters]\nJ1 = "heavy"\n',
    "swapped.csv": "p_f_bar,freq_hz\n0.3,100\n0.4,60\n0.5,40\n",
    "extra.csv": "freq_hz,p_f_bar,extra\n100,0.3,1\n60,0.4,2\n40,0.5,3\n",
    "unknown.csv": "foo,bar\n100,0.3\n",
    "ragged.csv": "freq_hz,p_f_bar\n100,0.3,7\n",
    "noheader3.csv": "100,0.3,1\n60,0.4,2\n",
    "negfreq.csv": "freq_hz,p_f_bar\n-100,0.3\n",
    "infamp.csv": "freq_hz,p_f_bar\n100,inf\n",
    "ok.csv": "freq_hz,p_f_bar\n100,0.3\n60,0.4\n40,0.5\n",
    "afile": "user data\n",
    "user.npz": "not judder's\n",
    "user.png": "not judder's\n",
    "user.toml": "# my notes\n",
    "pm_bar.toml": 'model = "4dof"\n[parameters]\np_m = 10\n',
}

MAP = ["map", "--freq", "100:110:2", "--pf", "0:0.3:2"]
FIT = ["fit", "--boundary", "{d}/ok.csv"]
SIM = ["simulate", "--freq", "100", "--pf", "0.1"]

CASES = [
    # parameters: --set, files, magnitudes, units
    (["eig", "--set", "J1=1e300"], 2, ["J1", "1e+300", "magnitude"]),
    (["eig", "--set", "J1=1e-300"], 2, ["J1", "magnitude"]),
    (["eig", "--set", "J1=-1"], 2, ["J1", "> 0"]),
    (["eig", "--set", "J1=nan"], 2, ["J1", "not allowed"]),
    (["eig", "--set", "J1=inf"], 2, ["J1"]),
    (["eig", "--set", "J1="], 2, ["NAME=VALUE"]),
    (["eig", "--set", "bogus=1"], 2, ["bogus", "allowed names"]),
    (["eig", "--set", "N_c=2.5"], 2, ["N_c", "integer"]),
    (["eig", "--set", "J1=3kg"], 2, ["J1", "kg m^2"]),
    (["eig", "--set", "J1=1 parsec"], 2, ["J1"]),
    (["eig", "--set", "J1=1/0"], 2, ["J1"]),
    (["eig", "--set", "p_m=10"], 2, ["p_m", "10bar"]),
    (["eig", "--set", "p_m=0.5"], 2, ["p_m", "bar"]),
    (["eig", "--param-file", "{d}/pm_bar.toml"], 2,
     ["p_m = 10 Pa", "1e+06"]),
    (["sensitivity", "--params", "mean_pressure_damping", "--factors", "3",
      "--freq", "90:120:5"], 2, ["mean_pressure_damping is 0", "--values"]),
    (["eig", "--set", "p_m=10bar"], 0, []),
    (["eig", "--set", "p_m=50000Pa"], 0, []),
    (["eig", "--set", "c12=5 N*m*s/rad"], 0, []),
    (["floquet", "--freq", "100", "--pf", "0.3", "--set", "mu_g=1e300"], 2,
     ["mu_g", "magnitude"]),
    (["map", "--freq", "100", "--pf", "0.3", "--set", "mu_g=1e300"], 2,
     ["mu_g"]),
    (["tongues", "--freq", "100:110:2", "--set", "mu_g=1e300"], 2, ["mu_g"]),
    (["eig", "--param-file", "{d}/bad.bin"], 2, ["UTF-8", "bad.bin"]),
    (["eig", "--param-file", "{d}/bool.toml"], 2, ["J1", "not a number"]),
    (["eig", "--param-file", "{d}/string.toml"], 2, ["J1", "not a number"]),
    (["eig", "--param-file", "{d}/missing.toml"], 2, ["missing.toml"]),
    (["eig", "--param-file", "{d}"], 2, ["--param-file"]),
    (["eig", "--param-file", "/dev/zero"], 2, ["regular file"]),
    (["eig", "--preset", "nope"], 2, ["--preset"]),
    # frequencies and amplitudes, with and without units
    (["floquet", "--freq", "1e300", "--pf", "0.3"], 2, ["--freq", "100000"]),
    (["floquet", "--freq", "2MHz", "--pf", "0.3"], 2, ["--freq", "100000"]),
    (["floquet", "--freq", "0", "--pf", "0.3"], 2, ["--freq"]),
    (["floquet", "--freq", "1e-300", "--pf", "0.3"], 2, ["--freq"]),
    (["floquet", "--freq", "nan", "--pf", "0.3"], 2, ["--freq"]),
    (["floquet", "--freq", "abc", "--pf", "0.3"], 2, ["--freq", "abc"]),
    (["floquet", "--freq", "100rpm", "--pf", "0.3"], 2, ["--freq", "rpm"]),
    (["floquet", "--freq", "100", "--pf", "1e4"], 2, ["--pf", "Pa"]),
    (["floquet", "--freq", "100", "--pf", "30000"], 2, ["--pf", "30000Pa"]),
    (["floquet", "--freq", "100", "--pf", "-1"], 2, ["--pf"]),
    (["floquet", "--freq", "100", "--pf", "3kg"], 2, ["--pf", "bar"]),
    (["floquet", "--freq", "100", "--pf", "200bar"], 0,
     ["warning", "reaches the mean pressure"]),
    (["floquet", "--freq", "100", "--pf", "15"], 0, ["warning", "p_m"]),
    (["floquet", "--freq", "1.2kHz", "--pf", "300mbar"], 0, []),
    (["floquet", "--freq", "102.9", "--pf", "30000Pa"], 0, []),
    (["floquet", "--freq", "100", "--pf", "0", "--json"], 0, []),
    # grids
    (["map", "--freq", "100", "--pf", "0.1:0.3:100000000000"], 2,
     ["--pf", "100000"]),
    (["map", "--freq", "0.01:100:10", "--pf", "0:1:100000"], 2, ["GiB"]),
    (["map", "--freq", "100:90:3"], 2, ["--freq"]),
    (["map", "--freq", "100:110:0"], 2, ["--freq"]),
    (["map", "--freq", "100:110"], 2, ["--freq", "not a grid"]),
    (["map", "--freq", "a:b:c"], 2, ["--freq"]),
    (["map", "--freq", "100:110:2.5"], 2, ["--freq"]),
    (["map", "--pf", "-1:1:3", "--freq", "100"], 2, ["--pf"]),
    (["map", "--freq", "100:200:3", "--pf", "0:300mbar:3"], 0, []),
    (["threshold", "--mu-g", "-0.002:0.002:9", "--c-ext", "0:2:3"], 0, []),
    (["threshold", "--c-ext", "-1:2:3"], 2, ["--c-ext"]),
    (["tongues", "--freq", "1e6:2e6:3"], 2, ["--freq"]),
    (["tongues", "--freq", "100:110:2", "--pf-max", "0"], 2, ["--pf-max"]),
    (["tongues", "--freq", "100:110:2", "--pf-max", "nan"], 2, ["--pf-max"]),
    (["tongues", "--freq", "100:110:2", "--min-growth", "inf"], 2,
     ["--min-growth"]),
    (["crosscheck", "--freq", "0:10:3"], 2, ["--freq"]),
    (["campaign", "--out", "{d}/c", "--freq", "0:1:2"], 2, ["--freq"]),
    # options of one command
    (["sensitivity", "--params", "c12", "--values", "1", "--factors", "2"],
     2, ["--values", "--factors"]),
    (["sensitivity", "--params", "c12", "--factors", "-1"], 2,
     ["--factors"]),
    (["sensitivity", "--params", "c12", "--factors", "x"], 2,
     ["--factors"]),
    (["sensitivity", "--params", "c12", "--workers", "-1"], 2,
     ["--workers"]),
    (["sensitivity", "--params", "c12", "--workers", "0"], 2, ["--workers"]),
    (["sensitivity", "--params", "c12", "--workers", "100000"], 2,
     ["--workers"]),
    (FIT + ["--fit", "bogus"], 2, ["--fit", "bogus"]),
    # the kernel names its arguments (`names`, `scatter`): the options here
    (FIT, 2, ["fit fewer parameters (--fit)", "known scatter (--scatter)"]),
    (FIT + ["--fit", "c12,c12"], 2, ["--fit", "distinct"]),
    (FIT + ["--bounds", "c12=nan:5"], 2, ["c12"]),
    (FIT + ["--bounds", "c12=-1:5"], 2, ["c12", ">= 0"]),
    (FIT + ["--bounds", "c12=5:1"], 2, ["LOW < HIGH"]),
    (FIT + ["--bounds", "c12=1"], 2, ["--bounds"]),
    (FIT + ["--bounds", "k12=1:5"], 2, ["--bounds", "--fit"]),
    (FIT + ["--starts", "0"], 2, ["--starts"]),
    (FIT + ["--seed", "-1"], 2, ["--seed"]),
    (FIT + ["--pf-max", "-1"], 2, ["--pf-max"]),
    (["fit", "--boundary", "{d}/unknown.csv"], 2, ["unknown column", "foo"]),
    (["fit", "--boundary", "{d}/extra.csv"], 2, ["extra"]),
    (["fit", "--boundary", "{d}/ragged.csv"], 2, ["line 2", "cells"]),
    (["fit", "--boundary", "{d}/noheader3.csv"], 2, ["line 1"]),
    (["fit", "--boundary", "{d}/negfreq.csv"], 2, ["line 2"]),
    (["fit", "--boundary", "{d}/infamp.csv"], 2, ["line 2"]),
    (["fit", "--boundary", "{d}/bad.bin"], 2, ["UTF-8"]),
    (["fit", "--chart", "{d}/bad.bin"], 2, ["--chart"]),
    (SIM + ["--bench", "p_load=-5"], 2, ["p_load", "at least 0 Pa"]),
    (SIM + ["--bench", "w_motor=0"], 2, ["w_motor 0 rad/s", "below w_motor"]),
    (SIM + ["--bench", "w_motor=100Hz"], 2, ["w_motor", "rpm"]),
    (SIM + ["--bench", "N_c_load=0.5"], 2, ["N_c_load", "at least 1"]),
    (SIM + ["--bench", "bogus=1"], 2, ["bogus", "w_motor"]),
    (SIM + ["--bench", "w_gearbox=200"], 2,
     ["--bench w_gearbox 200 rad/s", "below w_motor"]),
    (SIM + ["--duration", "0.01"], 2, ["duration", "0.6"]),
    (SIM + ["--duration", "-1"], 2, ["--duration"]),
    (SIM + ["--duration", "1e300"], 2, ["--duration"]),
    (SIM + ["--compare", "abc"], 2, ["--compare", "abc"]),
    (["crosscheck", "--freq", "100", "--pf", "0.1", "--duration", "0.01"],
     2, ["--duration", "periods"]),
    (["campaign", "--out", "", "--freq", "100", "--pf", "0.1"], 2,
     ["--out"]),
    (["campaign", "--out", "{d}/afile", "--freq", "100", "--pf", "0.1"], 2,
     ["is a file"]),
    (["campaign", "--out", "{d}/c", "--format", "xls"], 2, ["--format"]),
    # one run id written twice to the index (issue 24)
    (["campaign", "--out", "{d}/c", "--rpm", "1000,1000"], 2,
     ["--rpm: 1000 is given twice"]),
    (["campaign", "--out", "{d}/c", "--temperatures", "65-70,65-70"], 2,
     ["--temperatures: 65-70 is given twice"]),
    (["campaign", "--out", "{d}/c", "--freq", "1:1000:100000", "--pf",
      "0.1:0.2:1000"], 2, ["1e+08 runs", "100000"]),
    (["campaign", "--out", "{d}/c", "--freq", "1:1000:1000", "--pf",
      "0.1:0.2:100", "--duration", "3000"], 2, ["GiB", "free"]),
    (["crosscheck", "--freq", "50:100:1000", "--pf", "0:1:1000"], 2,
     ["FMU runs"]),
    (["sensitivity", "--params", "c12", "--values",
      ",".join(["1"] * 100001)], 2, ["cases"]),
    (["campaign", "--out", "{d}/c", "--rpm", "-5"], 2, ["--rpm"]),
    (["campaign", "--out", "{d}/c", "--noise-rpm", "-1"], 2,
     ["--noise-rpm"]),
    (["campaign", "--out", "{d}/c", "--temperatures", "99-100"], 2,
     ["99-100"]),
    (["chart", "{d}/nothing"], 2, []),
    (["chart", "{d}/bad.bin", "--min-growth", "-1"], 2, ["--min-growth"]),
    # outputs: checked before any work
    (MAP + ["--out", "{d}/afile/sub.npz"], 2, ["afile", "is a file"]),
    (MAP + ["--out", "{d}"], 2, ["folder"]),
    (MAP + ["--out", "{d}/m.txt"], 2, ["unknown format", ".npz"]),
    (MAP + ["--out", "{d}/m.npz", "--plot", "{d}/x.xyz"], 2,
     ["unknown format"]),
    (MAP + ["--out", "{d}/user.npz"], 2, ["not written by judder",
                                           "--force"]),
    (MAP + ["--plot", "{d}/user.png"], 2, ["not written by judder"]),
    (MAP + ["--out", "{d}/same.npz", "--plot", "{d}/same.npz"], 2,
     ["unknown format"]),
    (MAP + ["--out", "{d}/ro/m.npz"], 2, ["not writable"]),
    (["params", "--save", "{d}/user.toml"], 2, ["not written by judder"]),
    (["floquet", "--freq", "105", "--pf", "0.2", "--plot", "{d}/user.png"],
     2, ["not written by judder", "--force"]),
    (["floquet", "--freq", "105", "--pf", "0.2", "--plot", "{d}/m.txt"], 2,
     ["unknown format"]),
    # Pa given for bar where amplitudes come as lists, tables and limits
    (["check", "--freq", "105", "--pf", "0.2,30000"], 2,
     ["--pf 30000 bar", "0.3 bar"]),
    (["check", "--freq", "105", "--pf", "0.2", "--pf-max", "30000"], 2,
     ["--pf-max 30000 bar"]),
    (["advise", "--no-design", "--valve-max", "30000"], 2,
     ["--valve-max 30000 bar"]),
    (["report", "--out", "{d}/r.html", "--freq", "105", "--pf", "30000"], 2,
     ["--pf 30000 bar"]),
    (["params", "--save", "{d}/p.json"], 2, ["unknown format"]),
    (FIT + ["--save-params", "{d}/user.toml"], 2, ["not written"]),
    (SIM + ["--out", "{d}/run.txt"], 2, ["unknown format"]),
    (["tongues", "--out", "{d}/afile/t.csv"], 2, ["is a file"]),
    (["sensitivity", "--params", "c12", "--out", "{d}"], 2, ["folder"]),
    (["threshold", "--out", "{d}/t.npz"], 2, ["unknown format"]),
    (["crosscheck", "--out", "{d}/x.npz"], 2, ["unknown format"]),
    (["chart", "{d}", "--boundary", "{d}/b.txt"], 2, ["unknown format"]),
    (["sensitivity", "--params", "c12", "--scheduler", "garbage"], 2,
     ["--scheduler garbage: not a scheduler address", "HOST:PORT"]),
    (["envelope", "--ranges", "{d}/bad.bin"], 2, ["not UTF-8"]),
    (["check", "--freq", "60:200:1000", "--pf", "0:0.7:1000"], 2,
     ["1000000 settings", "JUDDER_MAX_HOURS"]),
    (["report", "--out", "{d}/r.html", "--map-freq", "1:250:3000",
      "--map-pf", "0:1.5:3000"], 2, ["--map-freq x --map-pf", "9000000"]),
    (["crosscheck", "--freq", "100:105:2", "--pf", "0.3:0.3:1",
      "--duration", "1", "--perturb", "foo"], 2, ["no parameter 'foo'"]),
    (["check", "--freq", "105,", "--pf", "0.2"], 2, ["empty item"]),
    (["threshold", "--mu-g", "-1e300:0.1:10"], 2, ["mu_g = -1e+300 is"]),
    (["advise", "--no-design", "--margin-bar", "1e300"], 2,
     ["--margin-bar 1e+300 bar", "below --valve-max"]),
    (["check", "--freq", "100", "--pf", "0.3", "--pf-max", "0.2"], 2,
     ["--pf-max 0.2 bar", "above the largest setting, 0.3 bar"]),
    (["advise", "--no-design", "--margin-hz", "-1"], 2,
     ["--margin-hz -1", ">= 0 Hz"]),
    # argparse itself
    (["eig", "--bogus"], 2, ["unrecognized"]),
    (["floquet"], 2, ["required"]),
    (["nope"], 2, ["invalid choice"]),
]


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    d = tmp_path_factory.mktemp("hostile")
    for name, text in FILES.items():
        (d / name).write_text(text)
    (d / "bad.bin").write_bytes(BAD_UTF8)
    (d / "ro").mkdir()
    (d / "ro").chmod(0o555)
    yield d
    (d / "ro").chmod(0o755)


def run(argv, capsys):
    """Exit status, stdout and stderr of ``judder ARGV`` in-process."""
    try:
        status = main(argv)
    except SystemExit as exc:      # argparse
        status = exc.code
    out, err = capsys.readouterr()
    return status, out, err


@pytest.mark.parametrize("argv, status, words", CASES,
                         ids=[" ".join(c[0])[:60] for c in CASES])
def test_hostile_input(argv, status, words, folder, capsys):
    if "{d}/ro/m.npz" in argv and os.geteuid() == 0:
        pytest.skip("root writes into a read-only folder")
    argv = [a.replace("{d}", str(folder)) for a in argv]
    got, out, err = run(argv, capsys)
    assert "Traceback" not in err
    assert "internal error" not in err, err
    assert got == status, err
    if status:
        # one error line (argparse adds its usage lines before it)
        errors = [line for line in err.splitlines() if "error:" in line]
        assert len(errors) == 1, err
        for word in words:
            assert word in errors[0], err
    else:
        for word in words:
            assert word in err, err
    if status == 0 and "--json" in argv:
        json.loads(out)       # strict JSON: no NaN, no Infinity
        assert "NaN" not in out and "Infinity" not in out
