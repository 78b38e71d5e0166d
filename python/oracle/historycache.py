"""The oracle's history of a NEEM (``Bridge.history``), kept between calls: a rank after the robot
logged one more action reads that action from the store, not the whole NEEM again.

One entry per store and NEEM, a file in the user's private cache (``histories/`` beside the kept
fits; folder 0700, file 0600), named by a digest of the store's location, the NEEM id, the
Prolog sources and the ontology's fingerprint (what the rows are computed with). Inside, as
JSON: the store's AppendMark taken before the rows were read, and the rows.

The kept rows are extended, not read again, only when the store shows that what was added
since cannot change them (``extends``):

- the NEEM's tables are the same (token) and none of its triples was updated or deleted since
  (changes), and every triple added since has a subject that no earlier triple had, as
  subject or object (Store.appended's ``fresh``): every pattern of the history read starts at
  an action or an imagining and follows triples from subject to object, so no earlier row can
  reach the new triples;
- every interval begin added is later than the last kept row's begin, or belongs to added events
  that execute added tasks of no odb class and not soma:Imagining (a preference written for a
  decision ranked earlier); and every interval an added triple gives an event is itself added:
  new actions and imaginings come after the kept ones, and
  odb_history:situation_history_after/2 reads exactly them.

Otherwise (a store that cannot tell, such as MongoDB; an entry missing, damaged or not the
user's own; anything else) the whole history is read and the entry replaced. A temporary NEEM
(a session not yet persisted, wiped when the next one starts; thesis 3.5) is never kept. The cache is an
optimisation: a folder that cannot be written only makes every call read the whole history.
"""

from __future__ import annotations

import hashlib
import json
import math
import os
from collections.abc import Collection, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any, ClassVar

from oracle.bridge import Bridge, history_rows
from oracle.files import CacheFolder, write_private_bytes, written_by_user_alone
from oracle.neem.terms import BEGIN, EXECUTES, HAS_INTERVAL, IMAGINING
from oracle.store.base import Appended, AppendMark
from oracle.store.model import RDF_TYPE, decode_value

#: More triples added than this (~500 logged actions) and the whole history is read instead:
#: checking and reading that many added triples costs about as much.
MAX_APPENDED = 20_000
_FORMAT = "neem-oracle history 1"


@dataclass(frozen=True)
class HistoryCache(CacheFolder):
    """Histories under ``root`` (one file each)."""

    FOLDER: ClassVar[str] = "histories"
    SUFFIX: ClassVar[str] = ".json"

    def history(self, bridge: Bridge) -> list[dict[str, Any]]:
        """``bridge.history()``, from the kept entry and the actions added since when the
        store shows they extend it (module docstring); the entry then holds the result."""
        store, neem = bridge.store, bridge.neem_id
        if store.neem(neem).temporary:
            return bridge.history()  # wiped when its session ends: nothing of it may outlive it
        mark = store.append_mark(neem)
        if mark is None:
            return bridge.history()
        path = self.root / f"{_entry_key(bridge)}{self.SUFFIX}"
        kept = self._load(path)
        rows: list[dict[str, Any]] | None = None
        if kept is not None and kept[0] == mark:
            return kept[1]
        if kept is not None and kept[1] and same_tables(kept[0], mark) and mark.last - kept[0].last <= MAX_APPENDED:
            after = kept[1][-1]["begin"]
            added = store.appended(neem, kept[0].last)
            namespace = None if bridge.ontology is None else bridge.ontology.namespace
            if added is not None and extends(added, after, namespace):
                rows = kept[1] + bridge.history_after(after)
        if rows is None:
            rows = bridge.history()
        self._store(path, mark, rows)
        return rows

    def _load(self, path: Path) -> tuple[AppendMark, list[dict[str, Any]]] | None:
        try:
            with path.open("rb") as handle:
                if not written_by_user_alone(os.fstat(handle.fileno())):
                    return None
                data = json.loads(handle.read())
            if data["format"] != _FORMAT:
                return None
            token, changes, last = data["mark"]
            mark = AppendMark(str(token), int(changes), int(last))
            if not _well_formed(data["history"]):
                return None  # valid JSON, but not a history (edited or damaged)
            rows = history_rows(data["history"])
        except (OSError, ValueError, KeyError, TypeError, IndexError):
            return None  # missing or damaged: the whole history is read, the entry replaced
        return mark, rows

    def _store(self, path: Path, mark: AppendMark, rows: list[dict[str, Any]]) -> None:
        data = {"format": _FORMAT, "mark": [mark.token, mark.changes, mark.last], "history": compact(rows)}
        try:
            write_private_bytes(path, json.dumps(data, separators=(",", ":")).encode())
            self._prune()
        except OSError:
            return  # read-only or full: the next call reads the whole history


