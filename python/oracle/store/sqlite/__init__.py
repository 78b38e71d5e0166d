"""The embedded default backend: one SQLite file holding KnowRob documents, indexed.

Each NEEM gets the four KnowRob collections as tables (store.sqlite.tables). ``p*``/``o*`` are
stored by reference to content-addressed closures (store.sqlite.closures), IRIs and strings as
interned ids (store.sqlite.terms), so ``o* contains C`` is an indexed lookup of small integers.

``SQLiteStore`` is the ``Store`` interface over small parts that share one connection
(store.sqlite.connection): the registry of NEEMs and their tables, the write path, the read
path, and the matches the query compiler turns into one SQL join. It holds no logic of its own;
each method hands the call to the part that does it (docs/architecture.md lists the parts).
"""

from __future__ import annotations

import contextlib

import os
from collections.abc import Callable, Iterable, Iterator, Sequence
from contextlib import AbstractContextManager
from pathlib import Path
from typing import Any

from oracle.errors import StoreError
from oracle.store.base import Appended, AppendMark, Closed, NeemInfo, Store
from oracle.store.chunks import MatchChunk
from oracle.store.model import HIERARCHY, Annotation, DocumentBuilder, Hierarchy, NumberFormat, Scope, Term, TriplePattern, TripleRow
from oracle.store.sqlite.closures import Closures
from oracle.store.sqlite.connection import Connection
from oracle.store.sqlite.documents import Documents
from oracle.store.sqlite.matches import Matches
from oracle.store.sqlite.opening import open_read_only, open_writer
from oracle.store.sqlite.reads import Reads
from oracle.store.sqlite.registry import Registry
from oracle.store.sqlite.terms import Terms
from oracle.store.sqlite.writes import Writes


