"""A new NEEM's history view (``Bridge.history_view``) built as the logger writes it, so that
``import`` keeps the view and the fit without reading the whole NEEM back through Prolog
(that read held most of the import's memory peak and a third of its time).

It mirrors odb_history's rules on what the logger wrote, row by row:

- the rows are the executed actions and the idle actions the logger inserts before a gap (its
  rule, ``is_idle_gap``), in the order of their begin (``situation_history``'s sort; rows that
  share a begin are ordered by their IRIs there, which are not mirrored: see below);
- a row's call is the chain call as Prolog writes it (``pour(thermos,green_mug)``, ``idle``);
  its part of the day is that its interval was typed with (``none`` without a clock); its mode
  who performed it (an idle action: the robot, as the logger writes it);
- an action's available set is the sorted calls of the latest imagining that began at or before
  it, when that began after the row before (``history_rows/8``'s rule); the imaginings here
  are those the logger wrote with an action (``available``), at its begin;
- the latest situation is the imagining with the latest begin.

Only a NEEM the builder saw written from its start can be described so (a new or replacing
import); ``view`` says None where the rules above could be ambiguous (two imaginings at the
latest begin or two rows of one begin, an empty available set), and the caller then reads the NEEM as before.
tests/test_writtenview.py compares it with the Prolog read.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from oracle.bridge import HistoryRow, HistoryView, LatestSituation
from oracle.chains import ChainRow, TaskCall
from oracle.neem.records import checked_instant
from oracle.timeline import IDLE_THRESHOLD_S, Instant, is_idle_gap, sequence_instant

if TYPE_CHECKING:
    from oracle.ontology import OdbOntology
    from oracle.store import Store

#: The call of an idle action in a history row.
IDLE = "idle"


def prolog_text(call: TaskCall) -> str:
    """A call as odb_history writes it (``format('~w')`` of the call term: no spaces)."""
    return f"{call.task}({','.join(call.args)})" if call.args else call.task


def _standard_order(call: TaskCall) -> tuple[object, ...]:
    """Prolog's standard order of call terms: atoms before compounds; compounds by arity, then
    name, then arguments (atoms, by their characters)."""
    return (0, call.task) if not call.args else (1, len(call.args), call.task, call.args)


@dataclass(slots=True)  # one per action, held through the import (50,000 and more)
class _Row:
    begin: float
    end: float
    call: str
    part: str
    mode: str


@dataclass
class WrittenView:
    """What a logger writes into a new NEEM, as the history view will read it; ``logged`` is
    told each action in the order it is logged, with what the logger is given."""

    idle_threshold: float = IDLE_THRESHOLD_S
    _rows: list[_Row] = field(default_factory=list)
    #: (begin, sorted call texts) of each imagining, in the order written.
    _imaginings: list[tuple[float, list[str]]] = field(default_factory=list)
    #: The part of the day of each imagining, by its index in ``_imaginings``.
    _parts: list[str] = field(default_factory=list)
    #: The available sets seen (by the identity of their tuple, kept so that its id stays its
    #: own): a chains file's rows share one tuple per distinct set.
    _sets: dict[int, tuple[object, list[str]]] = field(default_factory=dict)
    #: Each call's text (``prolog_text``), made once.
    _calls: dict[TaskCall, str] = field(default_factory=dict)
    _last_end: Instant | None = None
    _ambiguous: bool = False

    def logged(self, call: TaskCall, begin: Instant, end: Instant, performed_by: str,
               available: Iterable[TaskCall] | None) -> None:
        """An action the logger writes (``NeemLogger.action``): its call, its interval as the
        logger's instants, who performed it and the calls available when it began (None: none).
        The idle action the logger inserts before it follows the logger's rule (``is_idle_gap``)."""
        last = self._last_end
        if last is not None and is_idle_gap(last.seconds, begin.seconds, self.idle_threshold):
            self._rows.append(_Row(last.seconds, begin.seconds, IDLE, _part(last), "robot"))
        text = self._calls.get(call)
        if text is None:  # one string per distinct call, shared by its rows
            if len(self._calls) >= 4096:
                self._calls.clear()
            text = self._calls[call] = prolog_text(call)
        self._rows.append(_Row(begin.seconds, end.seconds, text, _part(begin), performed_by))
        if available is not None:
            self._imaginings.append((begin.seconds, self._texts(available)))
            self._parts.append(_part(begin))
        if last is None or end.seconds > last.seconds:
            self._last_end = end

    def _texts(self, available: Iterable[TaskCall]) -> list[str]:
        known = self._sets.get(id(available))
        if known is not None and known[0] is available:
            return known[1]
        calls = sorted(set(available), key=_standard_order)
        if not calls:
            self._ambiguous = True  # an imagining of nothing is no situation: not mirrored here
        texts = [prolog_text(call) for call in calls]
        if type(available) is tuple:
            if len(self._sets) >= 4096:
                self._sets.clear()
            self._sets[id(available)] = (available, texts)
        return texts

    @property
    def actions(self) -> int:
        """Rows so far (executed and idle actions)."""
        return len(self._rows)

    def view(self) -> HistoryView | None:
        """The history view of the NEEM as written; None where it is not mirrored (module docstring)."""
        imaginings = sorted(range(len(self._imaginings)), key=lambda i: self._imaginings[i][0])
        latest_situation = self._latest(imaginings)
        if self._ambiguous:
            return None
        # Prolog orders rows of one begin by their IRIs, which are not mirrored here.
        rows = sorted(self._rows, key=lambda row: row.begin)
        if any(a.begin == b.begin for a, b in zip(rows, rows[1:])):
            return None
        out: list[HistoryRow] = []
        latest: tuple[float, list[str]] | None = None
        at = 0
        previous: float | None = None
        for row in rows:
            while at < len(imaginings) and self._imaginings[imaginings[at]][0] <= row.begin:
                latest = self._imaginings[imaginings[at]]
                at += 1
            available = None
            if row.call != IDLE and latest is not None and (previous is None or latest[0] > previous):
                available = latest[1]
            out.append(HistoryRow(begin=row.begin, end=row.end, call=row.call, part=row.part, available=available,
                                  mode=row.mode))
            previous = row.begin
        return HistoryView(out, latest_situation)

    def _latest(self, order: list[int]) -> LatestSituation | None:
        if not order:
            return None
        last = order[-1]
        begin, texts = self._imaginings[last]
        if len(order) > 1 and self._imaginings[order[-2]][0] == begin:
            self._ambiguous = True
        return LatestSituation(begin=begin, available=list(texts), part=self._parts[last])


