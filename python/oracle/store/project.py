"""KnowRob's writes that change what is stored (kb_project merging scopes, until/since
narrowing them, kb_unproject deleting), over the backends' three primitives: the stored
documents of a fact that overlap a time window, a new scope for one of them, and a delete."""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any, Literal

from oracle.errors import StoreError
from oracle.store.base import SUMMARY_KEY, Store, check_literal
from oracle.store.model import Scope, Triple

#: ``union``: kb_project (a stored fact whose scope overlaps the new one becomes one fact over
#: both); ``intersect``: ``until``/``since`` (the stored fact is narrowed to the new scope).
Merge = Literal["union", "intersect"]


def project(store: Store, neem_id: str, triples: Iterable[Triple], merge: Merge = "union") -> int:
    """Write ``triples`` as KnowRob's kb_project does; return how many new documents were stored.

    A triple with no stored document of the same s, p and o in its graph (each ontology graph
    keeps its own copy of a fact, as KnowRob's load_owl does) whose scope overlaps its own is
    stored as new. Otherwise, with ``union``, the first overlapping document gets the union of
    the scopes and the others are deleted; with ``intersect`` each overlapping document is
    narrowed to its intersection with the new scope and nothing is added. One transaction on
    SQLite. On MongoDB (no transactions) each document changes in one atomic update, the widened
    one before the ones it subsumes are deleted: a kill in between leaves a fact twice, never
    a time it was not stated for.
    """
    if merge not in ("union", "intersect"):
        raise StoreError(f"merge must be 'union' or 'intersect', not {merge!r}")
    batch = list(triples)
    for triple in batch:
        for term in (triple.s, triple.p, triple.o):
            check_literal(term)
        if triple.since > triple.until:
            raise StoreError(f"scope of {triple} ends before it starts")
    #: New facts not stored yet, by (s, p, o): what a later triple of the batch merges with.
    pending: dict[tuple[Any, ...], list[Triple]] = {}
    deleted = False
    with store.transaction():
        for triple in batch:
            key = (triple.s, triple.p, type(triple.o), triple.o, triple.graph)
            stored = store._overlapping(neem_id, triple.s, triple.p, triple.o, Scope(triple.since, triple.until), triple.graph)
            waiting = pending.setdefault(key, [])
            mates = [t for t in waiting if t.since <= triple.until and t.until >= triple.since]
            others = [t for t in waiting if not (t.since <= triple.until and t.until >= triple.since)]
            if merge == "intersect":
                for doc, since, until in stored:
                    store._rescope(neem_id, doc, max(since, triple.since), min(until, triple.until))
                narrowed = [_scoped(t, max(t.since, triple.since), min(t.until, triple.until)) for t in mates]
                pending[key] = others + (narrowed if stored or mates else [triple])
                continue
            since = min([triple.since, *(s for _, s, _ in stored), *(t.since for t in mates)])
            until = max([triple.until, *(u for _, _, u in stored), *(t.until for t in mates)])
            if stored:
                store._rescope(neem_id, stored[0][0], since, until)
                if len(stored) > 1:
                    store._delete_triples(neem_id, [doc for doc, _, _ in stored[1:]])
                    deleted = True
                pending[key] = others
            else:
                pending[key] = [*others, _scoped(triple, since, until)]
        new = [t for ts in pending.values() for t in ts]
        count = store.insert(neem_id, new) if new else 0
        if deleted:  # a delete may bring the write mark back to a value a kept summary has seen
            store.update_meta(neem_id, **{SUMMARY_KEY: None})
        return count


def retract(store: Store, neem_id: str, s: Any = None, p: Any = None, o: Any = None, graph: str | None = None) -> int:
    """Delete the documents whose asserted s, p and o match (None: any) in ``graph`` (None:
    any; KnowRob's drop_graph is ``retract(store, neem, graph=G)``), as kb_unproject; return
    how many. The closures of other documents are left as they are (KnowRob does the
    same), so retracting a subClassOf triple does not shrink the ``o*`` already stored."""
    for term in (s, p, o):
        check_literal(term)
    with store.transaction():
        found = [doc for doc, _, _ in store._overlapping(neem_id, s, p, o, None, graph)]
        if found:
            store._delete_triples(neem_id, found)
            store._hierarchies.pop(neem_id, None)
            store.update_meta(neem_id, **{SUMMARY_KEY: None})  # counted again at the next listing
    return len(found)


def _scoped(triple: Triple, since: float, until: float) -> Triple:
    return Triple(triple.s, triple.p, triple.o, triple.graph, since, until)


__all__ = ["Merge", "project", "retract"]
