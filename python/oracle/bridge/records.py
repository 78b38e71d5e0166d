"""What the oracle reads of a NEEM through the bridge: history rows, the latest imagined
situation, and the history view that holds both."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, TypedDict


class HistoryRow(TypedDict):
    """One executed action of the oracle's history (odb_history:situation_history/1), in begin
    order: its interval (unix seconds, or positions on a NEEM's sequence clock), its call in the
    chain syntax (``idle`` for an odb:IdleTask action), the part of the day it was logged with
    (``none`` if not), the calls of the imagined situation it was chosen in (None: none) and who
    performed it (odb_history:action_modes/2: ``user``, ``robot``, ``together`` or ``unknown``)."""

    begin: float
    end: float
    call: str
    part: str
    available: list[str] | None
    mode: str


class LatestSituation(TypedDict):
    """The NEEM's latest imagined situation (odb_history:latest_situation/3): when it began,
    the calls it found available (sorted) and the part of the day it was logged with."""

    begin: float
    available: list[str]
    part: str


@dataclass(frozen=True)
class HistoryView:
    """What the oracle reads of a NEEM: the ``situation_history`` rows (``Bridge.history``) and
    the latest imagined situation (``Bridge.latest_situation``)."""

    rows: list[HistoryRow]
    latest: LatestSituation | None


#: Values per row in odb_history:situation_history_json's flat ``rows``: begin, end, call
#: index, part of day, available set index and mode.
ROW_WIDTH = 6


def history_rows(reply: dict[str, Any]) -> list[HistoryRow]:
    """odb_history:situation_history_json's reply as rows (Bridge.history)."""
    calls: list[str] = reply["calls"]
    sets = [[calls[i] for i in indexes] for indexes in reply["sets"]]
    flat = reply["rows"]
    return [HistoryRow(begin=flat[i], end=flat[i + 1], call=calls[flat[i + 2]], part=flat[i + 3],
                       available=sets[flat[i + 4]] if flat[i + 4] >= 0 else None, mode=flat[i + 5])
            for i in range(0, len(flat), ROW_WIDTH)]
