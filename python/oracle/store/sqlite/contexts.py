"""The shared prior's counts in one SQL statement over a SQLite store's NEEMs (oracle.neem.sharing).

Per NEEM: its executed actions (``rdf:type dul:Action``, the task class their task has, the begin of
their interval) named as ``prior.task_key`` names them (the task class's name, then its objects'
classes' names in order: at most two, so ``MIN`` and ``MAX`` sort them), ordered by begin and IRI
(as ``neem.query.executed_actions``); the 1-3 tokens before each (window functions, never across
NEEMs); then per user each cell's count clipped at ``clip``, summed over users, with the number of
users, kept when at least ``k`` users gave it. Only those sums leave the database.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

from oracle.neem import terms as T
from oracle.store import RDF_TYPE
from oracle.store.sqlite.tables import neem_table

#: one released count: order, context (oldest first), task, clipped sum, users
Row = tuple[tuple[str, ...], str, float, int]


def _values(rows: Sequence[tuple[int, str]]) -> tuple[str, list[Any]]:
    if not rows:
        return "SELECT -1, '' WHERE 0", []
    return "VALUES " + ", ".join("(?, ?)" for _ in rows), [v for row in rows for v in row]


def count_cells(store: Any, neems: Sequence[tuple[str, str]], tasks: Mapping[str, str], objects: Mapping[str, str],
                clip: int, k: int) -> list[Row]:
    """The kept cells of the NEEMs ``(id, user)`` of a SQLiteStore; ``tasks`` and ``objects``
    name each class IRI as a token does (the idle task: ``idle``)."""
    if not neems:
        return []
    conn, terms = store._conn, store._terms
    ids = {name: terms.known_id(iri) for name, iri in
           (("type", RDF_TYPE), ("action", T.ACTION), ("executes", T.EXECUTES), ("interval", T.HAS_INTERVAL),
            ("begin", T.BEGIN), ("participant", T.PARTICIPANT))}
    task_rows = [(terms.known_id(iri), name) for iri, name in tasks.items()]
    object_rows = [(terms.known_id(iri), name) for iri, name in objects.items()]
    task_sql, task_args = _values([r for r in task_rows if r[0] >= 0])
    object_sql, object_args = _values([r for r in object_rows if r[0] >= 0])
    acts: list[str] = []
    objs: list[str] = []
    args_acts: list[str] = []
    for n, (neem, user) in enumerate(neems):
        t = neem_table(neem, "triples")
        acts.append(f"SELECT {n} AS n, ? AS usr, ex.s AS act, bg.o AS t, tn.name AS task FROM {t} ex "
                    f"JOIN {t} ty ON ty.s = ex.o AND ty.p = :type JOIN task_names tn ON tn.id = ty.o "
                    f"JOIN {t} ac ON ac.s = ex.s AND ac.p = :type AND ac.o = :action "
                    f"JOIN {t} hi ON hi.s = ex.s AND hi.p = :interval JOIN {t} bg ON bg.s = hi.o AND bg.p = :begin "
                    f"WHERE ex.p = :executes")
        args_acts.append(user)
        objs.append(f"SELECT {n} AS n, pa.s AS act, MIN(o.name) AS lo, MAX(o.name) AS hi, COUNT(*) AS many "
                    f"FROM {t} pa JOIN {t} pt ON pt.s = pa.o AND pt.p = :type JOIN object_names o ON o.id = pt.o "
                    f"WHERE pa.p = :participant GROUP BY pa.s")
    sql = f"""
WITH task_names(id, name) AS ({task_sql}),
object_names(id, name) AS ({object_sql}),
acts AS ({" UNION ALL ".join(acts)}),
objs AS ({" UNION ALL ".join(objs)}),
tokens AS (
  SELECT a.n, a.usr, a.t, iri.value AS iri,
         CASE WHEN o.many IS NULL THEN a.task
              WHEN o.many = 1 THEN a.task || '(' || o.lo || ')'
              ELSE a.task || '(' || o.lo || ',' || o.hi || ')' END AS tok
  FROM acts a LEFT JOIN objs o ON o.n = a.n AND o.act = a.act JOIN terms iri ON iri.id = a.act),
seq AS (
  SELECT usr, tok, LAG(tok, 1) OVER w AS c1, LAG(tok, 2) OVER w AS c2, LAG(tok, 3) OVER w AS c3
  FROM tokens WINDOW w AS (PARTITION BY n ORDER BY t, iri)),
cells AS (
  SELECT usr, 0 AS ord, '' AS x1, '' AS x2, '' AS x3, tok FROM seq WHERE tok <> 'idle'
  UNION ALL SELECT usr, 1, c1, '', '', tok FROM seq WHERE tok <> 'idle' AND c1 IS NOT NULL
  UNION ALL SELECT usr, 2, c2, c1, '', tok FROM seq WHERE tok <> 'idle' AND c2 IS NOT NULL
  UNION ALL SELECT usr, 3, c3, c2, c1, tok FROM seq WHERE tok <> 'idle' AND c3 IS NOT NULL),
per_user AS (
  SELECT ord, x1, x2, x3, tok, MIN(COUNT(*), :clip) AS n FROM cells GROUP BY ord, x1, x2, x3, tok, usr)
SELECT ord, x1, x2, x3, tok, SUM(n), COUNT(*) FROM per_user GROUP BY ord, x1, x2, x3, tok HAVING COUNT(*) >= :k
"""
    # positional arguments first (VALUES, users), then the named ones: sqlite3 takes one style,
    # so the named ones are written in as numbers (term ids and settings, never text from a NEEM)
    named = {**ids, "clip": int(clip), "k": int(k)}
    for name, value in sorted(named.items(), key=lambda item: -len(item[0])):
        sql = sql.replace(f":{name}", str(int(value)))
    args = [*task_args, *object_args, *args_acts]
    found: list[Row] = []
    for order, x1, x2, x3, tok, total, users in conn.execute(sql, args):
        context = tuple((x1, x2, x3)[:order])
        found.append((context, tok, float(total), int(users)))
    return found


__all__ = ["Row", "count_cells"]
