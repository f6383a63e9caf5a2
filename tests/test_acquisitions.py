"""Bench acquisition readers (pysim.bench): every format written by
the library that owns it, read back in SI on its own time bases; the bad
inputs; and the files of the bench emulator."""

import json
import math
from pathlib import Path
import re
import subprocess
import sys

import numpy as np
from numpy.testing import assert_allclose
import pytest
import scipy.io

from facts import names
from infra.errors import JudderError
from pysim.bench.acquisition import Acquisition, ChannelSpec
from pysim.bench.channels import parse_channel_option
from pysim.bench.readers import FORMATS, READERS, read_acquisition
from pysim.bench.units import unit_factor
from pysim.simulation.export import write_csv

ROOT = Path(__file__).resolve().parents[1]
# expected factors, written independently of the module's table
TO_SI = {"rpm": 2 * math.pi / 60, "rad/s": 1.0, "bar": 1e5, "kPa": 1e3}
METADATA = {"dither_frequency_hz": 105.0, "dither_amplitude_bar": 0.1,
            "oil_temperature_degC": "65-70", "engine_speed_rpm": 1000.0}
ROLES = {"upstream_speed": ChannelSpec("EngSpd_up"),
         "pressure": ChannelSpec("PressEVEN"),
         "downstream_speed": ChannelSpec("OutSpd_dn")}
UNIT_CASES = [("rpm", "bar"), ("rad/s", "kPa")]


def _pickup(seed, n, rpm):
    """Tooth-passage times of a 41-tooth wheel near ``rpm`` (non-uniform)."""
    rng = np.random.default_rng(seed)
    period = 60 / (rpm * 41)
    return 0.002 + np.cumsum(period * (1 + 0.2 * rng.random(n)))


@pytest.fixture
def bench():
    """Signals in rpm / bar on three independent time bases."""
    t_up = _pickup(1, 300, 1000.0)
    t_down = _pickup(2, 250, 800.0)
    t_p = np.arange(500) * 1e-3
    return {
        "EngSpd_up": (t_up, 1000 + 30 * np.sin(2 * np.pi * 105 * t_up)),
        "OutSpd_dn": (t_down, 800 + 10 * np.cos(2 * np.pi * 40 * t_down)),
        "PressEVEN": (t_p, 3 + 0.1 * np.sin(2 * np.pi * 105 * t_p)),
    }


def _in(values, unit):
    """Values given in rpm / bar, expressed in ``unit``."""
    base = "rpm" if unit in ("rpm", "rad/s") else "bar"
    return values * TO_SI[base] / TO_SI[unit]


def _check(acq, bench, units, rtol=1e-12, exact_time=True):
    speed_unit, pressure_unit = units
    for role, unit in [("upstream_speed", speed_unit),
                       ("downstream_speed", speed_unit),
                       ("pressure", pressure_unit)]:
        channel = acq.channels[role]
        time, values = bench[channel.name]
        base = "rpm" if unit in ("rpm", "rad/s") else "bar"
        assert channel.unit_in_file == unit
        assert_allclose(channel.values, values * TO_SI[base], rtol=rtol)
        if exact_time:
            assert_allclose(channel.time, time, rtol=1e-12, atol=0)


# --- each format, written by the library that owns it ---------------------

def _write_mf4(path, bench, units, version="4.10"):
    from asammdf import MDF, Signal
    mdf = MDF(version=version)
    for name, (time, values) in bench.items():
        unit = units[0] if "Spd" in name else units[1]
        mdf.append([Signal(samples=_in(values, unit), timestamps=time,
                           name=name, unit=unit)])
    mdf.header.comment = json.dumps(METADATA)
    mdf.save(path, overwrite=True)
    mdf.close()


@pytest.mark.parametrize("units", UNIT_CASES)
def test_mf4_channels_keep_their_time_bases(tmp_path, bench, units):
    path = tmp_path / "run.mf4"
    _write_mf4(path, bench, units)
    acq = read_acquisition(path, ROLES)
    assert isinstance(acq, Acquisition) and acq.format == "mf4"
    assert acq.path == path
    _check(acq, bench, units)
    assert acq.metadata == METADATA
    # three different lengths: nothing was resampled
    assert {len(c.time) for c in acq.channels.values()} == {300, 250, 500}


def test_mdf3_reads_too(tmp_path, bench):
    path = tmp_path / "run.mdf"
    _write_mf4(path, bench, ("rpm", "bar"), version="3.30")
    acq = read_acquisition(path, ROLES)
    assert acq.format == "mdf"
    _check(acq, bench, ("rpm", "bar"))
    assert {k: acq.metadata[k] for k in METADATA} == METADATA


def _write_tdms(path, bench, units):
    from nptdms import ChannelObject, GroupObject, RootObject, TdmsWriter
    (t_up, n_up), (t_down, n_down), (_, p) = (
        bench["EngSpd_up"], bench["OutSpd_dn"], bench["PressEVEN"])
    speed, pressure = units
    objects = [
        RootObject(properties=METADATA),
        GroupObject("Speeds"),
        ChannelObject("Speeds", "Time", t_up, properties={"unit_string": "s"}),
        ChannelObject("Speeds", "EngSpd_up", _in(n_up, speed),
                      properties={"unit_string": speed}),
        GroupObject("Output"),
        ChannelObject("Output", "time", t_down * 1e3,
                      properties={"unit_string": "ms"}),
        ChannelObject("Output", "OutSpd_dn", _in(n_down, speed),
                      properties={"unit_string": speed}),
        GroupObject("Hydraulics"),
        ChannelObject("Hydraulics", "PressEVEN", _in(p, pressure),
                      properties={"unit_string": pressure,
                                  "wf_increment": 1e-3,
                                  "wf_start_offset": 0.0,
                                  "wf_samples": len(p)}),
    ]
    with TdmsWriter(str(path)) as writer:
        writer.write_segment(objects)


@pytest.mark.parametrize("units", UNIT_CASES)
def test_tdms_waveform_and_time_channels(tmp_path, bench, units):
    path = tmp_path / "run.tdms"
    _write_tdms(path, bench, units)
    acq = read_acquisition(path, ROLES)
    assert acq.format == "tdms"
    _check(acq, bench, units)
    assert acq.metadata == METADATA


def test_tdms_group_slash_channel_and_ambiguous_names(tmp_path, bench):
    from nptdms import ChannelObject, TdmsWriter
    path = tmp_path / "two.tdms"
    time, values = bench["EngSpd_up"]
    with TdmsWriter(str(path)) as writer:
        writer.write_segment([
            ChannelObject(group, name, data, properties={"unit_string": u})
            for group in ("A", "B") for name, data, u in
            [("time", time, "s"), ("EngSpd_up", values, "rpm")]])
    acq = read_acquisition(path,
                           {"upstream_speed": ChannelSpec("B/EngSpd_up")})
    assert_allclose(acq.channels["upstream_speed"].values,
                    values * TO_SI["rpm"], rtol=1e-12)
    with pytest.raises(JudderError, match="several groups.*'A/EngSpd_up'"):
        read_acquisition(path, {"upstream_speed": ChannelSpec("EngSpd_up")})


