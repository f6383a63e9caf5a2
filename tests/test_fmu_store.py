"""The one door to FMU files (fmu/store.py): FMUs named by the content of
their sources, built and unpacked into the user's cache, never into the
checkout."""

import json
import os
from pathlib import Path
import subprocess
import sys

import pytest

pytest.importorskip("rumoca")
from fmu import store  # noqa: E402
from fmu.build import build_fmu, build_key, built_from  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
CLASS = "MyLib.H3Collide"
#: The clutch damper's damping (N m s/rad) of each version of the class.
DAMPING = {"v1": 2.0, "v2": 8.0}


def _library(folder, c12):
    """``MyLib.H3Collide``: the 4-DOF driveline with the damping ``c12``."""
    package = folder / "MyLib"
    package.mkdir(parents=True)
    (package / "package.mo").write_text("package MyLib\nend MyLib;\n")
    (package / "H3Collide.mo").write_text(
        "within MyLib;\n"
        'model H3Collide "The 4-DOF driveline, its damper changed"\n'
        f"  extends Judder.Examples.Driveline4DOF(c12={c12:g});\n"
        "end H3Collide;\n")
    return folder


@pytest.fixture
def versions(tmp_path):
    """Two versions of one class, the second older on disk (as an
    unpacked release or a checkout of an older tag can be)."""
    folders = {name: _library(tmp_path / name, c12)
               for name, c12 in DAMPING.items()}
    for source in (folders["v2"] / "MyLib").iterdir():
        os.utime(source, ns=(10**18, 10**18))       # 2001
    return folders


def _simulate(library, cwd, cache):
    """``judder simulate --modelica CLASS --library DIR --json`` in a
    process of its own, its caches under ``cache``."""
    env = {key: value for key, value in os.environ.items()
           if key != "JUDDER_FMU_CACHE"}
    env.update(XDG_CACHE_HOME=str(cache), PYTHONDONTWRITEBYTECODE="1")
    done = subprocess.run(
        [sys.executable, "-m", "judder", "simulate", "--modelica", CLASS,
         "--library", str(library), "--freq", "60", "--pf", "0.3",
         "--duration", "1", "--json"],
        cwd=cwd, env=env, capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


def test_two_versions_of_a_class_run_their_own_fmus(versions, tmp_path):
    # v2 is older on disk than v1's FMU: a cache named by the class and
    # the sources' times ran v1's FMU for it (issue 42)
    runs = {name: _simulate(folder, tmp_path, tmp_path / "cache")
            for name, folder in versions.items()}
    cache = tmp_path / "cache" / "judder" / "fmu"
    for name, run in runs.items():
        assert Path(run["fmu"]).parent.parent == cache
        assert store.parameter_default(run["fmu"], "c12") == DAMPING[name]
    assert runs["v1"]["fmu"] != runs["v2"]["fmu"]
    # the damper's damping shows in the forced oscillation (rpm)
    forced = [runs[name]["runs"][0]["forced_rpm"] for name in DAMPING]
    assert abs(forced[0] - forced[1]) > 0.1 * max(forced)


def _snapshot(root):
    """Every file under the checkout with its size and modification
    time (git's own folder, the environment and Python's byte code
    left out)."""
    skip = {".git", ".venv", "__pycache__", ".pytest_cache"}
    found = {}
    for folder, names, files in os.walk(root):
        names[:] = [n for n in names if n not in skip]
        for name in files:
            stat = (Path(folder) / name).stat()
            found[str(Path(folder, name).relative_to(root))] = (
                stat.st_size, stat.st_mtime_ns)
    return found


def test_simulate_of_a_users_class_writes_nothing_under_the_checkout(
        versions, tmp_path):
    before = _snapshot(ROOT)
    run = _simulate(versions["v1"], ROOT, tmp_path / "cache")
    assert _snapshot(ROOT) == before
    assert Path(run["fmu"]).is_relative_to(tmp_path / "cache")
    unpacked = tmp_path / "cache" / "judder" / "fmu" / "unpacked"
    assert [p.parent.parent for p in unpacked.glob(
        "*/modelDescription.xml")] == [unpacked]


def test_the_key_follows_the_content_not_the_modification_time(tmp_path):
    library = _library(tmp_path / "lib", 2.0)
    roots = [library, store.LIBRARY]
    source = library / "MyLib" / "H3Collide.mo"
    first = build_key(CLASS, "2.0", roots)
    os.utime(source, ns=(10**18, 10**18))
    assert build_key(CLASS, "2.0", roots) == first
    text = source.read_text()
    source.write_text(text.replace("c12=2", "c12=3"))
    assert build_key(CLASS, "2.0", roots) != first
    source.write_text(text)
    assert build_key(CLASS, "2.0", roots) == first
    assert build_key(CLASS, "3.0", roots) != first


def test_a_built_fmu_is_used_while_its_sources_are_unchanged(
        tmp_path, monkeypatch):
    # as `make fmu` leaves build/fmu: used by its content, not its time
    monkeypatch.setattr(store, "BUILT", tmp_path / "built")
    monkeypatch.setenv("JUDDER_FMU_CACHE", str(tmp_path / "cache"))
    library = _library(tmp_path / "lib", 2.0)
    source = library / "MyLib" / "H3Collide.mo"
    made = build_fmu(source, CLASS, tmp_path / "built" / "H3Collide.fmu",
                     roots=[library, store.LIBRARY]).path
    assert built_from(made) == build_key(CLASS, "2.0",
                                         [library, store.LIBRARY])
    os.utime(source, ns=(10**18, 10**18))     # older than the FMU ...
    assert store.ensure_fmu(CLASS, library=library) == made
    os.utime(source, ns=(4 * 10**18, 4 * 10**18))   # ... and newer
    assert store.ensure_fmu(CLASS, library=library) == made
    source.write_text(source.read_text().replace("c12=2", "c12=3"))
    fresh = store.ensure_fmu(CLASS, library=library)
    assert fresh.parent.parent == tmp_path / "cache"
    assert store.parameter_default(fresh, "c12") == 3.0
    assert store.parameter_default(made, "c12") == 2.0


def test_of_two_processes_making_one_entry_the_first_wins(tmp_path):
    # the other process renamed its folder into place while this one
    # was making its own: this one keeps the first and drops its own
    def make(staging):
        (staging / "entry").write_text("second")
        (tmp_path / "key").mkdir()
        (tmp_path / "key" / "entry").write_text("first")
    target = store._entry(tmp_path, "key", "entry", make)
    assert target.read_text() == "first"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["key"]


def test_an_fmu_is_unpacked_once_per_content(tmp_path, monkeypatch):
    monkeypatch.setenv("JUDDER_FMU_CACHE", str(tmp_path / "cache"))
    library = _library(tmp_path / "lib", 2.0)
    fmu = store.ensure_fmu(CLASS, library=library)
    copy = tmp_path / "elsewhere.fmu"
    copy.write_bytes(fmu.read_bytes())
    folder = store.unpacked(fmu)
    assert Path(folder).is_relative_to(tmp_path / "cache" / "unpacked")
    assert store.unpacked(copy) == folder
    assert store.digest(copy) == store.digest(fmu)
