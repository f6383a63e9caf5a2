"""modelDescription.xml for FMI 2.0 and FMI 3.0 (ME + CS).

Value references follow ``fmu/c/model.h``: 0 time, then the states,
their derivatives, the tunable parameters, the calculated parameters,
the outputs, the locals (every other variable of the model, causality
``local``) and the inputs. A variable equal to another (connected flange
angles and torques) is its alias: the same value reference in FMI 2, an
``<Alias>`` element in FMI 3. States are calculated at initialisation
from the parameters (their Modelica start values may depend on them), so
their start values are set through parameters.
"""

from datetime import datetime, timezone
import re
import warnings
from xml.sax.saxutils import quoteattr

from .units import DISPLAY_UNITS, UnitWarning, UnknownUnit, base_unit

__all__ = ["Layout", "model_description", "build_description", "SOURCES"]


class Layout:
    """Value references and names of every FMU variable of an OdeModel."""

    def __init__(self, ode):
        self.states = ode.states
        self.parameters = ode.parameters
        self.calculated = ode.calculated
        self.outputs = ode.outputs
        self.locals = ode.locals
        self.aliases = ode.aliases
        self.inputs = ode.inputs
        nx, np_, nc = len(ode.states), len(ode.parameters), len(ode.calculated)
        self.vr_states = 1
        self.vr_derivatives = 1 + nx
        self.vr_parameters = 1 + 2 * nx
        self.vr_calculated = self.vr_parameters + np_
        self.vr_outputs = self.vr_calculated + nc
        self.vr_locals = self.vr_outputs + len(ode.outputs)
        self.vr_inputs = self.vr_locals + len(ode.locals)
        self.vr_indicators = self.vr_inputs + len(ode.inputs)
        self.relations = ode.relations
        #: locals that change at events only (Integer, Boolean variables)
        self.discrete = {q.name for q in ode.discretes}

    def units(self):
        names = {q.unit for group in (self.states, self.parameters,
                                      self.calculated, self.outputs,
                                      self.locals, self.inputs,
                                      [q for q, _ in self.aliases])
                 for q in group if q.unit}
        for q in self.states:
            if q.unit:
                names.add(_derivative_unit(q.unit))
        return sorted(names)


def _variability(layout, name):
    """A local's: ``discrete`` for an Integer or Boolean variable (held
    between events), else ``continuous``."""
    return "discrete" if name in layout.discrete else "continuous"


def _derivative_unit(unit):
    """Unit of a time derivative: rad -> rad/s, rad/s -> rad/s2."""
    numerator, slash, denominator = unit.partition("/")
    if not slash:
        return "1/s" if unit == "1" else f"{unit}/s"
    found = re.fullmatch(r"s(\d*)", denominator)
    if found:
        return f"{numerator}/s{int(found.group(1) or 1) + 1}"
    return f"{unit}.s"


def _attr(**items):
    return "".join(f" {k}={quoteattr(str(v))}" for k, v in items.items()
                   if v is not None and v != "")


def _number(value):
    return repr(float(value))


def _display_unit(q):
    """The quantity's display unit if the FMU can declare it."""
    unit = DISPLAY_UNITS.get(q.display_unit, ("",))[0]
    return q.display_unit if q.unit and unit == q.unit else None


def _typed(q):
    """unit, quantity and displayUnit attributes of a variable."""
    return dict(unit=q.unit or None, quantity=q.quantity or None,
                displayUnit=_display_unit(q))


