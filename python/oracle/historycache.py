"""The oracle's view of a NEEM (``Bridge.history_view``: its history and its latest imagined
situation), kept between calls: a rank after the robot logged one more action reads that action
from the store, not the whole NEEM again, and a rank after nothing but rankings were written
reads nothing through Prolog at all.

Kept in the store itself where it can keep it (oracle.store.kept: the SQLite file, beside the
NEEM's triples, so the first rank after an import finds what the import kept), else in a file
of the user's private cache (``histories/`` beside the kept fits; folder 0700, file 0600) named
by a digest of the store's location and the entry's key. The key is a digest of the NEEM id,
the Prolog sources and the ontology's fingerprint (what the rows are computed with). Inside,
as JSON: the key, the store's AppendMark taken before the rows were read, the rows and the
latest situation.

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
  odb_history:situation_history_after/2 reads exactly them. When every added event is such a
  preference (``extends`` with no last begin), neither the rows nor the latest situation
  change, and nothing is read.

Otherwise (a store that cannot tell, such as MongoDB; an entry missing, damaged or not the
user's own; anything else) the whole history is read (in bounded slices, oracle.slicedread)
and the entry replaced. A temporary NEEM
(a session not yet persisted, wiped when the next one starts; thesis 3.5) is never kept. The cache is an
optimisation: a folder that cannot be written only makes every call read the whole history.
"""

from __future__ import annotations

import hashlib
import json
import math
import os
import re
from collections.abc import Callable, Collection, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, ClassVar

from oracle.bridge import ROW_WIDTH, Bridge, HistoryRow, HistoryView, history_rows
from oracle.files import CacheFolder, written_by_user_alone
from oracle.neem.terms import BEGIN, EXECUTES, HAS_INTERVAL, IMAGINING
from oracle.slicedread import sliced_view
from oracle.store.base import Appended, AppendMark
from oracle.store.model import RDF_TYPE, decode_value

if TYPE_CHECKING:
    from oracle.ontology import OdbOntology
    from oracle.store import Store

#: More triples added than this (~500 logged actions) and the whole history is read instead:
#: checking and reading that many added triples costs about as much.
MAX_APPENDED = 20_000
_FORMAT = "neem-oracle history 3"


#: The kind of entry the store keeps (oracle.store.kept).
KIND = "history"


@dataclass(frozen=True)
class _Entry:
    mark: AppendMark
    view: HistoryView


@dataclass(frozen=True)
class HistoryCache(CacheFolder):
    """Views kept in the store, or else under ``root`` (one file each)."""

    FOLDER: ClassVar[str] = "histories"
    SUFFIX: ClassVar[str] = ".json"

    def history(self, bridge: Bridge) -> list[HistoryRow]:
        """``bridge.history()``, as ``view`` keeps it."""
        return self.view(bridge).rows

    def view(self, bridge: Bridge, whole: Callable[[Bridge], HistoryView] = sliced_view) -> HistoryView:
        """``bridge.history_view()``, from the kept entry and the actions added since when the
        store shows they extend it (module docstring); the entry then holds the result. ``whole``
        reads the whole view when it must be (the service's reads the first slices before, each
        its own job on the engine thread: oracle.service.explore_routes)."""
        store, neem = bridge.store, bridge.neem_id
        if store.neem(neem).temporary:
            return whole(bridge)  # wiped when its session ends: nothing of it may outlive it
        mark = store.append_mark(neem)
        if mark is None:
            return whole(bridge)
        key = _entry_key(bridge)
        path = self.root / f"{_file_name(key, store.location)}{self.SUFFIX}"
        entry = _best(mark, key, [raw for raw in (store.read_kept(neem, KIND), self._load(path)) if raw is not None])
        if entry is not None and entry.mark == mark:
            return entry.view
        view = _extended(bridge, entry, mark) if entry is not None else None
        if view is None:
            view = whole(bridge)
        data = _dumps(key, mark, view)
        if not store.write_kept(neem, KIND, data):
            self._store(path, data)
        return view

    def keep(self, store: Store, ontology: OdbOntology | None, neem: str, view: HistoryView) -> bool:
        """Keep ``view`` as NEEM ``neem``'s view at the store's mark now, as ``view`` would after
        reading it: the caller vouches that it is what the history read gives there (``import``
        builds it as it writes, oracle.writtenview). False when nothing can be kept (a temporary
        NEEM, a store that cannot tell what is added later)."""
        if store.neem(neem).temporary:
            return False
        mark = store.append_mark(neem)
        if mark is None:
            return False
        key = _key_of(neem, ontology)
        data = _dumps(key, mark, view)
        if not store.write_kept(neem, KIND, data):
            self._store(self.root / f"{_file_name(key, store.location)}{self.SUFFIX}", data)
        return True

    def _load(self, path: Path) -> bytes | None:
        try:
            with path.open("rb") as handle:
                if not written_by_user_alone(os.fstat(handle.fileno())):
                    return None
                return handle.read()
        except OSError:
            return None


