"""Every analysis command on a driveline of your own (--modelica CLASS,
--fmu FILE.fmu): the Modelica 4-DOF class reproduces the paper's Eq. (6)
to round-off, so each command must give the preset's numbers for it; the
geared 5-DOF class is checked against independent computations (Floquet
growth rates at the reported points, its steady slip); and what cannot
be done is refused in one line, from the command line and from Python.
"""

import json
from pathlib import Path

import numpy as np
import pytest
from numpy.testing import assert_allclose

from sources import get_preset
from sources.fmus import FmuParameters
from sources.modelica import ModelicaParameters
from infra.errors import JudderError
from judder import api
from judder.cli import main
from fmu.store import ensure_fmu
from stability import build_driveline, floquet

BAR = 1e5
FOUR = "Judder.Examples.Driveline4DOF"
GEARED = "Judder.Examples.Driveline5DOFGeared"


@pytest.fixture(scope="module")
def four_fmu():
    return str(ensure_fmu(FOUR))


def _json(capsys, *args):
    """``judder ARGS --json`` in this process: its JSON."""
    status = main([*args, "--json"])
    out, err = capsys.readouterr()
    assert status == 0, err
    return json.loads(out)


def _refused(capsys, *args):
    """``judder ARGS``: exit 2 and its one-line message."""
    status = main(list(args))
    err = capsys.readouterr().err
    assert status == 2 and err.startswith("judder: error:"), err
    assert len(err.splitlines()) == 1 and "Traceback" not in err
    return err


def _same_numbers(ours, theirs, rtol, path="",
                  skip=("model", "seconds", "provenance")):
    """Two JSON trees with the same keys and numbers within ``rtol``."""
    if isinstance(theirs, dict):
        assert set(ours) == set(theirs), path
        for key in theirs:
            if key not in skip:
                _same_numbers(ours[key], theirs[key], rtol, f"{path}.{key}",
                              skip)
    elif isinstance(theirs, list):
        assert len(ours) == len(theirs), path
        for i, (a, b) in enumerate(zip(ours, theirs)):
            _same_numbers(a, b, rtol, f"{path}[{i}]", skip)
    elif isinstance(theirs, float):
        assert ours == pytest.approx(theirs, rel=rtol, abs=1e-12), path
    else:
        assert ours == theirs, path


def test_eig_of_a_class_and_of_its_fmu_is_the_presets(capsys, four_fmu):
    preset = _json(capsys, "eig", "--preset", "paper-4dof", "--driveline",
                   "chain")
    for source in (["--modelica", FOUR], ["--fmu", four_fmu]):
        ours = _json(capsys, "eig", *source)
        assert set(ours) == set(preset) and ours["model"] == FOUR
        assert ours["driveline"] == preset["driveline"] == "chain"
        # Eq. (14) of the class's Jacobian against the closed form Eq. (15)
        assert_allclose(ours["natural_frequencies_hz"],
                        preset["closed_form_frequencies_hz"], rtol=1e-12)
        _same_numbers(ours["damped_modes"], preset["damped_modes"], 1e-10)
        # the paper's formulas are not the class's
        assert ours["closed_form_frequencies_hz"] is None
        assert ours["damping_factor_12"] is None
    geared = api.eig(ModelicaParameters(GEARED))
    # docs/onemodel.md: f1 = 7.24, f2 = 18.94, f3 = 102.88 Hz
    assert_allclose(geared.natural_frequencies_hz, [7.237, 18.939, 102.884],
                    atol=1e-3)
    assert len(geared.damped_frequencies_hz) == 3   # two rigid angles gone


