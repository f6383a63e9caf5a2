"""The README's commands, run as written.

Every line of a ```sh block of README.md that starts with ``judder``,
``make`` or ``python -m`` is a command (a trailing ``\\`` continues it,
``#`` starts a comment). Each is run in order in one scratch folder that
holds a copy of ``examples/``, so a later command reads what an earlier
one wrote (the recipe's ``chart.npz``, the catalogue's ``campaign/``).
``judder`` commands run in-process through :func:`judder.cli.main`; to
keep the suite fast, :data:`SMALLER` puts smaller grids and shorter runs
on the commands that take them (the same options a user would give;
nothing else changes). ``make run`` runs the ``judder`` line of the
Makefile's ``run`` recipe. The ```python block runs last.

Each command runs once: the same run is checked for its text, the files
it writes and its key numbers (what its ``--json`` holds, compared with
tests/golden/readme_key_numbers.json within stated tolerances).
"""

import json
import math
import os
import re
import shlex
import shutil
from pathlib import Path

import pytest
from threadpoolctl import threadpool_limits

from fmu.cache import cache_folder
from fmu.store import BUILT
from judder.cli import main
from judder.cli import build_parser

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"

#: Lines not run here, with the reason.
NOT_RUN = {
    "make setup": "the suite runs in what it made",
    "make test": "it is this test suite",
    "make fmu": "it builds build/fmu/*.fmu, which the simulate commands "
                "here build into the user's cache when build/fmu has none "
                "of the sources as they stand (the same ensure_fmu) and "
                "run, and tests/test_fmu.py builds and validates",
}

#: Options put on each command to keep the suite fast: smaller grids,
#: shorter runs, fewer starts. They replace the README's value where it
#: gives one.
SMALLER = {
    "map": {"--freq": "5:250:40", "--pf": "0:1.5:16"},
    "tongues": {"--freq": "10:220:60"},
    "compare": {"--grid": "10:220:60"},
    "sensitivity": {"--freq": "10:220:24", "--workers": "1"},
    "threshold": {"--mu-g": "-0.001:0.001:9", "--c-ext": "0:2:5"},
    "fit": {"--starts": "1", "--workers": "1"},
    "simulate": {"--duration": "2.5"},
    "crosscheck": {"--freq": "100:106:2", "--pf": "0.3", "--duration": "0.6",
                   "--workers": "1"},
    "campaign": {"--freq": "204:208:2", "--pf": "0.3", "--duration": "2",
                 "--workers": "1"},
    "chart": {"--workers": "1"},
    "envelope": {"--freq": "60:200:8", "--samples": "2", "--refine": "2",
                 "--workers": "1"},
    "report": {"--grid": "10:220:40", "--map-freq": "5:250:30",
               "--map-pf": "0:1.5:12", "--sensitivity": "mu_g",
               "--fit": "mu_g", "--workers": "1"},
}


def _blocks(language):
    text = README.read_text()
    return re.findall(rf"^```{language}\n(.*?)^```", text, re.S | re.M)


def readme_commands():
    """The commands of the README's sh blocks, in order, as strings."""
    commands = []
    for block in _blocks("sh"):
        for line in block.replace("\\\n", " ").splitlines():
            words = shlex.split(line, comments=True)
            if words and (words[0] in ("judder", "make")
                          or words[:2] == ["python", "-m"]):
                commands.append(" ".join(words))
    return commands


def _smaller(words):
    """``words`` (after ``judder``) with :data:`SMALLER` applied."""
    extra = dict(SMALLER.get(words[0], {}))
    out = []
    index = 0
    while index < len(words):
        word = words[index]
        if word in extra:
            out.append(f"{word}={extra.pop(word)}")
            index += 2
            continue
        out.append(word)
        index += 1
    return out + [f"{option}={value}" for option, value in extra.items()]