def kept_history(store: Store, ontology: OdbOntology | None, neem: str) -> dict[str, Any] | None:
    """The NEEM's history in ``compact``'s shape as the store keeps it, when its entry is at the
    store's mark now (what ``HistoryCache.view`` would give without reading anything); None
    otherwise (nothing kept in the store, kept behind the mark, a temporary NEEM, a store that
    cannot tell). Reads only the store, never Prolog: a reader with a connection of its own (the
    explorer's, oracle.service.explore_reader) sends the first paint's timeline with it."""
    if store.neem(neem).temporary:
        return None
    mark = store.append_mark(neem)
    raw = None if mark is None else store.read_kept(neem, KIND)
    if raw is None:
        return None
    key = _key_of(neem, ontology)
    if _header(raw, key) != mark:
        return None
    try:
        data = json.loads(raw)
        history = data["history"]
        return history if _well_formed(history) else None
    except (ValueError, KeyError, TypeError, IndexError):
        return None


def _best(mark: AppendMark, key: str, raws: Sequence[bytes]) -> _Entry | None:
    """Of the kept entries ``raws`` (the store's, the user's file), the one to start from at
    ``mark``: one taken at ``mark`` itself, else the one the fewest triples behind it that
    may be extended (``same_tables``, at most MAX_APPENDED behind). Only that one is parsed
    whole (a view of 50,000 rows takes 0.2 s); the others are judged by their mark
    (``_header``), and a damaged one gives way to the next."""
    marks = [(found, raw) for raw in raws if (found := _header(raw, key)) is not None]
    usable = [(found, raw) for found, raw in marks
              if found == mark or (same_tables(found, mark) and mark.last - found.last <= MAX_APPENDED)]
    for found, raw in sorted(usable, key=lambda pair: (pair[0] == mark, pair[0].last), reverse=True):
        entry = _parse(raw, key)
        if entry is not None and entry.mark == found:
            return entry
    return None


#: The start of an entry as ``_dumps`` writes it (compact JSON, its keys in that order).
_HEAD = re.compile(rb'\{"format":"([^"\\]*)","key":"([0-9a-f]*)","mark":\["([^"\\]*)",(\d+),(\d+)\]')


def _header(raw: bytes, key: str) -> AppendMark | None:
    """The mark of an entry written by ``_dumps`` for ``key``, read from its first bytes; None
    for another's entry or anything else (``_parse`` then checks the whole entry)."""
    found = _HEAD.match(raw[:256])
    if found is None or found[1].decode() != _FORMAT or found[2].decode() != key:
        return None
    return AppendMark(found[3].decode(), int(found[4]), int(found[5]))


def _extended(bridge: Bridge, entry: _Entry, mark: AppendMark) -> HistoryView | None:
    """The kept view with what was added since its mark, when that only adds (module
    docstring); None when the whole view must be read."""
    rows = entry.view.rows
    how = growth(bridge, entry.mark, rows, mark)
    if how == "same":
        return entry.view  # only rankings written since
    if how == "whole":
        return None
    after = bridge.history_view(rows[-1]["begin"])
    return HistoryView(rows + after.rows, after.latest)


def growth(bridge: Bridge, kept: AppendMark, rows: Sequence[HistoryRow], now: AppendMark) -> str:
    """How the history ``rows`` read at mark ``kept`` stand at mark ``now`` (module docstring):
    ``same`` (only rankings written since: neither the rows nor the latest situation changed),
    ``after`` (the rows after the last one's begin are to be added: ``Bridge.history_after``)
    or ``whole`` (the history is to be read whole)."""
    if not same_tables(kept, now) or now.last - kept.last > MAX_APPENDED:
        return "whole"
    added = bridge.store.appended(bridge.neem_id, kept.last)
    if added is None:
        return "whole"
    namespace = None if bridge.ontology is None else bridge.ontology.namespace
    if extends(added, None, namespace):
        return "same"
    if not rows or not extends(added, rows[-1]["begin"], namespace):
        return "whole"
    return "after"


def _dumps(key: str, mark: AppendMark, view: HistoryView) -> bytes:
    data = {"format": _FORMAT, "key": key, "mark": [mark.token, mark.changes, mark.last], "history": compact(view.rows),
            "latest": view.latest}
    return json.dumps(data, separators=(",", ":")).encode()


def _parse(raw: bytes | None, key: str) -> _Entry | None:
    """An entry's bytes as written by ``_dumps`` for ``key``; None when missing, damaged or another's."""
    if raw is None:
        return None
    try:
        data = json.loads(raw)
        if data["format"] != _FORMAT or data["key"] != key:
            return None
        token, changes, last = data["mark"]
        mark = AppendMark(str(token), int(changes), int(last))
        latest = data["latest"]
        if not _well_formed(data["history"]) or not _well_formed_latest(latest):
            return None  # valid JSON, but not a history (edited or damaged)
        return _Entry(mark, HistoryView(history_rows(data["history"]), latest))
    except (ValueError, KeyError, TypeError, IndexError):
        return None  # damaged: the whole history is read, the entry replaced