def _unit_definitions(layout, extra=()):
    units = sorted(set(layout.units()) | set(extra))
    displays = {}
    for group in (layout.states, layout.parameters, layout.calculated,
                  layout.outputs, layout.locals, layout.inputs,
                  [q for q, _ in layout.aliases]):
        for q in group:
            if _display_unit(q):
                displays.setdefault(q.unit, set()).add(q.display_unit)
    if not units:
        return []   # an empty UnitDefinitions element is invalid
    lines = ["  <UnitDefinitions>"]
    for unit in units:
        try:
            found = base_unit(unit)
        except UnknownUnit as exc:
            # kept as written: a Unit without BaseUnit is valid FMI
            warnings.warn(UnitWarning(
                f"{exc}; kept as written in the FMU, without its SI base "
                f"units (variable {_first_with(layout, unit)}); allowed: "
                "the units of the Modelica specification (SI units with "
                "prefixes, N.m, rad/s2, degC, ...)"), stacklevel=2)
            lines.append(f"    <Unit name={quoteattr(unit)}/>")
            continue
        base = "<BaseUnit" + _attr(
            **found.exponents,
            factor=None if found.factor == 1.0 else _number(found.factor),
            offset=None if not found.offset else _number(found.offset)) \
            + "/>"
        shown = "".join(
            "<DisplayUnit" + _attr(name=name, factor=_number(
                DISPLAY_UNITS[name][1]), offset=None if not DISPLAY_UNITS[
                    name][2] else _number(DISPLAY_UNITS[name][2])) + "/>"
            for name in sorted(displays.get(unit, ())))
        lines.append(f"    <Unit name={quoteattr(unit)}>{base}{shown}</Unit>")
    lines.append("  </UnitDefinitions>")
    return lines


def _first_with(layout, unit):
    """The name of the first variable declared with ``unit``."""
    for group in (layout.states, layout.parameters, layout.calculated,
                  layout.outputs, layout.locals, layout.inputs,
                  [q for q, _ in layout.aliases]):
        for q in group:
            if q.unit == unit:
                return q.name
    for q in layout.states:
        if q.unit and _derivative_unit(q.unit) == unit:
            return f"der({q.name})"
    return "?"


def _experiment(ode, tolerance):
    exp = ode.experiment
    return ["  <DefaultExperiment" + _attr(
        startTime="0.0", stopTime=_number(exp.get("StopTime", 1.0)),
        tolerance=_number(tolerance),
        stepSize=_number(exp.get("Interval", 1e-3))) + "/>"]


def model_description(ode, version, identifier, guid, tolerance=1e-10,
                      tool="judder fmu", author="", model_version=""):
    """The XML text of modelDescription.xml.

    Parameters
    ----------
    ode : fmu.backend.OdeModel
    version : {'2.0', '3.0'}
    identifier : str
        modelIdentifier (name of the shared library).
    guid : str
        GUID (FMI 2) or instantiationToken (FMI 3).
    tolerance : float
        Default relative tolerance of the experiment.
    author, model_version : str
        The ``author`` and ``version`` attributes (left out when empty).
    """
    layout = Layout(ode)
    about = {"author": author, "version": model_version}
    if version == "2.0":
        return _fmi2(ode, layout, identifier, guid, tolerance, tool, about)
    if version == "3.0":
        return _fmi3(ode, layout, identifier, guid, tolerance, tool, about)
    raise ValueError(f"FMI version {version!r}; allowed: 2.0, 3.0")


def _variables(layout):
    """(name, vr, kind, quantity) of every variable in index order."""
    rows = []
    for i, q in enumerate(layout.states):
        rows.append((q.name, layout.vr_states + i, "state", q))
    for i, q in enumerate(layout.states):
        rows.append((f"der({q.name})", layout.vr_derivatives + i,
                     "derivative", q))
    for i, q in enumerate(layout.parameters):
        rows.append((q.name, layout.vr_parameters + i, "parameter", q))
    for i, q in enumerate(layout.calculated):
        rows.append((q.name, layout.vr_calculated + i, "calculated", q))
    for i, q in enumerate(layout.outputs):
        rows.append((q.name, layout.vr_outputs + i, "output", q))
    for i, q in enumerate(layout.locals):
        rows.append((q.name, layout.vr_locals + i, "local", q))
    for i, q in enumerate(layout.inputs):
        rows.append((q.name, layout.vr_inputs + i, "input", q))
    return rows


def _aliases_of(layout):
    """``{name: [alias Quantity, ...]}``: the aliases of each variable."""
    found = {}
    for q, target in layout.aliases:
        found.setdefault(target, []).append(q)
    return found


