"""The layers of the project: who may import whom, statically and at run
time, and the driveline registry as the one place that knows each model."""

import ast
import json
import re
import subprocess
import sys
from pathlib import Path

import casadi
import pytest

from drivelines import MODELS
from sources import get_preset
from fmu.frontend import load_flat_model

ROOT = Path(__file__).resolve().parents[1]
LIBRARY = ROOT / "modelica"

#: What each package may import from the project (lower layers only).
ALLOWED = {
    "infra": set(),
    "fmu": {"infra"},
    "drivelines": {"infra", "fmu"},
    "sources": {"infra", "fmu", "drivelines"},
    "stability": {"infra", "drivelines", "sources"},
    "pysim": {"infra", "drivelines", "sources", "fmu"},
    "studies": {"infra", "drivelines", "sources", "stability", "pysim",
                "fmu"},
    "judder": {"infra", "drivelines", "sources", "stability", "pysim",
               "fmu", "studies"},
}

#: What each subpackage of pysim may import of the others: running FMUs
#: makes runs, reading and judging runs (measured or simulated) takes
#: them, and neither knows the other.
PYSIM_ALLOWED = {"simulation": set(), "bench": set()}


def _imported_packages(path):
    """Project packages named by the imports of one file (any depth)."""
    tree = ast.parse(path.read_text())
    names = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            names |= {alias.name.split(".")[0] for alias in node.names}
        elif isinstance(node, ast.ImportFrom) and node.level == 0:
            names.add(node.module.split(".")[0])
        elif isinstance(node, ast.Call) and getattr(
                node.func, "attr", getattr(node.func, "id", "")) in (
                "import_module", "__import__"):
            names |= {arg.value.split(".")[0] for arg in node.args
                      if isinstance(arg, ast.Constant)
                      and isinstance(arg.value, str)}
    return names & set(ALLOWED)


@pytest.mark.parametrize("package", sorted(ALLOWED))
def test_no_import_goes_up_or_sideways(package):
    for path in sorted((ROOT / package).rglob("*.py")):
        used = _imported_packages(path) - {package}
        assert used <= ALLOWED[package], (
            f"{path.relative_to(ROOT)} imports {sorted(used - ALLOWED[package])}")


@pytest.mark.parametrize("package", sorted(set(ALLOWED) - {"judder"}))
def test_importing_a_library_loads_nothing_above_it(package):
    # every module of the package, imported in a fresh interpreter: what
    # it pulls in at run time stays within the allowed layers
    modules = [".".join(p.relative_to(ROOT).with_suffix("").parts)
               for p in sorted((ROOT / package).rglob("*.py"))
               if p.name != "__main__.py"]
    code = ("import importlib, json, sys\n"
            f"for m in {modules!r}: importlib.import_module(m)\n"
            "print(json.dumps(sorted({n.split('.')[0] for n in sys.modules})))")
    loaded = set(json.loads(subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True,
        check=True, cwd=ROOT).stdout))
    forbidden = set(ALLOWED) - ALLOWED[package] - {package}
    assert not loaded & forbidden


@pytest.mark.parametrize("room", sorted(PYSIM_ALLOWED))
def test_pysim_subpackages_import_one_way(room):
    for path in sorted((ROOT / "pysim" / room).rglob("*.py")):
        used = {name.split(".")[1] for name in _absolute_imports(path)
                if name.startswith("pysim.") and name.count(".") >= 1}
        assert used - {room} <= PYSIM_ALLOWED[room], (
            f"{path.relative_to(ROOT)} imports pysim."
            f"{sorted(used - {room} - PYSIM_ALLOWED[room])}")


def test_pysim_has_no_module_outside_its_subpackages():
    loose = [p.name for p in (ROOT / "pysim").glob("*.py")
             if p.name != "__init__.py"]
    assert not loose


def _module_imports(package):
    """``{module: modules of the same package it imports}``, any depth
    (lazy imports inside functions included)."""
    graph = {}
    for path in sorted((ROOT / package).rglob("*.py")):
        parts = path.relative_to(ROOT).with_suffix("").parts
        module = ".".join(parts[:-1] if parts[-1] == "__init__" else parts)
        here = ".".join(parts[:-1])          # the module's package
        used = set()
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ImportFrom):
                base = node.module or ""
                if node.level:
                    anchor = here.rsplit(".", node.level - 1)[0] \
                        if node.level > 1 else here
                    base = f"{anchor}.{base}" if base else anchor
                used.add(base)
                used |= {f"{base}.{alias.name}" for alias in node.names}
            elif isinstance(node, ast.Import):
                used |= {alias.name for alias in node.names}
        graph[module] = used
    return {m: {u for u in used if u in graph and u not in (m, package)}
            for m, used in graph.items()}


