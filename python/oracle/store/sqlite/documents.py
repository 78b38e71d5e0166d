"""A triple document and its row: the row a document as given is stored as (its BSON kept
only when the columns cannot rebuild the very same bytes, so dumps round-trip byte for byte),
and the document a row reads back as."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from datetime import datetime, timezone
from typing import Any

import bson
from bson.codec_options import DEFAULT_CODEC_OPTIONS, DatetimeConversion
from bson.decimal128 import Decimal128
from bson.int64 import Int64
from bson.objectid import ObjectId

from oracle.store.model import TAXONOMIC, NumberFormat, encode_number, unix_seconds
from oracle.store.sqlite.closures import Closures
from oracle.store.sqlite.terms import K_DATE, K_DECIMAL, K_DOUBLE, K_LONG, Terms

#: The ``sk`` column: the number type a rebuilt document's scope has.
SK_DECIMAL, SK_DOUBLE = 1, 2
CODEC = DEFAULT_CODEC_OPTIONS.with_options(datetime_conversion=DatetimeConversion.DATETIME_AUTO)


def blob(doc: Mapping[str, Any]) -> bytes:
    """A document's BSON: the bytes it was read with when it came from a dump."""
    raw = getattr(doc, "raw", None)
    return raw if raw is not None else bson.encode(doc, codec_options=CODEC)


class Documents:
    """Rows and documents of triples, through the store's terms and closures, with two small
    caches (scope documents, the seconds of Decimal128 times)."""

    def __init__(self, terms: Terms, closures: Closures) -> None:
        self.terms = terms
        self.closures = closures
        self._scopes: dict[tuple[Any, ...], dict[str, Any]] = {}
        self._times: dict[bytes, float] = {}

    def document(self, row: Sequence[Any]) -> dict[str, Any]:
        """A stored document (``tables.DOC_COLUMNS``): the raw one when loaded, else rebuilt
        from the columns."""
        oid, s, p, o, ok, pstar, ostar, graph, since, until, sk, raw = row
        if raw is not None:
            return bson.decode(raw, codec_options=CODEC)
        if ok in (K_DECIMAL, K_DOUBLE) and o is None:
            o = math.nan  # SQLite keeps NaN as NULL
        if ok == K_DECIMAL:
            value: Any = encode_number(o, "decimal128")
        elif ok == K_LONG:
            value = Int64(o)
        elif ok == K_DATE:
            value = datetime.fromtimestamp(o, timezone.utc).replace(tzinfo=None)  # as pymongo decodes Dates
        else:
            value = self.terms.out(o, ok)
        members = self.closures.members
        return {
            "_id": ObjectId(oid),
            "s": self.terms.value(s),
            "p": self.terms.value(p),
            "o": value,
            "p*": list(members(pstar)),
            "o*": [value] if ostar == 0 else list(members(ostar)),
            "graph": graph,
            "scope": self._scope(since, until, sk),
        }

    def _scope(self, since: float, until: float, sk: int) -> dict[str, Any]:
        key = (since, until, sk)
        cached = self._scopes.get(key)
        if cached is None:
            fmt: NumberFormat = "decimal128" if sk == SK_DECIMAL else "double"
            cached = {"time": {"since": encode_number(since, fmt), "until": encode_number(until, fmt)}}
            if len(self._scopes) < 4096:
                self._scopes[key] = cached
        return {"time": dict(cached["time"])}

    def _seconds(self, value: Any) -> float | None:
        if isinstance(value, Decimal128):
            cached = self._times.get(value.bid)
            if cached is None:
                cached = float(value.to_decimal())
                if len(self._times) < 4096:
                    self._times[value.bid] = cached
            return cached
        return unix_seconds(value)

    def row(self, doc: Mapping[str, Any]) -> tuple[Any, ...]:
        """Columns of a document stored as given (``tables.DOCUMENT_COLUMNS``; kept whole in
        ``raw`` for an exact dump)."""
        raw = getattr(doc, "raw", None)  # bytes kept by the dump reader
        if "_id" not in doc:
            doc = {"_id": ObjectId(), **doc}
            raw = None
        p = doc.get("p")
        o = doc.get("o")
        sql_o, kind = self.terms.sql(o)
        s = doc.get("s")
        pstar = doc.get("p*")
        ostar = doc.get("o*")
        cid = self.closures.cid
        pstar_cid = None if pstar is None else cid(pstar)
        if ostar is None:
            ostar_cid = None
        elif p not in TAXONOMIC and len(ostar) == 1 and type(ostar[0]) is type(o) and ostar[0] == o:
            ostar_cid = 0  # the trivial [o] of a non-taxonomic triple needs no closure row
        else:
            ostar_cid = cid(ostar)
        time_ = (doc.get("scope") or {}).get("time") or {}
        since = self._seconds(time_.get("since"))
        until = self._seconds(time_.get("until"))
        oid = doc["_id"].binary if isinstance(doc["_id"], ObjectId) else b""
        tid = self.terms.tid
        row = (oid, tid(s) if type(s) is str else None, tid(p) if type(p) is str else None, sql_o, kind,
               pstar_cid, ostar_cid, doc.get("graph"), since, until, None, raw or bson.encode(doc, codec_options=CODEC))  # fmt: skip
        return self._without_raw(row)

    def _without_raw(self, row: tuple[Any, ...]) -> tuple[Any, ...]:
        """The row without its BSON copy when the columns rebuild the very same bytes (every
        document this program wrote): a loaded NEEM then takes the space an imported one does."""
        oid, s, p, _o, _ok, pstar, ostar, graph, since, until, _sk, raw = row
        if len(oid) != 12 or s is None or p is None or pstar is None or ostar is None or since is None or until is None:
            return row
        if graph is not None and type(graph) is not str:
            return row
        for sk in (SK_DECIMAL, SK_DOUBLE):
            lean = (*row[:10], sk, None)
            try:
                same = bson.encode(self.document(lean), codec_options=CODEC) == raw
            except Exception:  # noqa: BLE001 - any value the columns cannot rebuild: keep the copy
                return row
            if same:
                return lean
        return row