def _mat_variables(bench, units):
    speed, pressure = units
    (t_up, n_up), (t_down, n_down), (t_p, p) = (
        bench["EngSpd_up"], bench["OutSpd_dn"], bench["PressEVEN"])
    return {"EngSpd_up": _in(n_up, speed), "EngSpd_up_time": t_up,
            "OutSpd_dn": _in(n_down, speed), "t_OutSpd_dn": t_down,
            "PressEVEN": _in(p, pressure), "time": t_p,
            "units": {"EngSpd_up": speed, "OutSpd_dn": speed,
                      "PressEVEN": pressure}}


@pytest.mark.parametrize("units", UNIT_CASES)
def test_mat_variables_with_their_time_vectors(tmp_path, bench, units):
    path = tmp_path / "run.mat"
    scipy.io.savemat(path, {**_mat_variables(bench, units),
                            "metadata": METADATA})
    acq = read_acquisition(path, ROLES)
    assert acq.format == "mat"
    _check(acq, bench, units)
    assert acq.metadata == METADATA


def test_mat_struct_with_shared_time_and_scalar_metadata(tmp_path, bench):
    path = tmp_path / "struct.mat"
    scipy.io.savemat(path, {"acq": _mat_variables(bench, ("rpm", "bar")),
                            "dither_frequency_hz": 105.0})
    acq = read_acquisition(path, ROLES)
    _check(acq, bench, ("rpm", "bar"))
    assert acq.metadata == {"dither_frequency_hz": 105.0}
    dotted = read_acquisition(path, {"upstream_speed":
                                     ChannelSpec("acq.EngSpd_up")})
    assert_allclose(dotted.channels["upstream_speed"].time,
                    bench["EngSpd_up"][0], rtol=1e-12)


def _csv_rounded(values):
    """What ``write_csv`` keeps of a float (9 significant digits)."""
    return np.array([float(f"{v:.9g}") for v in values])


@pytest.mark.parametrize("units", UNIT_CASES)
def test_csv_of_export_with_nan_dropped_per_channel(tmp_path, bench, units):
    speed, pressure = units
    t_up, n_up = bench["EngSpd_up"]
    n_down = np.interp(t_up, *bench["OutSpd_dn"], left=np.nan)
    p = np.interp(t_up, *bench["PressEVEN"])
    path = tmp_path / "run.csv"
    write_csv(path, t_up, {"EngSpd_up": _in(n_up, speed),
                           "OutSpd_dn": _in(n_down, speed),
                           "PressEVEN": _in(p, pressure)},
              {"EngSpd_up": speed, "OutSpd_dn": speed,
               "PressEVEN": pressure}, METADATA)
    acq = read_acquisition(path, ROLES)
    assert acq.format == "csv"
    assert acq.metadata == METADATA
    up = acq.channels["upstream_speed"]
    assert_allclose(up.time, _csv_rounded(t_up), rtol=1e-12)
    assert_allclose(up.values, _csv_rounded(_in(n_up, speed))
                    * TO_SI[speed], rtol=1e-12)
    down = acq.channels["downstream_speed"]
    valid = ~np.isnan(n_down)
    assert 0 < valid.sum() < len(t_up)     # the NaN head is dropped
    assert_allclose(down.time, _csv_rounded(t_up[valid]), rtol=1e-12)
    assert_allclose(down.values, _csv_rounded(_in(n_down[valid], speed))
                    * TO_SI[speed], rtol=1e-12)
    assert_allclose(acq.channels["pressure"].values,
                    _csv_rounded(_in(p, pressure)) * TO_SI[pressure],
                    rtol=1e-12)


def test_csv_plain_names_with_units_given(tmp_path):
    path = tmp_path / "plain.csv"
    path.write_text("# source: \"rig 2\"\ntime;EngSpd_up;PressEVEN\n"
                    "0.0;1000;2.5\n0.001;;2.6\n0.002;1010;2.7\n")
    acq = read_acquisition(path, {
        "upstream_speed": ChannelSpec("EngSpd_up", "1/min"),
        "pressure": ChannelSpec("PressEVEN", "psi")})
    up = acq.channels["upstream_speed"]
    assert_allclose(up.time, [0.0, 0.002])
    assert_allclose(up.values, np.array([1000, 1010]) * TO_SI["rpm"],
                    rtol=1e-12)
    assert_allclose(acq.channels["pressure"].values,
                    np.array([2.5, 2.6, 2.7]) * 6894.757293168361,
                    rtol=1e-12)
    assert acq.metadata == {"source": "rig 2"}


def test_given_unit_overrides_the_files(tmp_path, bench):
    path = tmp_path / "run.mf4"
    _write_mf4(path, bench, ("rpm", "bar"))
    acq = read_acquisition(path, {"upstream_speed":
                                  ChannelSpec("EngSpd_up", "rad/s")})
    channel = acq.channels["upstream_speed"]
    assert channel.unit_in_file == "rad/s"
    assert_allclose(channel.values, bench["EngSpd_up"][1], rtol=1e-12)


# --- units and options ----------------------------------------------------

@pytest.mark.parametrize("unit, kind, factor", [
    ("rpm", "speed", 2 * math.pi / 60), ("rev/min", "speed", 2 * math.pi / 60),
    ("1/min", "speed", 2 * math.pi / 60), ("min^-1", "speed",
                                           2 * math.pi / 60),
    ("RPM", "speed", 2 * math.pi / 60), ("rad/s", "speed", 1.0),
    ("Hz", "speed", 2 * math.pi), ("Pa", "pressure", 1.0),
    ("kPa", "pressure", 1e3), ("MPa", "pressure", 1e6),
    ("bar", "pressure", 1e5), ("mbar", "pressure", 100.0),
    ("psi", "pressure", 6894.757293168361)])
def test_unit_factors(unit, kind, factor):
    assert unit_factor(unit, kind) == pytest.approx(factor, rel=1e-15)


@pytest.mark.parametrize("unit, kind, words", [
    ("bar", "speed", ["'bar' is a pressure unit", "rpm", "rad/s"]),
    ("rpm", "pressure", ["'rpm' is a speed unit", "kPa", "psi"]),
    ("mPa", "pressure", ["unknown", "MPa"]),
    ("furlong/s", "speed", ["unknown", "rpm"])])