def _indicators(layout):
    """FMI 3 event indicators: local variables (name, vr, description)."""
    return [(f"_eventIndicator{i + 1}", layout.vr_indicators + i,
             f"Event indicator of the {q.description}")
            for i, q in enumerate(layout.relations)]


def _bounds(q):
    out = {}
    for key, value in (("min", q.minimum), ("max", q.maximum)):
        if value is not None:
            try:
                out[key] = _number(float(value))
            except (TypeError, RuntimeError):
                pass   # a bound that depends on parameters is not exported
    return out


#: C files of the FMU's sources/ folder that make its binary, per version
#: (the headers beside them: model.h, instance.h, model_config.h,
#: model_functions.h): the generated functions, the model core, the FMI
#: calls common to both versions and the version's adapter.
SOURCES = {"2.0": ("model_functions.c", "model.c", "instance.c", "fmi2.c"),
           "3.0": ("model_functions.c", "model.c", "instance.c", "fmi3.c")}


def _source_files(version):
    """FMI 2 <SourceFiles> of an interface element."""
    return (["    <SourceFiles>"]
            + [f"      <File name={quoteattr(name)}/>"
               for name in SOURCES[version]] + ["    </SourceFiles>"])


def build_description(identifier, version="3.0"):
    """sources/buildDescription.xml of an FMI 3 FMU."""
    files = "".join(f'\n      <SourceFile name={quoteattr(name)}/>'
                    for name in SOURCES[version])
    return ('<?xml version="1.0" encoding="UTF-8"?>\n'
            '<fmiBuildDescription fmiVersion="3.0">\n'
            f'  <BuildConfiguration modelIdentifier={quoteattr(identifier)}>\n'
            '    <SourceFileSet language="C99">'
            f'{files}\n    </SourceFileSet>\n'
            '  </BuildConfiguration>\n'
            '</fmiBuildDescription>\n')


def _dependencies(ode):
    """Knowns each unknown depends on, from the Jacobian's sparsity.

    Returns ``{("derivative" | "output", i): [("state" | "input", j)]}``:
    the states and inputs (the knowns of FMI's ModelStructure) that
    ``der(x_i)`` or output ``i`` depends on.
    """
    nx, np_ = len(ode.states), len(ode.parameters)
    rows, cols = ode.jacobian()[1].get_triplet()
    found = {("derivative", i): [] for i in range(nx)}
    found.update({("output", i): [] for i in range(len(ode.outputs))})
    for row, col in sorted(zip(rows, cols), key=lambda rc: (rc[0], rc[1])):
        unknown = ("derivative", row) if row < nx else ("output", row - nx)
        if col < nx:
            found[unknown].append(("state", col))
        elif col >= nx + np_:
            found[unknown].append(("input", col - nx - np_))
    return found