@pytest.mark.parametrize("package", sorted(ALLOWED))
def test_no_import_circle_inside_a_package(package):
    # a circle hides which module is the lower one (issue 22: the
    # stability.linear <-> stability.model circle, broken by a lazy import)
    graph = _module_imports(package)

    def reaches(start, goal, seen):
        for nxt in graph[start] - seen:
            if nxt == goal or reaches(nxt, goal, seen | {nxt}):
                return True
        return False
    circles = [m for m in graph if reaches(m, m, set())]
    assert not circles


def test_stability_does_not_import_matplotlib():
    code = "import stability, sys; print('matplotlib' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True,
                         text=True, check=True, cwd=ROOT).stdout
    assert out.strip() == "False"


#: What a plot module may import from the project: the shared look, the
#: names of the kinds and the judder criterion, and other plot modules. A
#: plot draws what its result holds; a kernel it called would compute.
PLOT_IMPORTS = {"stability/plots": ("infra", "stability.kinds",
                                    "stability.decisions.relevance",
                                    "stability.plots"),
                "studies/figures": ("infra", "stability.plots")}


def _absolute_imports(path):
    """Modules one file imports, relative imports made absolute."""
    package = ".".join(path.relative_to(ROOT).parent.parts)
    names = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            names |= {alias.name for alias in node.names}
        elif isinstance(node, ast.ImportFrom):
            base = package.rsplit(".", node.level - 1)[0] if node.level \
                else ""
            names.add(".".join(filter(None, [base, node.module])))
    return names


@pytest.mark.parametrize("folder", sorted(PLOT_IMPORTS))
def test_plots_import_no_kernel(folder):
    for path in sorted((ROOT / folder).glob("*.py")):
        project = {name for name in _absolute_imports(path)
                   if name.split(".")[0] in ALLOWED}
        for name in project:
            assert any(name == allowed or name.startswith(allowed + ".")
                       for allowed in PLOT_IMPORTS[folder]), \
                f"{path.relative_to(ROOT)} imports {name}"


#: Calls that make a figure or axes: a command or a study delegates them
#: to studies/figures or stability/plots.
DRAWING_CALLS = {"subplots", "subplot", "figure", "add_subplot", "add_axes",
                 "subplot_mosaic"}


def _drawing_calls(path):
    """``plt.subplots(...)``-like calls of one file: on ``plt``/``pyplot``
    any of :data:`DRAWING_CALLS`, on anything ``add_subplot``/``add_axes``."""
    found = []
    for node in ast.walk(ast.parse(path.read_text())):
        if not (isinstance(node, ast.Call)
                and isinstance(node.func, ast.Attribute)
                and node.func.attr in DRAWING_CALLS):
            continue
        owner = node.func.value
        if (isinstance(owner, ast.Name) and owner.id in ("plt", "pyplot")) \
                or node.func.attr in ("add_subplot", "add_axes"):
            found.append(f"{path.relative_to(ROOT)}:{node.lineno}")
    return found


def test_no_command_or_study_draws_its_own_figure():
    drawn = [call for folder in ("judder/commands", "studies")
             for path in sorted((ROOT / folder).glob("*.py"))
             for call in _drawing_calls(path)]
    assert not drawn
    # the check sees a figure drawn where figures live
    assert _drawing_calls(ROOT / "studies" / "figures" / "threshold.py")


@pytest.mark.parametrize("folder, mention", [
    ("infra", ":mod:`infra.{}`"), ("judder/commands", "``{}``")])
def test_package_docstring_names_every_shared_module(folder, mention):
    # infra lists all its modules; judder.commands its shared _-modules
    doc = ast.get_docstring(ast.parse((ROOT / folder / "__init__.py")
                                      .read_text()))
    modules = [path.stem for path in sorted((ROOT / folder).glob("*.py"))
               if path.stem != "__init__"
               and (folder == "infra" or path.stem.startswith("_"))]
    assert modules
    missing = [m for m in modules if mention.format(m) not in doc]
    assert not missing
    named = set(re.findall(r"``(_[a-z_]+)``", doc)) if folder != "infra" \
        else set(re.findall(r":mod:`infra\.([a-z_]+)`", doc))
    assert named <= set(modules), named - set(modules)


def test_no_model_name_branches_outside_the_registry():
    # knowledge of each driveline lives in drivelines/registry.py only
    for package in ALLOWED:
        for path in (ROOT / package).rglob("*.py"):
            if path == ROOT / "drivelines" / "registry.py":
                continue
            text = path.read_text()
            for name in MODELS:
                assert f'== "{name}"' not in text and \
                    f'!= "{name}"' not in text, path