def test_bad_units(unit, kind, words):
    with pytest.raises(JudderError) as info:
        unit_factor(unit, kind)
    for word in words:
        assert word in str(info.value)


def test_channel_option():
    assert parse_channel_option("upstream_speed=EngSpd_up") == (
        "upstream_speed", ChannelSpec("EngSpd_up"))
    assert parse_channel_option("downstream_speed=CAN:OutSpd:rpm") == (
        "downstream_speed", ChannelSpec("CAN:OutSpd", "rpm"))
    with pytest.raises(JudderError, match="role 'speed' is unknown.*"
                       "upstream_speed"):
        parse_channel_option("speed=EngSpd_up")
    with pytest.raises(JudderError, match="pressure unit"):
        parse_channel_option("upstream_speed=EngSpd_up:bar")
    with pytest.raises(JudderError, match="ROLE=NAME"):
        parse_channel_option("upstream_speed")
    # what a speed channel's samples are (pysim.bench.speed_channels)
    assert parse_channel_option("upstream_speed=Enc:deg:angle") == (
        "upstream_speed", ChannelSpec("Enc", "deg", "angle"))
    assert parse_channel_option("upstream_speed=CAN:N:rpm:sampled") == (
        "upstream_speed", ChannelSpec("CAN:N", "rpm", "sampled"))
    with pytest.raises(JudderError, match="a kind is for a speed channel"):
        parse_channel_option("pressure=P:bar:sampled")
    with pytest.raises(JudderError, match="unit before the kind"):
        parse_channel_option("upstream_speed=N:passage")


# --- bad input -------------------------------------------------------------

@pytest.fixture
def mf4(tmp_path, bench):
    path = tmp_path / "run.mf4"
    _write_mf4(path, bench, ("rpm", "bar"))
    return path


def _message(path, channels):
    with pytest.raises(JudderError) as info:
        read_acquisition(path, channels)
    message = str(info.value)
    assert "\n" not in message
    return message


def test_missing_channel_lists_the_files_names(mf4):
    message = _message(mf4, {"upstream_speed": ChannelSpec("n_up")})
    assert str(mf4) in message and "'n_up'" in message
    for name in ("EngSpd_up", "OutSpd_dn", "PressEVEN"):
        assert repr(name) in message
    assert "'time'" not in message          # master channels are not listed


def test_missing_channel_in_csv_lists_columns(tmp_path):
    path = tmp_path / "run.csv"
    write_csv(path, np.arange(3.0), {"a": np.ones(3), "b": np.ones(3)},
              {"a": "rpm", "b": "bar"}, {})
    message = _message(path, {"upstream_speed": ChannelSpec("c")})
    assert "'a', 'b'" in message and "'time'" not in message


def test_missing_unit_says_how_to_give_it(tmp_path, bench):
    path = tmp_path / "run.mat"
    variables = _mat_variables(bench, ("rpm", "bar"))
    del variables["units"]
    scipy.io.savemat(path, variables)
    message = _message(path, {"upstream_speed": ChannelSpec("EngSpd_up")})
    assert str(path) in message and "upstream_speed" in message
    assert "`channels` upstream_speed=EngSpd_up:UNIT" in message


def test_wrong_unit_kind_in_the_file(tmp_path, bench):
    path = tmp_path / "run.mf4"
    _write_mf4(path, bench, ("bar", "bar"))
    message = _message(path, {"upstream_speed": ChannelSpec("EngSpd_up")})
    assert "upstream_speed" in message and "'bar' is a pressure unit" \
        in message and "rpm" in message


def test_wrong_unit_kind_given(mf4):
    message = _message(mf4, {"pressure": ChannelSpec("PressEVEN", "rpm"),
                             "upstream_speed": ChannelSpec("EngSpd_up")})
    assert "pressure channel 'PressEVEN'" in message
    assert "'rpm' is a speed unit" in message


def test_upstream_speed_is_required_and_roles_are_known(mf4):
    assert "upstream_speed" in _message(
        mf4, {"pressure": ChannelSpec("PressEVEN")})
    message = _message(mf4, {"upstream_speed": ChannelSpec("EngSpd_up"),
                             "torque": ChannelSpec("PressEVEN")})
    assert "'torque'" in message and "downstream_speed" in message


def test_unknown_suffix(tmp_path):
    path = tmp_path / "run.xlsx"
    path.write_bytes(b"PK")
    message = _message(path, {"upstream_speed": ChannelSpec("x")})
    assert str(path) in message and "'.xlsx'" in message
    for suffix in (".mf4", ".csv", ".tdms", ".mat"):
        assert suffix in message


def test_readers_registry_names_every_format():
    # one reader per suffix, each with the name a corrupt file's message
    # gives; the unknown-suffix message lists the registry's keys
    assert set(READERS) == set(FORMATS) == {".mf4", ".mdf", ".csv", ".tdms",
                                            ".mat"}
    assert all(callable(reader) for reader in READERS.values())


def test_no_such_file(tmp_path):
    message = _message(tmp_path / "gone.csv",
                       {"upstream_speed": ChannelSpec("x")})
    assert "gone.csv: no such file" in message


@pytest.mark.parametrize("suffix, words", [
    (".mf4", ["not a readable ASAM MDF4 file"]),
    (".mdf", ["not a readable ASAM MDF file"]),
    (".tdms", ["not a readable NI TDMS file"]),
    (".mat", ["not a readable MATLAB MAT file"]),
    (".csv", ["not UTF-8", "save the CSV as UTF-8"])])
def test_corrupt_files(tmp_path, suffix, words):
    path = tmp_path / f"noise{suffix}"
    noise = np.random.default_rng(0).integers(0, 256, 4096, dtype=np.uint8)
    path.write_bytes(b"\xff\xfe" + noise.tobytes())
    message = _message(path, {"upstream_speed": ChannelSpec("x")})
    assert str(path) in message
    for word in words:
        assert word in message


def test_truncated_mf4(tmp_path, mf4):
    path = tmp_path / "cut.mf4"
    path.write_bytes(mf4.read_bytes()[:700])
    assert str(path) in _message(path, ROLES)


@pytest.mark.parametrize("text, words", [
    ("time [s],a [rpm]\n0,1\n0.1,x\n", ["line 3", "'x' is not a number"]),
    ("time [s],a [rpm]\n0,1\n0.1\n", ["line 3", "1 fields"]),
    ("when,a [rpm]\n0,1\n", ["no time column", "'when'"]),
    ("time [h],a [rpm]\n0,1\n", ["column 'time'", "'h' is unknown"]),
    ("time [s],a [rpm]\n0.2,1\n0.1,2\n", ["time goes backwards"]),
    ("time [s],a [rpm]\n0,nan\n", ["upstream_speed channel 'a' has no "
                                   "finite samples"]),
    ("# only: 1\n", ["no header line"]),
])
def test_bad_csv(tmp_path, text, words):
    path = tmp_path / "bad.csv"
    path.write_text(text)
    message = _message(path, {"upstream_speed": ChannelSpec("a")})
    assert str(path) in message
    for word in words:
        assert word in message


