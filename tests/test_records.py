"""The parameter records of the Modelica library, read by the registry.

The presets are read from ``modelica/Judder/Data`` by a small reader
(:mod:`drivelines.records`); the project's Modelica compiler (rumoca and
:mod:`fmu.frontend`), an independent reader of the same files, must find
the same defaults in the examples that extend the records.
"""

import re

import pytest

from sources import get_preset
from drivelines.records import DATA, RecordError, record_values


def _write(folder, name, body):
    (folder / f"{name}.mo").write_text(
        f'within Lib;\nrecord {name} "a record"\n{body}\n'
        '  annotation (Documentation(info="<html><p>extends X(a=b); '
        'parameter Real z=q;</p></html>"));\n'
        f"end {name};\n")


def test_extends_with_modifiers_and_products(tmp_path):
    _write(tmp_path, "Base", '  parameter Real a(min=0)=1.5e3 "first";\n'
           '  parameter Units.Length b=-2 // a comment\n    "second";\n'
           '  parameter Real c=3/4*2 "third";')
    _write(tmp_path, "Changed", "  extends Base(b=32885*1.06, c=-0.5);\n"
           '  parameter Real d=7 "own";')
    base = record_values("Base", tmp_path)
    assert list(base.items()) == [("a", 1500.0), ("b", -2.0), ("c", 1.5)]
    changed = record_values("Changed", tmp_path)
    # own parameters first, then the inherited ones in their order; the
    # product evaluated left to right in floating point
    assert list(changed) == ["d", "a", "b", "c"]
    assert changed["b"] == 32885.0 * 1.06 and changed["c"] == -0.5


@pytest.mark.parametrize("body, words", [
    ('  parameter Real a=J1*2 "a name";', "value 'J1*2' is not allowed"),
    ('  parameter Real a=2+3 "a sum";', "value '2+3' is not allowed"),
    ('  extends Base(x=1);', "'x' is not a parameter of Base"),
    ('  extends Base(a);', "modifier 'a' is not allowed"),
    ('  extends Missing;', "Missing.mo cannot be read"),
])
def test_what_is_not_data_is_refused(tmp_path, body, words):
    _write(tmp_path, "Base", '  parameter Real a=1 "a";')
    _write(tmp_path, "Bad", body)
    with pytest.raises(RecordError, match=re.escape(words)) as err:
        record_values("Bad", tmp_path)
    assert "Bad.mo" in str(err.value) or "Missing.mo" in str(err.value)


@pytest.mark.parametrize("record, preset", [
    ("Driveline4DOFData", "paper-4dof"),
    ("Driveline4DOFFitted", "paper-4dof-fitted"),
    ("Driveline3DOFData", "paper-3dof")])
def test_presets_are_the_records(record, preset):
    assert dict(get_preset(preset).values) == dict(record_values(record))


@pytest.mark.parametrize("example, preset", [
    ("Driveline4DOF", "paper-4dof"), ("Driveline3DOF", "paper-3dof"),
    ("TestBenchEngagement", "paper-4dof"),
    ("Driveline4DOFTwoClutches", "paper-4dof")])
def test_compiler_reads_the_same_defaults_in_the_examples(example, preset):
    # rumoca flattens the example, which extends the record: its tunable
    # parameters of the preset's names have the preset's values
    pytest.importorskip("rumoca")
    from fmu.frontend import load_flat_model
    library = DATA.parents[1]
    flat = load_flat_model(library / "Judder" / "Examples" / f"{example}.mo",
                           f"Judder.Examples.{example}", roots=[library])
    defaults = {v.name: float(v.binding) for v in flat.variables
                if v.role == "parameter" and v.binding is not None
                and v.binding.is_constant()}
    values = get_preset(preset).values
    assert {name: defaults[name] for name in values} == dict(values)