def _generated():
    """generationDateAndTime: now, UTC, ISO 8601 to the second."""
    return datetime.now(timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ")


def _derivative_description(q):
    return f"Time derivative of {q.name}" + (
        f" ({q.description})" if q.description else "")


def _fmi2(ode, layout, identifier, guid, tolerance, tool, about):
    lines = ['<?xml version="1.0" encoding="UTF-8"?>',
             "<fmiModelDescription" + _attr(
                 fmiVersion="2.0", modelName=ode.name, guid=guid, **about,
                 generationTool=tool, generationDateAndTime=_generated(),
                 variableNamingConvention="structured",
                 numberOfEventIndicators=str(len(ode.relations))) + ">",
             "  <ModelExchange" + _attr(
                 modelIdentifier=identifier,
                 canNotUseMemoryManagementFunctions="true",
                 canGetAndSetFMUstate="true",
                 canSerializeFMUstate="true",
                 providesDirectionalDerivative="true") + ">",
             *_source_files("2.0"), "  </ModelExchange>",
             "  <CoSimulation" + _attr(
                 modelIdentifier=identifier,
                 canHandleVariableCommunicationStepSize="true",
                 canNotUseMemoryManagementFunctions="true",
                 canGetAndSetFMUstate="true",
                 canSerializeFMUstate="true",
                 providesDirectionalDerivative="true") + ">",
             *_source_files("2.0"), "  </CoSimulation>"]
    lines += _unit_definitions(layout)
    lines += _experiment(ode, tolerance)
    lines.append("  <ModelVariables>")
    index_of = {}
    rows = _variables(layout)
    aliases = _aliases_of(layout)
    for name, vr, kind, q in rows:
        index_of[(kind, name)] = len(index_of) + 1
        common = dict(name=name, valueReference=vr,
                      description=q.description or None)
        if kind == "state":
            head = _attr(**common, causality="local",
                         variability="continuous", initial="calculated")
            real = _attr(**_typed(q))
        elif kind == "derivative":
            state = index_of[("state", q.name)]
            common["description"] = _derivative_description(q)
            head = _attr(**common, causality="local",
                         variability="continuous", initial="calculated")
            real = _attr(unit=_derivative_unit(q.unit) if q.unit else None,
                         derivative=state)
        elif kind == "parameter":
            head = _attr(**common, causality="parameter",
                         variability="tunable", initial="exact")
            real = _attr(**_typed(q), start=_number(q.start),
                         **_bounds(q))
        elif kind == "calculated":
            head = _attr(**common, causality="calculatedParameter",
                         variability="tunable", initial="calculated")
            real = _attr(**_typed(q))
        elif kind == "input":
            head = _attr(**common, causality="input",
                         variability="continuous")
            real = _attr(**_typed(q), start=_number(q.start),
                         **_bounds(q))
        elif kind == "local":
            head = _attr(**common, causality="local",
                         variability=_variability(layout, name),
                         initial="calculated")
            real = _attr(**_typed(q))
        else:
            head = _attr(**common, causality="output",
                         variability="continuous", initial="calculated")
            real = _attr(**_typed(q))
        lines.append(f"    <ScalarVariable{head}><Real{real}/></ScalarVariable>")
        for alias in aliases.get(name, ()):
            head = _attr(name=alias.name, valueReference=vr,
                         description=alias.description or None,
                         causality="local", variability="continuous")
            lines.append(f"    <ScalarVariable{head}><Real"
                         f"{_attr(**_typed(alias))}/></ScalarVariable>")
            index_of[("alias", alias.name)] = len(index_of) + 1
    lines.append("  </ModelVariables>")
    outputs = [i for (k, _), i in index_of.items() if k == "output"]
    derivatives = [i for (k, _), i in index_of.items() if k == "derivative"]
    initial = sorted(i for (k, _), i in index_of.items()
                     if k in ("output", "state", "derivative", "calculated"))
    names = {"state": [q.name for q in layout.states],
             "input": [q.name for q in layout.inputs]}
    depends = {}
    for (kind, i), knowns in _dependencies(ode).items():
        name = f"der({layout.states[i].name})" if kind == "derivative" \
            else layout.outputs[i].name
        depends[index_of[(kind, name)]] = " ".join(
            str(index_of[(k, names[k][j])]) for k, j in knowns)
    lines.append("  <ModelStructure>")
    for tag, indices in (("Outputs", outputs), ("Derivatives", derivatives),
                         ("InitialUnknowns", initial)):
        if indices:
            lines.append(f"    <{tag}>")
            lines += [f'      <Unknown index="{i}"' + (
                f' dependencies="{depends[i]}"' if i in depends and tag !=
                "InitialUnknowns" else "") + "/>" for i in indices]
            lines.append(f"    </{tag}>")
    lines.append("  </ModelStructure>")
    lines.append("</fmiModelDescription>")
    return "\n".join(lines) + "\n"


def _fmi3(ode, layout, identifier, guid, tolerance, tool, about):
    lines = ['<?xml version="1.0" encoding="UTF-8"?>',
             "<fmiModelDescription" + _attr(
                 fmiVersion="3.0", modelName=ode.name,
                 instantiationToken=guid, **about, generationTool=tool,
                 generationDateAndTime=_generated(),
                 variableNamingConvention="structured") + ">",
             "  <ModelExchange" + _attr(
                 modelIdentifier=identifier, canGetAndSetFMUState="true",
                 canSerializeFMUState="true",
                 providesDirectionalDerivatives="true",
                 providesAdjointDerivatives="true") + "/>",
             "  <CoSimulation" + _attr(
                 modelIdentifier=identifier, canGetAndSetFMUState="true",
                 canSerializeFMUState="true",
                 providesDirectionalDerivatives="true",
                 providesAdjointDerivatives="true",
                 canHandleVariableCommunicationStepSize="true") + "/>"]
    lines += _unit_definitions(layout, extra=("s",))   # of time
    lines += _experiment(ode, tolerance)
    lines.append("  <ModelVariables>")
    lines.append('    <Float64 name="time" valueReference="0" '
                 'causality="independent" variability="continuous" '
                 'description="Simulation time" unit="s"/>')
    state_vr = {}
    aliases = _aliases_of(layout)
    for name, vr, kind, q in _variables(layout):
        common = dict(name=name, valueReference=vr,
                      description=q.description or None)
        if kind == "state":
            state_vr[q.name] = vr
            attrs = _attr(**common, causality="local",
                          variability="continuous", initial="calculated",
                          **_typed(q))
        elif kind == "derivative":
            common["description"] = _derivative_description(q)
            attrs = _attr(**common, causality="local",
                          variability="continuous", initial="calculated",
                          unit=_derivative_unit(q.unit) if q.unit else None,
                          derivative=state_vr[q.name])
        elif kind == "parameter":
            attrs = _attr(**common, causality="parameter",
                          variability="tunable", initial="exact",
                          **_typed(q), start=_number(q.start),
                          **_bounds(q))
        elif kind == "calculated":
            attrs = _attr(**common, causality="calculatedParameter",
                          variability="tunable", initial="calculated",
                          **_typed(q))
        elif kind == "input":
            attrs = _attr(**common, causality="input",
                          variability="continuous", **_typed(q),
                          start=_number(q.start), **_bounds(q))
        elif kind == "local":
            attrs = _attr(**common, causality="local",
                          variability=_variability(layout, name),
                          initial="calculated", **_typed(q))
        else:
            attrs = _attr(**common, causality="output",
                          variability="continuous", initial="calculated",
                          **_typed(q))
        shown = ["      <Alias" + _attr(
                     name=a.name, description=a.description or None,
                     displayUnit=_display_unit(a)) + "/>"
                 for a in aliases.get(name, ())]
        lines += [f"    <Float64{attrs}>", *shown, "    </Float64>"] \
            if shown else [f"    <Float64{attrs}/>"]
    for name, vr, text in _indicators(layout):
        lines.append("    <Float64" + _attr(
            name=name, valueReference=vr, description=text,
            causality="local", variability="continuous") + "/>")
    lines.append("  </ModelVariables>")
    lines.append("  <ModelStructure>")
    rows = _variables(layout)
    start = {"state": layout.vr_states, "input": layout.vr_inputs,
             "derivative": layout.vr_derivatives,
             "output": layout.vr_outputs}
    depends = {start[kind] + i: " ".join(str(start[k] + j)
                                         for k, j in knowns)
               for (kind, i), knowns in _dependencies(ode).items()}
    lines += [f'    <Output valueReference="{vr}" '
              f'dependencies="{depends[vr]}"/>'
              for _, vr, kind, _ in rows if kind == "output"]
    lines += [f'    <ContinuousStateDerivative valueReference="{vr}" '
              f'dependencies="{depends[vr]}"/>'
              for _, vr, kind, _ in rows if kind == "derivative"]
    lines += [f'    <InitialUnknown valueReference="{vr}"/>'
              for _, vr, kind, _ in rows
              if kind in ("state", "derivative", "calculated", "output")]
    lines += [f'    <EventIndicator valueReference="{vr}"/>'
              for _, vr, _ in _indicators(layout)]
    lines.append("  </ModelStructure>")
    lines.append("</fmiModelDescription>")
    return "\n".join(lines) + "\n"