@pytest.mark.parametrize("model", sorted(MODELS))
def test_presets_match_the_modelica_defaults(model):
    # the Appendix values are written twice (Python presets, .mo files):
    # every default of the Modelica class equals the preset's value
    entry = MODELS[model]
    preset = get_preset(entry.default_preset)
    classes = [entry.modelica_class] + (
        [entry.bench_class] if entry.bench_class else [])
    for name in classes:
        source = LIBRARY.joinpath(*name.split(".")).with_suffix(".mo")
        flat = load_flat_model(source, name, roots=[LIBRARY])
        defaults = {v.name: float(casadi.evalf(v.binding))
                    for v in flat.by_role("parameter")
                    if v.binding is not None and casadi.SX(v.binding).is_constant()}
        for parameter, value in preset.values.items():
            assert parameter in defaults, f"{name} lacks {parameter}"
            assert defaults[parameter] == pytest.approx(value, rel=1e-12), \
                f"{name}.{parameter}"


@pytest.mark.parametrize("model", sorted(MODELS))
def test_registry_topology_is_the_modelica_one(model):
    # the bodies the registry names are inertias of the Modelica class,
    # and the signals it promises are its outputs
    entry = MODELS[model]
    source = LIBRARY.joinpath(*entry.modelica_class.split(".")) \
        .with_suffix(".mo")
    flat = load_flat_model(source, entry.modelica_class, roots=[LIBRARY])
    names = {v.name for v in flat.variables}
    for body in entry.bodies:
        assert f"{body.instance}.w" in names
        assert f"{body.instance}.J" in names
    outputs = {v.name for v in flat.by_role("output")}
    assert set(entry.signals) <= outputs
    assert set(entry.free_response_speeds) <= names


# -- the application layer: one room per command ------------------------

#: Who may import whom inside judder (module prefixes): the command line
#: over the registry, the commands over their shared private modules and
#: the studies, the API facade over the studies alone.
JUDDER_ROOMS = {
    "judder.__main__": {"judder.cli"},
    "judder.cli": {"judder.commands"},     # and, lazily, its _-modules
    "judder.api": {"studies"},
    "judder.commands._": {"judder.commands._", "studies."},
    "judder.commands.": {"judder.commands.", "studies."},
}


def _room(module):
    return next(prefix for prefix in JUDDER_ROOMS
                if module == prefix or module.startswith(prefix))


def test_judder_modules_import_only_the_rooms_below_them():
    graph = _module_imports("judder")
    for module, used in graph.items():
        if module in ("judder", "judder.commands"):
            assert not used, f"{module} imports {used}"
            continue
        allowed = JUDDER_ROOMS[_room(module)]
        for name in used:
            assert any(name == a or name.startswith(a) for a in allowed), \
                f"{module} imports {name}"
        if _room(module) == "judder.commands._":
            # the shared modules know no command
            assert all(n.split(".")[-1].startswith("_") for n in used
                       if n.startswith("judder.commands.")), module


#: A command-line option in a string: ``--name``.
OPTION = re.compile(r"(?<![\w-])--[a-z][a-z0-9-]*")
#: Library modules that are command lines themselves.
COMMAND_LINES = {"fmu/__main__.py"}
#: Modules that call another program with its own command line (Chromium).
OTHER_PROGRAMS = {"infra/pdf.py"}


def _strings_outside_docstrings(path):
    """``(line, text)`` of every string constant of a file (the literal
    parts of f-strings included) but its docstrings."""
    tree = ast.parse(path.read_text())
    documented = (ast.Module, ast.FunctionDef, ast.AsyncFunctionDef,
                  ast.ClassDef)
    docstrings = {id(node.body[0].value) for node in ast.walk(tree)
                  if isinstance(node, documented) and node.body
                  and isinstance(node.body[0], ast.Expr)
                  and isinstance(node.body[0].value, ast.Constant)}
    return [(node.lineno, node.value) for node in ast.walk(tree)
            if isinstance(node, ast.Constant) and isinstance(node.value, str)
            and id(node) not in docstrings]


def test_the_option_scan_sees_options_in_messages(tmp_path):
    module = tmp_path / "m.py"
    module.write_text('"""Docs may say --pf."""\nx = 1\n'
                      'raise ValueError(f"--fmu {x}: bad")\n'
                      'y = "`path` --> a-- b"\n')
    found = [(line, OPTION.findall(text))
             for line, text in _strings_outside_docstrings(module)]
    assert [f for f in found if f[1]] == [(3, ["--fmu"])]


