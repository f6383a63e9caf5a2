"""The version and input digest in every output, and the map as a table a
spreadsheet opens (issue 33)."""

import csv
import json
import shutil

import numpy as np
from numpy.testing import assert_allclose
import pytest

from infra.files import written_by_us
from infra.provenance import input_digest, tool_version
from judder.cli import main
from studies.inputs import read_boundary, read_boundary_min_growth

MAP = ["map", "--freq", "95:110:4", "--pf", "0:0.6:3", "--preset",
       "paper-4dof"]


def _json(capsys, argv):
    assert main(argv + ["--json"]) == 0
    return json.loads(capsys.readouterr().out)


def test_map_csv_is_a_long_table_with_the_npz_numbers(tmp_path, capsys):
    table, arrays = tmp_path / "m.csv", tmp_path / "m.npz"
    data = _json(capsys, MAP + ["--out", str(table)])
    _json(capsys, MAP + ["--out", str(arrays)])
    lines = table.read_text().splitlines()
    # the header on the first line, no comment before it
    assert lines[0] == ("freq_hz,p_f_bar,leading_abs,growth_rate_per_s,"
                        "kind,judder,leading_re,leading_im")
    rows = list(csv.DictReader(line for line in lines
                               if not line.startswith("#")))
    assert len(rows) == 4 * 3
    with np.load(arrays) as npz:
        # one row per grid point, frequency outer, amplitude inner
        assert_allclose([float(r["freq_hz"]) for r in rows],
                        np.repeat(npz["freq_hz"], 3))
        assert_allclose([float(r["p_f_bar"]) for r in rows],
                        np.tile(npz["p_f_bar"], 4))
        assert_allclose([float(r["leading_abs"]) for r in rows],
                        npz["leading_abs"].ravel(), rtol=1e-11)
        assert_allclose([float(r["growth_rate_per_s"]) for r in rows],
                        npz["growth_rate_per_s"].ravel(), rtol=1e-8)
        names = list(npz["kind_names"])
        assert [r["kind"] for r in rows] == [names[k] for k in
                                             npz["kind"].ravel()]
        # the same inputs: the same digest, whatever the output
        assert str(npz["input_sha256"]) == data["provenance"]["input_sha256"]
    assert sum(int(r["judder"]) for r in rows) == \
        data["judder_relevant_points"]
    # metadata after the rows, the mark last
    comments = dict(line[2:].split(": ", 1) for line in lines
                    if line.startswith("# ") and ": " in line)
    assert json.loads(comments["model"]) == "4dof"
    assert json.loads(comments["parameters"])["J4"] == 0.122
    provenance = data["provenance"]
    assert lines[-1] == (f"# written by judder {tool_version()}, inputs "
                         f"sha256:{provenance['input_sha256']}")
    assert provenance["judder_version"] == tool_version()


def test_the_digest_follows_the_inputs_not_their_place(tmp_path, capsys):
    first, second = tmp_path / "a", tmp_path / "b"
    first.mkdir()
    second.mkdir()
    assert main(["params", "--preset", "paper-4dof", "--save",
                 str(first / "p.toml")]) == 0
    shutil.copy(first / "p.toml", second / "other-name.toml")
    capsys.readouterr()

    def digest(path, *more):
        return _json(capsys, ["eig", "--param-file", str(path), *more]
                     )["provenance"]["input_sha256"]
    same = digest(first / "p.toml")
    assert digest(second / "other-name.toml") == same
    assert digest(first / "p.toml", "--set", "J4=0.13") != same
    with open(second / "other-name.toml", "a") as stream:
        stream.write("# a comment changes the bytes\n")
    assert digest(second / "other-name.toml") != same
    # the outputs' names are no input
    npz = _json(capsys, MAP + ["--out", str(tmp_path / "x.npz")])
    again = _json(capsys, MAP + ["--out", str(tmp_path / "y.npz"),
                                 "--force"])
    assert npz["provenance"] == again["provenance"]
    with np.load(tmp_path / "x.npz") as arrays:
        assert str(arrays["input_sha256"]) == \
            npz["provenance"]["input_sha256"]
        assert str(arrays["judder_version"]) == tool_version()


