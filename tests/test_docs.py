"""The documentation stays true where a machine can tell.

What README.md and docs/*.md name must exist: every ``judder`` command
and option of their command lines (as ``judder CMD --help`` declares
them), every file of the checkout they name, every module, function or
constant of the project they name by its dotted path, every link and
its anchor. And docs/ stays short enough to be read (issue 42: under
25 000 words, ``wc -w docs/*.md``).
"""

import importlib
import re
import shlex
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PAGES = [ROOT / "README.md"] + sorted((ROOT / "docs").glob("*.md"))
#: The packages and folders of the checkout a path or a dotted name starts with.
TOP = ("judder", "stability", "pysim", "fmu", "sources", "drivelines",
       "infra", "modelica", "examples", "tests", "benchmarks", "docs")
#: Folders the tool writes into at run time: named, never checked in.
WRITTEN = ("build/", "out/")
MAX_WORDS = 25_000
#: Endings that make a dotted word a file name, not a Python name.
FILE_SUFFIXES = {"py", "mo", "toml", "csv", "md", "json", "npz", "fmu",
                 "png", "mf4", "html", "txt", "xml"}


def _name(page):
    return page.relative_to(ROOT).as_posix()


def _code_spans(text):
    """Inline code spans and the lines of fenced blocks."""
    blocks = re.findall(r"^```[a-z]*\n(.*?)^```", text, re.S | re.M)
    inline = re.findall(r"`([^`\n]+)`", re.sub(r"^```.*?^```", "", text,
                                               flags=re.S | re.M))
    return blocks, inline


def test_docs_are_under_25k_words():
    # as `wc -w docs/*.md` counts them: runs of non-blank characters
    words = {_name(p): len(p.read_text().split()) for p in PAGES[1:]}
    assert sum(words.values()) < MAX_WORDS, (
        f"docs/ has {sum(words.values())} words, allowed < {MAX_WORDS}: "
        f"{sorted(words.items(), key=lambda kv: -kv[1])[:3]}")


def _command_lines():
    """(page, words) of every ``judder`` command line the pages show,
    in fenced blocks and in inline code."""
    found = []
    for page in PAGES:
        blocks, inline = _code_spans(page.read_text())
        lines = [line for block in blocks
                 for line in block.replace("\\\n", " ").splitlines()]
        for line in lines + inline:
            line = line.strip().lstrip("$ ").strip()
            if not line.startswith("judder "):
                continue
            try:
                words = shlex.split(line, comments=True)
            except ValueError:      # an inline span cut mid-quote
                continue
            found.append((_name(page), words))
    return found


def _options():
    """{command: set of its option strings}, from the parser itself."""
    from judder.cli import build_parser
    parser = build_parser()
    sub = next(a for a in parser._actions if a.choices
               and "check" in a.choices)
    return {name: {o for action in p._actions for o in action.option_strings}
            for name, p in sub.choices.items()}


def test_every_command_and_option_the_docs_name_exists():
    options = _options()
    lines = _command_lines()
    assert len(lines) > 50      # the pages do show their command lines
    wrong = []
    for page, words in lines:
        if (len(words) < 2 or words[1].startswith("-")
                or not words[1].islower()):
            continue            # `judder --help`, `judder COMMAND`
        command = words[1]
        if command not in options:
            wrong.append(f"{page}: `judder {command}`: no such command; "
                         f"allowed: {', '.join(sorted(options))}")
            continue
        for word in words[2:]:
            option = word.split("=", 1)[0]
            if (option.startswith("--") and option != "--"
                    and option not in options[command]):
                wrong.append(f"{page}: `judder {command} {option}`: "
                             f"not an option of judder {command}")
    assert not wrong, "\n".join(wrong)


def _paths(text):
    """Paths of the checkout named in code spans: words that start with a
    top-level folder and hold a slash, less a ``:LINE`` suffix."""
    blocks, inline = _code_spans(text)
    spans = inline + [line for block in blocks for line in
                      block.splitlines()]
    found = set()
    for span in spans:
        for word in re.findall(r"[\w./\-*<>]+", span):
            if "<" in word:
                continue        # a placeholder, `pysim/bench_data/_<format>.py`
            word = re.sub(r":\d+(-\d+)?$", "", word).rstrip(".")
            if ("/" in word and word.split("/")[0] in TOP
                    and not word.startswith(WRITTEN)):
                found.add(word)
    return found


def test_every_file_the_docs_name_exists():
    missing = []
    for page in PAGES:
        for path in sorted(_paths(page.read_text())):
            if "*" in path or "..." in path:
                exists = bool(list(ROOT.glob(path.replace("...", "**"))))
            else:
                exists = (ROOT / path).exists()
            if not exists:
                missing.append(f"{_name(page)}: {path}")
    assert not missing, "files named but not in the checkout:\n" + "\n".join(
        missing)


def _dotted(text):
    """Dotted names of the project's packages in inline code
    (``stability.friction.linear_range``), with no call or spaces."""
    _, inline = _code_spans(text)
    return {span for span in inline
            if re.fullmatch(r"[a-z_]+(\.[A-Za-z_][A-Za-z0-9_]*)+", span)
            and span.split(".")[0] in TOP
            and span.rsplit(".", 1)[1] not in FILE_SUFFIXES}


def _resolves(dotted):
    """Whether ``dotted`` is a module or an attribute of one."""
    parts = dotted.split(".")
    for cut in range(len(parts), 0, -1):
        try:
            obj = importlib.import_module(".".join(parts[:cut]))
        except ImportError:
            continue
        for attribute in parts[cut:]:
            if not hasattr(obj, attribute):
                return False
            obj = getattr(obj, attribute)
        return True
    return False


def test_every_module_and_name_the_docs_name_exists():
    unknown = [f"{_name(page)}: {name}" for page in PAGES
               for name in sorted(_dotted(page.read_text()))
               if not _resolves(name)]
    assert not unknown, "names the code does not have:\n" + "\n".join(unknown)


def _anchor(heading):
    """GitHub's anchor of a heading."""
    text = re.sub(r"[^\w\- ]", "", heading.strip().lower())
    return text.replace(" ", "-")


@pytest.mark.parametrize("page", PAGES, ids=_name)
def test_every_link_and_anchor_resolves(page):
    text = page.read_text()
    broken = []
    for target in re.findall(r"\]\(([^)\s]+)\)", text):
        if re.match(r"[a-z]+:", target):
            continue            # https:, mailto:
        path, _, anchor = target.partition("#")
        file = (page.parent / path).resolve() if path else page
        if not file.exists():
            broken.append(f"{target}: no file {file.relative_to(ROOT)}")
            continue
        if anchor and file.suffix == ".md":
            anchors = {_anchor(h) for h in re.findall(
                r"^#+ (.*)$", file.read_text(), re.M)}
            if anchor not in anchors:
                broken.append(f"{target}: no heading of that anchor in "
                              f"{file.relative_to(ROOT)}")
    assert not broken, f"{_name(page)}:\n" + "\n".join(broken)
