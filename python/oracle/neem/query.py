"""Reading a NEEM back for listings and tests: executed actions in time order, one-line summaries.

The oracle itself reads its history through Prolog (``odb_model:situation_history``); this module
is the small Python-side reader the CLI's listings and the logger's own resume need.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

from oracle.neem import terms as T
from oracle.store import RDF_TYPE, Store, TriplePattern, Var


@dataclass(frozen=True)
class ActionView:
    """An executed action as read from a NEEM (for the oracle and for listings)."""

    iri: str
    task_class: str
    begin: float
    end: float
    participants: tuple[str, ...]


def executed_actions(store: Store, neem_id: str) -> Iterator[ActionView]:
    """Executed (non-mental) actions in time order, each with its task class and participants."""
    executed = {doc["s"] for doc in store.find(neem_id, p=RDF_TYPE, o=T.ACTION, exact=True)}
    rows = store.match(
        neem_id,
        [
            TriplePattern(Var("A"), T.EXECUTES, Var("T")),
            TriplePattern(Var("T"), RDF_TYPE, Var("C")),
            TriplePattern(Var("A"), T.HAS_INTERVAL, Var("I")),
            TriplePattern(Var("I"), T.BEGIN, Var("B")),
            TriplePattern(Var("I"), T.END, Var("E")),
        ],
    )
    found: dict[str, tuple[str, float, float]] = {}
    for row in rows:
        if row["A"] in executed and row["C"] != T.NAMED_INDIVIDUAL:
            found[row["A"]] = (row["C"], row["B"], row["E"])
    performers = {(row["A"], row["X"]) for row in store.match(neem_id, [TriplePattern(Var("A"), T.PERFORMED_BY, Var("X"))])}
    participants: dict[str, list[str]] = {}
    for row in store.match(neem_id, [TriplePattern(Var("A"), T.PARTICIPANT, Var("O"))]):
        if (row["A"], row["O"]) in performers:
            continue
        if row["A"] in found and row["O"] not in participants.setdefault(row["A"], []):
            participants[row["A"]].append(row["O"])
    for iri, (cls_iri, begin, end) in sorted(found.items(), key=lambda item: (item[1][1], item[0])):
        yield ActionView(iri, cls_iri, begin, end, tuple(participants.get(iri, ())))


@dataclass(frozen=True)
class NeemSummary:
    """One line of ``python -m oracle neems``."""

    id: str
    user: str | None
    actions: int
    begin: float | None
    end: float | None
    temporary: bool


def summarize_neem(store: Store, neem_id: str) -> NeemSummary:
    """User, number of executed actions and time span of a NEEM (ours or a loaded one)."""
    info = store.neem(neem_id)
    actions = {
        doc["s"]
        for doc in store.find(neem_id, p=RDF_TYPE, o=T.ACTION)
        if T.MENTAL_ACTION not in (doc.get("o*") or ()) and doc.get("o") != T.MENTAL_ACTION
    }
    begins = [row["B"] for row in store.match(neem_id, [TriplePattern(Var("I"), T.BEGIN, Var("B"))])]
    ends = [row["E"] for row in store.match(neem_id, [TriplePattern(Var("I"), T.END, Var("E"))])]
    numbers = lambda values: [v for v in values if isinstance(v, (int, float))]  # noqa: E731
    return NeemSummary(
        id=neem_id,
        user=info.user,
        actions=len(actions),
        begin=min(numbers(begins), default=None),
        end=max(numbers(ends) or numbers(begins), default=None),
        temporary=info.temporary,
    )
