"""The Modelica library: MSL conventions, and an independent front end.

rumoca (a Modelica compiler independent of this project) parses and
flattens every example, checks it is balanced, and simulates the 4-DOF
model with its own solver; the result must be Eq. (1) as the stability
layer writes it, and the sensors must read what the bodies and the
clutch do. The source itself is checked for what a graphical Modelica
tool needs: documentation, icons, placements and connection lines that
end on their connectors.
"""

import math
import re
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from sources import get_preset
from stability import build_driveline

rumoca = pytest.importorskip("rumoca")

LIBRARY = Path(__file__).resolve().parents[1] / "modelica"
PACKAGE = LIBRARY / "Judder"
EXAMPLES = ["Driveline4DOF", "Driveline3DOF", "TestBenchEngagement"]
#: Examples wire the 4-DOF chain once, in PartialDriveline4DOF, and
#: extend it: an example's diagram (instances, connections, outputs) is
#: that of its file and of the files of the examples it extends.
# rumoca counts as a state every variable that appears under der() and
# does not reduce the index: besides the angle and speed of each body
# (8, 6, 8) it keeps the relative angle phi_rel of every compliant
# component (spring-dampers, dampers, clutches: 7, 5, 8) and of the
# relative speed sensor, the flange angle of the two speed sensors, and on
# the bench the flange angle of the motor. All of these are fixed by the
# bodies' angles; the project's back end (fmu/) reduces the index and
# keeps the bodies' 8, 6 and 8 states (tests/test_fmu_backend.py).
STATES = {"Driveline4DOF": 8 + 7 + 3, "Driveline3DOF": 6 + 5 + 3,
          "TestBenchEngagement": 8 + 8 + 3 + 1,
          "TestBenchLockUp": 8 + 8 + 3 + 1 + 4,
          "TestBenchCurveLockUp": 8 + 8 + 3 + 1 + 4}
# the bench with its EVEN clutch redeclared as LockingWetClutch (straight
# line) or LockingCurveWetClutch (the bench's curve): rumoca also keeps
# the clutch's relative speed (under der() in the stuck branch) and the
# three mode states of Interfaces.PartialLockingClutch
MODE_STATES = dict.fromkeys(
    ["TestBenchLockUp", "TestBenchCurveLockUp"],
    {"clutch.w_rel", "clutch.lockups", "clutch.breakaways", "clutch.sense"})


@pytest.fixture(scope="module")
def session():
    return rumoca.Session(roots=[str(LIBRARY)])


def _load(session, name):
    return session.load(str(PACKAGE / "Examples" / f"{name}.mo"),
                        model=f"Judder.Examples.{name}")


@pytest.mark.parametrize("name", EXAMPLES + ["TestBenchLockUp",
                                             "TestBenchCurveLockUp"])
def test_example_is_valid_and_balanced(session, name):
    path = PACKAGE / "Examples" / f"{name}.mo"
    assert rumoca.validate(str(path), model=f"Judder.Examples.{name}") == []
    model = _load(session, name)
    info = model.structure()
    assert info.is_balanced and info.is_matched
    assert info.n_equations == info.n_unknowns
    assert info.n_states == STATES[name]
    # the states beyond the bodies' are relative angles and sensor or
    # motor flange angles, which the back end eliminates, and the modes
    extra = [s.name for s in model.states
             if not re.fullmatch(r"inertia\d+\.(phi|w)", s.name)]
    modes = MODE_STATES.get(name, set())
    assert modes <= set(extra)
    assert all(s.endswith(".phi_rel") or s.endswith("flange.phi")
               or s in modes for s in extra), extra


@pytest.mark.parametrize("folder", sorted(p for p in PACKAGE.rglob("*")
                                          if p.is_dir()) + [PACKAGE])
def test_package_order_lists_every_class(folder):
    listed = (folder / "package.order").read_text().split()
    present = sorted(p.stem for p in folder.glob("*.mo")
                     if p.name != "package.mo")
    present += sorted(p.name for p in folder.iterdir() if p.is_dir())
    assert sorted(listed) == sorted(present)


@pytest.mark.parametrize("path", sorted(PACKAGE.rglob("*.mo")),
                         ids=lambda p: p.stem)