def test_check_of_a_class_and_of_its_fmu_is_the_presets(capsys, four_fmu):
    setting = ("--freq", "102.9,60", "--pf", "0.3", "--params", "k24,J4")
    preset = _json(capsys, "check", "--preset", "paper-4dof", "--driveline",
                   "chain", *setting)
    assert [s["verdict"] for s in preset["settings"]] == ["JUDDER", "STABLE"]
    # the preset's chain also weighs its linear forced response (a class
    # is judged by its growth: its clutch's forcing is not extracted)
    response = set(preset["settings"][0]) - set(
        _json(capsys, "check", "--modelica", FOUR, *setting)["settings"][0])
    assert response == {"forced_amplitude_rpm", "settled_amplitude_rpm",
                        "amplitude_from", "response_growth_per_s",
                        "quasi_periodic", "converged", "integrated_s",
                        "judder", "mechanism", "judder_limit_rpm",
                        "forced_limit_p_f_bar", "forced_limit_found"}
    for setting_record in preset["settings"]:
        for key in response:
            del setting_record[key]
    for source in (["--modelica", FOUR], ["--fmu", four_fmu]):
        ours = _json(capsys, "check", *source, *setting)
        # margins are roots of the boundary: round-off of Eq. (6) plus the
        # finite differences of the sensitivities
        # the highest safe amplitude and the safe band weigh the preset's
        # forced response: the class's band is the parametric one, and
        # the preset's lies within it (the forced response only narrows)
        skip = ("highest_safe_p_f_bar", "highest_safe_limited_by",
                "safe_band_hz", "safe_band_low_limited_by",
                "safe_band_high_limited_by", "safe_band_low_tongue",
                "safe_band_high_tongue")
        _same_numbers(ours, preset, 1e-8, skip=(
            "model", "seconds", "provenance", "driveline_description",
            *skip))
        stable_ours, stable_preset = ours["settings"][1], preset["settings"][1]
        assert {stable_ours["safe_band_low_limited_by"],
                stable_ours["safe_band_high_limited_by"]} <= {"parametric",
                                                               None}
        low, high = stable_ours["safe_band_hz"]
        narrower = stable_preset["safe_band_hz"]
        # (a parametric edge of both is the same root to round-off)
        assert low * (1 - 1e-8) <= narrower[0] < 60.0 < narrower[1] \
            <= high * (1 + 1e-8)


def test_check_of_the_geared_class_puts_its_margin_on_the_growth_boundary():
    params = ModelicaParameters(GEARED)
    result = api.check([102.9], [0.3], params)
    record = result.records()[0]
    # the default parameters are those of the 4-DOF names it has (no mu_g)
    assert {r["parameter"] for r in record["sensitivity"]} == {
        "J2", "J4", "k12", "k24", "c12"}
    assert record["verdict"] == "JUDDER"
    assert record["margin_bar_tongue"]["resonance"] == "f3"
    # at the boundary amplitude the class's Floquet growth is min_growth
    driveline = build_driveline(params)
    rate = floquet(driveline, 102.9,
                   record["boundary_p_f_bar"] * BAR).growth_rate
    assert rate == pytest.approx(result.min_growth, rel=1e-6)
    # and at the crossing frequency, at the setting's amplitude
    rate = floquet(driveline, record["crossing_hz"], 0.3 * BAR).growth_rate
    assert rate == pytest.approx(result.min_growth, rel=1e-6)


def test_advise_on_a_class_gives_the_presets_ranking():
    preset = api.advise(design=False, driveline="chain")
    ours = api.advise(ModelicaParameters(FOUR), design=False)
    assert [r[0] for r in ours.ranking] == [r[0] for r in preset.ranking]
    assert_allclose([r[1] for r in ours.ranking],
                    [r[1] for r in preset.ranking], rtol=1e-6)
    assert_allclose(ours.safe_p_f, preset.safe_p_f, rtol=1e-9, atol=1e-6)
    # section 4.3: J2, J4 and k24 move the tongues most
    assert {r[0] for r in ours.ranking[:3]} == {"J2", "J4", "k24"}


def test_advise_on_the_geared_class_is_plausible():
    params = ModelicaParameters(GEARED)
    result = api.advise(params, names=("k24", "J4", "k35"), design=False,
                        freq_range=(80.0, 130.0))
    ranking = {name: share for name, share, _ in result.ranking}
    # tongue 3 grows from f3, which k24 and J4 set; the output shaft k35
    # sets f1 (7.24 Hz) and moves only the combination tongues f3 -+ f1
    assert ranking["k24"] > ranking["J4"] > 10 * abs(ranking["k35"])
    full = [w for w in result.windows if w.full_range]
    assert full and not any(w.freq_hz[0] <= 102.88 <= w.freq_hz[1]
                            for w in full)
    # a window keeps its margins: 5 Hz either side grows slower than 1/s
    # at the highest operating amplitude plus the amplitude margin
    driveline = build_driveline(params)
    for window in full:
        for f in window.freq_hz:
            for df in (-5.0, 0.0, 5.0):
                assert floquet(driveline, f + df, 0.8 * BAR).growth_rate \
                    < result.min_growth


