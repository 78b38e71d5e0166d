"""The Store interface both backends implement, and the insert path they share.

Closure and propagation are computed here once, in Python, so SQLite and MongoDB hold the very
same documents; a backend only stores documents, finds them, and rewrites closures on request.

Why this module is large: it is the one contract both backends implement (registry, atomic
replacement, inserting with closures, reading, and the primitives store/project.py changes
stored documents with); split, a backend could satisfy half of it.
"""

from __future__ import annotations

import contextlib

import os
import re
from abc import ABC, abstractmethod
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from contextlib import AbstractContextManager
from dataclasses import dataclass, field
from datetime import datetime
from typing import Any

from bson.decimal128 import Decimal128

from oracle.errors import StoreError
from oracle.store.chunks import MatchChunk, chunks_from_solutions
from oracle.store.ids import check_alias_free
from oracle.store.meta import new_meta
from oracle.store.staging import READY, STAGED_BY, STAGING, builder, drop_abandoned
from oracle.store.validate import check_document, validate_group, validate_order, validate_select
from oracle.store.model import (
    HIERARCHY,
    TAXONOMIC,
    Annotation,
    Cmp,
    DocumentBuilder,
    Hierarchy,
    NumberFormat,
    Scope,
    Term,
    TriplePattern,
    TripleRow,
    Var,
    annotation_document,
)

#: The logical collections of a NEEM, in KnowRob's order (``mng_client:collection_names``).
COLLECTION_KINDS: tuple[str, ...] = ("triples", "annotations", "tf", "inferred")

#: A triple with its ``p*`` and ``o*``, ready to store.
Closed = tuple[TripleRow, tuple[Any, ...], tuple[Any, ...]]

_NEEM_ID = re.compile(r"^[A-Za-z0-9][A-Za-z0-9\-]{0,63}$")


def check_neem_id(neem_id: str) -> str:
    """NEEM ids become collection and table prefixes, so they are restricted to safe names.

    Underscores are refused because ``<id>_triples`` must split back into id and kind.
    """
    if not isinstance(neem_id, str) or not _NEEM_ID.match(neem_id):
        raise StoreError(
            f"invalid NEEM id {neem_id!r}: use 1-64 letters, digits and '-', starting with a letter or digit"
        )
    return neem_id


@dataclass(frozen=True)
class AppendMark:
    """Where a NEEM's triples stand, for a reader that keeps what it read and later reads only
    what was added (oracle.historycache). ``token`` names the NEEM's tables (made anew, as by
    ``import --replace``, they get another), ``changes`` counts every update and deletion of
    one of its triples, ever, and ``last`` is the id of its last triple."""

    token: str
    changes: int
    last: int


@dataclass(frozen=True)
class Appended:
    """The triples a NEEM gained after a mark's ``last`` id, in the order they were added, and
    whether every subject among them is new: a term that no earlier triple of the NEEM has,
    as subject or as object. Then nothing reached from an earlier individual over a triple
    (subject to object) is among them."""

    docs: list[dict[str, Any]]
    fresh: bool


@dataclass(frozen=True)
class NeemInfo:
    """A NEEM's registry entry (openEASE's ``meta`` document, trimmed to what we use)."""

    id: str
    user: str | None = None
    created_at: str | None = None
    temporary: bool = False
    meta: Mapping[str, Any] = field(default_factory=dict, compare=False)

    @staticmethod
    def from_meta(neem_id: str, meta: Mapping[str, Any]) -> NeemInfo:
        return NeemInfo(
            id=neem_id,
            user=meta.get("created_by"),
            created_at=meta.get("created_at"),
            temporary=bool(meta.get("temporary", False)),
            meta=dict(meta),
        )


#: Registry key of the summary ``neems`` lists (oracle.neem.query keeps it); never exported.
SUMMARY_KEY = "summary"