def test_parameters_are_typed_bounded_and_described(path):
    for statement in _code(path).split(";"):
        found = re.search(r"\bparameter .*", " ".join(statement.split()))
        if found is None:
            continue
        declaration = found.group()
        assert '"' in declaration, f"{path.name}: no description: " \
            + declaration
        # a plain Real needs a bound (counts such as N_c)
        assert not re.match(r"parameter Real \w+\s*=", declaration), \
            f"{path.name}: untyped, unbounded parameter: {declaration}"


@pytest.mark.parametrize("name", EXAMPLES)
def test_examples_declare_outputs_and_experiment(name):
    text = (PACKAGE / "Examples" / f"{name}.mo").read_text()
    assert re.search(r"experiment\(StopTime=[\d.]+, Interval=[\d.e-]+\)",
                     text)
    outputs = [found for path in _example_files(name) for found in
               re.findall(r"output Units\.(\w+) (\w+)=", path.read_text())]
    assert len(outputs) == 5
    assert {o[1] for o in outputs} == {"w_upstream", "w_downstream", "slip",
                                       "clutch_torque", "actuation_pressure"}


def test_4dof_modelica_model_is_eq1(session):
    # a stable point (60 Hz, 0.3 bar), so the slip stays far from zero and
    # the clutch's smooth sign function is exactly 1
    model = _load(session, "Driveline4DOF")
    result = model.simulate(t=(0.0, 1.0), dt=1e-3,
                            params={"f_dither": 60.0, "p_f": 0.3e5},
                            config=rumoca.SimConfig(rtol=1e-10, atol=1e-10))
    names, data = list(result.names), np.asarray(result.to_numpy())
    time = np.asarray(result.time)

    params = get_preset("paper-4dof")
    driveline = build_driveline(params)
    torque = params["mu0"] * params.clutch_factor * params["p_m"]
    w_in = 1000 * 2 * np.pi / 60
    x0 = [0.0, -torque / 3856, -torque / 3856 - torque / 32885, 0.0,
          w_in, w_in, w_in, 0.0]

    def eq1(t, x):
        return (driveline.state_matrix(t, 60.0, 0.3e5) @ x
                + driveline.state_forcing(t, 60.0, 0.3e5,
                                          engine_torque=torque,
                                          resistant_torque=torque))
    reference = solve_ivp(eq1, (0.0, 1.0), x0, method="DOP853", rtol=1e-12,
                          atol=1e-12, t_eval=time)
    for name, row in [("inertia1.w", 4), ("inertia2.w", 5),
                      ("inertia4.w", 6), ("inertia3.w", 7),
                      ("inertia2.phi", 1)]:
        got = data[names.index(name)]
        scale = np.abs(reference.y[row]).max()
        assert np.abs(got - reference.y[row]).max() < 1e-5 * scale, name


# --- the source as a graphical Modelica tool reads it ----------------------

_STRING = re.compile(r'"(?:[^"\\]|\\.)*"', re.S)
_CLASS = re.compile(r"^\s*(?:partial\s+)?(package|model|block|connector|"
                    r"record|function|class|type)\s+(\w+)", re.M)
_NUMBER = r"[-+]?\d+(?:\.\d*)?(?:[eE][-+]?\d+)?"
#: classes with an icon; the connectors need one without the %name label
DRAWN = ["Components", "Sources", "Sensors"]
CONNECTORS = ["Flange_a", "Flange_b", "RealInput", "RealOutput"]
#: the paper's equation, figure or section each class must cite
CITES = {"PartialWetClutch": "Eq. (3)-(5)", "SlippingClutch": "Eq. (3)-(5)",
         "WetClutch": "Eq. (3)-(5)", "DitherPressure": "Eq. (4)",
         "Inertia": "Eq. (1)", "SpringDamper": "Eq. (2)",
         "Damper": "Eq. (2)", "ConstantTorque": "Eq. (1)",
         "SpeedDrive": "section 2.2", "TorqueSensor": "Eq. (3)",
         "RelSpeedSensor": "Eq. (5)", "SpeedSensor": "Eq. (5)",
         "Driveline4DOF": "Fig. 13", "Driveline3DOF": "Fig. 12",
         "TestBenchEngagement": "section 2.2"}


