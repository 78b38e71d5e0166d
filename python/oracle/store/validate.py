"""The door check: documents and registry entries from outside (dumps, callers) that a reader
could not read are refused before they are stored (a store never holds a row a reader
cannot read). A message names the document and the field. The same door for a query: its
selected, ordered and grouped variables must be the patterns' own."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from datetime import datetime
from typing import Any

from bson.decimal128 import Decimal128

from oracle.errors import StoreError
from oracle.store.model import TriplePattern
from oracle.timeline import TimeValueError, parse_iso

#: Registry fields and the types a reader expects of them (None allowed for each).
_META_TYPES: dict[str, tuple[type, ...]] = {"created_by": (str,), "created_at": (str,), "temporary": (bool,),
                                            "id": (str,), "name": (str,), "alias": (str,)}  # fmt: skip
_MAX_DEPTH = 64


def check_keys(doc: Mapping[str, Any], where: str) -> None:
    """No key may start with ``$`` or hold a ``.`` or NUL at any depth: MongoDB would read it as
    an operator or a path (``{"$where": ...}``), and no KnowRob document has one."""
    stack: list[tuple[Any, int]] = [(doc, 0)]
    while stack:
        value, depth = stack.pop()
        if depth > _MAX_DEPTH:
            raise StoreError(f"{where}: nested more than {_MAX_DEPTH} levels deep")
        if isinstance(value, Mapping):
            for key, item in value.items():
                if not isinstance(key, str) or key.startswith("$") or "." in key or "\x00" in key:
                    raise StoreError(f"{where}: key {str(key)[:40]!r} is not allowed (no '$' prefix, '.' or NUL)")
                stack.append((item, depth + 1))
        elif isinstance(value, (list, tuple)):
            stack.extend((item, depth + 1) for item in value)


def _number(value: Any) -> float | None:
    """A time bound as float (Decimal128, int, float or a BSON date), or None if it is none."""
    if isinstance(value, bool):
        return None
    if isinstance(value, Decimal128):
        value = float(value.to_decimal())
    elif isinstance(value, datetime):
        try:
            return value.timestamp()
        except (OverflowError, OSError, ValueError):
            return None
    if isinstance(value, (int, float)) and not math.isnan(value):
        return float(value)
    return None


def _term(value: Any) -> bool:
    if isinstance(value, Decimal128):
        return not value.to_decimal().is_nan()
    if isinstance(value, float):
        return not math.isnan(value)
    # a plain str: bson's Code is a str subclass that the store's readers cannot hash
    return type(value) is str or isinstance(value, (int, bool, datetime))


def check_document(kind: str, doc: Mapping[str, Any], where: str) -> None:
    """Refuse a document of collection ``kind`` that the store's readers would choke on."""
    check_keys(doc, where)
    if kind == "triples":
        for field in ("s", "p"):
            value = doc.get(field)
            if type(value) is not str or not value:
                raise StoreError(f"{where}: {field!r} must be a non-empty string, got {_short(value)}")
        if "o" not in doc or not _term(doc["o"]):
            raise StoreError(f"{where}: 'o' must be a string, number, boolean or date, got {_short(doc.get('o'))}")
        for field in ("p*", "o*"):
            if field in doc and not (isinstance(doc[field], list) and all(_term(v) for v in doc[field])):
                raise StoreError(f"{where}: {field!r} must be a list of terms, got {_short(doc[field])}")
        if "graph" in doc and type(doc["graph"]) is not str:
            raise StoreError(f"{where}: 'graph' must be a string, got {_short(doc['graph'])}")
        if "scope" in doc:
            _check_scope(doc["scope"], where)
    elif kind == "annotations":
        for field in ("s", "p"):
            if type(doc.get(field)) is not str:
                raise StoreError(f"{where}: {field!r} must be a string, got {_short(doc.get(field))}")


def _check_scope(scope: Any, where: str) -> None:
    if not isinstance(scope, Mapping) or not isinstance(scope.get("time", {}), Mapping):
        raise StoreError(f"{where}: 'scope' must be {{time: {{since, until}}}}, got {_short(scope)}")
    bounds = scope.get("time", {})
    values = {}
    for field in ("since", "until"):
        if field in bounds:
            number = _number(bounds[field])
            if number is None:
                raise StoreError(f"{where}: scope.time.{field} must be a number of seconds, got {_short(bounds[field])}")
            values[field] = number
    if "since" in values and "until" in values and values["since"] > values["until"]:
        raise StoreError(f"{where}: scope.time.since {values['since']!r} is after until {values['until']!r}")


def check_meta(meta: Mapping[str, Any], where: str) -> None:
    """A registry entry (``meta.json``, ``create_neem(meta=...)``) a listing can show."""
    check_keys(meta, where)
    for field, types in _META_TYPES.items():
        value = meta.get(field)
        if value is not None and not isinstance(value, types):
            raise StoreError(f"{where}: {field!r} must be a {types[0].__name__}, got {_short(value)}")
    alias = meta.get("alias")
    if isinstance(alias, str):
        from oracle.store.ids import check_alias

        try:
            check_alias(alias)
        except StoreError as error:
            raise StoreError(f"{where}: {error}") from None
    user = meta.get("created_by")
    if isinstance(user, str) and not (user.strip() and user.isprintable() and len(user) <= 200):
        raise StoreError(f"{where}: 'created_by' {user[:40]!r} must be 1-200 printable characters")
    created = meta.get("created_at")
    if isinstance(created, str):
        try:
            parse_iso(created)
        except TimeValueError:
            raise StoreError(f"{where}: 'created_at' {created[:40]!r} is not an ISO-8601 time") from None


def _short(value: Any) -> str:
    text = repr(value)
    return text if len(text) <= 40 else text[:37] + "..."


def validate_group(
    patterns: Sequence[TriplePattern], kept: list[str] | None, group: str, limit: int | None,
    order: Sequence[tuple[str, bool]],
) -> list[str]:
    """The kept variables of a grouped match, ``group`` last: it must be a variable of the
    patterns (and kept, when ``select`` names some); a limit or an order would cut or sort rows
    that no longer exist after grouping, so neither may come with it."""
    names = sorted({name for pattern in patterns for name in pattern.variables()})
    if kept is None:
        kept = names
    if group not in kept:
        raise StoreError(f"group names {group!r}, which {'no pattern binds' if group not in names else 'select drops'}")
    if limit is not None or order:
        raise StoreError("a grouped match takes no limit or order")
    return [name for name in kept if name != group] + [group]


def validate_select(patterns: Sequence[TriplePattern], select: Sequence[str]) -> list[str]:
    """The variables a caller keeps, each one a variable of the patterns."""
    names = {name for pattern in patterns for name in pattern.variables()}
    kept = list(dict.fromkeys(select))
    for name in kept:
        if name not in names:
            raise StoreError(f"select names {name!r}, which no pattern binds")
    return kept


def validate_order(patterns: Sequence[TriplePattern], order: Sequence[tuple[str, bool]]) -> list[tuple[str, bool]]:
    names = {name for pattern in patterns for name in pattern.variables()}
    checked = []
    for name, descending in order:
        if name not in names:
            raise StoreError(f"cannot order by {name!r}: no pattern binds it")
        checked.append((name, bool(descending)))
    return checked