def _makefile_line(target, program):
    """The line of a Makefile target's recipe that runs ``program``; a
    target without a recipe is followed to its first prerequisite."""
    text = (ROOT / "Makefile").read_text()
    rule = re.search(rf"^{re.escape(target)}:(.*)\n((?:\t.*\n)*)", text,
                     re.M)
    assert rule, f"the Makefile has no target {target}"
    for line in rule.group(2).splitlines():
        if program in line:
            return shlex.split(line.strip().replace("$(BIN)/", ""))
    prerequisites = rule.group(1).split()
    assert prerequisites, f"make {target} runs no {program}"
    return _makefile_line(prerequisites[0], program)


@pytest.fixture(scope="module")
def workdir(tmp_path_factory):
    folder = tmp_path_factory.mktemp("readme")
    shutil.copytree(ROOT / "examples", folder / "examples")
    return folder


COMMANDS = readme_commands()


def test_the_readme_has_the_recipe():
    # the set-up, a verdict, the two make targets, then a step per task
    assert COMMANDS[0] == "make setup"
    assert {"make run", "make test", "make fmu"} <= set(COMMANDS)
    names = {c.split()[1] for c in COMMANDS if c.startswith("judder ")}
    assert {"params", "map", "tongues", "floquet", "chart", "fit",
            "sensitivity", "report", "simulate", "check",
            "advise"} <= names


def test_the_first_screen_gives_a_verdict():
    # a newcomer sees what the tool answers within the first 40 lines:
    # a `judder check` command and the verdict it prints
    screen = "\n".join(README.read_text().splitlines()[:40])
    command = next(c for c in COMMANDS if c.startswith("judder "))
    assert command.startswith("judder check ") and command in screen
    assert SHOWN.get(command), "its output is not shown after it"
    assert re.search(r"\b(JUDDER|SLOW GROWTH|STABLE)\b", SHOWN[command])


def _shown_outputs():
    """{command: the output the README shows for it}: a ```text block
    right after a ```sh block of one ``judder`` command."""
    text = README.read_text()
    shown = {}
    pattern = r"^```sh\n(.*?)^```\n\s*^```text\n(.*?)^```"
    for block, output in re.findall(pattern, text, re.S | re.M):
        commands = [" ".join(shlex.split(line, comments=True))
                    for line in block.splitlines()
                    if line.startswith("judder ")]
        if len(commands) == 1:
            shown[commands[0]] = output
    return shown


#: The outputs the README shows, by command.
SHOWN = _shown_outputs()
NUMBER = re.compile(r"-?\d+(?:\.\d+)?")
VERDICT = re.compile(r"\b(?:JUDDER|SLOW GROWTH|STABLE|NO JUDDER)\b")


def _shown_differences(shown, printed):
    """Where the output the README shows is not what was printed: its
    numbers (to the digits shown) and verdict words, in order; the README
    may wrap and shorten the sentences between them."""
    lines = []
    want, got = NUMBER.findall(shown), NUMBER.findall(printed)
    if want != got:
        lines.append(f"numbers shown {want}, printed {got}")
    if VERDICT.findall(shown) != VERDICT.findall(printed):
        lines.append(f"verdicts shown {VERDICT.findall(shown)}, printed "
                     f"{VERDICT.findall(printed)}")
    return lines


