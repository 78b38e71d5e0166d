"""odb + mapping + upper TBox -> the RDF graph of the odb ontology (rdflib; oracle.ontology.builder
calls it on a cache miss, so a command that finds the build cached never imports rdflib).

Objects become subclasses (never equivalents) of their mapped SOMA class; a mapped object keeps
its odb parents except unmapped root objects (such as ``_object``), whose place the SOMA class
takes; unmapped objects without parents go under ``root_object``. Tasks become classes under
their SOMA task (and their mapping parent), with their roles and disposition.
"""

from __future__ import annotations

from pathlib import Path

from rdflib import BNode, Graph, Literal, URIRef
from rdflib.collection import Collection
from rdflib.namespace import OWL, RDF, RDFS, XSD

from oracle.errors import OntologyError
from oracle.namespaces import DUL, SOMA
from oracle.ontology.inputs import DEFAULT_MAPPING, DEFAULT_ODB, BuildReport
from oracle.ontology.mapping import ActionMapping, Mapping, load_mapping
from oracle.ontology.model import GENERATED_MARK, VANN_NAMESPACE
from oracle.ontology.odb import OdbObject, read_odb
from oracle.ontology.upper import declared_entities
from oracle.ontology.vocabulary import Vocabulary


def generated_graph(odb_dir: Path | str | None = None, mapping: Path | str | None = None) -> Graph:
    """The odb ontology's own axioms, without the upper ontology they attach to (what a NEEM
    stores beside the official SOMA/DUL files, each of which goes in as its own graph)."""
    odb_path = Path(odb_dir).expanduser() if odb_dir is not None else DEFAULT_ODB
    mapping_path = Path(mapping).expanduser() if mapping is not None else DEFAULT_MAPPING
    return generate(read_odb(odb_path), load_mapping(mapping_path), Graph())[0]


def check_upper_iris(maps: Mapping, upper: Graph, what: str) -> None:
    known = declared_entities(upper)
    external = [(f"soma_odb_map.{o}", c) for o, c in maps.object_map.items()]
    external.append(("root_object", maps.root_object))
    for action in [maps.defaults, *maps.actions.values()]:
        label = "action_defaults" if action.name == "<defaults>" else f"actions.{action.name}"
        for field_name in ("task", "ref_role", "target_role", "disposition"):
            value = getattr(action, field_name)
            if value is not None:
                external.append((f"{label}.{field_name}", value))
    for entry, iri in external:
        if iri.startswith(maps.namespace):
            continue
        if iri not in known:
            raise OntologyError(f"{maps.source}: {entry}: {iri} is not declared in {what}")


def generate(objects: dict[str, OdbObject], maps: Mapping, upper: Graph) -> tuple[Graph, BuildReport]:
    ns = maps.namespace
    vocab = Vocabulary(ns)
    collisions = (set(objects) & (set(maps.actions) | {t for o in objects.values() for t in o.tasks})) | (
        set(objects) & vocab.locals
    )
    if collisions:
        name = sorted(collisions)[0]
        raise OntologyError(f"{objects[name].source}: {name!r} names both an odb object and a task or project entity")

    graph = Graph()
    for prefix, iri in maps.prefixes.items():
        graph.bind(prefix, iri)
    for triple in upper:
        graph.add(triple)
    onto = URIRef(ns.rstrip("#/") if ns.endswith("#") else ns)
    graph.add((onto, RDF.type, OWL.Ontology))
    graph.add((onto, RDFS.comment, Literal(GENERATED_MARK)))
    graph.add((onto, URIRef(VANN_NAMESPACE), Literal(ns)))
    _add_vocabulary(graph, vocab)

    def cls(iri: str) -> URIRef:
        node = URIRef(iri)
        graph.add((node, RDF.type, OWL.Class))
        return node

    # Tasks: every mapped action plus every task an odb object names without a mapping.
    actions: dict[str, ActionMapping] = dict(maps.actions)
    default_tasks = sorted({t for o in objects.values() for t in o.tasks} - set(actions))
    for name in default_tasks:
        actions[name] = ActionMapping(name, maps.defaults.task, maps.defaults.ref_role, maps.defaults.target_role,
                                      maps.defaults.disposition, None, True)
    for name, action in actions.items():
        node = cls(ns + name)
        graph.add((node, RDFS.label, Literal(name)))
        if action.parent is not None:
            graph.add((node, RDFS.subClassOf, URIRef(ns + action.parent)))
        if action.explicit_task:
            graph.add((node, RDFS.subClassOf, URIRef(action.task)))
        for role, prop in ((action.target_role, vocab.target_role), (action.ref_role, vocab.reference_role)):
            if role is not None:
                graph.add((node, URIRef(prop), URIRef(role)))
                graph.add((node, RDFS.subClassOf, _some(graph, DUL.isTaskOf, URIRef(role))))
        if action.disposition is not None:
            graph.add((node, URIRef(vocab.disposition), URIRef(action.disposition)))

    # Objects.
    unmapped_roots = {n for n, o in objects.items() if not o.parents and n not in maps.object_map}
    for name, obj in objects.items():
        node = cls(ns + name)
        graph.add((node, RDFS.label, Literal(name)))
        parents = list(obj.parents)
        if name in maps.object_map:
            parents = [p for p in parents if p not in unmapped_roots]
            graph.add((node, RDFS.subClassOf, URIRef(maps.object_map[name])))
        elif not parents:
            graph.add((node, RDFS.subClassOf, URIRef(maps.root_object)))
        for parent in parents:
            graph.add((node, RDFS.subClassOf, URIRef(ns + parent)))
        if obj.mass is not None:
            graph.add((node, RDFS.comment, Literal(f"mass {obj.mass} kg")))
        for task in obj.tasks:
            graph.add((node, URIRef(vocab.affords), URIRef(ns + task)))
            disposition = actions[task].disposition
            if disposition is not None:
                affords = _some(graph, SOMA.affordsTask, URIRef(ns + task))
                both = BNode()
                graph.add((both, RDF.type, OWL.Class))
                members = BNode()
                Collection(graph, members, [URIRef(disposition), affords])
                graph.add((both, OWL.intersectionOf, members))
                graph.add((node, RDFS.subClassOf, _some(graph, SOMA.hasDisposition, both)))

    report = BuildReport(
        n_objects=len(objects),
        n_abstract=sum(1 for o in objects.values() if o.abstract),
        n_tasks=len(actions),
        unmapped=tuple(sorted(unmapped_roots)),
        mapped_absent=tuple(sorted(set(maps.object_map) - set(objects))),
        default_tasks=tuple(default_tasks),
        n_triples=len(graph),
    )
    return graph, report