def _code(path):
    """The Modelica text of a file with every string literal emptied."""
    return _STRING.sub('""', Path(path).read_text())


def _class_files():
    return sorted(PACKAGE.rglob("*.mo"))


def _class_name(path):
    return path.parent.name if path.name == "package.mo" else path.stem


@pytest.mark.parametrize("path", _class_files(),
                         ids=lambda p: str(p.relative_to(PACKAGE)))
def test_every_class_is_documented(path):
    # one class per file (the unit types of Units.mo aside, which carry a
    # description string as in Modelica.Units.SI); its annotation, the
    # last element of the class, holds Documentation(info="<html>...")
    name = _class_name(path)
    classes = [c for c in _CLASS.findall(_code(path)) if c[0] != "type"]
    assert [c[1] for c in classes] == [name]
    text = path.read_text()
    found = re.findall(r'Documentation\(info="(.*?)"\)', text, re.S)
    assert len(found) == 1, f"{path.name}: one Documentation annotation"
    info = found[0]
    assert info.startswith("<html>") and info.endswith("</html>")
    assert re.search(r"<p>\s*\w", info), "a paragraph of text"
    assert len(re.sub(r"<[^>]+>", "", info).split()) >= 15, "says something"
    # the annotation closes a short class definition (connector X = ...)
    # or comes just before the end of a long one
    short = re.search(rf"\b{name}\s*=", _code(path))
    tail = text[text.index("Documentation(info="):]
    assert re.fullmatch(r'Documentation\(info=".*?"\)\);\s*'
                        + ("" if short else rf"end {name};\s*"), tail,
                        re.S), f"{path.name}: not the class annotation"
    if name in CITES:
        assert CITES[name] in info, f"{name} should cite {CITES[name]}"


def _icon_classes():
    drawn = [p for folder in DRAWN for p in sorted((PACKAGE / folder).glob(
        "*.mo")) if p.name != "package.mo"]
    return drawn + [PACKAGE / "Interfaces" / f"{c}.mo" for c in CONNECTORS]


def _enclosed(text, start):
    """The text between the bracket at ``start`` and its partner."""
    pairs = {"(": ")", "{": "}"}
    depth, opening = 0, text[start]
    for index in range(start, len(text)):
        if text[index] == opening:
            depth += 1
        elif text[index] == pairs[opening]:
            depth -= 1
            if depth == 0:
                return text[start + 1:index]
    raise ValueError(f"unbalanced {opening!r} at {start}")


def _bases(path):
    """Files of the classes a library class extends, directly or not
    (``Interfaces.PartialWetClutch``, ``Icons.Clutch``, a sibling)."""
    found = []
    for base in re.findall(r"\bextends\s+([\w.]+)", _code(path)):
        parts = base.split(".")
        candidates = [PACKAGE.joinpath(*parts).with_suffix(".mo"),
                      path.parent.joinpath(*parts).with_suffix(".mo")]
        for candidate in candidates:
            if candidate.exists():
                found += [candidate] + _bases(candidate)
                break
    return found


def _graphics(path):
    """The graphic primitives of a class's own icon (empty without)."""
    text = path.read_text()
    if "Icon(" not in text:
        return ""
    icon = _enclosed(text, text.index("Icon(") + len("Icon"))
    assert re.match(r"coordinateSystem\(.*extent=\{\{-100,-100\},"
                    r"\{100,100\}\}", icon)
    return _enclosed(icon, icon.index("graphics={") + len("graphics="))


@pytest.mark.parametrize("path", _icon_classes(), ids=lambda p: p.stem)
def test_components_sources_sensors_and_connectors_have_icons(path):
    # a class draws its own icon on top of those of the classes it
    # extends (Icons.Clutch), as in MSL
    assert path.read_text().count("Icon(") == 1, \
        f"{path.name}: one Icon annotation"
    graphics = _graphics(path)
    primitives = re.findall(r"\b(Line|Rectangle|Ellipse|Polygon|Text)\(",
                            "".join([graphics] + [_graphics(base) for base
                                                  in _bases(path)]))
    assert primitives, f"{path.name}: an empty icon"
    if path.stem not in CONNECTORS:
        assert 'textString="%name"' in graphics
        assert len(primitives) >= 3


