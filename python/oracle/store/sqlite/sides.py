"""A NEEM's side table (docs/store.md): the triples of one non-taxonomic property with many
triples per subject (an imagining's plans) kept apart from its triples table, with one index
(on ``s``); every query and dump sees the same documents. Here: where a pattern's rows are
(``Side``, for the compiler) and which closures the side rows hold."""

from __future__ import annotations

from collections.abc import Callable, Collection
from dataclasses import dataclass
from typing import Any

from oracle.store.model import TAXONOMIC, TriplePattern, Var
from oracle.store.sqlite.closures import Closures
from oracle.store.sqlite.connection import Connection
from oracle.store.sqlite.tables import SIDE, TAXONOMIC_SQL, neem_table, non_taxonomic

#: A NEEM's row of ``side_tables``: the term id of its side property, and the ids of the
#: closures its side rows hold, comma-separated.
SideRow = tuple[int, str]


@dataclass(frozen=True)
class Side:
    """A NEEM's side table: every triple whose asserted ``p`` is ``p`` (a term id) lives there
    instead of in the main table, with the same columns and one index (on ``s``).

    ``closures`` are the members of every ``p*`` its rows hold; ``main_has(term)`` says whether
    a main-table row has ``term`` in its ``p*`` (one index probe)."""

    table: str
    p: int
    closures: tuple[tuple[Any, ...], ...]
    main_has: Callable[[int], bool]

    def sources(self, main: str, pattern: TriplePattern, exact: bool, term_id: Callable[[Any], int]) -> str:
        """The table (or union of both) the rows a pattern can match are in."""
        p = pattern.p
        both = f"(SELECT * FROM {main} UNION ALL SELECT * FROM {self.table})"
        if p is None or isinstance(p, Var):
            return both
        if exact:
            return self.table if term_id(p) == self.p else main
        if not isinstance(p, str) or p in TAXONOMIC:
            return main
        if not any(p in members for members in self.closures):
            return main
        return both if self.main_has(term_id(p)) else self.table


def held(row: SideRow) -> list[int]:
    """The ids of the closures a NEEM's side rows hold."""
    return [int(cid) for cid in row[1].split(",") if cid]


def side_of(conn: Connection, closures: Closures, neem_id: str, row: SideRow | None) -> Side | None:
    """What the query compiler needs to know of a NEEM's side table (None: it has none)."""
    if row is None:
        return None
    main = neem_table(neem_id, "triples")

    def main_has(term: int) -> bool:
        # The (pstar, o) index answers this with a probe per closure holding the term.
        probe = (f"SELECT 1 FROM {main} WHERE pstar IN (SELECT cid FROM closure_member WHERE value=?)"
                 f" AND p NOT IN {TAXONOMIC_SQL} AND {non_taxonomic('p')} LIMIT 1")  # fmt: skip
        return conn.execute(probe, (term,)).fetchone() is not None

    members = tuple(closures.members(cid) for cid in held(row))
    return Side(neem_table(neem_id, SIDE), row[0], members, main_has)


def note_closures(conn: Connection, neem_id: str, row: SideRow, closures: Collection[int | None]) -> None:
    """Record the closures side rows now hold (their p*, and an o* that is not just [o]): the
    compiler asks which terms they contain, the taxonomy which terms are used."""
    have = set(held(row))
    cids = {cid for cid in closures if cid}  # 0: the trivial [o]; None: a document without one
    if not cids <= have:
        text = ",".join(str(cid) for cid in sorted(have | cids))
        conn.execute("UPDATE side_tables SET closures=? WHERE neem=?", (text, neem_id))
