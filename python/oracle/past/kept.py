"""What the answers about the past read of a NEEM's whole history, kept between answers: its
actions (the predictor's kept history, oracle.historycache), its "now", the workflows stored in
it and the routines mined from its actions.

Each NEEM's entry holds the store's AppendMark it was read at. Every use asks the store for the
mark again (one small query) and reads nothing else while it is the same: the mark names the
NEEM's tables, counts every update and deletion of one of its triples and moves with every
triple added (oracle.store.base.AppendMark), so an equal mark is the same triples and the same
answers. When it moved (an action, a ranking, a saved workflow), the first answer that needs
the actions has the history cache's rule say how the kept rows stand (oracle.historycache's
``growth``): the same (only rankings written since), extended by the rows after the last
(``Bridge.history_after``: a new action), or to be read whole (through the history cache).
The mined routines are kept (each for the actions begun by a time, which added actions, all
begun later, leave as they were). A store without a mark (MongoDB) keeps nothing.

The service keeps one per engine (oracle.service.engine); a command-line answer, made once,
keeps a fresh one for its own question: one code path, with or without what was kept.
"""

from __future__ import annotations

from collections import OrderedDict
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from oracle.past.routines import Done, MiningSettings, Routine, begun_by, done_from_history, mine_routines

if TYPE_CHECKING:
    from oracle.bridge import Bridge, HistoryRow
    from oracle.ontology import OdbOntology
    from oracle.words import Lexicon
    from oracle.store.base import AppendMark

#: How many NEEMs an engine keeps the history of (the least recently asked is dropped).
NEEMS = 8
#: How many minings of one NEEM's actions are kept (one per distinct "as of" time asked).
MININGS = 8

#: Routines mined, by how many actions had begun by the time asked (the actions begun by one
#: time include those begun by any earlier one, so their count names them) and the settings.
Minings = OrderedDict[tuple[int, MiningSettings | None], list[Routine]]


@dataclass
class _Entry:
    mark: AppendMark | None
    rows: list[HistoryRow] | None = None  # the history rows, and their non-idle actions
    done: list[Done] | None = None
    now: tuple[float | None] | None = None  # (now,) once read: None is a NEEM without events
    stored: list[dict[str, Any]] | None = None
    mined: Minings = field(default_factory=OrderedDict)
    # the latest entry of an earlier mark whose rows were read, until this one's are
    earlier: _Entry | None = None


class KeptPast:
    """The kept reads of one store's NEEMs, read through one ontology (an engine's)."""

    def __init__(self) -> None:
        self._entries: OrderedDict[str, _Entry] = OrderedDict()
        self._lexicon: tuple[OdbOntology, Lexicon] | None = None

    def lexicon(self, onto: OdbOntology) -> Lexicon:
        """The tablet's words of ``onto`` (oracle.words.load_lexicon), read once: the
        labels file and the ontology's labels do not change while a process runs."""
        from oracle.words import load_lexicon

        if self._lexicon is None or self._lexicon[0] is not onto:
            self._lexicon = (onto, load_lexicon(ontology=onto))
        return self._lexicon[1]

    def _entry(self, bridge: Bridge) -> _Entry:
        neem = bridge.neem_id
        mark = bridge.store.append_mark(neem)
        entry = self._entries.get(neem)
        if entry is not None and mark is not None and entry.mark == mark:
            self._entries.move_to_end(neem)
            return entry
        fresh = _Entry(mark)
        if mark is None:
            self._entries.pop(neem, None)
            return fresh  # nothing to check a kept read against: this answer's own
        if entry is not None:
            fresh.earlier = entry.earlier if entry.rows is None else entry
        self._entries[neem] = fresh
        self._entries.move_to_end(neem)
        while len(self._entries) > NEEMS:
            self._entries.popitem(last=False)
        return fresh

    def done(self, bridge: Bridge) -> list[Done]:
        """The NEEM's non-idle actions as the predictor keeps its history (do not change the list)."""
        return _done(self._entry(bridge), bridge)

    def now(self, bridge: Bridge) -> float | None:
        """The NEEM's "now" (oracle.past.evidence.now_of)."""
        from oracle.past.evidence import now_of

        entry = self._entry(bridge)
        if entry.now is None:
            entry.now = (now_of(bridge),)
        return entry.now[0]

    def stored(self, bridge: Bridge) -> list[dict[str, Any]]:
        """The workflows stored in the NEEM (oracle.past.workflows.stored_routines)."""
        from oracle.past.workflows import stored_routines

        entry = self._entry(bridge)
        if entry.stored is None:
            entry.stored = stored_routines(bridge)
        return entry.stored

    def mined(self, bridge: Bridge, at: float | None, settings: MiningSettings | None) -> tuple[list[Done], list[Routine]]:
        """The actions begun by ``at`` (all for None) and the routines mined from them
        (oracle.past.routines.mine_routines; do not change the lists)."""
        entry = self._entry(bridge)
        done = begun_by(_done(entry, bridge), at)
        key = (len(done), settings)
        routines = entry.mined.get(key)
        if routines is None:
            routines = entry.mined[key] = mine_routines(done, settings)
            while len(entry.mined) > MININGS:
                entry.mined.popitem(last=False)
        return done, routines


def _done(entry: _Entry, bridge: Bridge) -> list[Done]:
    if entry.done is None:
        _read(entry, bridge)
    assert entry.done is not None
    return entry.done


def _read(entry: _Entry, bridge: Bridge) -> None:
    """The entry's rows and actions: the earlier entry's, extended where the history cache's
    rule allows (its minings carried over), else read whole."""
    from oracle.historycache import growth

    earlier, entry.earlier = entry.earlier, None
    if (earlier is not None and earlier.mark is not None and earlier.rows is not None and earlier.done is not None
            and entry.mark is not None):
        how = growth(bridge, earlier.mark, earlier.rows, entry.mark)
        if how != "whole":
            added = bridge.history_after(earlier.rows[-1]["begin"]) if how == "after" else []
            new = done_from_history(added)
            entry.rows, entry.done = earlier.rows + added, (earlier.done + new if new else earlier.done)
            # the added actions began after every kept one: the actions begun by any time are
            # the same as before or more than before, so each kept mining still names its own
            entry.mined = earlier.mined
            return
    entry.rows = _history(bridge)
    entry.done = done_from_history(entry.rows)
    if earlier is not None and earlier.done == entry.done:  # the same actions (a workflow saved again)
        entry.done, entry.mined = earlier.done, earlier.mined


def _history(bridge: Bridge) -> list[Any]:
    from oracle.historycache import HistoryCache

    return HistoryCache.default().history(bridge)