PRESSURE_INPUT = "RealInput p(unit=\"Pa\")"


def test_every_pressure_clutch_extends_one_partial_and_one_icon():
    # the clutches with a pressure input are the components that extend
    # Interfaces.PartialPressureClutch; it alone declares the plate pack
    # and the input, and only Icons.Clutch draws the plates
    clutches = [p for p in sorted((PACKAGE / "Components").glob("*.mo"))
                if "Clutch" in p.stem]
    assert len(clutches) == 8
    partial = PACKAGE / "Interfaces" / "PartialPressureClutch.mo"
    icon = PACKAGE / "Icons" / "Clutch.mo"
    for path in clutches:
        assert partial in _bases(path), path.stem
        assert icon in _bases(path), path.stem
    plates = "Rectangle(extent={{-30,60},{-10,-60}}"
    for path in PACKAGE.rglob("*.mo"):
        code = _code(path)
        assert (plates in code) == (path == icon), path.name
        assert (PRESSURE_INPUT in path.read_text()) == (path == partial), \
            path.name
        assert (re.search(r"parameter Real N_c\b", code) is not None) == (
            path in (partial, PACKAGE / "Data" / "ClutchData.mo")), path.name


#: each friction law and the locking modes, written once: the partial
#: that holds the equation, by a fragment of it that no other file has
WRITTEN_ONCE = {
    "mu_g*slip*(p - (1 - mean_pressure_damping)*p_mean)": "PartialWetClutch",
    "delta_mu*tanh(mu_g*(noEvent(abs(slip)) - w_op)/delta_mu)":
        "PartialCurveWetClutch",
    "reinit(lockups, pre(lockups) + 1)": "PartialLockingClutch",
    "reinit(breakaways, pre(breakaways) + 1)": "PartialLockingClutch",
    "*(w_table - mu_pos[i, 1])/(mu_pos[i + 1, 1] - mu_pos[i, 1])":
        "PartialFrictionTable"}


@pytest.mark.parametrize("fragment, owner", WRITTEN_ONCE.items())
def test_friction_laws_and_locking_modes_are_written_once(fragment, owner):
    # the locking clutches combine a law and the modes by extending both
    # partials (as MSL's Clutch extends PartialFriction): no equation of
    # either is copied into a component
    holders = [p.stem for p in PACKAGE.rglob("*.mo") if fragment in _code(p)]
    assert holders == [owner]
    for locking, law in (("LockingWetClutch", "PartialWetClutch"),
                         ("LockingCurveWetClutch", "PartialCurveWetClutch")):
        bases = _bases(PACKAGE / "Components" / f"{locking}.mo")
        assert PACKAGE / "Interfaces" / f"{law}.mo" in bases, locking
        assert PACKAGE / "Interfaces" / "PartialLockingClutch.mo" in bases


def _declarations(path, types):
    """(type, instance name, statement) of each declaration of one of
    ``types`` (regular expression of the type name) in a .mo file."""
    found = []
    for statement in _code(path).split(";"):
        # the first declaration of a class follows its header
        statement = re.sub(r"^\s*(?:partial\s+)?(?:model|block|connector)"
                           r"\s+\w+\s*(?:\"\")?", "", statement)
        match = re.match(r"\s*(?:input |output |replaceable )?("
                         + types + r")\s+(\w+)", statement)
        if match:
            found.append((match.group(1), match.group(2), statement))
    return found


@pytest.mark.parametrize("path", sorted(PACKAGE.rglob("*.mo")),
                         ids=lambda p: str(p.relative_to(PACKAGE)))
def test_connectors_in_classes_are_placed(path):
    for kind, name, statement in _declarations(
            path, r"(?:Interfaces\.)?(?:" + "|".join(CONNECTORS) + ")"):
        assert re.search(r"annotation\s*\(Placement\(transformation\(",
                         statement), f"{path.name}: {name} has no Placement"


