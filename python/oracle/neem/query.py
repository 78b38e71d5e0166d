"""Reading a NEEM back for listings and tests: executed actions in time order, one-line summaries.

The oracle itself reads its history through Prolog (``odb_history:situation_history``); this module
is the small Python-side reader the CLI's listings and the logger's own resume need.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from oracle.neem import terms as T
from oracle.errors import StoreError
from oracle.store.ids import alias_of
from oracle.store import RDF_TYPE, NeemInfo, Store, TriplePattern, Var
from oracle.store.model import TripleRow
from oracle.store.base import SUMMARY_KEY
from oracle.timeline import TIME_OF_DAY_NAMES

if TYPE_CHECKING:  # the ontology package imports rdflib and numpy, which a listing never needs
    from oracle.ontology.vocabulary import Vocabulary


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
    #: The NEEM's alias (``--neem`` takes it or the id), None for a NEEM without one.
    name: str | None = None


def summarize_neem(store: Store, neem_id: str, info: NeemInfo | None = None) -> NeemSummary:
    """User, number of executed actions and time span of a NEEM (ours or a loaded one).

    The registry keeps them under SUMMARY_KEY with the store's write mark (``Store.write_mark``)
    they were taken at; the logger moves them on as it commits, any other write (a load, a
    bare insert) moves the mark, and the next listing reads the triples once and keeps them."""
    info = store.neem(neem_id) if info is None else info
    mark = store.write_mark(neem_id)
    kept = info.meta.get(SUMMARY_KEY)
    if isinstance(kept, dict) and kept.get("mark") == mark:
        return NeemSummary(neem_id, info.user, int(kept["actions"]), kept.get("begin"), kept.get("end"), info.temporary,
                           alias_of(info))
    actions, begin, end = count_actions(store, neem_id)
    try:
        store.update_meta(neem_id, **{SUMMARY_KEY: {"actions": actions, "begin": begin, "end": end, "mark": mark}})
    except StoreError:
        pass  # a store opened read-only lists what it reads, it just cannot keep the summary
    return NeemSummary(neem_id, info.user, actions, begin, end, info.temporary, alias_of(info))


def count_actions(store: Store, neem_id: str) -> tuple[int, float | None, float | None]:
    """Executed actions, earliest begin and latest end of a NEEM, read from its triples."""
    # An episode's top-level action (KnowRob's `is_setting_for(Episode, Action)`, ours and
    # neem-interface's) holds the executed ones as constituents: it is no action of its own.
    tops = {doc["s"] for doc in store.find(neem_id, p=T.HAS_CONSTITUENT)}
    tops.update(doc["o"] for p in (T.INCLUDES_ACTION, T.IS_SETTING_FOR) for doc in store.find(neem_id, p=p))
    actions = {
        doc["s"]
        for doc in store.find(neem_id, p=RDF_TYPE, o=T.ACTION)
        if T.MENTAL_ACTION not in (doc.get("o*") or ()) and doc.get("o") != T.MENTAL_ACTION and doc["s"] not in tops
    }
    begins = [row["B"] for row in store.match(neem_id, [TriplePattern(Var("I"), T.BEGIN, Var("B"))])]
    ends = [row["E"] for row in store.match(neem_id, [TriplePattern(Var("I"), T.END, Var("E"))])]
    def numbers(values: list[object]) -> list[float]:
        return [v for v in values if isinstance(v, (int, float))]

    return (
        len(actions),
        min(numbers(begins), default=None),
        max(numbers(ends) or numbers(begins), default=None),
    )


def summary_after(summary: dict[str, Any], triples: Iterable[TripleRow]) -> dict[str, Any]:
    """A summary moved on by triples written by the logger (which types executed actions
    exactly ``dul:Action`` and mental ones ``soma:MentalAction``)."""
    actions, begin, end = summary["actions"], summary["begin"], summary["end"]
    for _, p, o, _, _, _ in triples:  # unpacked, not read by name: the logger writes plain tuples
        if p == RDF_TYPE:
            if o == T.ACTION:
                actions += 1
        elif p == T.BEGIN and isinstance(o, (int, float)):
            begin = o if begin is None else min(begin, o)
            end = o if end is None else max(end, o)
        elif p == T.END and isinstance(o, (int, float)):
            end = o if end is None else max(end, o)
    return {"actions": actions, "begin": begin, "end": end}


def recorded_part_of_day(store: Store, neem_id: str, vocab: Vocabulary, begin: float) -> str | None:
    """The odb:TimeOfDay part an interval starting at ``begin`` was logged with (its wall clock
    as written, oracle.timeline), or None when no such interval is typed with one."""
    parts = {vocab.part_of_day(name): name for name in TIME_OF_DAY_NAMES}
    rows = store.match(neem_id, [TriplePattern(Var("I"), T.BEGIN, begin), TriplePattern(Var("I"), RDF_TYPE, Var("C"))])
    return next((parts[row["C"]] for row in rows if row["C"] in parts), None)
