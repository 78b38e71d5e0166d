import textwrap

import pytest

from oracle.errors import OntologyError
from oracle.namespaces import SOMA
from oracle.ontology.mapping import load_mapping

BASE = """
namespace: https://example.org/odb
imports:
  soma: http://www.ease-crc.org/ont/SOMA.owl#
soma_odb_map:
  _container: soma:DesignedContainer
root_object: dul:PhysicalObject
action_defaults:
  task: soma:PhysicalTask
  ref_role: False
  target_role: soma:Patient
  disposition: soma:Disposition
actions:
"""


def write(tmp_path, actions: str, extra: str = ""):
    path = tmp_path / "mapping.yaml"
    path.write_text(BASE + textwrap.indent(textwrap.dedent(actions), "  ") + extra)
    return path


def test_children_inherit_every_field_they_do_not_set(tmp_path):
    path = write(tmp_path, """
    open:
      task: soma:Opening
      target_role: soma:ShapedObject
      ref_role: False
      disposition: soma:Enclosing
    open_door:
      parent: open
    open_drawer:
      parent: open
      disposition: soma:Storage
    open_cabinet:
      parent: open_drawer
    roll_dice: {}
    """)
    m = load_mapping(path)
    assert m.namespace == "https://example.org/odb#"
    assert m.actions["open_door"].task == str(SOMA.Opening)
    assert m.actions["open_door"].target_role == str(SOMA.ShapedObject)
    assert m.actions["open_cabinet"].disposition == str(SOMA.Storage)
    assert m.actions["open_cabinet"].ref_role is None
    assert m.actions["roll_dice"].task == str(SOMA.PhysicalTask)
    assert m.actions["roll_dice"].target_role == str(SOMA.Patient)
    assert not m.actions["open_door"].explicit_task and m.actions["open"].explicit_task


@pytest.mark.parametrize(
    "actions, extra, message",
    [
        ("a:\n  task: soma:Pouring\n  colour: red\n", "", r"actions\.a: unknown key\(s\) colour"),
        ("a:\n  parent: nope\n", "", r"actions\.a: unknown parent 'nope'"),
        ("a:\n  parent: b\nb:\n  parent: a\n", "", "cyclic parent"),
        ("a:\n  task: foo:Bar\n", "", "unknown prefix 'foo'"),
        ("a: {}\n", "colour: red\n", r"unknown key\(s\) colour"),
        ("a:\n  task: [1]\n", "", r"actions\.a\.task: expected a task class"),
    ],
)
def test_bad_mappings_name_file_and_entry(tmp_path, actions, extra, message):
    path = write(tmp_path, actions, extra)
    with pytest.raises(OntologyError, match=message) as info:
        load_mapping(path)
    assert "mapping.yaml" in str(info.value)


def test_malformed_yaml_gives_line(tmp_path):
    path = tmp_path / "mapping.yaml"
    path.write_text("actions:\n  a: [\n")
    with pytest.raises(OntologyError, match=r"mapping\.yaml:\d+: malformed YAML"):
        load_mapping(path)
