import owlready2
import pytest
import rdflib
from rdflib.namespace import OWL, RDF, RDFS

from oracle.errors import OntologyError
from oracle.namespaces import DUL, SOMA
from oracle.ontology import build_with_report, load_ontology, write_ontology
from oracle.ontology.inputs import DEFAULT_MAPPING

from .conftest import manifest, write_manifest

KITCHEN_OBJECTS = (
    "kitchen_table counter_top thermos water_bottle bread big_drawer knife spoon fork chamomile_tea_bag "
    "peppermint_tea_bag green_tea_bag black_tea_bag chai_tea_bag small_drawer instant_coffee red_mug green_mug "
    "blue_mug drinking_glass espresso_cup cereal_bowl cereal_box plate fruit_bowl orange apple lemon banana "
    "fridge milk_carton juice beer_bottle cucumber avocado yogurt tap coffee_machine microwave dish_washer stove"
).split()
KITCHEN_TASKS = "pick place pour drink_from eat cut eat_with stir open close turn_on turn_off".split()
EDAN_OBJECTS = ("_robot _tool human _gripper _container _coffee_machine _content _fruit _microwave _phone _tray _cube "
                "edans_ikea_kitchen_door oven_knob").split()


def soma_or_dul(iri: str) -> bool:
    return iri.startswith((str(SOMA), str(DUL)))


def test_every_kitchen_object_and_task_has_a_soma_ancestor(kitchen):
    onto, report = kitchen
    for name in KITCHEN_OBJECTS + EDAN_OBJECTS + KITCHEN_TASKS:
        iri = onto.iri(name)
        assert any(soma_or_dul(a) and a != iri for a in onto.taxonomy.ancestors(iri)), name
    for name in KITCHEN_OBJECTS + EDAN_OBJECTS:
        assert onto.taxonomy.is_subclass_of(onto.iri(name), str(DUL.PhysicalObject)), name
    for name in KITCHEN_TASKS:
        assert onto.taxonomy.is_subclass_of(onto.iri(name), str(DUL.Task)), name
    assert report.unmapped == ("_object",)


def test_table_5_1_affordances(kitchen):
    onto, _ = kitchen
    assert set(onto.objects["thermos"].tasks) == {"pick", "place", "pour", "drink_from"}
    assert set(onto.objects["fork"].tasks) == {"pick", "place", "stir", "eat_with"}
    assert set(onto.objects["fridge"].tasks) == {"open", "close"}


def test_mapped_objects_are_subclasses_never_equivalents(kitchen):
    onto, _ = kitchen
    g = onto.graph
    assert (rdflib.URIRef(onto.iri("_container")), RDFS.subClassOf, SOMA.DesignedContainer) in g
    assert not any(str(s).startswith(onto.namespace) for s in g.subjects(OWL.equivalentClass, None))
    # The unmapped odb root gives way to the SOMA class: _container does not derive from _object.
    assert onto.iri("_object") not in onto.taxonomy.parents(onto.iri("_container"))
    assert onto.taxonomy.parents(onto.iri("_object")) == (str(DUL.PhysicalObject),)


def test_task_classes_carry_roles_and_mapping_parents(kitchen):
    onto, _ = kitchen
    pour = onto.tasks["pour"]
    assert pour.soma_task == str(SOMA.Pouring)
    assert (pour.ref_role, pour.target_role) == (str(SOMA.PouredObject), str(SOMA.RecipientRole))
    assert onto.tasks["open_fridge"].parent == "open_door"
    assert onto.tasks["open_fridge"].soma_task == str(SOMA.Opening)
    assert onto.task_roles("pour", 2) == (str(SOMA.PouredObject), str(SOMA.RecipientRole))
    assert onto.task_roles("pick", 1) == (str(SOMA.MovedObject),)
    with pytest.raises(OntologyError, match="unknown task 'fly'"):
        onto.task_roles("fly", 1)


def test_new_entities(kitchen):
    onto, _ = kitchen
    v = onto.vocab
    tax = onto.taxonomy
    assert tax.parents(v.idle_task) == (str(SOMA.PhysicalTask),)
    assert tax.is_subclass_of(v.time_of_day, str(DUL.TimeInterval))
    assert all(tax.parents(p) == (v.time_of_day,) for p in v.parts_of_day)
    g = onto.graph
    for prop in (v.imagines_situation, v.imagines_preference):
        assert (rdflib.URIRef(prop), RDF.type, OWL.ObjectProperty) in g


@pytest.mark.parametrize("suffix", [".owl", ".ttl"])
def test_written_file_loads_back_in_rdflib_and_owlready2(kitchen, tmp_path, suffix):
    onto, _ = kitchen
    out = write_ontology(onto, tmp_path / f"odb{suffix}")
    again = load_ontology(out)
    assert again.namespace == onto.namespace
    assert again.objects == onto.objects and again.tasks == onto.tasks
    assert again.taxonomy.classes == onto.taxonomy.classes
    if suffix == ".owl":
        world = owlready2.World()
        loaded = world.get_ontology(out.as_uri()).load()
        mug = world.search_one(iri=onto.iri("red_mug"))
        assert mug is not None
        ancestors = {a.iri for a in mug.ancestors()}
        assert str(SOMA.DesignedContainer) in ancestors and loaded is not None


def test_unknown_upper_iri_is_rejected(tmp_path):
    write_manifest(tmp_path / "odb", "cup", manifest("cup"))
    mapping = tmp_path / "mapping.yaml"
    mapping.write_text(DEFAULT_MAPPING.read_text().replace("soma:DesignedContainer", "soma:DesignedContainr"))
    with pytest.raises(OntologyError, match=r"soma_odb_map\._container: .*DesignedContainr is not declared"):
        build_with_report(tmp_path / "odb", mapping)


def test_object_and_task_name_collision_is_rejected(tmp_path):
    write_manifest(tmp_path / "odb", "pick", manifest("pick", snippets=["pick_sct.yml"]))
    with pytest.raises(OntologyError, match="'pick' names both an odb object and a task"):
        build_with_report(tmp_path / "odb")


def test_unmapped_snippet_tasks_get_action_defaults(tmp_path):
    write_manifest(tmp_path / "odb", "box", manifest("box", snippets=["juggle_sct.yml"]))
    onto, report = build_with_report(tmp_path / "odb")
    assert report.default_tasks == ("juggle",)
    assert onto.tasks["juggle"].soma_task == str(SOMA.PhysicalTask)
    assert onto.tasks["juggle"].target_role == str(SOMA.Patient)
    assert report.unmapped == ("box",)
    assert onto.taxonomy.parents(onto.iri("box")) == (str(DUL.PhysicalObject),)