def test_an_optional_channel_may_be_empty(tmp_path):
    path = tmp_path / "rest.csv"
    path.write_text("time [s],up [rpm],down [rpm]\n0,1000,nan\n"
                    "0.001,1001,nan\n")
    acq = read_acquisition(path, {"upstream_speed": ChannelSpec("up"),
                                  "downstream_speed": ChannelSpec("down")})
    down = acq.channels["downstream_speed"]
    assert down.time.shape == down.values.shape == (0,)


def test_mat_signal_without_time_vector(tmp_path):
    path = tmp_path / "notime.mat"
    scipy.io.savemat(path, {"EngSpd_up": np.ones(5)})
    message = _message(path, {"upstream_speed":
                              ChannelSpec("EngSpd_up", "rpm")})
    assert "no time vector" in message and "EngSpd_up_time" in message


def test_tdms_channel_without_time(tmp_path):
    from nptdms import ChannelObject, TdmsWriter
    path = tmp_path / "notime.tdms"
    with TdmsWriter(str(path)) as writer:
        writer.write_segment([ChannelObject("G", "EngSpd_up", np.ones(5),
                                            properties={"unit_string":
                                                        "rpm"})])
    message = _message(path, {"upstream_speed": ChannelSpec("EngSpd_up")})
    assert "no wf_increment" in message and "'time' channel" in message


def test_module_does_not_import_matplotlib(mf4):
    code = ("import sys; from pysim.bench.readers import "
            "read_acquisition\n"
            "from pysim.bench.acquisition import ChannelSpec\n"
            f"read_acquisition({str(mf4)!r}, "
            "{'upstream_speed': ChannelSpec('EngSpd_up')})\n"
            "print('matplotlib' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True,
                         text=True, check=True, cwd=ROOT).stdout
    assert out.strip() == "False"


# --- files of the bench emulator --------------------------------------------

def test_bench_campaign_csv_and_mf4_agree(tmp_path):
    pytest.importorskip("rumoca")
    pytest.importorskip("fmpy")
    from sources import get_preset
    from pysim.simulation.campaigns import Campaign, run_campaign
    campaign = Campaign(freq_hz=(105.0,), p_f_bar=(0.1,), duration=0.3,
                        formats=("csv", "mf4"))
    rows = run_campaign(campaign, get_preset("paper-4dof"), tmp_path,
                        workers=1)
    assert rows[0]["status"] == "ok", rows[0]["message"]
    roles = {"upstream_speed": ChannelSpec("n_upstream"),
             "downstream_speed": ChannelSpec("n_downstream"),
             "pressure": ChannelSpec("p_even")}
    run_id = rows[0]["run_id"]
    csv_run = read_acquisition(tmp_path / f"{run_id}.csv", roles)
    mf4_run = read_acquisition(tmp_path / f"{run_id}.mf4", roles)
    for acq in (csv_run, mf4_run):
        assert acq.metadata["dither_frequency_hz"] == 105.0
        assert acq.metadata["dither_amplitude_bar"] == 0.1
        assert acq.metadata["engine_speed_rpm"] == 1000.0
        assert acq.metadata["oil_temperature_degC"] == "65-70"
        assert acq.channels["upstream_speed"].unit_in_file == "rpm"
        assert acq.channels["pressure"].unit_in_file == "bar"
    # the upstream pick-up is the CSV's time base: the same samples
    up_csv, up_mf4 = (a.channels["upstream_speed"] for a in (csv_run,
                                                             mf4_run))
    assert len(up_csv.time) == len(up_mf4.time) > 50
    assert_allclose(up_csv.time, up_mf4.time, rtol=1e-8)
    assert_allclose(up_csv.values, up_mf4.values, rtol=1e-8)
    # near 1000 rpm, in rad/s
    assert np.median(up_mf4.values) == pytest.approx(1000 * TO_SI["rpm"],
                                                     rel=0.1)
    # the MF4 keeps the pressure at 1 kHz and the downstream pick-up on its
    # own passages; the CSV has them interpolated on the upstream passages
    p_mf4 = mf4_run.channels["pressure"]
    assert_allclose(np.diff(p_mf4.time), 1e-3, rtol=1e-9)
    assert not np.array_equal(mf4_run.channels["downstream_speed"].time,
                              up_mf4.time)
    p_csv = csv_run.channels["pressure"]
    assert_allclose(p_csv.time, up_csv.time)
    assert_allclose(p_csv.values, np.interp(p_csv.time, p_mf4.time,
                                            p_mf4.values),
                    rtol=1e-7, atol=1e-7 * np.abs(p_mf4.values).max())
    # from rest, the downstream wheel sees few passages in 0.3 s: the CSV
    # column is NaN until there are two, and those samples are dropped
    down_csv, down_mf4 = (a.channels["downstream_speed"]
                          for a in (csv_run, mf4_run))
    if len(down_mf4.time) < 2:
        assert len(down_csv.time) == 0
    else:
        assert down_csv.time[0] >= down_mf4.time[0]
        assert_allclose(down_csv.values, np.interp(
            down_csv.time, down_mf4.time, down_mf4.values), rtol=1e-7,
            atol=1e-7 * np.abs(down_mf4.values).max())


@pytest.mark.parametrize("column, value, expected", [
    ("n_up", 2.9e161, "upstream_speed channel 'n_up': 2.9e+161 rpm at 0.6 s "
     "is not a value a bench records; allowed: -100000 to 100000 rpm"),
    ("p", -50.0, "pressure channel 'p': -50 bar at 0.6 s is not a value a "
     "bench records; allowed: -1 to 1000 bar"),
])
def test_a_value_no_bench_records_is_refused(tmp_path, column, value,
                                             expected):
    # a broken writer's speed (issue 19) or a pressure in the wrong unit:
    # the run is refused with the channel, the value and the range, not
    # folded into a verdict
    t = np.linspace(0.0, 1.0, 101)
    signals = {"n_up": np.full_like(t, 1000.0), "p": np.full_like(t, 10.0)}
    signals[column] = signals[column].copy()
    signals[column][60] = value
    write_csv(tmp_path / "run.csv", t, signals, {"n_up": "rpm", "p": "bar"},
              {})
    with pytest.raises(JudderError, match=re.escape(expected)):
        read_acquisition(tmp_path / "run.csv",
                         {"upstream_speed": ChannelSpec("n_up"),
                          "pressure": ChannelSpec("p")})


