import pytest

from oracle.errors import OntologyError
from oracle.ontology.odb import inherited_tasks, read_odb, task_of_snippet

from .conftest import manifest, write_manifest


def test_snippet_names_become_tasks():
    assert task_of_snippet("pick_from_side_sct.yml") == "pick_from_side"
    assert task_of_snippet("pour.yaml") == "pour"


def test_tasks_are_inherited_by_children(tmp_path):
    write_manifest(tmp_path, "_bottle", manifest("_bottle", snippets=["pour_sct.yml"]))
    write_manifest(tmp_path, "thermos", manifest("thermos", ["_bottle"], ["pick_from_side_sct.yml"]))
    odb = read_odb(tmp_path)
    assert odb["_bottle"].abstract and not odb["thermos"].abstract
    assert inherited_tasks(odb, "thermos") == ("pick_from_side", "pour")


def test_thesis_manifest_fields(tmp_path):
    write_manifest(tmp_path, "thermos", """<?xml version="1.0" encoding="UTF-8"?>
<object><name>thermos</name><author>x</author><mass>0.1</mass><updir>0 0 1</updir>
<dimension>0.03 0.03 0.236</dimension><logic><code_snippet>pour_sct.yml</code_snippet></logic></object>""")
    obj = read_odb(tmp_path)["thermos"]
    assert obj.mass == 0.1 and obj.dimension == (0.03, 0.03, 0.236) and obj.parents == ()


@pytest.mark.parametrize(
    "body, message",
    [
        ("<object><name>a</name>", r"a/manifest\.xml:1:\d+: malformed XML"),
        ("<object><mass>1</mass></object>", r"a/manifest\.xml: missing <name>"),
        ("<object><name>a</name><derive>_nope</derive></object>", "derives from unknown object '_nope'"),
        ("<object><name>a</name><mass>heavy</mass></object>", "<mass> 'heavy' of 'a' is not a number"),
        ("<thing><name>a</name></thing>", "root element must be <object>"),
    ],
)
def test_bad_manifests_name_file_and_entry(tmp_path, body, message):
    write_manifest(tmp_path, "a", body)
    with pytest.raises(OntologyError, match=message):
        read_odb(tmp_path)


def test_cyclic_parents_are_reported(tmp_path):
    write_manifest(tmp_path, "a", manifest("a", ["b"]))
    write_manifest(tmp_path, "b", manifest("b", ["a"]))
    with pytest.raises(OntologyError, match="cyclic derive: a -> b -> a|cyclic derive: b -> a -> b"):
        read_odb(tmp_path)


def test_duplicate_names_are_reported(tmp_path):
    write_manifest(tmp_path, "a", manifest("x"))
    write_manifest(tmp_path, "b", manifest("x"))
    with pytest.raises(OntologyError, match="object 'x' is also defined in"):
        read_odb(tmp_path)


def test_empty_folder_is_not_an_odb(tmp_path):
    with pytest.raises(OntologyError, match="no \\*/manifest.xml found"):
        read_odb(tmp_path)
