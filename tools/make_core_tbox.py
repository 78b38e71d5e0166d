"""Regenerate ontology/soma-core.ttl from the official SOMA/DUL files.

The core TBox holds every SOMA/DUL class and property this project uses with the asserted
(named) rdfs:subClassOf / rdfs:subPropertyOf chains of the official files, so the project runs
without them. Usage: python tools/make_core_tbox.py ../shared/soma ontology/soma-core.ttl
"""

from __future__ import annotations

import sys
from pathlib import Path

from rdflib import Graph, URIRef
from rdflib.namespace import OWL, RDF, RDFS

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "python"))
from oracle.namespaces import DUL, SOMA  # noqa: E402
from oracle.ontology.mapping import load_mapping  # noqa: E402

#: Entities the logger, the Prolog model and the vocabulary use beyond the mapping.
EXTRA_CLASSES = [
    DUL.Action, DUL.Event, DUL.Task, DUL.Role, DUL.Agent, DUL.Object, DUL.PhysicalObject, DUL.Situation,
    DUL.TimeInterval, DUL.Plan, DUL.Concept, DUL.Entity, SOMA.PhysicalAction, SOMA.MentalAction, SOMA.PhysicalTask,
    SOMA.MentalTask, SOMA.Imagining, SOMA.Reasoning, SOMA.ActionExecutionPlan, SOMA.Episode, SOMA.PreferenceOrder,
    SOMA.Preference, SOMA.Order, SOMA.OrderedElement, SOMA.Singleton, SOMA.AgentRole, SOMA.Patient, SOMA.Instrument,
    SOMA.Cup, SOMA.Glass, SOMA.Bottle, SOMA.Bowl, SOMA.Plate, SOMA.Knife, SOMA.Spoon, SOMA.Fork, SOMA.Cutlery,
    SOMA.Crockery, SOMA.Table, SOMA.Countertop, SOMA.Placing, SOMA.PouringInto, SOMA.Pouring, SOMA.Transporting,
    SOMA.Kitchen, SOMA.ExecutionStateRegion, SOMA.Destination,
    # used by the mappings the dataset converters write (python/oracle/evaluation/convert_*.py)
    DUL.DesignedArtifact, DUL.DesignedSubstance, SOMA.Door, SOMA.Cupboard, SOMA.Fluid, SOMA.Hand, SOMA.Pan,
    SOMA.Pot, SOMA.Cleaning, SOMA.LookingAt, SOMA.Mixing, SOMA.ModifyingPhysicalObject, SOMA.Positioning,
    SOMA.PushingDown, SOMA.PuttingDown, SOMA.Squeezing, SOMA.AlteredObject, SOMA.Dish, SOMA.Bread,
    SOMA.Refrigerator, SOMA.Dishwasher, SOMA.Stove, SOMA.Tap, SOMA.Drawer, SOMA.CutObject,
]
EXTRA_PROPERTIES = [
    DUL.executesTask, DUL.isExecutedIn, DUL.hasParticipant, DUL.isParticipantIn, SOMA.isPerformedBy,
    DUL.classifies, DUL.isClassifiedBy, DUL.hasRole, DUL.isRoleOf, DUL.hasTimeInterval, SOMA.hasIntervalBegin,
    SOMA.hasIntervalEnd, SOMA.isPlanFor, DUL.isTaskOf, DUL.hasTask, SOMA.hasDisposition, SOMA.affordsTask,
    SOMA.orders, SOMA.isOrderedBy, SOMA.encapsulates, DUL.precedes, DUL.follows, DUL.includesAction,
    DUL.isSettingFor, DUL.hasConstituent, SOMA.hasPhase, DUL.satisfies, SOMA.hasExecutionState, DUL.hasLocation,
    SOMA.hasPreference, SOMA.isPreferenceOf, DUL.describes, DUL.hasComponent, DUL.includesObject, DUL.includesAgent,
]


def main(soma_dir: str, out: str) -> None:
    official = Graph()
    for name in ("DUL.owl", "SOMA.owl", "SOMA-HOME.owl"):
        official.parse(Path(soma_dir) / name, format="xml")
    mapping = load_mapping(Path(__file__).resolve().parents[1] / "ontology" / "mapping.yaml")
    seeds = {URIRef(i) for i in mapping.object_map.values()} | {URIRef(mapping.root_object)}
    for action in [mapping.defaults, *mapping.actions.values()]:
        seeds |= {URIRef(v) for v in (action.task, action.ref_role, action.target_role, action.disposition) if v}
    seeds |= set(EXTRA_CLASSES)
    core = Graph()
    core.bind("soma", SOMA)
    core.bind("dul", DUL)
    core.bind("owl", OWL)

    def close(start: set[URIRef], kind: URIRef, edge: URIRef) -> set[URIRef]:
        done: set[URIRef] = set()
        todo = list(start)
        while todo:
            node = todo.pop()
            if node in done:
                continue
            if (node, RDF.type, kind) not in official:
                raise SystemExit(f"{node} is not declared as {kind} in the official files")
            done.add(node)
            for parent in official.objects(node, edge):
                if isinstance(parent, URIRef):
                    todo.append(parent)
        return done

    classes = close(seeds, OWL.Class, RDFS.subClassOf)
    for cls in classes:
        core.add((cls, RDF.type, OWL.Class))
        for parent in official.objects(cls, RDFS.subClassOf):
            if isinstance(parent, URIRef):
                core.add((cls, RDFS.subClassOf, parent))
    props: set[URIRef] = set()
    for p in EXTRA_PROPERTIES:
        kind = OWL.ObjectProperty if (p, RDF.type, OWL.ObjectProperty) in official else OWL.DatatypeProperty
        props |= close({p}, kind, RDFS.subPropertyOf)
    for p in props:
        for kind in (OWL.ObjectProperty, OWL.DatatypeProperty):
            if (p, RDF.type, kind) in official:
                core.add((p, RDF.type, kind))
        for parent in official.objects(p, RDFS.subPropertyOf):
            if isinstance(parent, URIRef):
                core.add((p, RDFS.subPropertyOf, parent))
        for inverse in official.objects(p, OWL.inverseOf):
            if inverse in props:
                core.add((p, OWL.inverseOf, inverse))
    header = (
        "# Core TBox of neem-oracle: the SOMA/DUL classes and properties the project uses, with the\n"
        "# asserted subclass and subproperty chains of the official SOMA.owl, SOMA-HOME.owl and DUL.owl\n"
        "# (ease-crc/soma, LGPL-3.0; DUL by the DOLCE authors, CC BY). Generated by\n"
        "# tools/make_core_tbox.py; do not edit by hand.\n"
    )
    Path(out).write_text(header + core.serialize(format="turtle"))
    print(f"{out}: {len(classes)} classes, {len(props)} properties, {len(core)} triples")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