def _some(graph: Graph, prop: URIRef, filler: URIRef | BNode) -> BNode:
    node = BNode()
    graph.add((node, RDF.type, OWL.Restriction))
    graph.add((node, OWL.onProperty, prop))
    graph.add((node, OWL.someValuesFrom, filler))
    return node


def _add_vocabulary(graph: Graph, vocab: Vocabulary) -> None:
    def cls(iri: str, parent: URIRef, comment: str) -> None:
        node = URIRef(iri)
        graph.add((node, RDF.type, OWL.Class))
        graph.add((node, RDFS.subClassOf, parent))
        graph.add((node, RDFS.comment, Literal(comment)))

    cls(vocab.idle_task, SOMA.PhysicalTask, "The robot is in shared grasping for 20 s or more, executing no task.")
    cls(vocab.time_of_day, DUL.TimeInterval, "A part of the day in which an event happens.")
    for part in vocab.parts_of_day:
        cls(part, URIRef(vocab.time_of_day), f"The time interval of an event that happens at {part.rsplit('#', 1)[-1].lower()}.")

    def prop(iri: str, kind: URIRef, domain: URIRef, range_: URIRef, comment: str) -> None:
        node = URIRef(iri)
        graph.add((node, RDF.type, kind))
        graph.add((node, RDFS.domain, domain))
        graph.add((node, RDFS.range, range_))
        graph.add((node, RDFS.comment, Literal(comment)))

    prop(vocab.imagines_situation, OWL.ObjectProperty, SOMA.MentalAction, SOMA.ActionExecutionPlan,
         "A mental action imagining a task that is available at its time.")
    prop(vocab.imagines_preference, OWL.ObjectProperty, SOMA.MentalAction, SOMA.PreferenceOrder,
         "A reasoning action imagining the user's preference over the available tasks.")
    prop(vocab.has_rank, OWL.DatatypeProperty, SOMA.OrderedElement, XSD.integer, "Rank of an ordered element, 1 = most preferred.")
    prop(vocab.has_score, OWL.DatatypeProperty, SOMA.OrderedElement, XSD.double, "Score of an ordered element; lower is preferred.")
    for iri, comment in (
        (vocab.target_role, "Role the target object plays in this odb task."),
        (vocab.reference_role, "Role the reference object plays in this odb task."),
        (vocab.disposition, "Disposition an object needs to afford this odb task."),
        (vocab.affords, "An odb object affords this odb task (inherited by its children)."),
    ):
        graph.add((URIRef(iri), RDF.type, OWL.AnnotationProperty))
        graph.add((URIRef(iri), RDFS.comment, Literal(comment)))
