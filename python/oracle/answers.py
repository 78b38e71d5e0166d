"""English sentences for the robot's answers (thesis 4.6), built from the reason terms of
prolog/answers.pl as the bridge hands them over (JSON dicts)."""

from __future__ import annotations

from typing import Any

from oracle.timeline import clock


def _when(seconds: float | None, clocked: bool = True) -> str:
    """A time as the answers say it; in a NEEM without a clock (oracle.timeline), a position."""
    if seconds is None:
        return "lately"
    if not clocked:
        return f"position {seconds:g}"
    return clock(seconds).strftime("%Y-%m-%d %H:%M")


def _ranked(items: list[dict[str, Any]]) -> str:
    """Tasks with their ranks; the scores stay in the JSON (lower ranks higher, and what a score
    means depends on the predictor that wrote it: docs/algorithm.md)."""
    return ", ".join(f"{i['task']} ({ordinal(int(i['rank']))})" for i in items)


def ordinal(n: int) -> str:
    """1st, 2nd, 3rd, 11th, 22nd."""
    suffix = "th" if 10 <= n % 100 <= 20 else {1: "st", 2: "nd", 3: "rd"}.get(n % 10, "th")
    return f"{n}{suffix}"


def reason_sentence(reason: dict[str, Any], clocked: bool = True) -> str:
    kind = reason["reason"]
    task = reason["task"]
    at = _when(reason.get("time"), clocked)
    if kind == "done":
        return f"I did {task}: it started at {at}."
    if kind == "not_available":
        if reason.get("why") == "object_not_perceived":
            return f"{task} was not available at {at}: I had not perceived any {reason['object']}."
        return f"{task} was not available at {at}: a precondition did not hold (the NEEM does not say which)."
    if kind == "ranked_lower":
        return f"At {at} I ranked {task} {ordinal(int(reason['rank']))}; ranked higher: {_ranked(reason['higher'])}."
    if kind == "ranked_first":
        return f"At {at} I ranked {task} first: it is what I suggested."
    if kind == "user_chose":
        return f"You chose {task} instead, at {at}."
    if kind == "done_later":
        return f"I did {task} later, at {at}."
    if kind == "done_earlier":
        return f"I had already done {task} earlier, at {at}."
    return f"{kind}: {reason}"


def why_not_sentence(answer: dict[str, Any], clocked: bool = True) -> str:
    reasons = answer.get("reasons") or []
    if not reasons:
        return f"I cannot tell why {answer['task']} was not done: the NEEM holds no decision about it."
    if any(r["reason"] == "ranked_first" for r in reasons):
        # not "already done earlier": that reads as why it was not suggested, and it was
        return " ".join(_when_done(r, clocked) if r["reason"] in ("done_earlier", "done_later") else
                        reason_sentence(r, clocked) for r in reasons)
    return " ".join(reason_sentence(r, clocked) for r in reasons)


def _when_done(reason: dict[str, Any], clocked: bool) -> str:
    """When a task suggested first was last (or next) done, as a plain fact."""
    at = _when(reason.get("time"), clocked)
    if reason["reason"] == "done_later":
        return f"It was done later, at {at}."
    return f"It was last done at {at}."


#: How many alternatives a spoken answer names; the JSON answer keeps them all.
SPOKEN_ALTERNATIVES = 4


def what_next_sentence(answer: dict[str, Any]) -> str:
    chain = answer.get("chain") or []
    if not chain:
        return "I have not imagined any preference yet, so I cannot say what comes next."
    head = f"Next I expect {chain[0]['task']}"
    rest = chain[1:SPOKEN_ALTERNATIVES]
    more = len(chain) - 1 - len(rest)
    if not rest:
        return head + "."
    tail = f" and {more} less likely" if more > 0 else ""
    return f"{head}; otherwise {_ranked(rest)}{tail}."


def something_else_sentence(answer: dict[str, Any]) -> str:
    alternatives = answer.get("alternatives") or []
    current = answer.get("current") or "the current task"
    if not alternatives:
        return f"I know of no alternative to {current}."
    best = alternatives[0]
    return f"Instead of {current} I would do {best['task']} ({ordinal(int(best['rank']))} of my suggestions)."


def support_sentence(entry: dict[str, Any]) -> str:
    """Why a ranked task stands where it does, short enough for a touch target: the service's
    ranking entry (``support`` and, from the routine predictor, ``context_order``, ``context``
    and the times of the supporting past ``situations``, latest last; ``focus``: the objects in
    hand it uses; ``new``: newly offered; ``resumed``: after a break, it once followed the last
    action before it; ``done``: whether the user ever did it). The sentence
    names the last two steps of the context; the entry holds it all."""
    n = int(entry.get("support") or 0)
    order = entry.get("context_order")
    times = entry.get("situations") or []
    last = f", last {clock(times[-1]).strftime('%a %H:%M')}" if times else ""
    if order is None:  # the thesis oracle: |H(s_o)|, the similar past situations
        return f"like {n} past situation{'s' if n != 1 else ''}" if n else "new to me"
    if order > 0:
        context = ["a break" if c == "idle" else c for c in entry.get("context") or []]
        after = ("\u2026 " if len(context) > SHOWN_CONTEXT else "") + " \u2192 ".join(context[-SHOWN_CONTEXT:])
        return f"after {after}: {n}\u00d7{last}"
    notes = lifts(entry.get("focus") or [], bool(entry.get("new")), bool(entry.get("resumed")), entry.get("since"))
    if order == 0 or entry.get("done"):
        return (f"done {n}\u00d7, not at this point{last}" if n else "done before, not at this point") + \
            "".join(f"; {note}" for note in notes)
    return f"never done: {'; '.join(notes)}" if notes else "never done: like similar tasks"


def lifts(held: list[str], new: bool, resumed: bool = False, since: float | None = None) -> list[str]:
    """The words naming what lifts a task: the objects in hand it uses, that it is newly
    possible, that it goes on from before a break, when it was last done where the clock weighed
    the ranking (said only where no counted context backs it: by the tablet's reason and by
    ``rank``'s text)."""
    return ([f"uses {', '.join(held)} in hand"] if held else []) + (["newly possible"] if new else []) + (
        ["goes on from before the break"] if resumed else []) + ([f"last done {ago(since)}"] if since is not None else [])


def ago(seconds: float) -> str:
    """A time span as the tablet says it: ``40 s ago``, ``5 min ago``, ``3 h ago``, ``2 days ago``."""
    if seconds < 90:
        return f"{max(0, round(seconds))} s ago"
    if seconds < 90 * 60:
        return f"{round(seconds / 60)} min ago"
    if seconds < 36 * 3600:
        return f"{round(seconds / 3600)} h ago"
    return f"{round(seconds / 86400)} days ago"


#: Context steps a support sentence names (the latest ones).
SHOWN_CONTEXT = 2
