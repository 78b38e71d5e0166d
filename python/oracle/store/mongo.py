"""The MongoDB backend: KnowRob 2.x's layout to the letter (knowrob-2x-facts §2-§3).

Database ``roslog`` unless the URI names one; collections ``<neem>_triples``, ``_annotations``,
``_tf``, ``_inferred``; the ``one`` collection every mongolog query starts from; the 15
indexes on triples. NEEM registry entries live in ``meta`` as on openEASE.

Why this module is large: it is the whole of one backend against the Store interface (writes,
reads, registry, indexes, the compiled patterns' ``$match`` documents with their two-bound
ranges); the aggregation pipelines and contexts already live apart (mongo_contexts.py).
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from datetime import datetime, timezone
from typing import Any

from bson.decimal128 import Decimal128
from bson.objectid import ObjectId

from oracle.errors import StoreError
from oracle.store.base import COLLECTION_KINDS, NeemInfo, Store
from oracle.store.staging import STAGING
from oracle.store.uri import short_reason
from oracle.store.meta import HUB_TEXT_FIELDS, HUB_TEXT_INDEX
from oracle.store.model import (
    HIERARCHY,
    TAXONOMIC,
    Annotation,
    Cmp,
    NumberFormat,
    Scope,
    TriplePattern,
    Var,
    decode_value,
    encode_number,
    query_values,
)

DEFAULT_DB = "roslog"
META = "meta"

#: The 15 ascending indexes KnowRob creates on ``triples`` (lang/db.pl; same in the C++ rewrite).
TRIPLE_INDEXES: tuple[tuple[str, ...], ...] = (
    ("s",), ("p",), ("o",), ("p*",), ("o*",),
    ("s", "p"), ("s", "o"), ("o", "p"), ("s", "p*"), ("s", "o*"), ("o", "p*"), ("p", "o*"),
    ("s", "o", "p"), ("s", "o", "p*"), ("s", "o*", "p"),
)  # fmt: skip
ANNOTATION_INDEXES: tuple[tuple[str, ...], ...] = (("s",), ("p",), ("s", "p"))
#: KnowRob's order (mongolog_add_fluent for tf: the time field, then the time field and the key).
TF_INDEXES: tuple[tuple[str, ...], ...] = (("header.stamp",), ("header.stamp", "child_frame_id"))
INDEXES: dict[str, tuple[tuple[str, ...], ...]] = {
    "triples": TRIPLE_INDEXES,
    "annotations": ANNOTATION_INDEXES,
    "tf": TF_INDEXES,
    "inferred": (),
}
ONE_DOCUMENT = {"v_scope": {"time": {"since": Decimal128("0"), "until": Decimal128("Infinity")}}}


def meta_key(neem_id: str) -> str | ObjectId:
    """The registry ``_id`` of a NEEM: an ObjectId when the id is one (24 hex digits), as
    openEASE looks NEEMs up (``find_one({"_id": ObjectId(id)})``), else the id itself."""
    return ObjectId(neem_id) if ObjectId.is_valid(neem_id) and len(neem_id) == 24 else neem_id


def _meta_filter(neem_id: str) -> dict[str, Any]:
    # Entries written before ids became ObjectIds keep the string form.
    return {"_id": {"$in": [neem_id, meta_key(neem_id)]}}


class MongoStore(Store):
    """NEEMs in a MongoDB database (or a pymongo-compatible test double)."""

    def __init__(self, client: Any, db_name: str = DEFAULT_DB, number_format: NumberFormat = "decimal128",
                 location: str | None = None) -> None:  # fmt: skip
        super().__init__(number_format)
        self.client = client
        self.db = client[db_name]
        self.location = location or f"mongodb database {db_name!r}"
        #: NEEM ids seen to exist, so each write does not ask the server again.
        self._present: set[str] = set()
        try:
            if self.db["one"].count_documents({}) == 0:
                self.db["one"].insert_one(dict(ONE_DOCUMENT))
        except Exception as error:  # pymongo raises many types; all mean "no usable server"
            raise StoreError(f"{self.location}: cannot reach MongoDB ({short_reason(error)})") from None

    def close(self) -> None:
        self.client.close()

    @contextmanager
    def transaction(self) -> Iterator[None]:
        # KnowRob writes without transactions (they need a replica set); each bulk write is atomic
        # per document only.
        yield

    def _coll(self, neem_id: str, kind: str) -> Any:
        return self.db[f"{neem_id}_{kind}"]

    # -- registry ---------------------------------------------------------------------------
    def _registry(self) -> dict[str, NeemInfo]:
        """Every NEEM, hidden staging ones included."""
        infos = {str(doc["_id"]): NeemInfo.from_meta(str(doc["_id"]), {k: v for k, v in doc.items() if k != "_id"})
                 for doc in self.db[META].find({}) if isinstance(doc.get("_id"), (str, ObjectId))}  # fmt: skip
        # NEEMs restored with mongorestore have collections but no meta entry.
        for name in self.db.list_collection_names():
            if name.endswith("_triples"):
                neem_id = name[: -len("_triples")]
                infos.setdefault(neem_id, NeemInfo(neem_id))
        return infos

    def neems(self) -> list[NeemInfo]:
        infos = self._registry()
        return [infos[key] for key in sorted(infos) if not infos[key].meta.get(STAGING)]  # replacements being built are hidden

    def staging_neems(self) -> list[NeemInfo]:
        infos = self._registry()
        return [infos[key] for key in sorted(infos) if infos[key].meta.get(STAGING)]

    def neem(self, neem_id: str) -> NeemInfo:
        info = self._registry().get(neem_id)
        if info is None:
            raise StoreError(f"{self.location}: no NEEM {neem_id!r}")
        return info

    def has_neem(self, neem_id: str) -> bool:
        if neem_id in self._present:
            return True
        found = bool(self.db[META].count_documents(_meta_filter(neem_id), limit=1)) or (
            f"{neem_id}_triples" in self.db.list_collection_names()
        )
        if found:
            self._present.add(neem_id)
        return found

    def _create_neem(self, neem_id: str, record: dict[str, Any], side_property: str | None) -> None:
        del side_property  # KnowRob's layout: every triple in the one collection
        for kind in COLLECTION_KINDS:
            coll = self.db.create_collection(f"{neem_id}_{kind}")
            for keys in INDEXES[kind]:
                coll.create_index([(key, 1) for key in keys])
        self.db[META].insert_one({"_id": meta_key(neem_id), **record})
        # openEASE's NEEM hub searches the registry with $text (idempotent: created once)
        self.db[META].create_index([(field, "text") for field in HUB_TEXT_FIELDS], name=HUB_TEXT_INDEX,
                                   weights=HUB_TEXT_FIELDS)  # fmt: skip

    def _drop_neem(self, neem_id: str) -> None:
        for kind in COLLECTION_KINDS:
            self._coll(neem_id, kind).drop()
        self.db[META].delete_one(_meta_filter(neem_id))
        self._present.discard(neem_id)

    def _rename_neem(self, neem_id: str, new_id: str, info: NeemInfo) -> None:
        names = set(self.db.list_collection_names())
        for kind in COLLECTION_KINDS:
            if f"{neem_id}_{kind}" in names:
                self._coll(neem_id, kind).rename(f"{new_id}_{kind}")
        self.db[META].delete_one(_meta_filter(neem_id))
        self.db[META].insert_one({"_id": meta_key(new_id), **dict(info.meta)})
        self._present.discard(neem_id)

    def interrupted_rename(self, neem_id: str, new_id: str) -> bool:
        names = set(self.db.list_collection_names())
        moved = any(f"{neem_id}_{kind}" not in names and f"{new_id}_{kind}" in names for kind in COLLECTION_KINDS)
        return moved and not self.db[META].count_documents(_meta_filter(new_id), limit=1)

    def update_meta(self, neem_id: str, **fields: Any) -> NeemInfo:
        meta = dict(self.neem(neem_id).meta)
        meta.update(fields)
        key = meta_key(neem_id)
        self.db[META].replace_one({"_id": key}, {"_id": key, **meta}, upsert=True)
        if key != neem_id:  # an entry written with the string form: the ObjectId one replaces it
            self.db[META].delete_one({"_id": neem_id})
        return NeemInfo.from_meta(neem_id, meta)

    # -- writing ----------------------------------------------------------------------------
    def _insert_documents(self, neem_id: str, kind: str, docs: list[dict[str, Any]]) -> None:
        if not self.has_neem(neem_id):
            raise StoreError(f"{self.location}: no NEEM {neem_id!r}")
        try:
            self._coll(neem_id, kind).insert_many(docs, ordered=True)
        except Exception as error:
            raise StoreError(f"{self.location}: NEEM {neem_id!r}: cannot store {kind} documents ({error})") from None

    def _propagate(self, neem_id: str, subject: str, gained: tuple[Any, ...]) -> None:
        coll = self._coll(neem_id, "triples")
        taxonomic = sorted(TAXONOMIC)
        coll.update_many({"o*": subject, "p": {"$in": taxonomic}}, {"$addToSet": {"o*": {"$each": list(gained)}}})
        coll.update_many({"p*": subject, "p": {"$nin": taxonomic}}, {"$addToSet": {"p*": {"$each": list(gained)}}})

    def _overlapping(
        self, neem_id: str, s: Any, p: Any, o: Any, scope: Scope | None, graph: str | None = None
    ) -> list[tuple[Any, float, float]]:
        if not self.has_neem(neem_id):
            raise StoreError(f"{self.location}: no NEEM {neem_id!r}")
        query = _pattern_filter(TriplePattern(s, p, o, graph), self.number_format, exact=True)
        query.update(_scope_filter(scope, self.number_format))
        found = []
        for doc in self._coll(neem_id, "triples").find(query, {"_id": 1, "scope": 1}):
            time = (doc.get("scope") or {}).get("time") or {}
            since, until = time.get("since", 0.0), time.get("until", math.inf)
            # the key keeps the document's number type, so a new scope is written alike
            kind = "double" if isinstance(since, float) and isinstance(until, float) else "decimal128"
            found.append(((doc["_id"], kind), _float(since), _float(until)))
        return found

    def _rescope(self, neem_id: str, key: Any, since: float, until: float) -> None:
        doc_id, kind = key
        scope = {"scope.time.since": encode_number(since, kind), "scope.time.until": encode_number(until, kind)}
        self._coll(neem_id, "triples").update_one({"_id": doc_id}, {"$set": scope})  # one atomic update

    def _delete_triples(self, neem_id: str, keys: Sequence[Any]) -> None:
        if keys:
            self._coll(neem_id, "triples").delete_many({"_id": {"$in": [doc_id for doc_id, _ in keys]}})

    def _hierarchy_source(self, neem_id: str) -> tuple[list[tuple[str, tuple[Any, ...]]], set[Any]]:
        coll = self._coll(neem_id, "triples")
        edges = [
            (doc["s"], tuple(doc.get("o*") or (doc["o"],)))
            for doc in coll.find({"p": {"$in": sorted(HIERARCHY)}}, {"s": 1, "o": 1, "o*": 1})
        ]
        used: set[Any] = set()
        for value in coll.distinct("o*", {"p": {"$in": sorted(TAXONOMIC)}}):
            if isinstance(value, str):
                used.add(value)
        for value in coll.distinct("p*"):
            if isinstance(value, str):
                used.add(value)
        return edges, used

    # -- reading ----------------------------------------------------------------------------
    def read_documents(self, neem_id: str, kind: str) -> Iterator[dict[str, Any]]:
        if kind not in COLLECTION_KINDS:
            raise StoreError(f"unknown collection kind {kind!r}")
        self.neem(neem_id)
        yield from self._coll(neem_id, kind).find({})

    def annotations(self, neem_id: str, s: str | None = None, p: str | None = None) -> Iterator[Annotation]:
        if not self.has_neem(neem_id):
            raise StoreError(f"{self.location}: no NEEM {neem_id!r}")
        query = {k: v for k, v in (("s", s), ("p", p)) if v is not None}
        for doc in self._coll(neem_id, "annotations").find(query):
            yield Annotation(doc["s"], doc["p"], doc.get("v"))

    def _count(self, neem_id: str, kind: str) -> int:
        return int(self._coll(neem_id, kind).count_documents({}))

    def write_mark(self, neem_id: str) -> int:
        # The collection's document count from its metadata (count_documents would scan): it
        # moves with every insert; a scope merge (store.project) deletes only copies of a fact
        # it keeps, and kb_unproject drops the kept summary itself.
        return int(self._coll(neem_id, "triples").estimated_document_count())

    def _find(
        self, neem_id: str, pattern: TriplePattern, scope: Scope | None, limit: int | None, exact: bool
    ) -> Iterator[dict[str, Any]]:
        if not self.has_neem(neem_id):
            raise StoreError(f"{self.location}: no NEEM {neem_id!r}")
        query = _pattern_filter(pattern, self.number_format, exact)
        query.update(_scope_filter(scope, self.number_format))
        cursor = self._coll(neem_id, "triples").find(query)
        if limit is not None:
            cursor = cursor.limit(int(limit))
        yield from cursor

    def _match(
        self,
        neem_id: str,
        patterns: Sequence[TriplePattern],
        scope: Scope | None,
        limit: int | None,
        order: Sequence[tuple[str, bool]],
        select: Sequence[str] | None = None,
        group: str | None = None,
        written_order: bool = False,  # the pipeline's $lookups are always in the written order
    ) -> Iterator[dict[str, Any]]:
        if not self.has_neem(neem_id):
            raise StoreError(f"{self.location}: no NEEM {neem_id!r}")
        pipeline = compile_pipeline(f"{neem_id}_triples", patterns, scope, limit, self.number_format, order)
        names = sorted({name for pattern in patterns for name in pattern.variables()})
        if select is not None:
            names = [name for name in names if name in select]
        if group is not None:
            keys = [name for name in names if name != group]
            pipeline.append({"$group": {"_id": {f"v_{name}": f"$v_{name}" for name in keys} if keys else None,
                                        "values": {"$push": f"$v_{group}"}}})  # fmt: skip
            for row in self.db["one"].aggregate(pipeline):
                solution = {name: decode_value(row["_id"].get(f"v_{name}")) for name in keys}
                solution[group] = [decode_value(value) for value in row["values"]]
                yield solution
            return
        for row in self.db["one"].aggregate(pipeline):
            yield {name: decode_value(row.get(f"v_{name}")) for name in names}


def _value_condition(value: Any) -> Any:
    forms = query_values(value)
    return forms[0] if len(forms) == 1 else {"$in": forms}


def _float(value: Any) -> float:
    return float(value.to_decimal()) if isinstance(value, Decimal128) else float(value)


def _pattern_filter(pattern: TriplePattern, number_format: NumberFormat, exact: bool = False) -> dict[str, Any]:
    """The ``$match`` of the constant parts of a pattern (KnowRob's triple/3 query)."""
    query: dict[str, Any] = {}
    p = pattern.p
    taxonomic = isinstance(p, str) and p in TAXONOMIC
    if exact:
        for field, term in (("s", pattern.s), ("p", p), ("o", pattern.o)):
            if term is not None and not isinstance(term, Var):
                query[field] = _value_condition(term)
        if pattern.graph is not None:
            query["graph"] = _graph_condition(pattern.graph)
        return query
    if pattern.s is not None and not isinstance(pattern.s, Var):
        query["s"] = pattern.s
    if p is not None and not isinstance(p, Var):
        query["p" if taxonomic else "p*"] = p
    if pattern.o is not None and not isinstance(pattern.o, (Var, Cmp)):
        query["o*" if taxonomic else "o"] = _value_condition(pattern.o)
    if pattern.graph is not None:
        query["graph"] = _graph_condition(pattern.graph)
    return query


def _graph_condition(graph: str | tuple[str, ...]) -> Any:
    return graph if isinstance(graph, str) else {"$in": list(graph)}


def _scope_filter(scope: Scope | None, number_format: NumberFormat) -> dict[str, Any]:
    if scope is None:
        return {}
    until = encode_number(scope.until, number_format)
    since = encode_number(scope.since, number_format)
    return {
        "$and": [
            {"$or": [{"scope.time.since": {"$exists": False}}, {"scope.time.since": {"$lte": until}}]},
            {"$or": [{"scope.time.until": {"$exists": False}}, {"scope.time.until": {"$gte": since}}]},
        ]
    }


def compile_pipeline(
    collection: str,
    patterns: Sequence[TriplePattern],
    scope: Scope | None,
    limit: int | None,
    number_format: NumberFormat = "decimal128",
    order: Sequence[tuple[str, bool]] = (),
) -> list[dict[str, Any]]:
    """mongolog's shape: from the single ``one`` document, one ``$lookup`` per triple pattern.

    Variables are fields ``v_<name>`` of the flowing document; a variable bound by an earlier
    pattern enters the lookup through ``let`` and is compared in ``$expr``.
    """
    stages: list[dict[str, Any]] = [{"$limit": 1}, {"$project": {"_id": 0}}]
    bound: set[str] = set()
    for index, pattern in enumerate(patterns):
        match = _pattern_filter(pattern, number_format)
        match.update(_scope_filter(scope, number_format))
        taxonomic = isinstance(pattern.p, str) and pattern.p in TAXONOMIC
        exprs: list[dict[str, Any]] = []
        let: dict[str, str] = {}
        new: dict[str, str] = {}
        o = pattern.o
        if isinstance(o, Cmp):
            match.setdefault("$and", []).append(_compare_condition(o))
            o = o.var
        for field, term in (("s", pattern.s), ("p", pattern.p), ("o", o)):
            if not isinstance(term, Var):
                continue
            name = f"v_{term.name}"
            if term.name in bound:
                let[name] = f"${name}"
                if field == "o" and taxonomic:
                    exprs.append({"$in": [f"$${name}", "$o*"]})
                else:
                    exprs.append({"$eq": [f"${field}", f"$${name}"]})
            elif name in new:
                exprs.append({"$eq": [f"${field}", f"${new[name]}"]})
            else:
                new[name] = field
        exprs.append(_EXTENT)
        match["$expr"] = exprs[0] if len(exprs) == 1 else {"$and": exprs}
        lookup: dict[str, Any] = {"from": collection, "as": "next", "pipeline": [{"$match": match}]}
        if not new and index > 0:
            # No new variable: a test, as goal by goal (a ground goal succeeds once however
            # many documents match it; SqlCompiler.semi_joins).
            lookup["pipeline"].append({"$limit": 1})
        if let:
            lookup["let"] = let
        stages.append({"$lookup": lookup})
        stages.append({"$unwind": "$next"})
        if new:
            stages.append({"$set": {name: f"$next.{field}" for name, field in new.items()}})
        if index > 0:
            stages.extend(_intersect_scope())
        else:
            stages.append({"$set": {"k_since": _SINCE, "k_until": _UNTIL}})
        stages.append({"$unset": "next"})
        bound.update(name[2:] for name in new)
    if order:
        stages.append({"$sort": {f"v_{name}": -1 if descending else 1 for name, descending in order}})
    if limit is not None:
        stages.append({"$limit": int(limit)})
    return stages


#: KnowRob's extent rule (``kb_scope``): a document's scope (an open end where it has none).
_SINCE: dict[str, Any] = {"$ifNull": ["$next.scope.time.since", 0.0]}
_UNTIL: dict[str, Any] = {"$ifNull": ["$next.scope.time.until", math.inf]}
#: A document is seen only where its scope has an extent (since < until).
_EXTENT: dict[str, Any] = {"$lt": [{"$ifNull": ["$scope.time.since", 0.0]}, {"$ifNull": ["$scope.time.until", math.inf]}]}


def _intersect_scope() -> list[dict[str, Any]]:
    """mongolog's ``v_scope``: the running intersection of the joined documents' scopes,
    dropping a solution where it has no extent. ``$cond`` rather than ``$max``/``$min``, which
    the mongomock-ng test double cannot apply to Decimal128."""
    since = {"$cond": [{"$gt": [_SINCE, "$k_since"]}, _SINCE, "$k_since"]}
    until = {"$cond": [{"$lt": [_UNTIL, "$k_until"]}, _UNTIL, "$k_until"]}
    return [{"$set": {"k_since": since, "k_until": until}},
            {"$match": {"$expr": {"$lt": ["$k_since", "$k_until"]}}}]  # fmt: skip


_MONGO_OPS = {"<": "$lt", "=<": "$lte", ">": "$gt", ">=": "$gte"}


def _compare_condition(cmp: Cmp) -> dict[str, Any]:
    """``o OP value`` for numbers of every BSON type (MongoDB compares them by value) and,
    as Prolog sees Dates as unix seconds, for Dates."""
    tests = [(_MONGO_OPS[op], float(value)) for op, value in cmp.conditions()]
    if len({op for op, _ in tests}) < len(tests):  # one operator twice: each its own test
        return {"$and": [_compare_condition(Cmp(op, value)) for op, value in cmp.conditions()]}
    # One form per BSON type, each guarded by $type: MongoDB would compare across numeric
    # types by itself, but the mongomock-ng test double cannot compare Decimal128 with int.
    # Two bounds sit in one document on the field ("$gt" and "$lte"): one index range.
    forms: list[dict[str, Any]] = [
        {"o": {"$type": "double", **{op: value for op, value in tests}}},
        {"o": {"$type": "int", **{op: value for op, value in tests}}},
        {"o": {"$type": "long", **{op: value for op, value in tests}}},
        {"o": {"$type": "decimal", **{op: encode_number(value, "decimal128") for op, value in tests}}},
    ]
    if all(math.isfinite(value) and abs(value) < 2.5e11 for _, value in tests):
        forms.append({"o": {"$type": "date", **{op: _date(value) for op, value in tests}}})
    return {"$or": forms}


def _date(seconds: float) -> datetime:
    """Unix seconds as the naive UTC datetime pymongo stores as a BSON Date."""
    return datetime.fromtimestamp(seconds, timezone.utc).replace(tzinfo=None)
