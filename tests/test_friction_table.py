"""The clutch's friction characteristic as data (``--friction``): one
table read by the linearisation (``check``), the periodic orbit and the
bench FMU (``simulate``) alike.

References: the straight line of Eq. 5 (a table of slope mu_g gives the
Floquet multipliers of the preset with that mu_g: the homogeneous Eq. 6
holds mu_g alone); a flat characteristic (mu_g = 0 at every slip: no
slip damping, no parametric term, so no tongue and no parametric
judder, Eq. 6-9); NumPy's linear interpolation for the table itself.
"""

import numpy as np
import pytest

from drivelines.friction import FMU_ROWS, FrictionTable, straight_line
from infra.errors import JudderError
from sources import get_preset
from stability.bench import operating_slip
from studies.inputs import friction_of, read_friction_table
from tests.facts import names

PAPER = get_preset("paper-4dof")
SLIP = operating_slip(PAPER)
#: Settings in tongues 4 (double-period), 5 (combination) and 2's
#: neighbourhood on the paper's bench (all JUDDER, parametric, there).
PARAMETRIC = [(205.0, 0.4), (86.5, 0.5), (119.5, 0.6)]


def _write(folder, name, text):
    path = folder / name
    path.write_text(text)
    return str(path)


def test_the_table_is_interpolated_as_the_fmu_reads_it():
    table = FrictionTable((0.0, 40.0, 100.0, 200.0), (0.12, 0.1, 0.13, 0.11),
                          "rig")
    slips = np.linspace(-250.0, 250.0, 1001)
    mu, slope = table.curve(slips)
    assert mu == pytest.approx(np.interp(np.abs(slips), table.slip,
                                         table.mu), abs=1e-15)
    # the slope is the segment's: a central difference inside each
    step = 1e-6
    inside = [w for w in np.abs(slips) if min(abs(w - k) for k in
                                                table.slip) > 1e-3]
    numeric = (table.curve(np.add(inside, step))[0]
               - table.curve(np.subtract(inside, step))[0]) / (2 * step)
    assert table.curve(inside)[1] == pytest.approx(numeric, abs=1e-9)
    assert table.at(250.0) == (0.11, 0.0)            # held past the end
    assert table.linear_range(70.0) == pytest.approx(30.0)
    # the bench FMU's 64 rows: continued flat, the same interpolation
    padded = table.padded()
    assert padded.shape == (FMU_ROWS, 2)
    assert np.interp(np.abs(slips), padded[:, 0], padded[:, 1]) == \
        pytest.approx(mu, abs=1e-15)


def test_a_straight_table_gives_the_multipliers_of_the_presets_mu_g():
    from judder import api
    for mu_g in (0.017, 0.03):
        # a straight line of slope mu_g with another value at the slip
        table = FrictionTable((SLIP - 2.0, SLIP + 2.0),
                              (0.11 - 2 * mu_g, 0.11 + 2 * mu_g), "line")
        with_table = PAPER.replace(mu_g=mu_g).with_friction(table, SLIP)
        assert with_table["mu_g"] == pytest.approx(mu_g, rel=1e-12)
        for driveline in ("bench", "chain"):
            for freq, p_f in PARAMETRIC:
                expected = api.floquet(freq, p_f, driveline=driveline,
                                       parameters=PAPER.replace(mu_g=mu_g))
                got = api.floquet(freq, p_f, driveline=driveline,
                                  parameters=with_table)
                assert np.sort_complex(got.result.multipliers) == \
                    pytest.approx(np.sort_complex(
                        expected.result.multipliers), abs=1e-8)


def test_the_straight_built_in_is_eq_5_at_the_operating_slip():
    line = straight_line(0.09, 0.017, SLIP)
    assert line.at(SLIP) == pytest.approx((0.09, 0.017), rel=1e-12)
    # it ends where mu would leave mu0/2 .. 3 mu0/2
    assert line.curve(list(line.slip))[0] == pytest.approx([0.045, 0.135])
    assert friction_of(PAPER, "straight").friction == line


def test_a_flat_characteristic_gives_no_parametric_judder_in_check():
    from judder import api
    flat = PAPER.with_friction(FrictionTable((0.0, 300.0), (0.09, 0.09),
                                             "flat"), SLIP)
    freqs, amps = zip(*PARAMETRIC)
    records = api.check(list(freqs), list(amps), parameters=flat).records()
    # with the bounded curve every one of them is parametric judder
    curve = api.check(list(freqs), list(amps), parameters=PAPER).records()
    assert [r["mechanism"] for r in curve] == ["parametric"] * 3
    for record in records:
        assert record["kind"] == "stable"
        assert record["mechanism"] != "parametric"
        # only the structural damping is left: Eq. 6 with mu_g = 0
        assert record["growth_rate_per_s"] < 0


def test_orbit_and_simulate_read_the_same_table(tmp_path):
    """One table, three views: the orbit and the bench FMU run agree on
    the settled amplitude, check's linearisation on the growth; a flat
    table gives no parametric judder in the orbit or the run."""
    from judder import api
    line = _write(tmp_path, "line.csv",
                  "slip_rad_s,mu\n"
                  f"{SLIP - 5:.12g},{0.09 - 5 * 0.017:.12g}\n"
                  f"{SLIP + 5:.12g},{0.09 + 5 * 0.017:.12g}\n")
    flat = _write(tmp_path, "flat.csv", "slip_rpm;mu\n0;0,09\n3000;0,09\n")
    for path, parametric in ((line, True), (flat, False)):
        values = friction_of(PAPER, path)
        orbit = api.orbit([205.0], [0.4], parameters=values).rows()[0]
        run = api.simulate(205.0, 0.4, parameters=values)
        summary = run.summaries[0]
        assert (summary["mechanism"] == "parametric") is parametric
        assert (orbit["mechanism"] == "parametric") is parametric
        if parametric:
            assert orbit["settled_rpm"] == pytest.approx(
                summary["oscillation_rpm"], rel=0.05)
        assert "TestBenchTable" in str(run.fmu)
        assert path in run.friction_law