class SQLiteStore(Store):
    """A NEEM store in one SQLite file (WAL, synchronous=FULL: an action committed survives a
    killed process and a power loss, docs/security.md)."""

    def __init__(
        self,
        path: str | os.PathLike[str],
        number_format: NumberFormat = "decimal128",
        *,
        create: bool = True,
        read_only: bool = False,
        check_while_reading: bool = False,
    ) -> None:
        super().__init__(number_format)
        self.path = Path(path).expanduser()
        self.location = str(self.path)
        self.read_only = read_only
        if (read_only or not create) and not self.path.is_file():
            raise StoreError(f"{self.path}: no NEEM store there (check --store; 'import' or 'load' creates one)")
        # the whole-file check a writer's first write waits for (None: done at open, or nothing to check)
        if read_only:
            conn, has_sides = open_read_only(self.path)
            check = None
        else:
            (conn, check), has_sides = open_writer(self.path, check_while_reading), True
        self._conn = Connection(conn, self.location, check)
        self._terms = Terms(self._conn)
        self._closures = Closures(self._conn, self._terms)
        self._conn.forget += [self._terms.forget, self._closures.forget]
        self._registry = Registry(self._conn, self._terms, has_sides=has_sides, read_only=read_only)
        documents = Documents(self._terms, self._closures)
        self._writes = Writes(self._conn, self._registry, self._terms, self._closures, documents)
        self._reads = Reads(self._conn, self._registry, self._terms, self._closures, documents, self)
        self._matches = Matches(self._conn, self._terms, self._reads)

    # -- connection -------------------------------------------------------------------------
    def close(self) -> None:
        self._conn.close()

    @contextlib.contextmanager
    def deferred_sync(self) -> Iterator[None]:
        """synchronous=NORMAL inside: a WAL commit is written, not fsynced (SQLite's recommended
        setting for WAL; a killed process loses nothing committed), until ``sync``; FULL again after."""
        self._conn.execute("PRAGMA synchronous=NORMAL")
        try:
            yield
        finally:
            self._conn.execute("PRAGMA synchronous=FULL")
            self.sync()

    @contextlib.contextmanager
    def unsynced(self) -> Iterator[None]:
        """synchronous=NORMAL inside, FULL again after, with no flush (SQLite refuses the switch
        inside a transaction: enter it before one)."""
        self._conn.execute("PRAGMA synchronous=NORMAL")
        try:
            yield
        finally:
            self._conn.execute("PRAGMA synchronous=FULL")

    def sync(self) -> None:
        """The WAL file fsynced: every commit so far is on disk (a checkpoint fsyncs the rest)."""
        wal = Path(f"{self.path}-wal")
        try:
            fd = os.open(wal, os.O_RDONLY)
        except FileNotFoundError:
            return  # checkpointed and truncated: on disk already
        try:
            os.fsync(fd)
        finally:
            os.close(fd)

    def shrink_memory(self) -> None:
        """SQLite's page cache (up to 64 MiB, cache_size) freed: an import's writes filled it."""
        self._conn.execute("PRAGMA shrink_memory")

    def transaction(self) -> AbstractContextManager[None]:
        return self._conn.transaction()

    def defer_indexes(self, neem_id: str) -> None:
        self._registry.defer_indexes(neem_id)

    def make_indexes(self, neem_id: str) -> None:
        self._registry.make_indexes(neem_id)

    # -- registry ---------------------------------------------------------------------------
    def neems(self) -> list[NeemInfo]:
        return self._registry.neems()

    def staging_neems(self) -> list[NeemInfo]:
        return self._registry.staging_neems()

    def has_neem(self, neem_id: str) -> bool:
        return self._registry.has_neem(neem_id)

    def neem(self, neem_id: str) -> NeemInfo:
        return self._registry.neem(neem_id)

    def update_meta(self, neem_id: str, **fields: Any) -> NeemInfo:
        return self._registry.update_meta(neem_id, **fields)

    def _create_neem(self, neem_id: str, record: dict[str, Any], side_property: str | None) -> None:
        """A NEEM's tables; with ``side_property`` (a non-taxonomic property with many triples
        per subject, an imagining's plans) also its side table (docs/store.md): its triples are
        kept apart with one index, every query and dump sees the same documents."""
        self._registry.create(neem_id, record, side_property)

    def _drop_neem(self, neem_id: str) -> None:
        self._registry.drop(neem_id)

    def _rename_neem(self, neem_id: str, new_id: str, info: NeemInfo) -> None:
        self._registry.rename(neem_id, new_id)

    def append_mark(self, neem_id: str) -> AppendMark | None:
        return self._registry.append_mark(neem_id)

    def read_kept(self, neem_id: str, kind: str) -> bytes | None:
        return self._registry.read_kept(neem_id, kind)

    def write_kept(self, neem_id: str, kind: str, data: bytes) -> bool:
        return self._registry.write_kept(neem_id, kind, data)

    # -- terms (what the query compiler asks: compiler.TermIds) ----------------------------
    def known_term_id(self, value: str) -> int:
        """The id of a term for a query; -1 (matching nothing) when the store never saw it."""
        return self._terms.known_id(value)

    def closures_containing(self, term_id: int) -> list[int]:
        """Ids of the closures holding a term (what ``SqlCompiler`` inlines into ordered queries)."""
        return self._closures.containing(term_id)

    # -- writing ----------------------------------------------------------------------------
    def _insert_closed(self, neem_id: str, triples: Iterable[TripleRow], hierarchy: Hierarchy,
                       builder: DocumentBuilder) -> int:  # fmt: skip
        """A batch without subClassOf/subPropertyOf triples (every batch the logger writes)
        goes straight to rows, each closure looked up once per distinct property and class;
        a batch that changes the taxonomy takes the general path (``Store._insert_closed``)."""
        batch = triples if type(triples) is list else list(triples)
        if not batch:
            return 0
        if not HIERARCHY.isdisjoint({triple[1] for triple in batch}):
            return super()._insert_closed(neem_id, batch, hierarchy, builder)
        self._writes.closed(neem_id, batch, hierarchy, builder)
        return len(batch)

    def _insert_triples(self, neem_id: str, closed: list[Closed], builder: DocumentBuilder) -> None:
        self._writes.with_closures(neem_id, closed, builder)

    def _insert_documents(self, neem_id: str, kind: str, docs: list[dict[str, Any]]) -> None:
        self._writes.documents_as_given(neem_id, kind, docs)

    def _propagate(self, neem_id: str, subject: str, gained: tuple[Any, ...]) -> None:
        self._writes.propagate(neem_id, subject, gained)

    def _rescope(self, neem_id: str, key: Any, since: float, until: float) -> None:
        self._writes.rescope(neem_id, key, since, until)

    def _delete_triples(self, neem_id: str, keys: Sequence[Any]) -> None:
        self._writes.delete(neem_id, keys)

    # -- reading ----------------------------------------------------------------------------
    def read_documents(self, neem_id: str, kind: str) -> Iterator[dict[str, Any]]:
        return self._reads.documents_of(neem_id, kind)

    def _count(self, neem_id: str, kind: str) -> int:
        return self._reads.count(neem_id, kind)

    def write_mark(self, neem_id: str) -> int:
        return self._reads.write_mark(neem_id)

    def appended(self, neem_id: str, last: int) -> Appended | None:
        return self._reads.appended(neem_id, last)

    def _find(self, neem_id: str, pattern: TriplePattern, scope: Scope | None, limit: int | None,
              exact: bool) -> Iterator[dict[str, Any]]:  # fmt: skip
        return self._reads.find(neem_id, pattern, scope, limit, exact)

    def _overlapping(self, neem_id: str, s: Term, p: Term, o: Term, scope: Scope | None,
                     graph: str | None = None) -> list[tuple[Any, float, float]]:  # fmt: skip
        return self._reads.overlapping(neem_id, s, p, o, scope, graph)

    def _hierarchy_source(self, neem_id: str) -> tuple[list[tuple[str, tuple[Any, ...]]], Callable[[], set[Any]]]:
        return self._reads.hierarchy_source(neem_id)

    def annotations(self, neem_id: str, s: str | None = None, p: str | None = None) -> Iterator[Annotation]:
        return self._reads.annotations(neem_id, s, p)

    def _match(self, neem_id: str, patterns: Sequence[TriplePattern], scope: Scope | None, limit: int | None,
               order: Sequence[tuple[str, bool]], select: Sequence[str] | None = None, group: str | None = None,
               written_order: bool = False) -> Iterator[dict[str, Any]]:  # fmt: skip
        return self._matches.solutions(neem_id, patterns, scope, limit, order, select, group, written_order)

    def _match_chunks(self, neem_id: str, patterns: Sequence[TriplePattern], scope: Scope | None, limit: int | None,
                      order: Sequence[tuple[str, bool]], kept: list[str], group: str | None, written_order: bool,
                      size: int) -> Iterator[MatchChunk]:  # fmt: skip
        return self._matches.chunks(neem_id, patterns, scope, limit, order, kept, group, written_order, size)
