"""A NEEM's tables in the SQLite file: their names (quoted), columns and indexes, and the
term ids the schema fixes so SQL and partial indexes can name the taxonomic properties.

Each NEEM gets the four KnowRob collections as tables ``"<id>_triples"`` and so on, and
perhaps a side table (store.sqlite.sides). A triple row keeps the exact BSON document (so dumps
round-trip byte for byte) beside the columns the indexes need, or only the columns when they
rebuild the very same document (store.sqlite.documents).
"""

from __future__ import annotations

import os
from collections.abc import Collection
from functools import partial

from oracle.store.model import RDF_TYPE, SUBCLASS_OF, SUBPROPERTY_OF

#: The taxonomic properties get fixed term ids so SQL (and partial indexes) can name them.
RESERVED_TERMS = ((1, RDF_TYPE), (2, SUBCLASS_OF), (3, SUBPROPERTY_OF))
#: Term ids of rdf:type, rdfs:subClassOf and rdfs:subPropertyOf (``RESERVED_TERMS``).
TAXONOMIC_SQL = "(1, 2, 3)"
#: Term ids of rdfs:subClassOf and rdfs:subPropertyOf, the taxonomy's edges.
HIERARCHY_SQL = "(2, 3)"


def non_taxonomic(p: str) -> str:
    """``p`` is no taxonomic property, as schema 4's (pstar, o) index states it: three ``<>``
    rather than ``NOT IN``, which SQLite evaluates by building the list anew for every row it
    inserts (a quarter of the index's insert cost), and not ``p > 3``, a range on p that makes
    SQLite prefer the (o, p) index and reorder joins (why-not's role query at 10,000 actions:
    190 ms -> 113 s). Queries state it beside ``NOT IN``, which schema-3 indexes need."""
    return " AND ".join(f"{p} <> {term}" for term in (1, 2, 3))


#: Rows one INSERT statement writes into a table with one plain index (side rows, new terms):
#: SQLite then runs a statement per 80 rows instead of one per row, a third less CPU there.
#: Not into the triples table: with its partial indexes, grouped INSERTs measured slower
#: (docs/store.md). 80 rows of 13 columns stay below 999 parameters, the limit of SQLite
#: builds before 3.32.
GROUPED_ROWS = 80

#: The side table of a NEEM (store.sqlite.sides): the triples of its side property, same
#: columns as the triples table, indexed by subject only (the reads: an imagining's plans, or
#: all of them).
SIDE = "side"
TRIPLE_COLUMNS = (
    "(id INTEGER PRIMARY KEY, oid BLOB NOT NULL, s, p, o, ok INTEGER,"
    " pstar INTEGER, ostar INTEGER, graph, since REAL, until REAL, sk INTEGER, raw BLOB)"
)
#: The columns a triple written by this program fills (no ``raw``: its columns rebuild it).
INSERT_COLUMNS = "id, oid, s, p, o, ok, pstar, ostar, graph, since, until, sk"
#: The columns a document as given fills (``raw`` kept when the columns cannot rebuild it).
DOCUMENT_COLUMNS = "oid, s, p, o, ok, pstar, ostar, graph, since, until, sk, raw"
#: Columns ``Documents.document`` rebuilds a triple document from.
DOC_COLUMNS = ", ".join(f"t0.{c}" for c in ("oid", "s", "p", "o", "ok", "pstar", "ostar", "graph", "since", "until", "sk", "raw"))

# Partial indexes: the o* index only holds taxonomic rows and the p* index only the others,
# so each row updates three indexes; queries repeat the WHERE term so SQLite may use them.
TRIPLE_INDEXES = (
    ("sp", "s, p", ""),
    ("op", "o, p", ""),
    ("postar", "p, ostar", " WHERE ostar > 0"),
    ("pstaro", "pstar, o", f" WHERE {non_taxonomic('p')}"),
)


def quote(name: str) -> str:
    return '"' + name.replace('"', '""') + '"'


def neem_table(neem_id: str, kind: str) -> str:
    """The quoted name of one of a NEEM's tables (a collection kind, or ``SIDE``)."""
    return quote(f"{neem_id}_{kind}")


#: The indexes a bulk write into a new NEEM leaves out until it ends (Store.defer_indexes), by
#: kind: every index of its triple tables. Built after the rows, each is one sorted pass
#: instead of a B-tree insert per row (docs/store.md, "Import"). The import's logger reads
#: nothing back meanwhile (it knows every subject, Individuals.know_all); other reads stay
#: correct, only slower.
DEFERRED = frozenset({"triples_sp", "triples_op", "triples_postar", "triples_pstaro", "side_s", "side_o"})


def index_targets(neem_id: str, side: bool = False) -> list[tuple[str, str]]:
    """(kind, ``ON table(columns) WHERE ...``) of every index of a NEEM's tables: what an index
    is, whatever its name (SQLite keeps this text in sqlite_master, the table renamed in it)."""
    t = partial(neem_table, neem_id)
    made = [(f"triples_{name}", f"ON {t('triples')}({cols}){where}") for name, cols, where in TRIPLE_INDEXES]
    made += [("annotations_sp", f"ON {t('annotations')}(s, p)"), ("tf_cs", f"ON {t('tf')}(child, stamp)")]
    if side:
        # (o): whether a NEEM only grew (Reads.appended) asks if an old side row names a new
        # subject; without it SQLite scans the side table (0.17 s at 50,000 actions).
        made += [(f"{SIDE}_s", f"ON {t(SIDE)}(s)"), (f"{SIDE}_o", f"ON {t(SIDE)}(o)")]
    return made


def target_of(sql: str) -> str:
    """The ``ON ...`` part of a CREATE INDEX statement (``index_targets``)."""
    return sql[sql.index(" ON ") + 1:]


def indexes(neem_id: str, taken: Collection[str] = (), side: bool = False) -> list[tuple[str, str]]:
    """(name, CREATE INDEX statement) of every index of a NEEM's tables, each name made
    unique against ``taken`` (the store's index names: a renamed NEEM keeps its old ones)."""
    made = [(f"{neem_id}_{kind}", target) for kind, target in index_targets(neem_id, side)]
    unique = [(name if name not in taken else f"{name}_{os.urandom(4).hex()}", target) for name, target in made]
    return [(name, f"CREATE INDEX {quote(name)} {target}") for name, target in unique]