def test_advise_names_and_the_class_without_default_names(
        capsys, oscillator_library):
    err = _refused(capsys, "advise", "--modelica", GEARED, "--params",
                   "k24,k99", "--no-design")
    assert "'k99'" in err and "k35" in err and "w_slip" in err
    for command in ("advise", "check"):
        extra = ["--freq", "10", "--pf", "0.1"] if command == "check" else []
        err = _refused(capsys, command, "--modelica", "MyLib.Oscillator",
                       "--library", str(oscillator_library), *extra)
        assert "--params is required" in err and "p_f, f_dither, s, q" in err
    with pytest.raises(JudderError, match="`names` is required"):
        api.advise(ModelicaParameters("MyLib.Oscillator",
                                      str(oscillator_library)))


def test_envelope_of_a_class_by_its_modelica_names(capsys, tmp_path):
    ranges = tmp_path / "ranges.toml"
    ranges.write_text("[parameters]\nw_slip = [1.5, 2.5]\n"
                      "k24 = { relative = [0.98, 1.02] }\n")
    freqs = np.linspace(96.0, 110.0, 8)
    params = ModelicaParameters(GEARED)
    result = api.envelope(ranges, freqs, 0.6, samples=2, refine=0,
                          parameters=params, workers=1)
    e = result.envelope
    assert e.names == ("w_slip", "k24") and e.ok.all()
    # the nominal boundary is that of `tongues` at the same growth rate
    nominal = api.tongues(freqs, 0.6, params, min_growth=e.min_growth)
    assert_allclose(e.nominal, nominal.boundaries.amplitude, rtol=1e-9)
    # and the broadest region holds it
    def lowest(amplitude):
        return np.where(np.isnan(amplitude), np.inf, amplitude)
    assert np.all(lowest(e.broadest)
                  <= lowest(e.nominal).min(axis=1) * (1 + 1e-12))
    # somewhere a slip speed or stiffness of the ranges judders lower
    assert np.any(lowest(e.broadest) < 0.9 * lowest(e.nominal).min(axis=1))
    ranges.write_text("[parameters]\nmu_g = [0.01, 0.02]\n")
    err = _refused(capsys, "envelope", "--modelica", GEARED, "--ranges",
                   str(ranges), "--freq", "96:110:8", "--samples", "2")
    assert "'mu_g'" in err and "w_slip" in err


def test_report_of_a_class_is_the_presets(tmp_path, capsys):
    # c12: the sensitivity figure labels Eq. (16) for the preset only
    grids = ("--freq", "105", "--pf", "0.2", "--sensitivity", "k24,c12",
             "--grid=90:120:30", "--map-freq=90:120:8", "--map-pf=0:0.6:4",
             "--workers=1")
    import sys
    sys.path.insert(0, str(Path(__file__).parent))
    from test_report import (_assert_printed_text_readable,
                             _recording_figures)
    drawn, clashes = [], []
    with pytest.MonkeyPatch.context() as patch:
        _recording_figures(patch, drawn, clashes)
        ours = _json(capsys, "report", "--modelica", FOUR, *grids,
                     "--engagement", "--out", str(tmp_path / "class.html"))
    # the engagement figures too print their text at 7 pt or more, with
    # none clipped or colliding (issue 33: 13 in wide, printed at half)
    _assert_printed_text_readable((tmp_path / "class.html").read_text(),
                                  drawn)
    assert clashes == [], "\n".join(clashes)
    preset = _json(capsys, "report", "--preset", "paper-4dof", "--driveline",
                   "chain", *grids, "--out", str(tmp_path / "preset.html"))
    assert ours["driveline"] == preset["driveline"] == "chain"
    _same_numbers(ours["tongues"], preset["tongues"], 1e-8)
    # the preset's verdict also weighs the chain's forced response (and
    # its highest safe amplitude with it)
    verdict = {key: value for key, value in preset["verdict"].items()
               if key in ours["verdict"]}
    _same_numbers(ours["verdict"], verdict, 1e-8, skip=(
        "model", "seconds", "provenance", "highest_safe_p_f_bar",
        "highest_safe_limited_by", "safe_band_hz",
        "safe_band_low_limited_by", "safe_band_high_limited_by",
        "safe_band_low_tongue", "safe_band_high_tongue"))
    # Fig. 19 is a study of the paper's chains; the class's run is its FMU
    assert "mu_g_threshold" in preset and "mu_g_threshold" not in ours
    assert ours["engagement"]["floquet_kind"] == ours["verdict"]["kind"]
    html = (tmp_path / "class.html").read_text()
    assert "engagement of the class's FMU" in html and "Without dither" not in html