def _transformation(statement):
    """extent, origin and rotation of a Placement annotation."""
    body = re.search(r"Placement\(transformation\((.*?)\)\)", statement,
                     re.S).group(1)
    extent = re.search(r"extent=\{\{(N),(N)\},\{(N),(N)\}\}".replace(
        "N", _NUMBER), body)
    origin = re.search(r"origin=\{(N),(N)\}".replace("N", _NUMBER), body)
    rotation = re.search(r"rotation=(" + _NUMBER + ")", body)
    return ([float(v) for v in extent.groups()],
            [float(v) for v in origin.groups()] if origin else [0.0, 0.0],
            float(rotation.group(1)) if rotation else 0.0)


def _place(point, transformation):
    """A point of a class's icon (-100..100) in its parent's diagram."""
    (x1, y1, x2, y2), (ox, oy), rotation = transformation
    x = (x1 + x2) / 2 + (x2 - x1) / 200 * point[0]
    y = (y1 + y2) / 2 + (y2 - y1) / 200 * point[1]
    angle = math.radians(rotation)
    return (round(x * math.cos(angle) - y * math.sin(angle) + ox, 9),
            round(x * math.sin(angle) + y * math.cos(angle) + oy, 9))


def _connector_positions(class_name):
    """Centres of the connectors of a class (``Components.Inertia``), with
    those it inherits, in its icon coordinates."""
    path = PACKAGE.joinpath(*class_name.split(".")).with_suffix(".mo")
    positions = {}
    for base in re.findall(r"\bextends\s+([\w.]+)", _code(path)):
        base = base if "." in base else f"{class_name.split('.')[0]}.{base}"
        positions.update(_connector_positions(base))
    for _, name, statement in _declarations(
            path, r"(?:Interfaces\.)?(?:" + "|".join(CONNECTORS) + ")"):
        positions[name] = _place((0, 0), _transformation(statement))
    return positions


def _example_files(name):
    """The file of an example and those of the examples it extends, the
    most basic first."""
    path = PACKAGE / "Examples" / f"{name}.mo"
    bases = re.findall(r"\bextends\s+(\w+)\b", _code(path))
    return [base for b in bases if (PACKAGE / "Examples" / f"{b}.mo").exists()
            for base in _example_files(b)] + [path]


def _example(name):
    """Instances (name -> (type, transformation)), connections
    ((a, b, line points)) and output bindings of an example, with those
    it inherits. An instance of a replaceable model (``Clutch clutch``)
    has the class last bound to it (``redeclare model Clutch = ...``)."""
    instances, connections, bindings, classes = {}, [], {}, {}
    for path in _example_files(name):
        classes.update(re.findall(r"(?:replaceable|redeclare) model (\w+)"
                                  r"\s*=\s*([\w.]+)", _code(path)))
        for kind, instance, statement in _declarations(
                path, r"(?:Components|Sources|Sensors)\.\w+|"
                + "|".join(classes or ["(?!)"])):
            assert "Placement(transformation(" in statement, \
                f"{name}: {instance} has no Placement"
            instances[instance] = (kind, _transformation(statement))
        for a, b, annotation in re.findall(
                r"connect\(([\w.]+),\s*([\w.]+)\)\s*(annotation\s*\(Line\("
                r"points=\{[^;]*?\}\)?[^;]*?\))?;", _code(path)):
            points = [(float(x), float(y)) for x, y in re.findall(
                r"\{(N),(N)\}".replace("N", _NUMBER), annotation)]
            connections.append((a, b, points))
        bindings.update(re.findall(r"output Units\.\w+ (\w+)=([^\"]+?)\s*\"",
                                   path.read_text()))
    instances = {instance: (classes.get(kind, kind), transformation)
                 for instance, (kind, transformation) in instances.items()}
    return instances, connections, bindings


@pytest.mark.parametrize("name", EXAMPLES)
def test_every_instance_of_the_examples_is_placed(session, name):
    instances, _, _ = _example(name)
    # every component of the flat model, as rumoca sees it, is declared
    # with a Placement
    flat = _load(session, name).to_dict()["storage"]["variables"]
    components = {v["name"].split(".")[0] for v in flat if "." in v["name"]}
    assert components == set(instances)