@pytest.mark.parametrize("command", COMMANDS)
def test_readme_command_runs(command, workdir, monkeypatch, capsys, golden):
    """Each README command, run once: it exits with 0, prints its text,
    writes the files it names, and its key numbers (:data:`KEYS`) are the
    recorded ones within their tolerance (:data:`TOLERANCES`)."""
    monkeypatch.chdir(workdir)
    words = shlex.split(command)
    if command in NOT_RUN:
        pytest.skip(NOT_RUN[command])
    if words == ["make", "run"]:
        words = _makefile_line("run", "judder")
    assert words[0] == "judder", f"unknown kind of command: {command}"
    emitted = _record_emitted(words[1], monkeypatch)
    status = main(_smaller(words[1:]))
    captured = capsys.readouterr()
    assert status == 0, captured.err
    assert captured.out.strip(), f"{command} printed nothing"
    # what the README shows it printing is what it printed
    if command in SHOWN:
        problems = _shown_differences(SHOWN[command], captured.out)
        assert not problems, "\n".join([command] + problems)
    # every file the command names as output exists and is not empty
    for option in ("--out", "--plot", "--save", "--boundary"):
        if option in words and not (words[1] == "fit"
                                    and option == "--boundary"):
            path = Path(words[words.index(option) + 1])
            # a chart of several groups writes STEM_GROUP.csv per group
            written = [path] if path.exists() else list(
                path.parent.glob(f"{path.stem}_*{path.suffix}"))
            assert written, path
            assert all(p.is_dir() or p.stat().st_size > 0 for p in written)
    # what --json would print (less the provenance), from this one run
    assert len(emitted) == 1, f"{command} emitted {len(emitted)} results"
    got = key_numbers(words[1], emitted[0])
    assert got, f"no key number of {command} was found: {KEYS[words[1]]}"
    if RECORD:
        golden[command] = got
        return
    assert command in golden, (
        f"{command} has no recorded key numbers (JUDDER_RECORD_JSON=1)")
    problems = _differences(got, golden[command])
    assert not problems, "\n".join([command] + problems[:40])


def test_readme_python_block_runs_as_a_script(workdir):
    # after the commands: campaign/ and the examples are in place. Run as
    # a user runs it, a script of its own: Dask's worker processes import
    # it again (without its __main__ guard it started three times and
    # died with "Nanny failed to start")
    import subprocess
    import sys
    (block,) = _blocks("python")
    code = (block.replace("np.linspace(5, 250, 300), np.linspace(0, 1.5, 150)",
                          "np.linspace(5, 250, 30), np.linspace(0, 1.5, 10)")
            .replace("np.linspace(10, 220, 500)", "np.linspace(10, 220, 60)"))
    assert 'if __name__ == "__main__":' in code
    script = workdir / "snippet.py"
    script.write_text(code)
    for name in ("map.npz", "map.png"):
        (workdir / name).unlink(missing_ok=True)
    # as the command line does: BLAS threads only contend on tiny matrices
    env = {**os.environ, "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1",
           "PYTHONPATH": str(ROOT)}
    proc = subprocess.run([sys.executable, str(script)], cwd=workdir,
                          capture_output=True, text=True, env=env,
                          timeout=900)
    assert proc.returncode == 0, proc.stderr[-2000:]
    assert "Nanny" not in proc.stderr
    assert (workdir / "map.npz").stat().st_size > 0
    assert (workdir / "map.png").stat().st_size > 0


def test_params_lists_the_allowed_range_of_every_parameter(capsys):
    # the README says so: the table and the saved file both give it
    from sources import get_preset, dumps_toml
    assert main(["params"]) == 0
    out = capsys.readouterr().out.splitlines()
    assert out[1].split()[:5] == ["name", "value", "unit", "allowed",
                                  "meaning"]
    params = get_preset("paper-4dof")
    rows = {line.split()[0]: line for line in out[2:]}
    saved = dumps_toml(params)
    for name, spec in params.specs.items():
        assert f" {spec.allowed()} " in rows[name], name
        assert f"(allowed: {spec.allowed()})" in saved, name


# The key numbers of every README command, against tests/golden/
# readme_key_numbers.json: per command (:data:`KEYS`, by its subcommand)
# the answers a user reads (verdicts, kinds, tongue tips, growth, margins,
# eigenfrequencies, amplitudes), each compared within the tolerance of its
# kind (:data:`TOLERANCES`, with the reason). Whole outputs are not pinned:
# a new field, a rounding of a file name or a reordered dict is no change
# of an answer. JUDDER_RECORD_JSON=1 records the file again after a
# deliberate change of an answer (say in the commit which and why).

GOLDEN = ROOT / "tests" / "golden" / "readme_key_numbers.json"
RECORD = os.environ.get("JUDDER_RECORD_JSON") == "1"