def _well_formed_latest(latest: Any) -> bool:
    """``Bridge.latest_situation``'s shape: None, or a finite begin, call texts and a part of day."""
    if latest is None:
        return True
    begin = latest["begin"]
    return (type(begin) in (int, float) and math.isfinite(begin) and isinstance(latest["available"], list)
            and all(type(c) is str for c in latest["available"]) and type(latest["part"]) is str)


def _well_formed(history: Any) -> bool:
    """``compact``'s shape: call texts, sets of call indexes, and rows of a finite begin and
    end, a call index, a part of day, a set index (-1: none) and a mode. Each column is checked by the
    types it holds and its least and greatest value (a kept view of 50,000 rows is read at
    every cold start)."""
    calls, sets, flat = history["calls"], history["sets"], history["rows"]
    if not (isinstance(calls, list) and isinstance(sets, list) and isinstance(flat, list) and len(flat) % ROW_WIDTH == 0):
        return False
    members = [i for s in sets if isinstance(s, list) for i in s]
    return (all(isinstance(s, list) for s in sets) and {type(c) for c in calls} <= {str}
            and _numbers(flat[0::ROW_WIDTH]) and _numbers(flat[1::ROW_WIDTH])
            and _indexes(flat[2::ROW_WIDTH], 0, len(calls)) and {type(p) for p in flat[3::ROW_WIDTH]} <= {str}
            and _indexes(flat[4::ROW_WIDTH], -1, len(sets)) and {type(m) for m in flat[5::ROW_WIDTH]} <= {str}
            and _indexes(members, 0, len(calls)))


def _numbers(column: list[Any]) -> bool:
    """Every value a finite number (an int or a float, not a bool): a NaN or an infinity makes
    the sum one (the values are times, far from overflowing it)."""
    return not column or ({type(x) for x in column} <= {int, float} and math.isfinite(sum(column)))


def _indexes(column: list[Any], least: int, end: int) -> bool:
    """Every value an int in [least, end)."""
    return not column or ({type(x) for x in column} == {int} and min(column) >= least and max(column) < end)


def same_tables(kept: AppendMark, now: AppendMark) -> bool:
    """The NEEM's tables are those of the kept mark, nothing in them was changed or deleted
    since, and nothing is missing."""
    return kept.token == now.token and kept.changes == now.changes and now.last >= kept.last


def extends(added: Appended, after: float | None, namespace: str | None) -> bool:
    """The triples ``added`` after a history whose last row began at ``after`` only add rows
    after it (module docstring). An added interval that begins at or before ``after`` is
    harmless only when it belongs to added events that execute added tasks of no class that
    makes a situation or an imagining (an odb class of ``namespace``, soma:Imagining): a
    preference written for a decision ranked earlier. ``after`` None: every added interval
    must be harmless, and then neither the rows nor the latest situation change."""
    if not added.fresh:
        return False
    docs_of, owners = _indexed(added)
    for doc in added.docs:
        properties = _properties(doc)
        if HAS_INTERVAL in properties and doc.get("o") not in docs_of:
            return False
        if BEGIN in properties:
            begin = decode_value(doc.get("o"))
            if isinstance(begin, bool) or not isinstance(begin, (int, float)):
                return False
            new = after is not None and begin > after
            if not new and not _no_situation(owners.get(doc.get("s"), []), docs_of, namespace):
                return False
    return True


def _indexed(added: Appended) -> tuple[dict[Any, list[Mapping[str, Any]]], dict[Any, list[Any]]]:
    """The added documents by subject, and the events of each added interval."""
    docs_of: dict[Any, list[Mapping[str, Any]]] = {}
    owners: dict[Any, list[Any]] = {}
    for doc in added.docs:
        docs_of.setdefault(doc.get("s"), []).append(doc)
        if HAS_INTERVAL in _properties(doc):
            owners.setdefault(doc.get("o"), []).append(doc.get("s"))
    return docs_of, owners


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


def compact(rows: Sequence[HistoryRow]) -> dict[str, Any]:
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
        flat += [row["begin"], row["end"], call, row["part"], index, row["mode"]]
    return {"calls": list(calls), "sets": [list(key) for key in sets], "rows": flat}


def _entry_key(bridge: Bridge) -> str:
    """What the rows are computed with: the NEEM, the Prolog sources and the ontology."""
    return _key_of(bridge.neem_id, bridge.ontology)


def _key_of(neem: str, ontology: OdbOntology | None) -> str:
    from oracle import modulecache
    from oracle.ontology.provenance import fingerprint
    from oracle.paths import prolog_dir

    digest = hashlib.sha256()
    text = "none" if ontology is None else fingerprint(ontology)
    for part in (_FORMAT, neem, modulecache.modules_key(prolog_dir(), ""), text):
        digest.update(part.encode() + b"\0")
    return digest.hexdigest()[:32]


def _file_name(key: str, location: str) -> str:
    """The user-cache file of an entry: its key, for the store at ``location``."""
    return hashlib.sha256(f"{key}\0{location}".encode()).hexdigest()[:32]