# the driveline from left to right in each diagram
CHAINS = {
    "Driveline4DOF": ["engine", "inertia1", "damper12", "inertia2",
                      "shaft24", "inertia4", "clutch", "torqueSensor",
                      "inertia3", "load"],
    "Driveline3DOF": ["engine", "inertia1", "damper", "inertia24", "clutch",
                      "torqueSensor", "inertia3", "load"],
    "TestBenchEngagement": ["motor", "inertia1", "damper12", "inertia2",
                            "shaft24", "inertia4", "clutch", "torqueSensor",
                            "inertia3", "rev"],
}


@pytest.mark.parametrize("name", EXAMPLES)
def test_diagram_lines_end_on_their_connectors(name):
    instances, connections, _ = _example(name)
    assert connections
    for a, b, points in connections:
        assert len(points) >= 2, f"{name}: connect({a}, {b}) has no Line"
        ends = []
        for reference in (a, b):
            instance, connector = reference.split(".")
            kind, transformation = instances[instance]
            local = _connector_positions(kind)[connector]
            ends.append(_place(local, transformation))
        assert (points[0], points[-1]) == tuple(ends), \
            f"{name}: the line of connect({a}, {b}) misses its connectors"
        # horizontal and vertical segments only
        for (x1, y1), (x2, y2) in zip(points, points[1:]):
            assert x1 == x2 or y1 == y2, f"{name}: connect({a}, {b})"
    centres = [_place((0, 0), instances[i][1]) for i in CHAINS[name]]
    assert [c[1] for c in centres] == [0.0] * len(centres)
    assert all(x1 < x2 for (x1, _), (x2, _) in zip(centres, centres[1:]))
    # the chain of the driveline is the one the connections make
    linked = {frozenset((a.split(".")[0], b.split(".")[0]))
              for a, b, _ in connections}
    for left, right in zip(CHAINS[name], CHAINS[name][1:]):
        assert frozenset((left, right)) in linked, (left, right)


# --- the outputs come from sensors -------------------------------------------

# the clutch whose quantities the outputs report, the body on each side
# and the source of its pressure
CLUTCHES = {"Driveline4DOF": ("clutch", "inertia4", "inertia3", "pressure"),
            "Driveline3DOF": ("clutch", "inertia24", "inertia3", "pressure"),
            "TestBenchEngagement": ("clutch", "inertia4", "inertia3",
                                    "pressure")}


@pytest.mark.parametrize("name", EXAMPLES)
def test_outputs_are_bound_to_sensors(name):
    instances, connections, bindings = _example(name)
    clutch, upstream, downstream, pressure = CLUTCHES[name]
    connected = {frozenset((a, b)) for a, b, _ in connections}

    def sensor(expression, kind, signal):
        found = re.fullmatch(r"(-?)(\w+)\." + signal, expression)
        assert found, f"{name}: {expression} is not {kind}.{signal}"
        assert instances[found.group(2)][0] == f"Sensors.{kind}"
        return found.group(1), found.group(2)

    for output, body in (("w_upstream", upstream),
                         ("w_downstream", downstream)):
        sign, speed = sensor(bindings[output], "SpeedSensor", "w")
        assert sign == ""
        assert {frozenset((f"{speed}.flange", f"{body}.{side}"))
                for side in ("flange_a", "flange_b")} & connected, output
    # slip = flange_a speed - flange_b speed of the clutch, and the
    # sensor's w_rel is flange_b minus flange_a
    sign, relative = sensor(bindings["slip"], "RelSpeedSensor", "w_rel")
    assert sign == "-"
    for side in ("flange_a", "flange_b"):
        assert frozenset((f"{relative}.{side}", f"{clutch}.{side}")) \
            in connected
    # the torque sensor sits between the clutch and the downstream body
    sign, torque = sensor(bindings["clutch_torque"], "TorqueSensor", "tau")
    assert sign == ""
    assert frozenset((f"{clutch}.flange_b", f"{torque}.flange_a")) \
        in connected
    assert frozenset((f"{torque}.flange_b", f"{downstream}.flange_a")) \
        in connected
    assert not any(f"{clutch}.flange_b" in pair and
                   any(p.startswith(f"{downstream}.") for p in pair)
                   for pair in connected), "a path that bypasses the sensor"
    assert bindings["actuation_pressure"] == f"{pressure}.p"
    assert frozenset((f"{pressure}.p", f"{clutch}.p")) in connected
    # nothing else is read from the components' internals
    for output, expression in bindings.items():
        if output != "actuation_pressure":
            assert instances[expression.lstrip("-").split(".")[0]][0] \
                .startswith("Sensors."), output