def _part(instant: Instant) -> str:
    return instant.part_of_day if instant.part_of_day is not None else "none"


def views_of_import(rows: Iterable[ChainRow], *, no_clock: bool = False,
                    idle_threshold: float = IDLE_THRESHOLD_S) -> dict[str, WrittenView]:
    """Each user's ``WrittenView`` of a chains file as ``import_chains`` logs it into a new NEEM
    (the same instants: a row's time and end, or on the sequence clock the user's n-th action
    from position n to n + 1)."""
    views: dict[str, WrittenView] = {}
    positions: dict[str, int] = {}
    for row in rows:
        written = views.get(row.user)
        if written is None:
            written = views[row.user] = WrittenView(idle_threshold)
        if no_clock:
            position = positions[row.user] = positions.get(row.user, -1) + 1
            begin, end = sequence_instant(position), sequence_instant(position + 1)
        else:
            assert row.time is not None  # checked by the import's first pass
            begin = checked_instant(row.time)
            end = begin if row.end is None else checked_instant(row.end)
        written.logged(row.action, begin, end, str(row.extra.get("performed_by", "robot")), row.available)
    return views


def keep_written(store: Store, ontology: OdbOntology, neem: str, views: Mapping[str, WrittenView]) -> bool:
    """Keep the view ``views`` holds for NEEM ``neem``'s user (oracle.historycache) at the
    store's mark now, where it is mirrored; True if kept (the first rank, and ``keep_neem``'s
    fit, then read nothing through Prolog). Call it only for a NEEM that was new when the
    import's logger began it and that nothing else wrote since."""
    from oracle.historycache import HistoryCache

    written = views.get(store.neem(neem).user or "")
    view = written.view() if written is not None else None
    return view is not None and HistoryCache.default().keep(store, ontology, neem, view)