def test_simulate_runs_the_class_fmu_crosscheck_runs():
    steady = api.simulate(100.0, 0.0, parameters=ModelicaParameters(GEARED))
    assert steady.fmu == ensure_fmu(GEARED)
    # without dither the class stays at its steady slip, w_slip = 2 rad/s
    assert steady.summaries[0]["final_slip_rad_s"] == pytest.approx(
        2.0, abs=1e-6)
    # and a run at --pf 0 is called what it is (it was "with dither")
    assert steady.summaries[0]["label"] == "without dither"
    run = api.simulate(102.9, 0.3, parameters=ModelicaParameters(FOUR))
    first = run.summaries[0]
    # the Floquet verdict is Eq. (6) of the paper (the preset's)
    paper = floquet(build_driveline(get_preset("paper-4dof")), 102.9,
                    0.3 * BAR)
    assert first["floquet_exponent_per_s"] == pytest.approx(
        paper.growth_rate, rel=1e-9)
    # the judder the run shows grows at that rate (fitted to 2 s of the
    # time histories, which the forced resonance also fills)
    assert first["judder"] and first["judder_kind"] == "single-period"
    assert first["judder_growth_per_s"] == pytest.approx(
        paper.growth_rate, rel=0.1)


def test_fit_through_the_fmu_recovers_the_friction_gradient(four_fmu):
    freqs = np.linspace(95.0, 112.0, 8)
    truth = ModelicaParameters(FOUR, values={"mu_g": 0.022})
    measured = api.tongues(freqs, 1.0, truth).boundaries.amplitude
    lowest = np.nanmin(measured, axis=1) / BAR
    report = api.fit(freqs, lowest, 1.0, names=["mu_g"],
                     parameters=FmuParameters(four_fmu), starts=1,
                     workers=1, min_growth=0.0)
    assert report.fit.values[0] == pytest.approx(0.022, rel=1e-6)
    assert report.as_dict()["model"] == FOUR


def test_params_of_an_fmu_round_trip(capsys, tmp_path, four_fmu):
    saved = tmp_path / "fmu.toml"
    assert main(["params", "--fmu", four_fmu, "--set", "c12=2", "--save",
                 str(saved)]) == 0
    capsys.readouterr()
    point = ("floquet", "--freq", "102.9", "--pf", "0.3")
    from_file = _json(capsys, *point, "--fmu", four_fmu, "--param-file",
                      str(saved))
    given = _json(capsys, *point, "--modelica", FOUR, "--set", "c12=2")
    assert from_file["leading_abs"] == pytest.approx(given["leading_abs"],
                                                     rel=1e-12)
    err = _refused(capsys, *point, "--modelica", GEARED, "--param-file",
                   str(saved))
    assert FOUR in err and GEARED in err