#: Tolerance of each kind of number: (rtol, atol, why).
TOLERANCES = {
    "exact": (0.0, 0.0,
              "a verdict, kind, mechanism, count or flag: any change is a "
              "change of the answer"),
    "preset": (1e-12, 0.0,
               "a stored value read back, not computed"),
    "linear": (1e-8, 1e-10,
               "eigenvalues of the linear model (LAPACK, double precision): "
               "room for another BLAS, not for a changed matrix"),
    "floquet": (1e-6, 1e-6,
                "multipliers from the Dyson product over a fixed step count "
                "and the growth ln|lambda|*f: deterministic up to summation "
                "order; 1e-6 is 1000 times finer than the README's digits"),
    "boundary": (1e-5, 1e-5,
                 "tongue tips and edges found by bisection to 1e-9*p_max on "
                 "a fixed grid: 1e-5 (bar or Hz) leaves room for the grid's "
                 "roundoff, far under the README's 3 digits"),
    "orbit": (1e-4, 1e-4,
              "a periodic orbit or settled motion integrated by an adaptive "
              "solver (rtol 1e-8 or finer): its amplitude to 1e-4 rpm"),
    "run": (1e-3, 1e-3,
            "a compiled FMU's run read through a spectrum: another C "
            "compiler or libm moves the last digits; 0.1 % is still 30 "
            "times under the 3 % that separates the README's verdicts"),
    "fit": (1e-4, 1e-7,
            "a least-squares optimum, stopped by its own tolerance"),
    "measured": (1e-9, 1e-12,
                 "the spectrum of a shipped measurement file: no solver"),
}

#: Per subcommand: (path, kind of tolerance). A path is keys joined by
#: dots; ``*`` is every item of a list or every value of a dict.
KEYS = {
    "params": [("parameters.*.value", "preset")],
    "eig": [("natural_frequencies_hz", "linear"),
            ("damped_modes.*.frequency_hz", "linear"),
            ("damped_modes.*.damping_ratio", "linear"),
            ("damping_factor_12", "linear"),
            ("driveline", "exact")],
    "map": [("counts", "exact"), ("judder_points", "exact"),
            ("judder_relevant_points", "exact"),
            ("forced_judder_points", "exact"),
            ("beyond_linear_range_points", "exact"),
            ("max_leading_abs", "floquet"),
            ("natural_frequencies_hz", "linear"), ("driveline", "exact")],
    "tongues": [("tongues.*.number", "exact"), ("tongues.*.kind", "exact"),
                ("tongues.*.tip_freq_hz", "boundary"),
                ("tongues.*.tip_p_f_bar", "boundary"),
                ("tongues.*.judder_tip_p_f_bar", "boundary"),
                ("natural_frequencies_hz", "linear")],
    "floquet": [("verdict", "exact"), ("kind", "exact"),
                ("leading_abs", "floquet"),
                ("growth_rate_per_s", "floquet"),
                ("multipliers.*.abs", "floquet")],
    "check": [("settings.*.verdict", "exact"), ("settings.*.kind", "exact"),
              ("settings.*.mechanism", "exact"),
              ("settings.*.tongue.number", "exact"),
              ("settings.*.growth_rate_per_s", "floquet"),
              ("settings.*.margin_bar", "boundary"),
              ("settings.*.margin_hz", "boundary"),
              ("settings.*.unstable_boundary_p_f_bar", "boundary"),
              ("settings.*.settled_amplitude_rpm", "orbit")],
    "compare": [("sets.*.natural_frequencies_hz", "linear"),
                ("sets.*.settings.*.verdict", "exact"),
                ("sets.*.settings.*.growth_rate_per_s", "floquet"),
                ("sets.*.settings.*.margin_bar", "boundary"),
                ("sets.*.tongues.*.tip_p_f_bar", "boundary"),
                ("sets.*.best_safe_setting", "boundary")],
    "sensitivity": [("nominal_tongues.*.tip_p_f_bar", "boundary"),
                    ("nominal_tongues.*.tip_freq_hz", "boundary"),
                    ("paper_conclusions.*.holds", "exact")],
    "threshold": [("mu_g_threshold", "floquet"),
                  ("mu_g_thresholds", "floquet"),
                  ("mu_g_thresholds_closed_form", "linear"),
                  ("max_real_part_per_s", "linear")],
    "advise": [("design.success", "exact"),
               ("design.factors", "fit"),
               ("design.max_growth_per_s_in_range", "fit"),
               ("best_safe_setting", "boundary"),
               ("ranking.*.parameter", "exact"),
               ("ranking.*.share_per_unit_log", "boundary")],
    "simulate": [("runs.*.verdict", "exact"), ("runs.*.mechanism", "exact"),
                 ("runs.*.oscillation_rpm", "run"),
                 ("runs.*.speed_peak_freq_hz", "run"),
                 ("runs.*.orbit_settled_rpm", "orbit"),
                 ("runs.*.floquet_exponent_per_s", "floquet")],
    "orbit": [("counts", "exact"), ("orbits.*.verdict", "exact"),
              ("orbits.*.settled_rpm", "orbit")],
    "campaign": [("runs", "exact"), ("ok", "exact")],
    "chart": [("runs.*.verdict", "exact"), ("runs.*.kind", "exact"),
              ("runs.*.oscillation_rpm", "run")],
    "fit": [("success", "exact"), ("fitted.*.value", "fit"),
            ("residual_rms_bar", "fit")],
    "crosscheck": [("points", "exact"), ("agreement", "exact")],
    "envelope": [("samples", "exact"),
                 ("broadest_p_f_bar", "boundary"),
                 ("unstable_share_at_p_max", "exact"),
                 ("convergence.area_bar_hz", "boundary")],
    "report": [("natural_frequencies_hz", "linear"),
               ("damping_factor_12_percent", "linear"),
               ("mu_g_threshold", "floquet"),
               ("tongues.*.tip_p_f_bar", "boundary"),
               ("advice.best_safe_setting", "boundary")],
}