def test_input_digest_hashes_folders_by_relative_names(tmp_path):
    for name in ("a", "b"):
        (tmp_path / name / "runs").mkdir(parents=True)
        (tmp_path / name / "runs" / "r1.csv").write_text("time [s]\n0\n")
    a = input_digest("chart", {"sources": [str(tmp_path / "a")]})
    assert a == input_digest("chart", {"sources": [str(tmp_path / "b")]})
    (tmp_path / "b" / "runs" / "r1.csv").rename(
        tmp_path / "b" / "runs" / "r2.csv")
    assert a != input_digest("chart", {"sources": [str(tmp_path / "b")]})


def test_the_digest_of_an_index_covers_every_acquisition_it_lists(
        tmp_path, capsys):
    # chart --index hashed the index alone: two data sets that differ in
    # one acquisition shared one input_sha256 (issue 44, item 11)
    from pathlib import Path
    bench = Path(__file__).resolve().parents[1] / "examples" / "bench"
    copies = [tmp_path / name for name in ("a", "b", "c")]
    for copy in copies:
        shutil.copytree(bench, copy)
    run = copies[1] / "run03.csv"
    lines = run.read_text().splitlines()
    time, speed, *rest = lines[4].split(",")
    lines[4] = ",".join([time, f"{float(speed) + 0.5:.6f}", *rest])
    run.write_text("\n".join(lines) + "\n")

    def digest(folder):
        return _json(capsys, ["chart", "--index", str(folder / "runs.csv"),
                              "--channel", "upstream_speed=EngSpd_up:rpm",
                              "--channel", "pressure=PressEVEN:bar"]
                     )["provenance"]["input_sha256"]
    same = digest(copies[0])
    assert digest(copies[2]) == same        # equal data, another place
    assert digest(copies[1]) != same        # one acquisition differs


def test_boundary_csv_is_read_back_and_replaced(tmp_path, capsys):
    out = tmp_path / "b.csv"
    _json(capsys, ["tongues", "--freq", "95:110:6", "--out", str(out)])
    freq, _ = read_boundary(out)
    assert_allclose(freq, np.linspace(95, 110, 6))
    # the rate comment after the rows is still found: the unstable
    # boundaries (the mark's "0." is no rate)
    assert read_boundary_min_growth(out) == 0.0
    assert written_by_us(out)
    # replaced without --force: the mark at the end is found
    _json(capsys, ["tongues", "--freq", "95:110:6", "--out", str(out)])
    user = tmp_path / "user.csv"
    user.write_text("freq_hz,p_f_bar\n100,0.3\n")
    assert main(["tongues", "--freq", "95:110:6", "--out", str(user)]) == 2
    assert "not written by judder" in capsys.readouterr().err


@pytest.mark.parametrize("suffix", ["png", "svg"])
def test_figures_carry_the_version_and_digest(tmp_path, capsys, suffix):
    plot = tmp_path / f"t.{suffix}"
    data = _json(capsys, ["threshold", "--mu-g", "-0.001:0.001:5",
                          "--c-ext", "0:1:2", "--plot", str(plot)])
    assert data["provenance"]["input_sha256"].encode() in plot.read_bytes()


def test_campaign_runs_written_by_workers_carry_the_digest(tmp_path,
                                                           capsys):
    # the runs are written in worker processes (--workers 2): they carry
    # the command's provenance as the parent's outputs do
    pytest.importorskip("fmpy")
    folder = tmp_path / "campaign"
    data = _json(capsys, ["campaign", "--freq", "100:110:2", "--pf",
                          "0.1:0.1:1", "--duration", "0.5", "--format",
                          "csv", "--out", str(folder), "--workers", "2"])
    digest = data["provenance"]["input_sha256"]
    runs = sorted(folder.glob("T*.csv"))
    assert len(runs) == 2
    for run in runs:
        assert run.read_text().splitlines()[-1] == (
            f"# written by judder {tool_version()}, inputs sha256:{digest}")
