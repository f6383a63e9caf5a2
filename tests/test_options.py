"""One vocabulary of options: a name means one thing in every command.

The table is read from the parsers themselves: for each option, what its
value is (a flag, a choice, names, a file, or numbers in a unit: one
number and a list or grid of them are the same quantity) must be the
same wherever the option appears. A former spelling kept for one release
(:class:`judder.commands._arguments.Renamed`) is left out of the table
and must say its new spelling.
"""

from collections import defaultdict
import json
import subprocess
import sys

import pytest

from judder.cli import build_parser
from judder.commands._arguments import Renamed


def _meaning(action):
    """What an option's value is: (kind, unit)."""
    kind = type(action.type).__name__
    unit = getattr(action.type, "unit", None)
    if action.nargs == 0:
        return ("flag", None)
    if action.choices:
        return ("choice", None)
    if kind in ("NameList", "Listed") and unit is None:
        return ("names", None)
    if unit is not None:
        return ("quantity", unit)
    if action.type is None and action.metavar and (
            "FILE" in action.metavar or "." in action.metavar
            or action.metavar == "DIR"):
        return ("file", None)
    return (kind, action.metavar)


def _table():
    """``{option: {meaning: [commands]}}`` over every subcommand, and the
    former spellings ``{option: [(command, new spelling)]}``."""
    parser = build_parser()
    sub = next(a for a in parser._actions if a.dest == "command")
    table, renamed = defaultdict(lambda: defaultdict(list)), defaultdict(list)
    for command, subparser in sub.choices.items():
        for action in subparser._actions:
            for option in action.option_strings:
                if not option.startswith("--") or option == "--help":
                    continue
                if isinstance(action, Renamed):
                    renamed[option].append((command, action.new))
                else:
                    table[option][_meaning(action)].append(command)
    return table, renamed


def test_every_option_has_one_meaning_across_commands():
    table, _ = _table()
    assert len(table) > 40          # the parsers were read
    split = {option: dict(meanings) for option, meanings in table.items()
             if len(meanings) > 1}
    assert not split


def test_the_table_tells_a_flag_from_a_value():
    # the check can fail: --freq as a flag in one command would split it
    table, _ = _table()
    assert set(table["--freq"]) == {("quantity", "Hz")}
    assert set(table["--pf-max"]) == {("quantity", "bar")}
    assert set(table["--valve-max"]) == {("quantity", "bar")}
    assert set(table["--driveline"]) == {("choice", None)}


def test_former_spellings_name_their_new_one():
    _, renamed = _table()
    assert dict(renamed["--pf-max"]) == {"advise": "--valve-max"}
    assert dict(renamed["--bench-linearisation"]) == {
        "fit": "--driveline bench", "chart": "--driveline bench"}


@pytest.mark.parametrize("args, new", [
    (["advise", "--no-design", "--pf-max", "0.6", "--freq-range", "90:120"],
     "--valve-max"),
])
def test_a_former_spelling_still_works_and_says_the_new_one(args, new):
    old = subprocess.run([sys.executable, "-m", "judder", *args, "--json"],
                         capture_output=True, text=True, timeout=300)
    now = subprocess.run([sys.executable, "-m", "judder",
                          *[new if a == "--pf-max" else a for a in args],
                          "--json"], capture_output=True, text=True,
                         timeout=300)
    assert old.returncode == now.returncode == 0, old.stderr
    assert new in old.stderr and new not in now.stderr
    # the same advice (all but the timing and the provenance)
    old, now = (json.loads(run.stdout) for run in (old, now))
    for data in (old, now):
        del data["seconds"], data["provenance"]
    assert old == now


#: A value the parser reads as a word (a choice, `none`, a preset, a
#: wave's name), not a number, a file, a name of the user's or a list.
KEYWORD = r"[a-z][a-z_]*(?:-[a-z0-9]+)*"
#: Values that are the user's, not the tool's words: parameter names,
#: Modelica classes, files, addresses, channels.
USERS = ("NAMES", "NAME=VALUE", "CLASS", "DIR", "ADDRESS", "FILE")


def _readme_option_values():
    """``(command or None, option, value)`` for every option the README
    gives a word value: in its ``sh`` blocks and in its inline code
    (``judder simulate --compare none``; an inline ``--opt value``
    without its command counts for every command with that option)."""
    import re
    import shlex
    from pathlib import Path
    text = (Path(__file__).parents[1] / "README.md").read_text()
    lines = []
    for block in re.findall(r"^```sh\n(.*?)^```", text, re.S | re.M):
        lines += [line for line in block.splitlines()
                  if line.startswith("judder ")]
    lines += re.findall(r"`([^`\n]*--[a-z][^`\n]*)`", text)
    found = set()
    for line in lines:
        try:
            words = shlex.split(line, comments=True)
        except ValueError:
            continue
        command = words[1] if words[:1] == ["judder"] and len(words) > 1 \
            else None
        for option, value in zip(words, words[1:]):
            if not option.startswith("--"):
                continue
            # square[:TAU_MS], dyson|solve_ivp: each word
            for word in re.split(r"[|:\[\]]", value):
                if re.fullmatch(KEYWORD, word):
                    found.add((command, option, word))
    return found


def test_help_lists_every_option_value_the_readme_uses():
    # `--compare none` in the README must be findable in simulate --help;
    # only the tool's own words count, not a user's names or files
    import re
    parser = build_parser()
    sub = next(a for a in parser._actions if a.dest == "command")
    uses = _readme_option_values()
    assert ("simulate", "--compare", "none") in uses    # the README was read
    missing = []
    checked = 0
    for command, option, value in sorted(uses, key=str):
        commands = [command] if command else list(sub.choices)
        for name in commands:
            subparser = sub.choices.get(name)
            action = None if subparser is None else next(
                (a for a in subparser._actions if option in a.option_strings),
                None)
            if action is None or isinstance(action, Renamed):
                continue
            metavar = action.metavar or ""
            if action.nargs == 0 or any(u in metavar for u in USERS):
                continue
            if _meaning(action)[0] in ("names", "file"):
                continue
            checked += 1
            if not re.search(rf"(?<![\w-]){re.escape(value)}(?![\w-])",
                             subparser.format_help()):
                missing.append(f"judder {name} {option} {value}")
    assert checked > 10
    assert not missing, "values the README uses, not in --help:\n" + \
        "\n".join(missing)
