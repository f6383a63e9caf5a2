"""The cache of rumoca's flat models (fmu/cache.py): a second compile of
an unchanged model does not flatten again; an edited source does."""

import os
from pathlib import Path
import shutil

import pytest

pytest.importorskip("rumoca")
import fmu.frontend as frontend  # noqa: E402
from fmu.backend import to_ode  # noqa: E402

CORPUS = Path(__file__).resolve().parent / "modelica_corpus"


@pytest.fixture
def counted(monkeypatch, tmp_path):
    """rumoca's flattening, counted; the cache in a folder of the test."""
    monkeypatch.setenv("JUDDER_FMU_CACHE", str(tmp_path / "cache"))
    calls = []
    real = frontend._flatten_with_rumoca

    def flatten(*args, **kwargs):
        calls.append(args[1])
        return real(*args, **kwargs)
    monkeypatch.setattr(frontend, "_flatten_with_rumoca", flatten)
    return calls


def _decay(library):
    ode = to_ode(frontend.load_flat_model(library / "Decay.mo", "Decay",
                                          [library]))
    return {q.name: q.start for q in ode.parameters}, str(ode.derivatives)


def test_unchanged_model_is_read_from_the_cache(counted, tmp_path):
    library = tmp_path / "lib"
    shutil.copytree(CORPUS, library)
    first = _decay(library)
    assert first[0] == {"k": 2.0}
    assert counted == ["Decay"]
    assert _decay(library) == first
    assert counted == ["Decay"]      # not flattened again
    assert len(list((tmp_path / "cache").glob("*.json"))) == 1
    # any edit of a source under the library's folder makes a new flat
    # model: here a change of the model's parameter value
    source = library / "Decay.mo"
    source.write_text(source.read_text().replace(") = 2", ") = 3"))
    stat = source.stat()
    os.utime(source, ns=(stat.st_atime_ns, stat.st_mtime_ns + 10**9))
    assert _decay(library) == ({"k": 3.0}, first[1])
    assert counted == ["Decay", "Decay"]


def test_cache_off(counted, monkeypatch):
    monkeypatch.setenv("JUDDER_FMU_CACHE", "off")
    _decay(CORPUS)
    _decay(CORPUS)
    assert counted == ["Decay", "Decay"]


def test_a_cached_flat_model_is_still_checked_from_the_source(counted,
                                                             tmp_path):
    # initial() is read with the Integer and Boolean variables
    # (``hybrid``) and refused without them; flattened and cached for the
    # first, the class is refused for the second by the source check, at
    # its place in the model, before the cache is read
    source = tmp_path / "InitialReal.mo"
    source.write_text("model InitialReal\n"
                      "  Real x(start = 1, fixed = true);\n"
                      "equation\n"
                      "  der(x) = if initial() then 0 else -x;\n"
                      "end InitialReal;\n")
    frontend.load_flat_model(source, "InitialReal", [tmp_path], hybrid=True)
    assert counted == ["InitialReal"]
    with pytest.raises(frontend.FrontEndError,
                       match=r"InitialReal.mo:4: initial\(\) \(equations "
                             r"that differ at the initialisation\) is not "
                             r"supported.*\(found before flattening\)"):
        frontend.load_flat_model(source, "InitialReal", [tmp_path])
    assert counted == ["InitialReal"]