def test_a_rig_export_is_read_in_its_units_and_temperatures(tmp_path):
    path = _write(tmp_path, "rig.csv",
                  "sep=;\n# SAE No. 2, lining A\n"
                  "slip [rpm];mu at 40 C;mu at 80 C\n"
                  "0;0,14;0,12\n500;0,135;0,125\n1500;0,12;0,13\n")
    table = read_friction_table(path)
    assert table.slip == pytest.approx([0.0, 500 * np.pi / 30,
                                        1500 * np.pi / 30])
    assert [t for t, _ in table.family] == [40.0, 80.0]
    warm = table.at_oil_temperature(60.0)
    assert warm.mu == pytest.approx([0.13, 0.13, 0.125])
    assert warm.oil_temperature_c == 60.0
    # the command's default: the paper's 65-70 C
    assert friction_of(PAPER, path).friction.mu == pytest.approx(
        table.at_oil_temperature(67.5).mu)


@pytest.mark.parametrize("text, facts", [
    ("speed,mu\n0,0.1\n100,0.12\n", ["'speed'", "slip_rpm", "slip_rad_s",
                                      "mu_<T>C"]),
    ("slip_rpm,mu\n0,0.1\n100,-0.1\n", ["-0.1", "> 0"]),
    ("slip_rpm,mu\n100,0.1\n50,0.12\n", ["increasing"]),
    ("slip_rpm,mu\n0,0.1\n", ["1 rows", "at least 2"]),
    ("slip_rpm,mu_40C,mu\n0,0.1,0.1\n9,0.1,0.1\n", ["'mu'", "mu_<T>C"]),
    ("slip_rpm,mu\n" + "".join(f"{i},0.1\n" for i in range(70)),
     ["70 rows", "at most 64"]),
])
def test_a_bad_table_is_refused_naming_what_is_allowed(tmp_path, text,
                                                       facts):
    path = _write(tmp_path, "bad.csv", text)
    with pytest.raises(JudderError) as error:
        read_friction_table(path)
    names(str(error.value), path, *facts)


def test_the_command_line_refuses_what_the_table_decides(tmp_path, capsys):
    from judder.cli import main
    table = _write(tmp_path, "rig.csv",
                   "slip_rpm,mu_40C,mu_80C\n0,0.1,0.1\n2000,0.12,0.11\n")
    cases = [
        (["check", "--freq", "100", "--pf", "0.3", "--friction", table,
          "--set", "mu_g=0.02"], ["--set", "mu_g", "--friction"]),
        (["check", "--freq", "100", "--pf", "0.3", "--friction", table,
          "--oil-temp", "90"], ["--oil-temp", "90", "40", "80"]),
        (["check", "--freq", "100", "--pf", "0.3", "--oil-temp", "60"],
         ["--oil-temp", "--friction"]),
        (["check", "--freq", "100", "--pf", "0.3", "--friction",
          "curvy"], ["--friction", "curvy"]),
        (["simulate", "--freq", "100", "--pf", "0.3", "--friction", table,
          "--engagement", "full"], ["--engagement", "full", "steady"]),
    ]
    for argv, facts in cases:
        assert main(argv) != 0
        names(capsys.readouterr().err, *facts)


def test_a_campaign_runs_the_table_at_each_temperature_and_speed(tmp_path):
    """The campaign's bench reads the table at each run's oil
    temperature, with mu0 at its slip; its runs are told apart from the
    curve's by their digests."""
    from judder import api
    from pysim.simulation.campaigns import TEMPERATURES, at_temperature
    rig = _write(tmp_path, "rig.csv",
                 "slip_rad_s,mu_50C,mu_90C\n0,0.1,0.08\n84.72,0.09,0.09\n"
                 "160,0.12,0.095\n")
    values = friction_of(PAPER, rig)
    hot = at_temperature(values, "85-90", 1500.0)
    slip = 1500 * np.pi / 30 - 20.0
    table = values.friction.at_oil_temperature(TEMPERATURES["85-90"])
    assert hot.friction == table
    assert (hot["mu0"], hot["mu_g"]) == pytest.approx(table.at(slip))
    result = api.campaign(tmp_path / "camp", [100.0], [0.2],
                          engine_rpm=(1000.0, 1500.0),
                          temperatures=("55-60", "85-90"), duration=1.0,
                          formats=("csv",), parameters=values, workers=1)
    assert [row["status"] for row in result.rows] == ["ok"] * 4
    curve = api.campaign(tmp_path / "camp", [100.0], [0.2],
                         engine_rpm=(1000.0,), temperatures=("55-60",),
                         duration=1.0, formats=("csv",),
                         parameters=PAPER, workers=1)
    assert not curve.rows[0].get("reused")
    assert curve.rows[0]["run_id"] not in {r["run_id"] for r in result.rows}
