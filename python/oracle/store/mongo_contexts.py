"""The shared prior's counts in one aggregation pipeline over a MongoDB store's NEEMs (oracle.neem.sharing).

The pipeline a hub runs over many robots' NEEMs in KnowRob's layout (``<neem>_triples``, fields
``s``/``p``/``o``): the same rules as the SQL statement of ``oracle.store.sqlite.contexts``, stage for
stage, so both stores release the same counts. Per NEEM (the first NEEM's collection, then
``$unionWith`` for each other one): its executed actions (``dul:executesTask`` to a task whose class
is a known task, the action typed ``dul:Action``, the begin of its interval) named as
``prior.task_key`` names them (the task class's name, then its objects' classes' names: at most two,
the least and the greatest, as SQL's ``MIN`` and ``MAX``), ordered by begin (as a double, as SQLite
holds it) and IRI; then ``$setWindowFields`` with ``$shift`` gives the 1-3 tokens before each token
within its NEEM; per user each cell's count clipped at ``clip``, summed over users, with the number
of users, kept when at least ``k`` users gave it. Only those sums leave the server.

Every value taken from outside (class IRIs, names, user ids) enters as a ``$literal`` or a ``$match``
constant, never as an expression: a name that starts with ``$`` stays a name.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

from oracle.errors import StoreError
from oracle.neem import terms as T
from oracle.store import RDF_TYPE
from oracle.store.sqlite.contexts import Row
from oracle.store.uri import short_reason

#: the token of an idle step (oracle.algorithm.prior.IDLE; a literal here keeps the store free of the algorithm)
IDLE = "idle"


def _name_of(field: str, names: Mapping[str, str]) -> dict[str, Any]:
    """The name ``names`` gives the IRI in ``field`` (the IRI was matched against its keys)."""
    iris = list(names)
    return {"$arrayElemAt": [{"$literal": [names[i] for i in iris]}, {"$indexOfArray": [{"$literal": iris}, field]}]}


def _join(coll: str, var: str, field: str, match: dict[str, Any], out: str) -> list[dict[str, Any]]:
    """An inner join, as SQL's ``JOIN``: the documents of ``coll`` whose ``s`` is this one's ``field``
    and that meet ``match``, one row per document found (none: the row is dropped)."""
    return [
        {"$lookup": {"from": coll, "let": {var: f"${field}"}, "as": out,
                     "pipeline": [{"$match": {**match, "$expr": {"$eq": ["$s", f"$${var}"]}}}]}},
        {"$unwind": f"${out}"},
    ]  # fmt: skip


def neem_tokens(coll: str, n: int, user: str, tasks: Mapping[str, str], objects: Mapping[str, str]) -> list[dict[str, Any]]:
    """The stages that turn one NEEM's ``coll`` into its tokens ``{n, usr, t, iri, tok}`` (unordered)."""
    participants = [
        {"$match": {"p": T.PARTICIPANT, "$expr": {"$eq": ["$s", "$$act"]}}},
        *_join(coll, "thing", "o", {"p": RDF_TYPE, "o": {"$in": list(objects)}}, "cls"),
        {"$group": {"_id": None, "lo": {"$min": "$name"}, "hi": {"$max": "$name"}, "many": {"$sum": 1}}},
    ]
    # the class's name before the group: $min/$max compare names (as SQL's MIN over names)
    participants.insert(-1, {"$set": {"name": _name_of("$cls.o", objects)}})
    task = _name_of("$ty.o", tasks)
    return [
        {"$match": {"p": T.EXECUTES}},
        *_join(coll, "task", "o", {"p": RDF_TYPE, "o": {"$in": list(tasks)}}, "ty"),
        *_join(coll, "act", "s", {"p": RDF_TYPE, "o": T.ACTION}, "ac"),
        *_join(coll, "act", "s", {"p": T.HAS_INTERVAL}, "hi"),
        *_join(coll, "interval", "hi.o", {"p": T.BEGIN}, "bg"),
        {"$lookup": {"from": coll, "let": {"act": "$s"}, "as": "objs", "pipeline": participants}},
        {"$set": {"objs": {"$arrayElemAt": ["$objs", 0]}}},  # a LEFT JOIN: missing when it has no object
        {"$project": {
            "_id": 0, "n": {"$literal": n}, "usr": {"$literal": user}, "t": {"$toDouble": "$bg.o"}, "iri": "$s",
            "tok": {"$switch": {"branches": [
                {"case": {"$eq": [{"$ifNull": ["$objs.many", 0]}, 0]}, "then": task},
                {"case": {"$eq": ["$objs.many", 1]}, "then": {"$concat": [task, "(", "$objs.lo", ")"]}},
            ], "default": {"$concat": [task, "(", "$objs.lo", ",", "$objs.hi", ")"]}}},
        }},
    ]  # fmt: skip