def test_mf4_with_one_name_in_several_groups(tmp_path):
    # a CAN copy of the speed at 100 Hz stored before the DAQ's 2 kHz one:
    # the name alone is refused with the groups to choose from; GROUP/NAME
    # (the group's acquisition name, or its index) reads that group's
    from asammdf import MDF, Signal
    mdf = MDF(version="4.10")
    for label, step in (("CAN", 0.01), ("DAQ", 0.0005)):
        t = np.arange(0.0, 1.0, step)
        mdf.append([Signal(1000 + 0 * t, t, name="EngSpd_up", unit="rpm")],
                   acq_name=label)
    mdf.save(tmp_path / "run.mf4", overwrite=True)
    message = _message(tmp_path / "run.mf4", {"upstream_speed": "EngSpd_up"})
    assert ("channel 'EngSpd_up' is in several groups; name one as "
            "GROUP/NAME") in message
    assert "CAN/EngSpd_up (100 samples), DAQ/EngSpd_up (2000 samples)" \
        in message
    for name, samples in (("DAQ/EngSpd_up", 2000), ("0/EngSpd_up", 100)):
        channel = read_acquisition(tmp_path / "run.mf4", {
            "upstream_speed": name}).channels["upstream_speed"]
        assert len(channel.time) == samples
    missing = _message(tmp_path / "run.mf4", {"upstream_speed": "Speed"})
    assert "'CAN/EngSpd_up', 'DAQ/EngSpd_up'" in missing


def _write_mat73(path, variables):
    """A MAT v7.3 file as MATLAB writes it, with h5py: the 512-byte
    header (version 0x0200: scipy refuses it as HDF5), column-major
    doubles, structs as groups, text as uint16 char arrays."""
    import h5py

    def put(parent, name, value):
        if isinstance(value, dict):
            group = parent.create_group(name)
            group.attrs["MATLAB_class"] = np.bytes_("struct")
            for key, item in value.items():
                put(group, key, item)
        elif isinstance(value, str):
            data = parent.create_dataset(name, data=np.array(
                [[ord(c)] for c in value], dtype=np.uint16))
            data.attrs["MATLAB_class"] = np.bytes_("char")
        else:
            data = parent.create_dataset(
                name, data=np.atleast_2d(np.asarray(value, dtype=float)))
            data.attrs["MATLAB_class"] = np.bytes_("double")
    with h5py.File(path, "w", userblock_size=512) as top:
        for key, value in variables.items():
            put(top, key, value)
    header = b"MATLAB 7.3 MAT-file, Platform: GLNXA64, Created on: " \
        b"Wed Dec  2 06:00:00 2026 HDF5 schema 1.00 ."
    with open(path, "r+b") as stream:
        stream.write(header.ljust(116) + b"\0" * 8 + b"\x00\x02" + b"IM")


@pytest.mark.parametrize("units", UNIT_CASES)
def test_mat_v73_reads_as_v7(tmp_path, bench, units):
    # the same variables saved as MATLAB's -v7.3 (HDF5) and -v7 read alike
    path = tmp_path / "run73.mat"
    _write_mat73(path, {"acq": _mat_variables(bench, units),
                        "dither_frequency_hz": 105.0,
                        "metadata": {"oil_temperature_degC": "65-70"}})
    with pytest.raises(NotImplementedError):     # scipy: not a v7 file
        scipy.io.loadmat(path)
    acq = read_acquisition(path, ROLES)
    assert acq.format == "mat"
    _check(acq, bench, units)
    assert acq.metadata == {"dither_frequency_hz": 105.0,
                            "oil_temperature_degC": "65-70"}


def test_csv_in_windows_1252_reads(tmp_path):
    # a European DAQ's export: Windows-1252 text (a time column in µs, an
    # oil temperature in °C), ';' and decimal commas
    text = ("Prüfstand;EVEN\nZeit [µs];EngSpd_up [rpm];Öl [°C];"
            "PressEVEN [bar]\n0;1000,5;65,2;10,0\n1000;1001,5;65,2;10,1\n"
            "2000;1002,5;65,3;10,2\n")
    (tmp_path / "run.csv").write_bytes(text.encode("cp1252"))
    acq = read_acquisition(tmp_path / "run.csv", {
        "upstream_speed": "EngSpd_up", "pressure": "PressEVEN"})
    assert acq.metadata["Prüfstand"] == "EVEN"
    assert_allclose(acq.channels["pressure"].time, [0.0, 1e-3, 2e-3])
    assert_allclose(acq.channels["upstream_speed"].values,
                    np.array([1000.5, 1001.5, 1002.5]) * TO_SI["rpm"])


# --- clocks started apart: aligned on absolute time (issue 31) ------------

def _ramp(time, start=1.84):
    """A pressure of 3 bar stepping to 8 bar at ``start`` (its own clock)."""
    return np.where(time < start, 3.0, 8.0)


def _ramp_time(channel):
    """When a read pressure first exceeds 5.5 bar, s."""
    return channel.time[np.argmax(channel.values > 5.5 * TO_SI["bar"])]


def test_tdms_clocks_started_apart_are_aligned(tmp_path, bench):
    """Pressure recorded by a task started 1.5 s before the speeds' (its
    wf_start_time), the speeds with date-time stamps: the pressure's step
    at 1.84 s of its own record is 0.34 s into the speeds' record."""
    from nptdms import ChannelObject, TdmsWriter
    t0 = np.datetime64("2026-12-03T07:00:00", "ns")
    t_up, n_up = bench["EngSpd_up"]
    t_p = np.arange(3000) * 1e-3
    stamps = t0 + (t_up * 1e9).astype("timedelta64[ns]")
    path = tmp_path / "tasks.tdms"
    with TdmsWriter(str(path)) as writer:
        writer.write_segment([
            ChannelObject("Speeds", "Time", stamps),
            ChannelObject("Speeds", "EngSpd_up", n_up,
                          properties={"unit_string": "rpm"}),
            ChannelObject("Hydraulics", "PressEVEN", _ramp(t_p),
                          properties={
                              "unit_string": "bar", "wf_increment": 1e-3,
                              "wf_start_offset": 0.0,
                              "wf_start_time": t0 - np.timedelta64(1500,
                                                                   "ms")})])
    roles = {"upstream_speed": ChannelSpec("EngSpd_up"),
             "pressure": ChannelSpec("PressEVEN")}
    acq = read_acquisition(path, roles)
    speed = acq.channels["upstream_speed"]
    # the speeds' clock: their first stamp is t_up[0] after t0
    speeds_zero = speed.time[0] - t_up[0]
    # (npTDMS reads date-time stamps to the microsecond)
    assert _ramp_time(acq.channels["pressure"]) - speeds_zero == \
        pytest.approx(0.34, abs=2e-6)
    assert_allclose(np.diff(speed.time), np.diff(t_up), atol=2e-6)