class Store(ABC):
    """A set of NEEMs in the KnowRob 2.x layout; see docs/store.md.

    Reads never change anything; every write of one call is one transaction on SQLite (the
    logger relies on it for crash safety); MongoDB has no transactions, as in KnowRob.
    """

    number_format: NumberFormat
    location: str

    def __init__(self, number_format: NumberFormat = "decimal128") -> None:
        if number_format not in ("decimal128", "double"):
            raise StoreError(f"number format must be 'decimal128' or 'double', not {number_format!r}")
        self.number_format = number_format
        self._hierarchies: dict[str, Hierarchy] = {}

    # -- registry ---------------------------------------------------------------------------
    @abstractmethod
    def neems(self) -> list[NeemInfo]:
        """Every NEEM in the store, sorted by id."""

    def neem(self, neem_id: str) -> NeemInfo:
        for info in self.neems():
            if info.id == neem_id:
                return info
        raise StoreError(f"{self.location}: no NEEM {neem_id!r}")

    def has_neem(self, neem_id: str) -> bool:
        return any(info.id == neem_id for info in self.neems())

    def create_neem(self, neem_id: str, *, user: str | None = None, temporary: bool = False,
                    meta: Mapping[str, Any] | None = None, side_property: str | None = None) -> NeemInfo:  # fmt: skip
        """Create the empty collections (KnowRob's indexes) and the registry entry; see SQLiteStore for ``side_property``."""
        check_neem_id(neem_id)
        if self.has_neem(neem_id):
            raise StoreError(f"{self.location}: NEEM {neem_id!r} already exists")
        record = new_meta(user, temporary, meta, name=neem_id)
        self._create_neem(neem_id, record, side_property)
        self._hierarchies.pop(neem_id, None)
        return NeemInfo.from_meta(neem_id, record)

    @abstractmethod
    def _create_neem(self, neem_id: str, record: dict[str, Any], side_property: str | None) -> None: ...

    def drop_neem(self, neem_id: str) -> None:
        """Delete a NEEM and everything in it."""
        self.neem(neem_id)
        self._drop_neem(neem_id)
        self._hierarchies.pop(neem_id, None)

    @abstractmethod
    def _drop_neem(self, neem_id: str) -> None: ...

    def rename_neem(self, neem_id: str, new_id: str) -> None:
        """Give a NEEM a new id (collection prefix); its documents are untouched."""
        info = self.neem(neem_id)
        check_neem_id(new_id)
        if self.has_neem(new_id):
            raise StoreError(f"{self.location}: NEEM {new_id!r} already exists")
        self._rename_neem(neem_id, new_id, info)
        self._hierarchies.pop(neem_id, None)

    @abstractmethod
    def _rename_neem(self, neem_id: str, new_id: str, info: NeemInfo) -> None: ...

    def interrupted_rename(self, neem_id: str, new_id: str) -> bool:
        """Whether renaming ``neem_id`` to ``new_id`` stopped half-way, leaving the NEEM split
        across both names (a kill between MongoDB's per-collection renames); never where a
        rename is one transaction."""
        del neem_id, new_id
        return False

    def finish_rename(self, neem_id: str, new_id: str) -> None:
        """Move what an interrupted rename (``interrupted_rename``) left under ``neem_id``."""
        self._rename_neem(neem_id, new_id, self.neem(neem_id))
        self._hierarchies.pop(neem_id, None)

    @abstractmethod
    def update_meta(self, neem_id: str, **fields: Any) -> NeemInfo:
        """Change registry fields such as ``temporary``."""

    # -- replacing a NEEM atomically --------------------------------------------------------
    def create_staging(self, target: str, *, user: str | None = None, meta: Mapping[str, Any] | None = None,
                       side_property: str | None = None) -> str:  # fmt: skip
        """A new, hidden NEEM to build ``target`` (or its replacement) in, which ``swap_in`` makes
        ``target``; a process killed meanwhile leaves ``target`` as it was (see store.staging)."""
        check_neem_id(target)
        drop_abandoned(self)
        staging = f"staging-{os.urandom(6).hex()}"  # the prefix is how backends find them (staging_neems)
        extra = {**(meta or {}), STAGING: target, STAGED_BY: builder()}
        temporary = bool(extra.pop("temporary", False))
        self.create_neem(staging, user=user, temporary=temporary, meta=extra, side_property=side_property)
        return staging

    @abstractmethod
    def staging_neems(self) -> list[NeemInfo]:
        """The hidden NEEMs under construction (``create_staging``), which ``neems()`` leaves out."""

    def swap_in(self, staging: str, target: str, *, replace: bool = True, **fields: Any) -> NeemInfo:
        """Make the complete NEEM ``staging`` visible as ``target``, replacing an existing one only
        if ``replace`` (else StoreError: another process took the id meanwhile). One transaction
        on SQLite; on MongoDB a rename per collection (KnowRob has no transactions)."""
        with self.transaction():
            check_alias_free(self, staging, target)  # two builders may have picked one name
            if self.has_neem(target):
                if not replace:
                    raise StoreError(f"{self.location}: NEEM {target!r} already exists")
                self.update_meta(staging, **{READY: True})
                self.drop_neem(target)
            self.rename_neem(staging, target)
            return self.update_meta(target, **{STAGING: None, STAGED_BY: None, READY: None, **fields})

    # -- writing ----------------------------------------------------------------------------
    @abstractmethod
    def transaction(self) -> AbstractContextManager[None]:
        """Group writes so they commit together (SQLite) or run as they come (MongoDB)."""

    def deferred_sync(self) -> AbstractContextManager[None]:
        """Inside, a commit is written but not flushed to disk (it survives a killed process,
        not a power loss) until ``sync``: a bulk import flushes once per user, not per commit.
        A store that flushes nothing itself (MongoDB: its write concern) changes nothing."""
        return contextlib.nullcontext()

    def sync(self) -> None:
        """Every commit made so far on disk (after ``deferred_sync``'s commits); nothing where
        each commit already is."""
        return None

    def unsynced(self) -> AbstractContextManager[None]:
        """Like ``deferred_sync`` but nothing is flushed as it ends: the caller calls ``sync``
        (from any thread) before it tells anyone the commits inside are stored (the service's
        group commit flushes on a thread of its own while the engine goes on). Enter it outside
        any transaction."""
        return contextlib.nullcontext()

    def shrink_memory(self) -> None:
        """Give back what the store's connection caches in memory (a bulk write's pages), before
        a long step that needs none of it; nothing for a store that keeps no such cache."""
        return None

    def defer_indexes(self, neem_id: str) -> None:
        """Before a bulk write into a new NEEM: its indexes that the writer's own reads do not use
        are left out until ``make_indexes`` builds each in one sorted pass (cheaper than keeping
        them row by row). Reads stay correct meanwhile, only slower. Nothing elsewhere."""
        return None

    def make_indexes(self, neem_id: str) -> None:
        """Every index of the NEEM there again (those ``defer_indexes`` left out, or a killed
        bulk write's); nothing when they are."""
        return None

    def insert(self, neem_id: str, triples: Iterable[TripleRow]) -> int:
        """Store triples (``Triple``s or plain tuples of the same six values) with KnowRob's
        ``p*``/``o*`` closure; return how many were stored.

        A subClassOf/subPropertyOf triple also extends the closures of stored documents that pass
        through its subject, as kb_project does, so load order does not change the result.
        """
        hierarchy = self.hierarchy(neem_id)
        builder = DocumentBuilder(hierarchy, self.number_format)
        try:
            count = self._insert_closed(neem_id, triples, hierarchy, builder)
        except BaseException:
            # The in-memory taxonomy may hold edges the rolled-back transaction never stored.
            self._hierarchies.pop(neem_id, None)
            raise
        return count

    def _insert_closed(
        self, neem_id: str, triples: Iterable[TripleRow], hierarchy: Hierarchy, builder: DocumentBuilder
    ) -> int:
        # The closures of DocumentBuilder.closures, inlined: a batch uses few properties and
        # classes, so p* per property and o* per class are looked up once per batch, until a
        # subClassOf/subPropertyOf triple may change them.
        pending: list[Closed] = []
        append = pending.append
        count = 0
        closure = hierarchy.closure
        pstars: dict[str, tuple[Any, ...]] = {}
        ostars: dict[str, tuple[Any, ...]] = {}
        with self.transaction():
            for triple in triples:
                s, p, o, _, since, until = triple
                if since > until:
                    raise ValueError(f"scope of {triple} ends before it starts")
                if p not in TAXONOMIC:
                    pstar = pstars.get(p)
                    if pstar is None:
                        pstar = pstars[p] = closure(p)
                    append((triple, pstar, (o,)))
                    continue
                if type(o) is str:
                    ostar = ostars.get(o)
                    if ostar is None:
                        ostar = ostars[o] = closure(o)
                else:
                    ostar = (o,)
                append((triple, (p,), ostar))
                if p in HIERARCHY and isinstance(o, str):
                    pstars.clear()
                    ostars.clear()
                    _, gained = hierarchy.add_edge(s, o)
                    if gained and s in hierarchy.used:
                        self._insert_triples(neem_id, pending, builder)
                        count += len(pending)
                        pending = []
                        append = pending.append
                        self._propagate(neem_id, s, gained)
                        hierarchy.patch_closures(s, gained)
                        hierarchy.used.update(gained)
            if pending:
                self._insert_triples(neem_id, pending, builder)
                count += len(pending)
        return count

    def insert_annotations(self, neem_id: str, annotations: Iterable[Annotation]) -> int:
        docs = [annotation_document(a) for a in annotations]
        with self.transaction():
            if docs:
                self._insert_documents(neem_id, "annotations", docs)
        return len(docs)

    def write_documents(self, neem_id: str, kind: str, docs: Iterable[Mapping[str, Any]]) -> int:
        """Store documents exactly as given (a NEEM being loaded keeps its own closures)."""
        if kind not in COLLECTION_KINDS:
            raise StoreError(f"unknown collection kind {kind!r}; expected one of {', '.join(COLLECTION_KINDS)}")
        batch: list[dict[str, Any]] = []
        count = 0
        with self.transaction():
            for number, doc in enumerate(docs, start=1):
                check_document(kind, doc, f"{getattr(docs, 'where', kind)}: document {number}")
                batch.append(doc if isinstance(doc, dict) else dict(doc))
                if len(batch) >= 5000:
                    self._insert_documents(neem_id, kind, batch)
                    count += len(batch)
                    batch = []
            if batch:
                self._insert_documents(neem_id, kind, batch)
                count += len(batch)
        if kind == "triples":  # only triples carry the taxonomy
            self._hierarchies.pop(neem_id, None)
        return count

    def _insert_triples(self, neem_id: str, closed: list[Closed], builder: DocumentBuilder) -> None:
        """Store triples whose closures are computed; backends may skip building documents."""
        self._insert_documents(neem_id, "triples", [builder.document(t, (ps, os_)) for t, ps, os_ in closed])

    @abstractmethod
    def _insert_documents(self, neem_id: str, kind: str, docs: list[dict[str, Any]]) -> None: ...

    @abstractmethod
    def _propagate(self, neem_id: str, subject: str, gained: tuple[Any, ...]) -> None:
        """Append ``gained`` to ``o*`` of taxonomic and ``p*`` of other documents containing ``subject``."""

    # -- changing stored documents (store.project: kb_project's merge, until/since, kb_unproject)
    @abstractmethod
    def _overlapping(
        self, neem_id: str, s: Term, p: Term, o: Term, scope: Scope | None, graph: str | None = None
    ) -> list[tuple[Any, float, float]]:
        """(key, since, until) of the documents with these asserted s, p, o (None: any) in
        ``graph`` (None: any) whose scope overlaps ``scope`` (None: any time); the key
        addresses the document for the two methods below."""

    @abstractmethod
    def _rescope(self, neem_id: str, key: Any, since: float, until: float) -> None: ...

    @abstractmethod
    def _delete_triples(self, neem_id: str, keys: Sequence[Any]) -> None: ...

    # -- hierarchy --------------------------------------------------------------------------
    def hierarchy(self, neem_id: str) -> Hierarchy:
        """The NEEM's taxonomy, read once from its subClassOf/subPropertyOf documents."""
        cached = self._hierarchies.get(neem_id)
        if cached is None:
            self.neem(neem_id)
            edges, used = self._hierarchy_source(neem_id)
            cached = self._hierarchies[neem_id] = Hierarchy(edges, used)
        return cached

    @abstractmethod
    def _hierarchy_source(self, neem_id: str) -> tuple[list[tuple[str, tuple[Any, ...]]],
                                                       set[Any] | Callable[[], set[Any]]]:  # fmt: skip
        """(subject, o*) of every hierarchy edge, and every term used in a stored closure (or
        how to find them when a new edge first asks: model.Hierarchy)."""

    # -- reading ----------------------------------------------------------------------------
    @abstractmethod
    def read_documents(self, neem_id: str, kind: str) -> Iterator[dict[str, Any]]:
        """Every document of one collection, in insertion order, exactly as stored."""

    def count(self, neem_id: str, kind: str = "triples") -> int:
        """How many documents one collection of a NEEM holds."""
        if kind not in COLLECTION_KINDS:
            raise StoreError(f"unknown collection kind {kind!r}")
        return self._count(neem_id, kind)

    @abstractmethod
    def _count(self, neem_id: str, kind: str) -> int: ...

    def append_mark(self, neem_id: str) -> AppendMark | None:
        """The NEEM's AppendMark, or None where the backend cannot tell additions from changes
        (then a reader reads everything again)."""
        return None

    def appended(self, neem_id: str, last: int) -> Appended | None:
        """The triples added after id ``last`` (an AppendMark's), or None (as append_mark)."""
        return None

    def read_kept(self, neem_id: str, kind: str) -> bytes | None:
        """What a reader kept of the NEEM under ``kind`` (oracle.store.kept), or None; a backend
        that keeps nothing returns None."""
        return None

    def write_kept(self, neem_id: str, kind: str, data: bytes) -> bool:
        """Keep ``data`` for the NEEM under ``kind``; False where nothing can be kept (a backend
        without the table, a read-only store)."""
        return False

    def write_mark(self, neem_id: str) -> int:
        """A number that changes whenever triples are added to a NEEM (what a kept summary is
        checked against); backends override it with one that costs the same at every size."""
        return self.count(neem_id)

    def find(
        self,
        neem_id: str,
        s: Term = None,
        p: Term = None,
        o: Term = None,
        *,
        graph: str | None = None,
        scope: Scope | None = None,
        limit: int | None = None,
        exact: bool = False,
    ) -> Iterator[dict[str, Any]]:
        """Documents matching one pattern with KnowRob's semantics (see TriplePattern).

        ``exact`` compares s, p and o with the asserted fields only (no ``p*``/``o*``), which
        also finds documents without closures such as version markers. ``scope`` None means any
        time (KnowRob's wildcard scope); otherwise a document is returned when its scope overlaps
        the given one.
        """
        for term in (s, p, o):
            if isinstance(term, (Var, Cmp)):
                raise StoreError("find() takes constants; use match() for variables and comparisons")
            check_literal(term)
        if graph is not None and not isinstance(graph, str):
            raise StoreError(f"graph must be a string, got {graph!r}")
        return self._find(neem_id, TriplePattern(s, p, o, graph), scope, limit, exact)

    @abstractmethod
    def _find(
        self, neem_id: str, pattern: TriplePattern, scope: Scope | None, limit: int | None, exact: bool
    ) -> Iterator[dict[str, Any]]: ...

    def match(
        self,
        neem_id: str,
        patterns: Sequence[TriplePattern],
        *,
        scope: Scope | None = None,
        limit: int | None = None,
        order: Sequence[tuple[str, bool]] = (),
        select: Sequence[str] | None = None,
        group: str | None = None,
        written_order: bool = False,
    ) -> Iterator[dict[str, Any]]:
        """Solutions of a conjunction of patterns, computed by the database in ONE query.

        Yields one dict per solution mapping variable names to plain Python values
        (numbers as float or int, IRIs and strings as str). SQLite runs one SQL join,
        MongoDB one aggregation on ``one`` with a ``$lookup`` per pattern, as mongolog does.
        ``order`` is ``[(variable, descending), ...]`` over numeric variables, applied before
        ``limit`` by the database ("the latest decision before T" is one row, not a scan);
        with a ``limit``, solutions equal in every key come in no fixed order (a top-N scan
        stops at its last row), so a caller that needs all the rows at the last key's value
        asks again with a larger limit; with a ``limit`` and no ``order``, the solutions are any
        ``limit`` of them (SQLite stops at the first it finds).
        ``select`` names the variables the caller keeps (all of them when None): the others
        are joined on but never converted to Python values; the solutions are the same rows.
        ``group`` names a kept variable whose values are collected: one dict per distinct
        combination of the other kept variables, ``group`` mapped to the list of its values in
        those solutions (duplicates kept; groups and values in no fixed order).
        ``written_order`` joins the patterns in the order given (MongoDB's pipeline always
        does; SQLite, without statistics, may otherwise start from a large index range), also
        with an ``order``: then the rows are sorted after the join, for a first pattern that
        binds few rows (without it, SQLite scans the order's key from its first value, which
        stops early only when the first rows in that order match).
        """
        validate_patterns(patterns)
        kept = None if select is None else validate_select(patterns, select)
        checked = validate_order(patterns, order)
        if group is not None:
            kept = validate_group(patterns, kept, group, limit, checked)
        return self._match(neem_id, patterns, scope, limit, checked, kept, group, written_order)

    def match_chunks(
        self,
        neem_id: str,
        patterns: Sequence[TriplePattern],
        select: Sequence[str],
        *,
        scope: Scope | None = None,
        limit: int | None = None,
        order: Sequence[tuple[str, bool]] = (),
        group: str | None = None,
        written_order: bool = False,
        size: int = 5000,
    ) -> Iterator[MatchChunk]:
        """``match``'s solutions as chunks of up to ``size`` rows (store.chunks): each row the
        positions of the values of ``select`` in that order, ``group`` (selected) last."""
        validate_patterns(patterns)
        kept = validate_select(patterns, select)
        checked = validate_order(patterns, order)
        if group is not None:
            kept = validate_group(patterns, kept, group, limit, checked)
        return self._match_chunks(neem_id, patterns, scope, limit, checked, kept, group, written_order, size)

    def _match_chunks(self, neem_id: str, patterns: Sequence[TriplePattern], scope: Scope | None,
                      limit: int | None, order: Sequence[tuple[str, bool]], kept: list[str], group: str | None,
                      written_order: bool, size: int) -> Iterator[MatchChunk]:
        solutions = self._match(neem_id, patterns, scope, limit, order, kept, group, written_order)
        return chunks_from_solutions(solutions, kept, group is not None, size)

    @abstractmethod
    def _match(
        self,
        neem_id: str,
        patterns: Sequence[TriplePattern],
        scope: Scope | None,
        limit: int | None,
        order: Sequence[tuple[str, bool]],
        select: Sequence[str] | None = None,
        group: str | None = None,
        written_order: bool = False,
    ) -> Iterator[dict[str, Any]]: ...

    def annotations(self, neem_id: str, s: str | None = None, p: str | None = None) -> Iterator[Annotation]:
        for doc in self.read_documents(neem_id, "annotations"):
            if (s is None or doc.get("s") == s) and (p is None or doc.get("p") == p):
                yield Annotation(doc["s"], doc["p"], doc.get("v"))

    # -- lifetime ---------------------------------------------------------------------------
    @abstractmethod
    def close(self) -> None: ...

    def __enter__(self) -> Store:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


def validate_patterns(patterns: Sequence[TriplePattern]) -> None:
    if not patterns:
        raise StoreError("a query needs at least one triple pattern")
    for pattern in patterns:
        if not isinstance(pattern, TriplePattern):
            raise StoreError(f"not a TriplePattern: {pattern!r}")
        if isinstance(pattern.s, Cmp) or isinstance(pattern.p, Cmp):
            raise StoreError(f"a comparison may only stand for the object: {pattern!r}")
        for term in (pattern.s, pattern.p, pattern.o):
            if isinstance(term, Cmp):
                for _, number in term.conditions():
                    check_literal(number)
            elif not isinstance(term, Var):
                check_literal(term)


def check_literal(term: Any) -> None:
    """A query constant is a plain value: a dict (``{"$gt": ""}``, a MongoDB operator) or a list is refused."""
    if term is not None and not isinstance(term, (str, int, float, bool, Decimal128, datetime)):
        raise StoreError(f"a query constant must be a string, number, boolean or date, got {term!r}")