def test_sensors_read_the_bodies_and_the_clutch(session):
    # rumoca's own simulation of the 4-DOF model at the default point
    # (102.9 Hz, 0.3 bar: inside the tongue, the oscillation grows)
    model = _load(session, "Driveline4DOF")
    result = model.simulate(t=(0.0, 1.0), dt=1e-3,
                            config=rumoca.SimConfig(rtol=1e-10, atol=1e-10))
    names, data = list(result.names), np.asarray(result.to_numpy())
    signal = dict(zip(names, data))
    w4, w3 = signal["inertia4.w"], signal["inertia3.w"]
    p, p_mean = signal["pressure.p"], signal["pressure.p_mean"]
    friction = 8 * 0.075 * 0.01 * (0.09 * p + 0.017 * (w4 - w3)
                                   * (p - p_mean))
    assert np.ptp(w4 - w3) > 1.0    # a real oscillation, not a constant
    for got, want in [("speedUpstream.w", w4), ("w_upstream", w4),
                      ("speedDownstream.w", w3), ("w_downstream", w3),
                      ("slipSensor.w_rel", w3 - w4), ("slip", w4 - w3),
                      ("slip", signal["clutch.slip"]),
                      ("torqueSensor.tau", friction),
                      ("clutch_torque", friction),
                      ("clutch_torque", signal["clutch.tau_c"]),
                      ("actuation_pressure", p)]:
        error = np.abs(signal[got] - want).max() / np.abs(want).max()
        assert error < 1e-6, f"{got}: {error:.2e}"


@pytest.mark.parametrize("name", EXAMPLES)
def test_compiled_outputs_are_the_sensed_body_quantities(name):
    # the project's compiler (rumoca front end, fmu back end) removes the
    # sensors: the outputs are exact formulas in the bodies' states,
    # checked at random states and times
    casadi = pytest.importorskip("casadi")
    from fmu.backend import to_ode
    from fmu.frontend import load_flat_model
    ode = to_ode(load_flat_model(PACKAGE / "Examples" / f"{name}.mo",
                                 f"Judder.Examples.{name}", roots=[LIBRARY]))
    clutch, upstream, downstream, _ = CLUTCHES[name]
    states = [s.name for s in ode.states]
    assert len(states) == {"Driveline3DOF": 6}.get(name, 8)
    assert {f"{upstream}.w", f"{downstream}.w"} <= set(states)
    _, outputs, _ = ode.functions()
    names = [o.name for o in ode.outputs]
    p = ode.parameter_vector()
    eliminated = ode.eliminated
    x_symbols = casadi.vertcat(*[s.expression for s in ode.states])
    p_symbols = casadi.vertcat(*[q.expression for q in ode.parameters])
    internal = casadi.Function(
        "internal", [ode.time, x_symbols, p_symbols],
        [casadi.vertcat(*[eliminated[f"{clutch}.tau_c"],
                          eliminated[f"{clutch}.slip"]])])
    rng = np.random.default_rng(1)
    for _ in range(5):
        t = rng.uniform(0.2, 1.0)
        x = rng.normal(size=len(states)) * 50
        y = dict(zip(names, np.asarray(outputs(t, x, p)).ravel()))
        tau_c, slip = np.asarray(internal(t, x, p)).ravel()
        w4 = x[states.index(f"{upstream}.w")]
        w3 = x[states.index(f"{downstream}.w")]
        assert y["w_upstream"] == pytest.approx(w4, rel=1e-12, abs=1e-12)
        assert y["w_downstream"] == pytest.approx(w3, rel=1e-12, abs=1e-12)
        assert y["slip"] == pytest.approx(w4 - w3, rel=1e-12, abs=1e-12)
        assert y["slip"] == pytest.approx(slip, rel=1e-12, abs=1e-12)
        assert y["clutch_torque"] == pytest.approx(tau_c, rel=1e-12,
                                                   abs=1e-9)