def _cell(order: int, context: list[str]) -> dict[str, Any]:
    return {"ord": order, "x1": context[0] if context else "", "x2": context[1] if len(context) > 1 else "",
            "x3": context[2] if len(context) > 2 else ""}


def counting(clip: int, k: int) -> list[dict[str, Any]]:
    """The stages after the tokens: the contexts (within a NEEM), the clipped per-user counts, the kept sums."""
    cells = [_cell(0, []), _cell(1, ["$c1"]), _cell(2, ["$c2", "$c1"]), _cell(3, ["$c3", "$c2", "$c1"])]
    present = [True, {"$ne": ["$c1", None]}, {"$ne": ["$c2", None]}, {"$ne": ["$c3", None]}]
    shift = {f"c{i}": {"$shift": {"output": "$tok", "by": -i, "default": None}} for i in (1, 2, 3)}
    key = {"ord": "$cell.ord", "x1": "$cell.x1", "x2": "$cell.x2", "x3": "$cell.x3", "tok": "$tok"}
    return [
        {"$setWindowFields": {"partitionBy": "$n", "sortBy": {"t": 1, "iri": 1}, "output": shift}},
        {"$match": {"tok": {"$ne": IDLE}}},
        {"$set": {"cell": [{"$cond": [p, c, None]} for p, c in zip(present, cells)]}},
        {"$unwind": "$cell"},
        {"$match": {"cell": {"$ne": None}}},
        {"$group": {"_id": {**key, "usr": "$usr"}, "count": {"$sum": 1}}},
        {"$group": {"_id": {name: f"$_id.{name}" for name in key},
                    "total": {"$sum": {"$cond": [{"$gt": ["$count", clip]}, clip, "$count"]}}, "users": {"$sum": 1}}},
        {"$match": {"users": {"$gte": k}}},
    ]  # fmt: skip


def pipeline(neems: Sequence[tuple[str, str]], tasks: Mapping[str, str], objects: Mapping[str, str], clip: int,
             k: int) -> tuple[str, list[dict[str, Any]]]:
    """The collection the aggregation starts from and its pipeline: the first NEEM's tokens, each
    other NEEM's through ``$unionWith``, then ``counting``."""
    colls = [f"{neem}_triples" for neem, _ in neems]
    stages = neem_tokens(colls[0], 0, neems[0][1], tasks, objects)
    for n, ((_, user), coll) in enumerate(zip(neems, colls)):
        if n:
            stages.append({"$unionWith": {"coll": coll, "pipeline": neem_tokens(coll, n, user, tasks, objects)}})
    return colls[0], stages + counting(int(clip), int(k))


def count_cells(store: Any, neems: Sequence[tuple[str, str]], tasks: Mapping[str, str], objects: Mapping[str, str],
                clip: int, k: int) -> list[Row]:
    """The kept cells of the NEEMs ``(id, user)`` of a MongoStore, as ``sqlite.contexts.count_cells``
    gives them; ``tasks`` and ``objects`` name each class IRI as a token does (the idle task: ``idle``)."""
    if not neems:
        return []
    start, stages = pipeline(neems, tasks, objects, clip, k)
    found: list[Row] = []
    try:
        # allowDiskUse: the groups and the window over a hub's NEEMs may pass the server's 100 MB per stage
        for row in store.db[start].aggregate(stages, allowDiskUse=True):
            cell = row["_id"]
            context = tuple((cell["x1"], cell["x2"], cell["x3"])[: int(cell["ord"])])
            found.append((context, str(cell["tok"]), float(row["total"]), int(row["users"])))
    except Exception as error:  # pymongo raises many types (a begin that is no number: a ConversionFailure)
        raise StoreError(f"{store.location}: cannot count the shared prior ({short_reason(error)})") from None
    return found


__all__ = ["count_cells", "counting", "neem_tokens", "pipeline"]
