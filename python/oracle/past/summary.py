"""The state summary of a NEEM: what a language model or another module may take as ground
truth about the user's recent past (RACCOON's state summaries), as one JSON-ready dict. No
language model runs here; every field comes from the NEEM through Prolog."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from oracle.past.ask import usual_after
from oracle.past.evidence import request, window
from oracle.past.kept import KeptPast
from oracle.timeline import format_clock, part_of_day_at

if TYPE_CHECKING:
    from oracle.bridge import Bridge

#: How many of the latest actions the summary lists.
RECENT = 10
#: The format of the summary (a reader checks it before trusting the fields).
FORMAT = 1


def state_summary(bridge: Bridge, at: float | None = None, clocked: bool = True,
                  kept: KeptPast | None = None) -> dict[str, Any]:
    """The summary as of ``at`` (default: the NEEM's latest event): the latest actions (today's,
    or the last ``RECENT`` of the NEEM when today has none), the latest action and what usually
    follows it, the routine in progress, the robot's latest ranking by then. ``kept``: what
    earlier answers read of the NEEM (oracle.past.kept; default: nothing)."""
    kept = KeptPast() if kept is None else kept
    now = at if at is not None else kept.now(bridge)
    summary: dict[str, Any] = {"format": FORMAT, "neem": bridge.neem_id, "now": now, "clock": None,
                               "part_of_day": None, "recent": [], "latest": None, "usual_next": [],
                               "routine": None, "predicted": []}
    if now is None:
        return summary
    if clocked:
        summary["clock"] = format_clock(now)
        summary["part_of_day"] = part_of_day_at(now)
        start, _ = window("today", now)
        today = request(bridge, ["done", start, now])["actions"]
    else:
        today = []
    recent = today or request(bridge, ["before", now, RECENT])["actions"]
    summary["recent"] = recent[-RECENT:]
    summary["today"] = len(today)
    if recent:
        latest = recent[-1]
        summary["latest"] = latest
        summary["usual_next"] = usual_after(latest["task"], kept.done(bridge))["next"]
    summary["routine"] = _routine(bridge, now, kept)
    summary["predicted"] = request(bridge, ["predicted", now])["predicted"]
    return summary


def _routine(bridge: Bridge, now: float, kept: KeptPast) -> dict[str, Any] | None:
    """The routine in progress at ``now`` (oracle.past.mine), with what remains of it."""
    from oracle.past.mine import neem_routines

    current = neem_routines(bridge, now, kept=kept).current
    return current.to_json() if current is not None else None
