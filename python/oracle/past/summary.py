"""The state summary of a NEEM: what a language model or another module may take as ground
truth about the user's recent past (RACCOON's state summaries), as one JSON-ready dict. No
language model runs here; every field comes from the NEEM through Prolog."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from oracle.chains import parse_call
from oracle.past.evidence import call_words, now_of, request, window
from oracle.timeline import format_clock, part_of_day_at

if TYPE_CHECKING:
    from oracle.bridge import Bridge

#: How many of the latest actions the summary lists.
RECENT = 10
#: The format of the summary (a reader checks it before trusting the fields).
FORMAT = 1


def state_summary(bridge: Bridge, at: float | None = None, clocked: bool = True) -> dict[str, Any]:
    """The summary as of ``at`` (default: the NEEM's latest event): the latest actions (today's,
    or the last ``RECENT`` of the NEEM when today has none), the latest action and what usually
    follows it, the robot's latest predicted chain."""
    now = at if at is not None else now_of(bridge)
    summary: dict[str, Any] = {"format": FORMAT, "neem": bridge.neem_id, "now": now, "clock": None,
                               "part_of_day": None, "recent": [], "latest": None, "usual_next": [],
                               "predicted": []}
    if now is None:
        return summary
    if clocked:
        summary["clock"] = format_clock(now)
        summary["part_of_day"] = part_of_day_at(now)
        start, _ = window("today", now)
        today = request(bridge, ["done", start, now])["actions"]
    else:
        today = []
    recent = today or request(bridge, ["done", None, now])["actions"]
    summary["recent"] = recent[-RECENT:]
    summary["today"] = len(today)
    if recent:
        latest = recent[-1]
        summary["latest"] = latest
        after = request(bridge, ["after", *call_words(parse_call(latest["task"]))])
        summary["usual_next"] = after["next"]
    summary["predicted"] = [{"task": r["task"], "rank": r["rank"], "score": r["score"]}
                            for r in bridge.what_next().get("chain", [])]
    return summary