def _select(value, keys):
    """The values of ``value`` at the path ``keys``, as {path: value}."""
    if not keys:
        return {"": value}
    key, rest = keys[0], keys[1:]
    if key == "*":
        items = (value.items() if isinstance(value, dict)
                 else enumerate(value) if isinstance(value, list) else ())
    elif isinstance(value, dict) and key in value:
        items = [(key, value[key])]
    else:
        return {}
    return {f"{name}.{path}".rstrip("."): found
            for name, item in items
            for path, found in _select(item, rest).items()}


def key_numbers(subcommand, data):
    """The key numbers of a command's JSON ``data``: {path: [value,
    kind]}, the path with the list indices and dict keys it was found at."""
    found = {}
    for path, kind in KEYS[subcommand]:
        for where, value in _select(data, path.split(".")).items():
            found[where] = [value, kind]
    return found


def _close(got, want, kind):
    """Whether ``got`` is ``want`` within the tolerance of ``kind``."""
    rtol, atol, _ = TOLERANCES[kind]
    if isinstance(want, dict) and isinstance(got, dict):
        return got.keys() == want.keys() and all(
            _close(got[k], want[k], kind) for k in want)
    if isinstance(want, list) and isinstance(got, list):
        return len(got) == len(want) and all(
            _close(g, w, kind) for g, w in zip(got, want))
    numbers = (int, float)
    if (isinstance(want, numbers) and isinstance(got, numbers)
            and not isinstance(want, bool) and not isinstance(got, bool)):
        return math.isclose(got, want, rel_tol=rtol, abs_tol=atol)
    return got == want


def _differences(got, want):
    """Where the key numbers ``got`` and ``want`` differ, as lines."""
    lines = [f"{path}: not found, recorded {want[path][0]!r}"
             for path in sorted(set(want) - set(got))]
    lines += [f"{path}: {got[path][0]!r} is new (JUDDER_RECORD_JSON=1)"
              for path in sorted(set(got) - set(want))]
    for path in sorted(set(got) & set(want)):
        (value, kind), (recorded, recorded_kind) = got[path], want[path]
        if kind != recorded_kind:
            lines.append(f"{path}: kind {kind}, recorded {recorded_kind}")
        elif not _close(value, recorded, kind):
            rtol, atol, why = TOLERANCES[kind]
            lines.append(f"{path}: {value!r}, recorded {recorded!r} "
                         f"(rtol {rtol:g}, atol {atol:g}: {why})")
    return lines