def test_tdms_clocks_that_cannot_be_aligned_are_refused(tmp_path, bench):
    from nptdms import ChannelObject, TdmsWriter
    t_up, n_up = bench["EngSpd_up"]
    path = tmp_path / "mixed.tdms"
    with TdmsWriter(str(path)) as writer:
        writer.write_segment([
            ChannelObject("Speeds", "Time", t_up,
                          properties={"unit_string": "s"}),
            ChannelObject("Speeds", "EngSpd_up", n_up,
                          properties={"unit_string": "rpm"}),
            ChannelObject("Hydraulics", "PressEVEN", np.full(100, 3.0),
                          properties={
                              "unit_string": "bar", "wf_increment": 1e-3,
                              "wf_start_offset": 0.0,
                              "wf_start_time": np.datetime64(
                                  "2026-12-03T07:00:00", "ns")})])
    message = _message(path, {"upstream_speed": ChannelSpec("EngSpd_up"),
                              "pressure": ChannelSpec("PressEVEN")})
    assert "'PressEVEN'" in message and "'EngSpd_up'" in message
    assert "one time base" in message


# --- numbers read as written (issue 31) -----------------------------------

SPEED_PRESSURE = {"upstream_speed": ChannelSpec("EngSpd_up"),
                  "pressure": ChannelSpec("PressEVEN")}


def _csv_read(tmp_path, text, roles=SPEED_PRESSURE):
    path = tmp_path / "export.csv"
    path.write_text(text)
    return path, roles


def test_us_thousands_separators_in_a_tab_separated_export(tmp_path):
    # integer speeds with a thousands comma; the time's and the
    # pressure's decimal points say the comma is not a decimal one
    path, roles = _csv_read(
        tmp_path, "time [s]\tEngSpd_up [rpm]\tPressEVEN [bar]\n"
        "0.000\t998\t3.05\n0.001\t\"1,000\"\t3.10\n0.002\t1,002\t3.15\n")
    acq = read_acquisition(path, roles)
    assert_allclose(acq.channels["upstream_speed"].values,
                    np.array([998, 1000, 1002]) * TO_SI["rpm"], rtol=1e-12)


def test_german_thousands_and_decimal_comma(tmp_path):
    path, roles = _csv_read(
        tmp_path, "time [s];EngSpd_up [rpm];PressEVEN [bar]\n"
        "0;1.000,60656;3\n0,001;1.001,5;3,1\n")
    acq = read_acquisition(path, roles)
    assert_allclose(acq.channels["upstream_speed"].values,
                    np.array([1000.60656, 1001.5]) * TO_SI["rpm"],
                    rtol=1e-12)
    assert_allclose(acq.channels["upstream_speed"].time, [0.0, 0.001])


def test_a_first_row_of_space_grouped_numbers_is_data(tmp_path):
    # every cell of the first data row is a number with a thousands
    # space, which float() does not read: it is data, not a units row
    path, roles = _csv_read(
        tmp_path, "time [ms];EngSpd_up [rpm];PressEVEN [mbar]\n"
        "1 000;1 000;3 050\n1 001;1 001;3 100\n1 002;1 002;3 150\n")
    acq = read_acquisition(path, roles)
    assert_allclose(acq.channels["upstream_speed"].time,
                    [1.0, 1.001, 1.002], rtol=1e-12)
    assert_allclose(acq.channels["upstream_speed"].values,
                    np.array([1000, 1001, 1002]) * TO_SI["rpm"], rtol=1e-12)
    assert_allclose(acq.channels["pressure"].values,
                    np.array([3.05, 3.1, 3.15]) * TO_SI["bar"], rtol=1e-12)
    assert acq.channels["pressure"].unit_in_file == "mbar"


@pytest.mark.parametrize("text, words", [
    # every separated cell reads both ways: refused, not guessed
    ("time [ms]\tEngSpd_up [rpm]\tPressEVEN [bar]\n0\t998\t3\n"
     "1\t1,000\t3\n", ["column 'EngSpd_up'", "'1,000'", "line 3", "1000",
                       "no cell of the file tells which"]),
    # columns written with different decimal separators
    ("time [s];EngSpd_up [rpm];PressEVEN [bar]\n0.001;1000;3,5\n",
     ["'0.001'", "'3,5'", "column 'time'", "column 'PressEVEN'"]),
    # a cell no convention reads is quoted as the file has it
    ("time [s];EngSpd_up [rpm];PressEVEN [bar]\n0;1.00.5;3\n",
     ["line 2", "'1.00.5' is not a number"]),
])
def test_numbers_that_cannot_be_read_as_written_are_refused(tmp_path, text,
                                                            words):
    path, roles = _csv_read(tmp_path, text)
    message = _message(path, roles)
    assert str(path) in message
    for word in words:
        assert word in message


def test_csv_date_time_column(tmp_path):
    path, roles = _csv_read(
        tmp_path, "Time;EngSpd_up [rpm];PressEVEN [bar]\n"
        "03.12.2026 07:41:59,998;1000,5;3\n"
        "03.12.2026 07:42:00,000;1001,5;3\n"
        "03.12.2026 07:42:00,003;1002,5;3\n")
    acq = read_acquisition(path, roles)
    assert_allclose(acq.channels["upstream_speed"].time, [0, 0.002, 0.005],
                    atol=1e-12)
    path.write_text("time,EngSpd_up [rpm]\n2026-12-03T07:41:59.5,1000\n"
                    "2026-12-03T07:42:00.25,1001\n")
    acq = read_acquisition(path, {"upstream_speed": ChannelSpec(
        "EngSpd_up")})
    assert_allclose(acq.channels["upstream_speed"].time, [0, 0.75])


# --- what had no way round (issue 31) -------------------------------------

def test_a_time_column_of_another_name_is_named_by_the_time_role(tmp_path):
    text = ("Zeit  1 - Standardmessrate [ms];EngSpd_up [rpm]\n"
            "0;1000\n1;1001\n2;1002\n")
    path = tmp_path / "catman.csv"
    path.write_text(text)
    speed = {"upstream_speed": ChannelSpec("EngSpd_up")}
    assert "`channels` time=NAME" in _message(path, speed)
    role, spec = parse_channel_option("time=Zeit  1 - Standardmessrate")
    acq = read_acquisition(path, {**speed, role: spec})
    assert set(acq.channels) == {"upstream_speed"}
    assert_allclose(acq.channels["upstream_speed"].time, [0, 1e-3, 2e-3])
    # its unit given overrides the file's
    acq = read_acquisition(path, {**speed, "time": ChannelSpec(
        "Zeit  1 - Standardmessrate", "s")})
    assert_allclose(acq.channels["upstream_speed"].time, [0, 1, 2])


