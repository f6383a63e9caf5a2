"""Cache of rumoca's flat models, so a model that uses the MSL is not
flattened again while no source of its libraries has changed.

rumoca loads every file of the library roots it is given (the MSL is
about 2,400 files): that costs 10-20 s on this project's machines, each
time, even with rumoca's own cache of parsed files. The flat model of a
class is kept here as JSON, keyed by the class, its file, rumoca's
version and the path, size and modification time of every ``.mo`` file
under the roots, so any edit, added or removed file in a library makes a
new flattening. Only the source texts the flat model's spans point to
are kept (rumoca's source map holds the whole library, 15 MB for MSL).

The folder is ``$JUDDER_FMU_CACHE``, else ``$XDG_CACHE_HOME/judder/flat``,
else ``~/.cache/judder/flat``; ``JUDDER_FMU_CACHE=off`` disables it.
"""

import hashlib
import json
import os
from pathlib import Path

from infra.errors import JudderError
from infra.files import atomic_write

__all__ = ["cache_folder", "cache_key", "load", "sources_stamp",
           "store"]


def cache_folder():
    """The cache folder, or None when the cache is off."""
    chosen = os.environ.get("JUDDER_FMU_CACHE")
    if chosen == "off":
        return None
    if chosen:
        return Path(chosen)
    base = os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache"
    return Path(base) / "judder" / "flat"


def sources_stamp(path, roots):
    """The path, size and modification time of ``path`` and of every
    ``.mo`` file under ``roots``, as bytes: what the keys of the flat
    models (:func:`cache_key`) and of the rewritten sources
    (:func:`fmu.rewrite.prepare`) say of the sources, read with one
    ``stat`` per file and not one read."""
    files = {Path(path).resolve()}
    for root in roots:
        root = Path(root).resolve()
        files |= set(root.rglob("*.mo")) if root.is_dir() else {root}
    lines = []
    for source in sorted(files):
        stat = source.stat()
        lines.append(f"{source}\0{stat.st_size}\0{stat.st_mtime_ns}\n")
    return "".join(lines).encode()


def cache_key(path, model_name, roots, version, stamp=None):
    """Hex digest naming the flat model of ``model_name`` as the sources
    under ``roots`` stand now (``stamp``: their :func:`sources_stamp`,
    when the caller has it)."""
    digest = hashlib.sha256()
    for item in (version, model_name, str(Path(path).resolve())):
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
    written is no error)."""
    folder = cache_folder()
    if folder is None:
        return
    used = _sources_used(flat["storage"])
    trimmed = dict(flat, source_map=dict(
        flat.get("source_map", {}), files=[
            entry for entry in flat.get("source_map", {}).get("files", [])
            if entry[0] in used]))
    text = json.dumps(trimmed).encode()
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