def _record_emitted(subcommand, monkeypatch):
    """The data a command hands to :func:`judder.commands._output.emit`,
    as its ``--json`` would print it: the command prints its text as
    usual, and the same run gives the numbers (no second run)."""
    import sys
    from judder.commands import _output, command_module
    command_module(subcommand)      # imported, so its ``emit`` is bound
    original = _output.emit
    emitted = []

    def emit(args, data, text):
        emitted.append(json.loads(_output.to_json(data)))
        original(args, data, text)

    # the modules that call it, not _output itself: a module imported
    # while the command runs binds _output's own emit, never this wrapper
    # (which would outlive the test and take the next test's results)
    for name, module in list(sys.modules.items()):
        if (name.startswith("judder") and module is not _output
                and getattr(module, "emit", None) is original):
            monkeypatch.setattr(module, "emit", emit)
    return emitted


@pytest.fixture(scope="module")
def golden():
    # recording updates the commands run and keeps the others (a README
    # command removed is caught by test_the_recorded_commands_are_the_readmes)
    recorded = (json.loads(GOLDEN.read_text())
                if GOLDEN.exists() or not RECORD else {})
    yield recorded
    if RECORD:
        GOLDEN.write_text(dumps_golden(recorded))


def dumps_golden(recorded):
    """The key numbers as JSON, one number (value, kind) a line."""
    commands = []
    for command in sorted(recorded):
        rows = [f"  {json.dumps(path)}: {json.dumps(entry)}"
                for path, entry in sorted(recorded[command].items())]
        commands.append(f" {json.dumps(command)}: {{\n" + ",\n".join(rows)
                        + "\n }")
    return "{\n" + ",\n".join(commands) + "\n}\n"


def test_the_recorded_commands_are_the_readmes():
    # a README command removed or renamed leaves no stale record behind
    run = {c for c in COMMANDS if c not in NOT_RUN}
    assert set(json.loads(GOLDEN.read_text())) == run


def test_every_kind_of_tolerance_has_a_reason():
    assert {kind for keys in KEYS.values() for _, kind in keys} <= set(
        TOLERANCES)
    assert all(len(why) > 20 and rtol >= 0 and atol >= 0
               for rtol, atol, why in TOLERANCES.values())


def test_a_changed_number_is_caught():
    # the comparison itself: a verdict flipped, a tip moved by 1e-3 bar
    # and a growth rate by 1e-4 are all found; the same numbers are not
    want = {"settings.0.verdict": ["STABLE", "exact"],
            "tongues.1.tip_p_f_bar": [0.0623, "boundary"],
            "growth_rate_per_s": [0.17, "floquet"]}
    assert _differences(dict(want), want) == []
    moved = {"settings.0.verdict": ["JUDDER", "exact"],
             "tongues.1.tip_p_f_bar": [0.0633, "boundary"],
             "growth_rate_per_s": [0.1701, "floquet"]}
    assert len(_differences(moved, want)) == 3
    assert len(_differences({}, want)) == 3


def test_a_changed_output_the_readme_shows_is_caught():
    # the README may wrap the sentence; a number or a verdict it shows
    # that the command no longer prints is found
    printed = "86.5 Hz, 0.5 bar: JUDDER in tongue 5; grows at 3.36 1/s"
    assert _shown_differences("86.5 Hz, 0.5 bar: JUDDER in\ntongue 5; "
                              "grows at 3.36 1/s", printed) == []
    assert _shown_differences(printed.replace("3.36", "3.35"), printed)
    assert _shown_differences(printed.replace("JUDDER", "STABLE"), printed)