def test_tdms_and_mat_time_of_another_name(tmp_path, bench):
    from nptdms import ChannelObject, TdmsWriter
    t_up, n_up = bench["EngSpd_up"]
    path = tmp_path / "run.tdms"
    with TdmsWriter(str(path)) as writer:
        writer.write_segment([
            ChannelObject("G", "Clock", t_up * 1e3,
                          properties={"unit_string": "ms"}),
            ChannelObject("G", "EngSpd_up", n_up,
                          properties={"unit_string": "rpm"})])
    speed = {"upstream_speed": ChannelSpec("EngSpd_up")}
    assert "`channels` time=NAME" in _message(path, speed)
    acq = read_acquisition(path, {**speed, "time": ChannelSpec("Clock")})
    assert_allclose(acq.channels["upstream_speed"].time, t_up, rtol=1e-12)
    path = tmp_path / "run.mat"
    scipy.io.savemat(path, {"Clock": t_up * 1e3, "EngSpd_up": n_up,
                            "units": {"EngSpd_up": "rpm"}})
    acq = read_acquisition(path, {**speed,
                                  "time": ChannelSpec("Clock", "ms")})
    assert_allclose(acq.channels["upstream_speed"].time, t_up, rtol=1e-12)


def test_a_pressure_recorded_in_ma_is_read_through_its_scale(tmp_path,
                                                             bench):
    t_up, n_up = bench["EngSpd_up"]
    current = np.linspace(4.0, 20.0, len(t_up))
    path = tmp_path / "ma.csv"
    path.write_text("time [s],EngSpd_up [rpm],Ch3 [mA]\n" + "".join(
        f"{t:.17g},{n:.17g},{c:.17g}\n"
        for t, n, c in zip(t_up, n_up, current)))
    role, spec = parse_channel_option("pressure=Ch3:4..20mA=0..25bar")
    acq = read_acquisition(path, {"upstream_speed": "EngSpd_up",
                                  role: spec})
    pressure = acq.channels["pressure"]
    # closed form: 4 mA is 0 bar, 20 mA 25 bar, linear between
    assert_allclose(pressure.values, (current - 4) / 16 * 25 * TO_SI["bar"],
                    rtol=1e-12, atol=1e-6)
    assert pressure.unit_in_file == "mA"
    # a scale from another unit than the file's is refused
    message = _message(path, {"upstream_speed": "EngSpd_up",
                              "pressure": ChannelSpec("Ch3",
                                                      "0..10V=0..25bar")})
    assert "'mA'" in message and "'V'" in message
    with pytest.raises(JudderError, match="LOW..HIGH UNIT=LOW..HIGH UNIT"):
        parse_channel_option("pressure=Ch3:4-20mA=0-25bar")
    with pytest.raises(JudderError, match="pressure unit"):
        parse_channel_option("pressure=Ch3:4..20mA=0..3000rpm")


def test_mdf_refuses_a_time_role(mf4):
    message = _message(mf4, {"upstream_speed": "EngSpd_up",
                             "time": ChannelSpec("t")})
    assert "master channel" in message


def test_dspace_struct_arrays(tmp_path, bench):
    """dSPACE ControlDesk's MAT export: judder_run.X (time bases) and
    judder_run.Y (a struct array of signals), written with savemat."""
    (t_up, n_up), (t_p, p) = bench["EngSpd_up"], bench["PressEVEN"]
    bases = np.zeros((1, 2), dtype=[("Name", "O"), ("Data", "O")])
    bases[0, 0] = ("Time", t_up)
    bases[0, 1] = ("Time", t_p)
    signals = np.zeros((1, 2), dtype=[("Name", "O"), ("Data", "O"),
                                      ("Unit", "O"), ("XIndex", "O")])
    signals[0, 0] = ("EngSpd_up", n_up, "rpm", 1)
    signals[0, 1] = ("PressEVEN", p, "bar", 2)
    path = tmp_path / "dspace.mat"
    scipy.io.savemat(path, {"judder_run": {"X": bases, "Y": signals}})
    acq = read_acquisition(path, {"upstream_speed": "judder_run.EngSpd_up",
                                  "pressure": "PressEVEN"})
    assert_allclose(acq.channels["upstream_speed"].time, t_up, rtol=1e-12)
    assert_allclose(acq.channels["upstream_speed"].values,
                    n_up * TO_SI["rpm"], rtol=1e-12)
    assert_allclose(acq.channels["pressure"].time, t_p, rtol=1e-12)
    assert_allclose(acq.channels["pressure"].values, p * TO_SI["bar"],
                    rtol=1e-12)


# --- the decimal separator given (issue 31: --decimal) ---------------------

US_INTEGERS = ("time [ms]\tEngSpd_up [rpm]\tPressEVEN [mbar]\n"
               "0\t998\t3,050\n1\t\"1,000\"\t3,100\n2\t1,002\t3,150\n")
GERMAN_INTEGERS = ("time [ms];EngSpd_up [rpm];PressEVEN [mbar]\n"
                   "0;998;3.050\n1;1.000;3.100\n2;1 002;3.150\n")


@pytest.mark.parametrize("text, decimal", [(US_INTEGERS, "."),
                                           (GERMAN_INTEGERS, ",")])
def test_a_given_decimal_separator_reads_what_the_cells_cannot_decide(
        tmp_path, text, decimal):
    # every separated cell is an integer with a thousands separator:
    # 1000 or 1.0 alike, so the cells alone are refused ...
    path, roles = _csv_read(tmp_path, text)
    message = _message(path, roles)
    assert "no cell of the file tells which" in message
    assert "`decimal`" in message
    # ... and read as written once the decimal separator is given
    acq = read_acquisition(path, roles, decimal=decimal)
    assert_allclose(acq.channels["upstream_speed"].values,
                    np.array([998, 1000, 1002]) * TO_SI["rpm"], rtol=1e-12)
    assert_allclose(acq.channels["pressure"].values,
                    np.array([3.05, 3.1, 3.15]) * TO_SI["bar"], rtol=1e-12)
    assert_allclose(acq.channels["upstream_speed"].time, [0, 1e-3, 2e-3])


