"""The user's routines in the NEEM as SOMA/DUL workflows, as KnowRob models them (its
``workflow_step/2``, ``workflow_first_step/2`` and the pancake test plans): a ``dul:Workflow``
with an ``rdfs:label`` (its name), ``soma:hasStep`` each step task (typed with the odb task
class, its roles classifying the NEEM's objects, as a logged task's), ``soma:hasFirstStep``, and
``soma:before``/``soma:after`` between consecutive steps; the days it was seen, its usual hour
and whether the user named it as ``odb:`` data. They live in a graph of their own, replaced
whole on every save."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace
from typing import TYPE_CHECKING, Any

from oracle.chains import parse_call
from oracle.neem import terms as T
from oracle.namespaces import DUL_IRI, RDFS_IRI, SOMA_IRI
from oracle.past.routines import Routine, jaccard
from oracle.store import Triple
from oracle.store.model import RDF_TYPE

if TYPE_CHECKING:
    from oracle.bridge import Bridge
    from oracle.neem.writer import NeemLogger
    from oracle.ontology import OdbOntology
    from oracle.store import Store

#: The named graph the workflows are written in.
GRAPH = "routines"
WORKFLOW = DUL_IRI + "Workflow"
HAS_STEP = SOMA_IRI + "hasStep"
FIRST_STEP = SOMA_IRI + "hasFirstStep"
BEFORE = SOMA_IRI + "before"
AFTER = SOMA_IRI + "after"
LABEL = RDFS_IRI + "label"
#: How alike (Jaccard of the steps) a new routine and a stored one must be to keep its user-given name.
SAME_ROUTINE = 0.5


def workflow_triples(objects: NeemLogger, onto: OdbOntology, routine: Routine, by_user: bool) -> list[Triple]:
    """The triples of one routine's workflow (in GRAPH); ``objects`` names the NEEM's object
    individuals (the logger is the one home of their IRIs)."""
    ns = onto.namespace
    wf = f"{ns}Workflow_{routine.key}"
    out = [Triple(wf, RDF_TYPE, WORKFLOW, GRAPH), Triple(wf, RDF_TYPE, T.NAMED_INDIVIDUAL, GRAPH),
           Triple(wf, LABEL, routine.name, GRAPH), Triple(wf, ns + "routineDays", routine.days, GRAPH),
           Triple(wf, ns + "routineUsualHour", round(routine.hour, 4), GRAPH),
           Triple(wf, ns + "routineNamedByUser", by_user, GRAPH)]
    previous = None
    for index, text in enumerate(routine.steps, start=1):
        call = parse_call(text)
        step = f"{wf}_step{index}"
        out += [Triple(step, RDF_TYPE, onto.task_iri(call.task), GRAPH), Triple(step, RDF_TYPE, T.NAMED_INDIVIDUAL, GRAPH),
                Triple(wf, HAS_STEP, step, GRAPH)]
        for slot, (arg, role_class) in enumerate(zip(call.args, onto.task_roles(call.task, len(call.args)))):
            if role_class is None:
                continue
            role = f"{step}_role{slot}"
            out += [Triple(role, RDF_TYPE, role_class, GRAPH), Triple(role, RDF_TYPE, T.NAMED_INDIVIDUAL, GRAPH),
                    Triple(step, T.IS_TASK_OF, role, GRAPH), Triple(role, T.CLASSIFIES, objects.object_iri(arg), GRAPH)]
        if previous is None:
            out.append(Triple(wf, FIRST_STEP, step, GRAPH))
        else:
            out += [Triple(previous, BEFORE, step, GRAPH), Triple(step, AFTER, previous, GRAPH)]
        previous = step
    return out


def save_routines(store: Store, onto: OdbOntology, neem_id: str, routines: Sequence[Routine],
                  named: Sequence[str] = ()) -> int:
    """Replace the NEEM's workflows by ``routines`` (``named``: the keys whose names the user
    gave); return how many triples were written."""
    from oracle.neem.writer import NeemLogger
    from oracle.store.ids import resolve_neem
    from oracle.store.project import retract

    neem_id = resolve_neem(store, neem_id)
    objects = NeemLogger(store, onto, neem_id)
    triples = [t for r in routines for t in workflow_triples(objects, onto, r, r.key in named)]
    with store.transaction():
        retract(store, neem_id, graph=GRAPH)
        store.insert(neem_id, triples)
    return len(triples)


def stored_routines(bridge: Bridge) -> list[dict[str, Any]]:
    """The workflows stored in the NEEM, read through Prolog (prolog/odb/routines.pl):
    ``{"iri", "name", "steps", "days", "hour", "by_user"}`` each."""
    import json

    from oracle.paths import prolog_dir

    bridge.use_module(prolog_dir() / "odb" / "routines.pl", "odb_routines:stored_routines_json/1")
    rows = bridge.ask("odb_routines:stored_routines_json(J)", [])
    text = rows[0]["J"]
    found: list[dict[str, Any]] = json.loads(text.decode("utf-8") if isinstance(text, bytes) else text)
    return found


def keep_user_names(routines: Sequence[Routine], stored: Sequence[dict[str, Any]]) -> tuple[list[Routine], list[str]]:
    """The routines with the names the user gave the stored workflows they continue (the most
    alike stored one, Jaccard of the steps >= SAME_ROUTINE); and the keys that kept one."""
    out, named = [], []
    given = [s for s in stored if s["by_user"]]
    for routine in routines:
        best = max(given, key=lambda s: jaccard(routine.steps, s["steps"]), default=None)
        if best is not None and jaccard(routine.steps, best["steps"]) >= SAME_ROUTINE:
            routine = replace(routine, name=best["name"])
            named.append(routine.key)
            given.remove(best)
        out.append(routine)
    return out, named
