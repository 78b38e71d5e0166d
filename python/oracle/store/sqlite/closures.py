"""``p*``/``o*`` closures stored by reference: one content-addressed row per distinct list,
shared by every NEEM (all ``rdf:type dul:Action`` triples share one), so a closure costs a
triple one integer and ``o* contains C`` is an indexed lookup of its members."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import bson

from oracle.store.sqlite.connection import Connection, inserted_id
from oracle.store.sqlite.terms import Terms


class Closures:
    """The ids of closure lists, made on first use, and the lists of ids, both cached
    (``forget``: after a rollback, the ids it cached may name no row)."""

    def __init__(self, conn: Connection, terms: Terms) -> None:
        self.conn = conn
        self.terms = terms
        self.ids: dict[Any, int] = {}
        self.lists: dict[int, tuple[Any, ...]] = {}

    def forget(self) -> None:
        self.ids.clear()
        self.lists.clear()

    def cid(self, closure: Sequence[Any]) -> int:
        """Id of a closure list, created on first use (content-addressed, shared by all NEEMs)."""
        cid = self.ids.get(closure) if type(closure) is tuple else None
        if cid is not None:
            return cid
        key: Any = tuple(closure)
        if not all(type(item) is str for item in key):
            key = bson.encode({"c": list(closure)})
        cid = self.ids.get(key)
        if cid is not None:
            return cid
        blob = key if isinstance(key, bytes) else bson.encode({"c": list(closure)})
        row = self.conn.execute("SELECT cid FROM closure WHERE key=?", (blob,)).fetchone()
        if row is None:
            tid = self.terms.tid
            cid = inserted_id(self.conn.execute("INSERT INTO closure(key) VALUES (?)", (blob,)))
            self.conn.executemany(
                "INSERT INTO closure_member VALUES (?, ?, ?)",
                [(cid, pos, tid(v) if type(v) is str else None) for pos, v in enumerate(closure)],
            )
        else:
            cid = row[0]
        self.ids[key] = cid
        return cid

    def members(self, cid: int) -> tuple[Any, ...]:
        """The closure list of an id."""
        members = self.lists.get(cid)
        if members is None:
            row = self.conn.execute("SELECT key FROM closure WHERE cid=?", (cid,)).fetchone()
            members = self.lists[cid] = tuple(bson.decode(row[0])["c"])
        return members

    def containing(self, term_id: int) -> list[int]:
        """Ids of the closures holding a term (what ``SqlCompiler`` inlines into ordered queries)."""
        rows = self.conn.execute("SELECT DISTINCT cid FROM closure_member WHERE value=?", (term_id,))
        return [cid for (cid,) in rows]
