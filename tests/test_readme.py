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
    # the two commands first, then a recipe step per task
    assert COMMANDS[:2] == ["make run", "make test"]
    names = {c.split()[1] for c in COMMANDS if c.startswith("judder ")}
    assert {"params", "map", "tongues", "floquet", "chart", "fit",
            "sensitivity", "report", "simulate", "check",
            "advise"} <= names
    assert "make fmu" in COMMANDS


@pytest.mark.parametrize("command", COMMANDS)
def test_readme_command_runs(command, workdir, monkeypatch, capsys):
    monkeypatch.chdir(workdir)
    words = shlex.split(command)
    if command in NOT_RUN:
        pytest.skip(NOT_RUN[command])
    if words == ["make", "run"]:
        words = _makefile_line("run", "judder")
    assert words[0] == "judder", f"unknown kind of command: {command}"
    status = main(_smaller(words[1:]))
    captured = capsys.readouterr()
    assert status == 0, captured.err
    assert captured.out.strip(), f"{command} printed nothing"
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


# --json of every README command, against the recording made before the
# command layer was restructured (issue 22): wall-clock times (``seconds``),
# the version and input digest (``provenance``, which change with every
# release and every default; tested in test_provenance.py) and the scratch
# folder's and the checkout's paths left out, numbers to
# 1e-9 relative (the same kernels in the same order). JUDDER_RECORD_JSON=1
# records it again after a deliberate change of an output (say why in the
# commit).

GOLDEN = ROOT / "tests" / "golden" / "readme_json.json"
RECORD = os.environ.get("JUDDER_RECORD_JSON") == "1"
#: Keys whose values are wall-clock times, and the provenance.
TIMES = {"seconds", "elapsed_s", "provenance"}
RTOL = 1e-9


def _judder_commands():
    return [c for c in COMMANDS if c.startswith("judder ")
            and c not in NOT_RUN]


def _normalised(value, folder):
    """``value`` without wall-clock times and provenance, with the scratch
    folder as ``<work>``, the checkout as ``<root>`` and the folder of an
    FMU of the compiler as ``<fmu>`` (``build/fmu`` after ``make fmu``,
    else its key's folder in the user's cache, fmu/store.py)."""
    if isinstance(value, dict):
        return {k: _normalised(v, folder) for k, v in value.items()
                if k not in TIMES}
    if isinstance(value, list):
        return [_normalised(v, folder) for v in value]
    if isinstance(value, str):
        value = re.sub(rf"^(?:{re.escape(str(BUILT))}|"
                       rf"{re.escape(str(cache_folder('fmu')))}/[0-9a-f]{{64}})/",
                       "<fmu>/", value)
        return value.replace(str(folder), "<work>").replace(str(ROOT),
                                                            "<root>")
    return value


def _differences(got, want, where="$"):
    """Where ``got`` and ``want`` differ, as lines."""
    if isinstance(want, dict) and isinstance(got, dict):
        lines = [f"{where}: keys {sorted(set(got) ^ set(want))} differ"
                 ] if set(got) != set(want) else []
        for key in sorted(set(got) & set(want)):
            lines += _differences(got[key], want[key], f"{where}.{key}")
        return lines
    if isinstance(want, list) and isinstance(got, list):
        if len(got) != len(want):
            return [f"{where}: {len(got)} items, recorded {len(want)}"]
        return [line for i, (g, w) in enumerate(zip(got, want))
                for line in _differences(g, w, f"{where}[{i}]")]
    numbers = (int, float)
    if (isinstance(want, numbers) and isinstance(got, numbers)
            and not isinstance(want, bool) and not isinstance(got, bool)):
        if math.isclose(got, want, rel_tol=RTOL, abs_tol=1e-12):
            return []
    elif got == want:
        return []
    return [f"{where}: {got!r}, recorded {want!r}"]


def test_every_readme_command_prints_the_recorded_json(
        tmp_path, monkeypatch, capsys):
    shutil.copytree(ROOT / "examples", tmp_path / "examples")
    monkeypatch.chdir(tmp_path)
    recorded = {} if RECORD else json.loads(GOLDEN.read_text())
    got = {}
    for command in _judder_commands():
        words = _smaller(shlex.split(command)[1:]) + ["--json"]
        status = main(words)
        captured = capsys.readouterr()
        assert status == 0, f"{command}: {captured.err}"
        got[command] = _normalised(json.loads(captured.out), tmp_path)
    if RECORD:
        GOLDEN.write_text(json.dumps(got, indent=1, sort_keys=True) + "\n")
        return
    assert sorted(got) == sorted(recorded), "the README's commands changed"
    problems = [line for command in got
                for line in _differences(got[command], recorded[command],
                                         command)]
    assert not problems, "\n".join(problems[:40])