@pytest.mark.parametrize("text, decimal, line, column, cell", [
    # a decimal point where a decimal comma was given
    ("time [s];EngSpd_up [rpm];PressEVEN [bar]\n0;1000;3,5\n0,001;1000;0.5\n",
     ",", 3, "PressEVEN", "'0.5'"),
    # a decimal comma where a decimal point was given
    ("time [s]\tEngSpd_up [rpm]\tPressEVEN [bar]\n0\t1000.5\t3\n"
     "0.001\t1000,25\t3\n", ".", 3, "EngSpd_up", "'1000,25'"),
    # a German thousands point in a file of decimal points
    ("time [s]\tEngSpd_up [rpm]\tPressEVEN [bar]\n0.001\t1.000,5\t3\n",
     ".", 2, "EngSpd_up", "'1.000,5'"),
])
def test_a_cell_contradicting_the_given_decimal_separator_is_refused(
        tmp_path, text, decimal, line, column, cell):
    path, roles = _csv_read(tmp_path, text)
    with pytest.raises(JudderError) as info:
        read_acquisition(path, roles, decimal=decimal)
    message = str(info.value)
    for word in (str(path), f"line {line}", f"column {column!r}", cell,
                 f"`decimal` {decimal!r}"):
        assert word in message


def test_an_unknown_decimal_separator_is_refused(tmp_path):
    path, roles = _csv_read(tmp_path, US_INTEGERS)
    with pytest.raises(JudderError, match="`decimal` ';': allowed"):
        read_acquisition(path, roles, decimal=";")


def test_excel_separator_line_declares_the_separator(tmp_path):
    """Excel writes ``sep=;`` first in a CSV export: the separator read,
    not a row of metadata; one the tool does not read is refused naming
    the file and the line."""
    path, roles = _csv_read(
        tmp_path, "sep=;\ntime [s];EngSpd_up [rpm];PressEVEN [bar]\n"
        "0;1.000,5;3\n0,001;1.001,5;3,1\n")
    acq = read_acquisition(path, roles)
    assert_allclose(acq.channels["upstream_speed"].values,
                    np.array([1000.5, 1001.5]) * TO_SI["rpm"], rtol=1e-12)
    assert_allclose(acq.channels["pressure"].values,
                    np.array([3.0, 3.1]) * TO_SI["bar"], rtol=1e-12)
    assert acq.metadata == {}
    path, roles = _csv_read(tmp_path, "sep=|\ntime [s]|EngSpd_up [rpm]\n"
                            "0|1000\n")
    assert _message(path, roles) == (
        f"{path}, line 1: 'sep=|' declares the field separator '|'; "
        "allowed: ',', ';' or tab")


# --- held-out exports (issue 44, item 4) ------------------------------------

_EXAMPLES = Path(__file__).parents[1] / "examples" / "bench"
_EXAMPLE_ROLES = {"upstream_speed": ChannelSpec("EngSpd_up"),
                  "pressure": ChannelSpec("PressEVEN", "bar"),
                  "downstream_speed": ChannelSpec("OutSpd")}


@pytest.mark.parametrize("encoding", ["utf-16", "utf-16-le", "utf-16-be"])
def test_a_utf16_export_with_its_bom_reads_as_the_utf8_one(tmp_path,
                                                           encoding):
    """Excel's "Unicode text" is UTF-16 with a byte-order mark (every
    other byte of its ASCII NUL): it was refused as "not a text file";
    it now reads as the same file in UTF-8, lines ending in CR LF."""
    import codecs
    text = (_EXAMPLES / "run03.csv").read_text()
    bom = {"utf-16": b"", "utf-16-le": codecs.BOM_UTF16_LE,
           "utf-16-be": codecs.BOM_UTF16_BE}[encoding]
    path = tmp_path / "run03.csv"
    path.write_bytes(bom + text.replace("\n", "\r\n").encode(encoding))
    read = read_acquisition(path, _EXAMPLE_ROLES)
    clean = read_acquisition(_EXAMPLES / "run03.csv", _EXAMPLE_ROLES)
    for role in _EXAMPLE_ROLES:
        assert_allclose(read.channels[role].values,
                        clean.channels[role].values, rtol=0, atol=0)


def test_a_milliampere_channel_without_its_scale_names_the_scale(tmp_path):
    """A pressure recorded in mA (a 4-20 mA transmitter) with no scale was
    refused as an unknown unit, with the pressure units only: the
    refusal now names the scale's syntax and an example of it."""
    header, *lines = (_EXAMPLES / "run03.csv").read_text().splitlines()
    path = tmp_path / "run03.csv"
    rows = [line.split(",") for line in lines]
    for cells in rows:     # 4-20 mA for 0-25 bar
        cells[3] = repr(4 + 16 * float(cells[3]) / 25)
    path.write_text("\n".join([header.replace("PressEVEN", "PressEVEN [mA]")]
                              + [",".join(cells) for cells in rows]))
    message = _message(path, {**_EXAMPLE_ROLES,
                              "pressure": ChannelSpec("PressEVEN")})
    names(message, str(path), "'PressEVEN'", "'mA'",
          "LOW..HIGH UNIT=LOW..HIGH UNIT", "`channels`", "4..20mA=0..25bar",
          "bar")
    # the scale it names reads the file
    role, spec = parse_channel_option("pressure=PressEVEN:4..20mA=0..25bar")
    scaled = read_acquisition(path, {**_EXAMPLE_ROLES, role: spec})
    clean = read_acquisition(_EXAMPLES / "run03.csv", _EXAMPLE_ROLES)
    assert_allclose(scaled.channels["pressure"].values,
                    clean.channels["pressure"].values, rtol=1e-9,
                    atol=1e-6)


def test_a_catman_refusal_quotes_the_line_naming_the_columns(tmp_path):
    """A catman export (a header block of key;value lines, then the names
    line) with no time column the tool knows: the refusal quoted line 1
    (``'catman Export', 'V5.0'``) as "the columns"; it now quotes the
    names line, line 4."""
    path = tmp_path / "catman.csv"
    path.write_text("catman Export;V5.0\nKommentar;Pruefstand 3\n\n"
                    "Zeit  1 - Standardmessrate [s];EngSpd_up [rpm];"
                    "PressEVEN [bar]\n0,000;1000,0;1,0\n0,001;1001,0;1,1\n"
                    "0,002;1002,0;1,2\n")
    message = _message(path, {"upstream_speed": ChannelSpec("EngSpd_up")})
    names(message, "line 4", "'Zeit  1 - Standardmessrate'", "'EngSpd_up'",
          "`channels` time=NAME")
    assert "catman Export" not in message


@pytest.mark.parametrize("encoding", ["utf-16-le", "utf-16-be"])
def test_utf16_without_its_bom_is_refused_naming_it(tmp_path, encoding):
    """UTF-16 without a byte-order mark cannot be told from a binary file
    for certain: it was refused as "not a text file (NUL bytes)"; the
    refusal now says what it is and what to save it as."""
    path = tmp_path / "run03.csv"
    path.write_bytes((_EXAMPLES / "run03.csv").read_text().encode(encoding))
    names(_message(path, _EXAMPLE_ROLES), str(path), "UTF-16",
          "byte-order mark", "UTF-8")