def _well_formed(history: Any) -> bool:
    """``compact``'s shape: call texts, sets of call indexes, and rows of a finite begin and
    end, a call index, a part of day and a set index (-1: none)."""
    calls, sets, flat = history["calls"], history["sets"], history["rows"]
    if not (isinstance(calls, list) and isinstance(sets, list) and isinstance(flat, list) and len(flat) % 5 == 0):
        return False
    n_calls, n_sets = len(calls), len(sets)
    index = lambda x, n: type(x) is int and 0 <= x < n  # noqa: E731
    number = lambda x: type(x) in (int, float) and math.isfinite(x)  # noqa: E731
    return (all(type(c) is str for c in calls)
            and all(isinstance(s, list) and all(index(i, n_calls) for i in s) for s in sets)
            and all(map(number, flat[0::5])) and all(map(number, flat[1::5]))
            and all(index(i, n_calls) for i in flat[2::5]) and all(type(p) is str for p in flat[3::5])
            and all(i == -1 or index(i, n_sets) for i in flat[4::5]))


def same_tables(kept: AppendMark, now: AppendMark) -> bool:
    """The NEEM's tables are those of the kept mark, nothing in them was changed or deleted
    since, and nothing is missing."""
    return kept.token == now.token and kept.changes == now.changes and now.last >= kept.last


def extends(added: Appended, after: float, namespace: str | None) -> bool:
    """The triples ``added`` after a history whose last row began at ``after`` only add rows
    after it (module docstring). An added interval that begins at or before ``after`` is
    harmless only when it belongs to added events that execute added tasks of no class that
    makes a situation or an imagining (an odb class of ``namespace``, soma:Imagining): a
    preference written for a decision ranked earlier."""
    if not added.fresh:
        return False
    docs_of: dict[Any, list[Mapping[str, Any]]] = {}
    owners: dict[Any, list[Any]] = {}
    for doc in added.docs:
        docs_of.setdefault(doc.get("s"), []).append(doc)
        if HAS_INTERVAL in _properties(doc):
            owners.setdefault(doc.get("o"), []).append(doc.get("s"))
    for doc in added.docs:
        properties = _properties(doc)
        if HAS_INTERVAL in properties and doc.get("o") not in docs_of:
            return False
        if BEGIN in properties:
            begin = decode_value(doc.get("o"))
            if isinstance(begin, bool) or not isinstance(begin, (int, float)):
                return False
            if not begin > after and not _no_situation(owners.get(doc.get("s"), []), docs_of, namespace):
                return False
    return True


def _no_situation(events: list[Any], docs_of: Mapping[Any, list[Mapping[str, Any]]], namespace: str | None) -> bool:
    """None of the (added) events can be an action or an imagining of the history read: each
    task they execute is added with its types, and none of those is under an odb class or
    soma:Imagining."""
    if namespace is None:
        return False
    for event in events:
        for doc in docs_of.get(event, []):
            if EXECUTES not in _properties(doc):
                continue
            task_docs = docs_of.get(doc.get("o"))
            if task_docs is None:
                return False  # an earlier task: its types are not among the added triples
            for typed in task_docs:
                if typed.get("p") != RDF_TYPE:
                    continue
                stars = typed.get("o*")
                classes = {typed.get("o"), *(stars if isinstance(stars, list) else ())}
                if any(isinstance(c, str) and (c.startswith(namespace) or c == IMAGINING) for c in classes):
                    return False
    return True


def _properties(doc: Mapping[str, Any]) -> Collection[Any]:
    stars = doc.get("p*")
    return {doc.get("p"), *(stars if isinstance(stars, list) else ())}


def compact(rows: list[dict[str, Any]]) -> dict[str, Any]:
    """Rows in the shape of odb_history:situation_history_json (each distinct call and each
    distinct available set written once); ``history_rows`` reads it back."""
    calls: dict[str, int] = {}
    sets: dict[tuple[int, ...], int] = {}
    # rows read together share one list per distinct set: each list is numbered once
    numbered: dict[int, tuple[list[str], int]] = {}
    flat: list[Any] = []
    for row in rows:
        call = calls.setdefault(row["call"], len(calls))
        available = row["available"]
        index = -1
        if available is not None:
            known = numbered.get(id(available))
            if known is not None and known[0] is available:
                index = known[1]
            else:
                key = tuple(calls.setdefault(c, len(calls)) for c in available)
                index = sets.setdefault(key, len(sets))
                numbered[id(available)] = (available, index)
        flat += [row["begin"], row["end"], call, row["part"], index]
    return {"calls": list(calls), "sets": [list(key) for key in sets], "rows": flat}


def _entry_key(bridge: Bridge) -> str:
    from oracle import modulecache
    from oracle.ontology.provenance import fingerprint
    from oracle.paths import prolog_dir

    digest = hashlib.sha256()
    ontology = "none" if bridge.ontology is None else fingerprint(bridge.ontology)
    for part in (_FORMAT, bridge.store.location, bridge.neem_id, modulecache.modules_key(prolog_dir(), ""), ontology):
        digest.update(part.encode() + b"\0")
    return digest.hexdigest()[:32]