@pytest.mark.parametrize("package", sorted(set(ALLOWED) - {"judder"}))
def test_no_library_module_names_a_command_line_option(package):
    # a library names its own arguments (`scatter`); judder.commands._flags
    # maps them to the options of the command line
    for path in sorted((ROOT / package).rglob("*.py")):
        relative = path.relative_to(ROOT).as_posix()
        if relative in COMMAND_LINES | OTHER_PROGRAMS:
            continue
        for line, text in _strings_outside_docstrings(path):
            assert not OPTION.search(text), f"{relative}:{line}: {text!r}"


def test_library_arguments_become_options_on_the_command_line():
    from judder.commands._flags import in_flags
    assert in_flags("fit fewer parameters (`names`), or give the bench's "
                    "known scatter (`scatter`); `seed`") == (
        "fit fewer parameters (--fit), or give the bench's known scatter "
        "(--scatter); `seed`")


def test_the_registry_is_the_one_place_a_command_is_added():
    from judder import api
    from judder.cli import build_parser
    from judder.commands import COMMANDS, command_module
    from studies import study
    modules = {p.stem for p in (ROOT / "judder" / "commands").glob("*.py")
               if not p.stem.startswith("_")}
    assert modules == set(COMMANDS)
    for name, command in COMMANDS.items():
        module = command_module(name)
        assert isinstance(module.DESCRIPTION, str) and module.DESCRIPTION
        assert all(len(output) == 3 for output in module.OUTPUTS)
        assert callable(module.add_arguments) and callable(module.run)
        assert getattr(api, command.function) is study(command.function)
    parser = build_parser()
    sub = next(a for a in parser._actions if a.dest == "command")
    assert list(sub.choices) == list(COMMANDS)
    assert sorted(api.__all__) == sorted(c.function
                                         for c in COMMANDS.values())
    # no table or branch keyed by the command's name outside its module
    for path in (ROOT / "judder").rglob("*.py"):
        assert "args.command" not in path.read_text(), path


def test_help_imports_no_command_and_nothing_numerical():
    code = ("import sys\n"
            "from judder.cli import build_parser\n"
            "build_parser(())\n"
            "print(sorted(m for m in sys.modules if m.startswith("
            "('numpy', 'judder.commands.'))))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True,
                         text=True, check=True, cwd=ROOT).stdout
    assert out.strip() == "[]"


def test_only_command_lines_import_argparse():
    # the studies and everything below them take Python arguments: no
    # module outside judder/commands, judder/cli and fmu's own command
    # line parses options
    for package in ALLOWED:
        for path in sorted((ROOT / package).rglob("*.py")):
            relative = path.relative_to(ROOT).as_posix()
            if relative in COMMAND_LINES or relative == "judder/cli.py" \
                    or relative.startswith("judder/commands/"):
                continue
            assert "argparse" not in _absolute_imports(path), relative


def test_the_api_runs_without_the_command_line():
    # scipy.linalg and matplotlib load argparse themselves (through
    # unittest.main), so it is imported first and then barred: a project
    # module that imported it now would fail
    code = (
        "import sys, importlib.abc\n"
        "import scipy.linalg, scipy.optimize, scipy.integrate\n"
        "import matplotlib.pyplot\n"
        "class Bar(importlib.abc.MetaPathFinder):\n"
        "    def find_spec(self, name, path, target=None):\n"
        "        if name.split('.')[0] in ('argparse', 'judder.commands'):\n"
        "            raise ImportError(name + ' barred')\n"
        "sys.modules.pop('argparse')\n"
        "sys.meta_path.insert(0, Bar())\n"
        "from judder import api\n"
        "check = api.check([102.9], [0.3], driveline='chain')\n"
        "grid = api.stability_map([100.0, 102.9], [0.0, 0.3])\n"
        "freqs = [100.0, 102.9, 106.0]\n"
        "onset = api.tongues(freqs, 1.0).boundaries.stability_boundary\n"
        "fit = api.fit(freqs, onset / 1e5, 1.0, names=['mu_g'], "
        "min_growth=0.0, starts=1, uncertainty='jacobian')\n"
        "print(check.records()[0]['kind'], fit.fit.success, sorted(\n"
        "    m for m in sys.modules if m == 'argparse'\n"
        "    or m.startswith(('judder.commands', 'judder.cli'))))\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True,
                         text=True, cwd=ROOT)
    assert out.returncode == 0, out.stderr[-2000:]
    assert out.stdout.split() == ["single-period", "True", "[]"]
