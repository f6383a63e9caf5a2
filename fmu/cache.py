"""Cache of rumoca's flat models, so a model that uses the MSL is not
flattened again while no source of its libraries has changed.

rumoca loads every file of the library roots it is given (the MSL is
about 2,400 files): that costs 10-20 s on this project's machines, each
time, even with rumoca's own cache of parsed files. The flat model of a
class is kept here as JSON, keyed by the class, its file, rumoca's
version and the content of every ``.mo`` file under the roots
(:func:`sources_digest`), so any edit, added or removed file in a library
makes a new flattening, and a file only touched (its modification time
changed) does not. Only the source texts the flat model's spans point to
are kept (rumoca's source map holds the whole library, 15 MB for MSL).

The folder is ``$JUDDER_FMU_CACHE``, else ``$XDG_CACHE_HOME/judder/flat``,
else ``~/.cache/judder/flat``; ``JUDDER_FMU_CACHE=off`` disables it.
The FMUs of :mod:`fmu.store` are kept by the same rules
(:func:`cache_folder` of ``"fmu"``).
"""

import hashlib
import json
import os
from pathlib import Path

from infra.errors import JudderError
from infra.files import atomic_write

__all__ = ["cache_folder", "cache_key", "load", "sources_digest",
           "sources_stamp", "store"]


def cache_folder(kind="flat"):
    """The cache folder of ``kind`` (``"flat"``: rumoca's flat models,
    ``"fmu"``: the FMUs and unpacked FMUs of :mod:`fmu.store`), or None
    when the cache is off.

    ``$JUDDER_FMU_CACHE`` (one folder for both kinds: their entries do
    not collide), else ``$XDG_CACHE_HOME/judder/KIND``, else
    ``~/.cache/judder/KIND``; ``JUDDER_FMU_CACHE=off`` turns it off.
    """
    chosen = os.environ.get("JUDDER_FMU_CACHE")
    if chosen == "off":
        return None
    if chosen:
        return Path(chosen)
    base = os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache"
    return Path(base) / "judder" / kind


def sources_digest(roots):
    """Hex sha256 of the Modelica sources under ``roots``: the path
    (relative to its root) and the content of every ``.mo`` and
    ``package.order`` file, root by root in their order (a root may be a
    ``.mo`` file holding a whole package). Modification times do not
    enter: a touched file keeps its digest, an edited one changes it."""
    digest = hashlib.sha256()
    for root in map(Path, roots):
        files = sorted(p for p in root.rglob("*") if p.is_file() and (
            p.suffix == ".mo" or p.name == "package.order")) \
            if root.is_dir() else [root]
        digest.update(f"root {len(files)}\n".encode())
        for source in files:
            name = source.relative_to(root) if root.is_dir() else source.name
            digest.update(f"{name}\0".encode()
                          + hashlib.sha256(source.read_bytes()).digest())
    return digest.hexdigest()


def sources_stamp(path, roots):
    """What the keys of the flat models (:func:`cache_key`) and of the
    rewritten sources (:func:`fmu.rewrite.prepare`) say of the sources:
    the :func:`sources_digest` of ``path`` and ``roots``, as bytes,
    computed once a build."""
    return sources_digest([path, *roots]).encode()


def cache_key(path, model_name, roots, version, stamp=None):
    """Hex digest naming the flat model of ``model_name`` as the sources
    under ``roots`` stand now (their content, :func:`sources_digest`;
    ``stamp``: their :func:`sources_stamp`, when the caller has it)."""
    digest = hashlib.sha256()
    # the places too: a flat model's source map names its files
    places = [str(Path(p).resolve()) for p in (path, *roots)]
    for item in (version, model_name, *places):
        digest.update(item.encode() + b"\0")
    digest.update(sources_stamp(path, roots) if stamp is None else stamp)
    return digest.hexdigest()


def load(key):
    """The flat model stored under ``key``, or None."""
    folder = cache_folder()
    if folder is None:
        return None
    try:
        return json.loads((folder / f"{key}.json").read_text())
    except (OSError, ValueError):
        return None   # absent, or written by a run that was killed


def store(key, flat):
    """Keep ``flat`` under ``key`` (best effort: a cache that cannot be
    written is no error). ``{"refused": message}`` keeps rumoca's own
    refusal of the sources (it depends on them and rumoca's version
    only), so the same build is refused again in about a second."""
    folder = cache_folder()
    if folder is None:
        return
    if "refused" not in flat:   # else rumoca's own refusal, kept whole
        used = _sources_used(flat["storage"])
        flat = dict(flat, source_map=dict(
            flat.get("source_map", {}), files=[
                entry for entry in flat.get("source_map", {}).get("files",
                                                                   [])
                if entry[0] in used]))
    text = json.dumps(flat).encode()
    try:
        folder.mkdir(parents=True, exist_ok=True)
        atomic_write(folder / f"{key}.json", lambda out: out.write(text))
    except (OSError, JudderError):
        pass


def _sources_used(item):
    """Ids of the source files that spans in a rumoca record point to."""
    found, pending = set(), [item]
    while pending:
        node = pending.pop()
        if isinstance(node, dict):
            span = node.get("span")
            if isinstance(span, dict) and "source" in span:
                found.add(span["source"])
            pending.extend(node.values())
        elif isinstance(node, list):
            pending.extend(node)
    return found
