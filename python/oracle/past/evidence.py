"""The evidence of the NEEM for a question about the past: one request to prolog/odb/past.pl
(odb_past:past_answer_json/1), values handed over as terms, the reply a JSON dict."""

from __future__ import annotations

import json
from collections.abc import Sequence
from datetime import timedelta
from typing import TYPE_CHECKING, Any

from oracle.errors import PrologError
from oracle.paths import prolog_dir
from oracle.timeline import PARTS_OF_DAY, clock, first_hour, seconds_of

if TYPE_CHECKING:
    from oracle.bridge import Bridge
    from oracle.chains import TaskCall

#: The Prolog module of the answers, loaded into the bridge's engine on first use.
PAST_MODULE = prolog_dir() / "odb" / "past.pl"


def ensure_loaded(bridge: Bridge) -> None:
    """Load odb_past into Prolog unless it is (one query when it is)."""
    from pyswip import Atom

    if not bridge.ask("current_predicate(odb_past:past_answer_json/1)", []):
        bridge.ask("neem_store:py_request(R), R = [F], use_module(user:F)", [Atom(str(PAST_MODULE))])


def request(bridge: Bridge, words: Sequence[Any]) -> dict[str, Any]:
    """odb_past:past_answer_json/1 on ``words`` (strings become atoms, None the atom none)."""
    ensure_loaded(bridge)
    rows = bridge.ask("odb_past:past_answer_json(J)", [_term(w) for w in words])
    if not rows:
        raise PrologError(f"Prolog found no answer to {words[0]}")
    text = rows[0]["J"]
    reply: dict[str, Any] = json.loads(text.decode("utf-8") if isinstance(text, bytes) else text)
    return reply


def call_words(call: TaskCall) -> list[Any]:
    """A call as the request's name and argument list."""
    return [call.task, list(call.args)]


def _term(value: Any) -> Any:
    from pyswip import Atom

    if value is None:
        return Atom("none")
    if isinstance(value, str):
        return Atom(value)
    if isinstance(value, list):
        return [_term(v) for v in value]
    return float(value) if isinstance(value, (int, float)) and not isinstance(value, bool) else value


def now_of(bridge: Bridge) -> float | None:
    """The NEEM's "now": the latest begin of any of its events (None for an empty NEEM)."""
    time = request(bridge, ["now"])["time"]
    return None if time is None else float(time)


def window(period: str, now: float) -> tuple[float, float]:
    """[from, to] of a period (``today``, ``week`` from Monday, or a part of the day, today)
    ending at ``now`` (unix seconds, the one clock of oracle.timeline)."""
    midnight = clock(now).replace(hour=0, minute=0, second=0, microsecond=0)
    if period == "today":
        return seconds_of(midnight), now
    if period == "week":
        return seconds_of(midnight - timedelta(days=midnight.weekday())), now
    starts = [start for start, name in PARTS_OF_DAY]
    begin = first_hour(period)
    end = min((s for s in starts if s > begin), default=24)
    return seconds_of(midnight + timedelta(hours=begin)), min(now, seconds_of(midnight + timedelta(hours=end)))
