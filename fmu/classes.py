"""Where a Modelica class is stored and where its definition stands in
its file, read from the source text as Modelica's rules for storing
classes and its grammar say (no parsing by rumoca): the library roots
(``--library``, ``MODELICAPATH``), the file of a class, the spans of the
class definitions in a file, and a file's text with its comments and
strings blanked.
"""

import os
from pathlib import Path
import re

from .errors import FrontEndError

__all__ = ["blank", "class_source", "class_spans", "find_class",
           "library_folders", "modelica_path"]


def class_source(library, name):
    """The ``.mo`` file that holds class ``name`` of ``library``.

    A class is found as ``A/B/C.mo`` (one class per file, package folders
    with ``package.mo``), inside its package's ``package.mo``, or inside a
    single file holding the whole package (``A.mo`` with ``package A ...
    end A;``), as Modelica's rules for storing classes allow.

    Raises
    ------
    FrontEndError
        If no such file exists.
    """
    library, parts = Path(library), name.split(".")
    for count in range(len(parts), 0, -1):
        folder = library.joinpath(*parts[:count])
        for candidate in (folder.with_suffix(".mo"), folder / "package.mo"):
            if candidate.is_file():
                return candidate
    raise FrontEndError(f"{name}: no file {library.joinpath(*parts)}.mo, "
                        f"nor a package file holding it, in {library}")


def library_folders(library):
    """The user's library folders as a list of paths: ``library`` is None
    (none), one folder (a ``str`` or path) or a sequence of them (the
    command line's repeated ``--library``), searched in that order."""
    if library is None:
        return []
    if isinstance(library, (str, os.PathLike)):
        return [Path(library)]
    return [Path(folder) for folder in library]


def modelica_path(libraries=()):
    """The library roots, searched as Modelica tools search them: the
    ``libraries`` given first, then the folders of the environment
    variable ``MODELICAPATH`` (separated by ``os.pathsep``), each once."""
    roots = []
    entries = list(libraries) + \
        os.environ.get("MODELICAPATH", "").split(os.pathsep)
    for entry in entries:
        if entry and Path(entry) not in roots:
            roots.append(Path(entry))
    return roots


def find_class(name, roots):
    """``(file, root)`` of class ``name``: the first root of ``roots``
    holding its top-level package (``Modelica`` of
    ``Modelica.Mechanics.Rotational.Examples.First``), as MODELICAPATH is
    searched; a root may be a ``.mo`` file holding a whole package.

    Raises
    ------
    FrontEndError
        If no root holds it (the message lists the roots searched), or
        the first root holding its package does not declare it.
    """
    top = name.split(".")[0]
    for root in map(Path, roots):
        if root.is_file() and root.suffix == ".mo":
            if root.stem == top:
                return root, root.parent
            continue
        if (root / top).is_dir() or (root / f"{top}.mo").is_file():
            source = class_source(root, name)
            short = name.split(".")[-1]
            if source.stem == short or _declares(source, short):
                return source, root
            raise FrontEndError(f"{name}: not found: package {top} is in "
                                f"{root}, but neither {short}.mo nor "
                                f"{source} declares {short}")
    searched = ", ".join(str(r) for r in roots) or "(none)"
    raise FrontEndError(f"{name}: no library on the path holds package "
                        f"{top} (searched the library roots and MODELICAPATH: "
                        f"{searched})")


def _declares(source, short_name):
    """Whether a package file holds a class named ``short_name``."""
    return re.search(r"\b(?:model|block|class|package|record|connector|"
                     r"function|type)\s+" + re.escape(short_name) + r"\b",
                     source.read_text(errors="replace")) is not None


_CLASS_HEAD = re.compile(
    r"\b(?:model|block|class|package|record|connector|function|type)\s+"
    r"(?:extends\s+)?(\w+)(?![\w.])(?!\s*\()(\s*=)?")
_CLASS_END = re.compile(r"\bend\s+(\w+)\s*;")
_WITHIN = re.compile(r"^\s*within\s+([\w.]*)\s*;")


def blank(text):
    """``text`` with its comments and string literals blanked (same
    length, newlines kept), so positions still index the source."""
    def spaces(found):
        return re.sub(r"[^\n]", " ", found.group(0))
    return re.sub(r'//[^\n]*|/\*.*?\*/|"(?:\\.|[^"\\])*"', spaces, text,
                  flags=re.S)


def class_spans(text):
    """``{full name: (start, end)}`` of the long class definitions in a
    source text (``within`` prefix included), from each ``model NAME``
    (or block, package, ...) to its ``end NAME;``; short definitions
    (``type T = Real``) have no body and are left out."""
    clean = blank(text)
    within = _WITHIN.match(clean)
    prefix = [within.group(1)] if within and within.group(1) else []
    events = [(m.start(), "head", m) for m in _CLASS_HEAD.finditer(clean)
              if not m.group(2)]
    events += [(m.start(), "end", m) for m in _CLASS_END.finditer(clean)]
    stack, spans = [], {}
    for at, kind, found in sorted(events, key=lambda e: e[0]):
        if kind == "head":
            stack.append((found.group(1), at))
        elif stack and stack[-1][0] == found.group(1):
            name, begin = stack.pop()
            full = ".".join(prefix + [n for n, _ in stack] + [name])
            spans[full] = (begin, found.end())
    return spans