@pytest.mark.parametrize("args, words", [
    (["crosscheck", "--fmu", "FMU", "--freq", "100:105:2", "--pf",
      "0.1:0.2:2"], ["crosscheck", "--fmu", "time domain",
                     "--modelica CLASS"]),
    (["simulate", "--fmu", "FMU", "--freq", "100", "--pf", "0.1"],
     ["simulate", "--fmu", "time domain"]),
    (["report", "--fmu", "FMU", "--freq", "100", "--pf", "0.1",
      "--engagement", "--out", "OUT"], ["engagement", "--fmu"]),
    (["fit", "--modelica", FOUR, "--boundary", "BOUNDARY", "--fit", "mu_g",
      "--driveline", "bench"], [FOUR, "no bench engagement model"]),
    (["simulate", "--modelica", FOUR, "--freq", "100", "--pf", "0.1",
      "--bench", "w_motor=100"], ["--bench w_motor", "--set"]),
    (["check", "--modelica", FOUR, "--freq", "100", "--pf", "0.1",
      "--params", "J9"], ["'J9'", "k24, c12"]),
])
def test_what_cannot_be_done_is_refused_in_one_line(capsys, tmp_path,
                                                    four_fmu, args, words):
    boundary = tmp_path / "b.csv"
    boundary.write_text("freq_hz,p_f_bar\n100,0.2\n")
    given = [{"FMU": four_fmu, "OUT": str(tmp_path / "r.html"),
              "BOUNDARY": str(boundary)}.get(a, a) for a in args]
    err = _refused(capsys, *given)
    for word in words:
        assert word in err
    assert not (tmp_path / "r.html").exists()


def test_the_python_api_refuses_alike(four_fmu, tmp_path):
    fmu = FmuParameters(four_fmu)
    # the studies name their own arguments (`path`: the FMU)
    with pytest.raises(JudderError, match="crosscheck of `path` .* time domain"):
        api.crosscheck([100.0], [0.1], parameters=fmu)
    with pytest.raises(JudderError, match="simulate of `path` .* time domain"):
        api.simulate(100.0, 0.1, parameters=fmu)
    with pytest.raises(JudderError, match="no bench engagement model"):
        api.fit([100.0], [0.2], names=["mu_g"], parameters=fmu, bench={})
    with pytest.raises(JudderError, match="Fig. 19"):
        api.threshold([0.0], [0.1], parameters=ModelicaParameters(FOUR))
    # the campaign emulates the registry's bench (it ended in an
    # AttributeError, 'driveline', from inside the runs)
    with pytest.raises(JudderError, match=f"{FOUR} .* no bench engagement "
                       "model"):
        api.campaign(tmp_path / "campaign", [100.0], [0.1],
                     parameters=ModelicaParameters(FOUR))
    assert not (tmp_path / "campaign").exists()


def test_a_library_file_that_is_not_utf8_is_named(tmp_path, capsys):
    package = tmp_path / "Usr"
    package.mkdir()
    (package / "package.mo").write_text("package Usr\nend Usr;\n")
    (package / "Ok.mo").write_text(
        "within Usr;\nmodel Ok\n  Real x(start=1, fixed=true);\n"
        "  parameter Real k = 1;\nequation\n  der(x) = -k*x;\nend Ok;\n")
    (package / "Bin.mo").write_bytes(b"within Usr;\nmodel Bin \xff end Bin;\n")
    assert main(["params", "--modelica", "Usr.Ok", "--library",
                 str(tmp_path)]) == 2
    err = capsys.readouterr().err
    assert "Bin.mo: not UTF-8 text (byte 0xff at offset 22)" in err
    assert "Traceback" not in err and "internal error" not in err


@pytest.mark.parametrize("command", ["simulate", "crosscheck"])
def test_a_time_domain_command_refuses_fmu_before_reading_it(
        capsys, tmp_path, command):
    # the reason, not "no such file" of a file it would never read; and
    # its --help offers no FMU (issue 33: it listed --fmu, then refused it)
    err = _refused(capsys, command, "--fmu", str(tmp_path / "none.fmu"),
                   "--freq", "100", "--pf", "0.1")
    assert command in err and "--fmu" in err and "time domain" in err
    assert "no such file" not in err
    with pytest.raises(SystemExit):
        main([command, "--help"])
    help_text = capsys.readouterr().out
    assert "--fmu FILE.fmu" not in help_text and "FMU instead" not in help_text
    assert "parameter of the class that is" in " ".join(help_text.split())
