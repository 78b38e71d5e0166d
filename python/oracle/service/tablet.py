"""What the tablet page shows, in the person's words: the view of a NEEM's latest ranking
(``GET .../tablet``) and the answers as one or two plain sentences (the ``said`` of why-not,
what-next and something-else), built from the JSON the robot's API answers, so the page and
the robot always see the same ranking; and the person's choice, kept in the NEEM."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any

from oracle.neem.decisions import Decision
from oracle.words import Words

if TYPE_CHECKING:
    from oracle.service.session import NeemSession


def tablet_view(neem: str, user: str | None, latest: Mapping[str, Any] | None, words: Words) -> dict[str, Any]:
    """The page's view of the latest ranking: each task's call (kept for the robot's syntax),
    rank, plain words, one-sentence reason and who usually does it; the workflow's steps, each
    with who does it unless the person changes it (the usual mode, else the robot); the routine
    in progress (None: none) with the steps that remain; the time on the person's clock."""
    ranking = (latest or {}).get("ranking") or []
    chain = (latest or {}).get("chain") or []
    chain_modes = list((latest or {}).get("chain_modes") or [])
    chain_modes += [None] * (len(chain) - len(chain_modes))
    at = (latest or {}).get("at")
    part = words.part_of_day((latest or {}).get("time_of_day"))
    clock = ", ".join(x for x in (part, words.clock(at)) if x) if ranking else ""
    return {
        "neem": neem, "user": user, "person": words.person(user), "lang": words.lang, "at": at, "clock": clock,
        "tasks": [{"task": t["task"], "rank": t["rank"], "said": words.said(t["task"]), "reason": words.reason(t),
                   "mode": t.get("mode"), "mode_said": words.mode(t.get("mode"), (t.get("mode_support") or {}).get("counts") or {},
                                                                str((t.get("mode_support") or {}).get("context") or "call"))}
                  for t in ranking],
        "workflow": [_step(c, m, words) for c, m in zip(chain, chain_modes)] if len(chain) >= 2 else [],
        "routine": _routine_view((latest or {}).get("routine"), words),
    }


def _step(call: str, mode: str | None, words: Words) -> dict[str, Any]:
    """A workflow step as the sheet shows it: who does it unless the person changes it."""
    who = mode or DEFAULT_MODE
    return {"task": call, "said": words.said(call), "mode": who, "who": words.who(who)}


#: Who does a chosen step no one's past says anything about: the robot, which was asked to.
DEFAULT_MODE = "robot"


def _routine_view(routine: Mapping[str, Any] | None, words: Words) -> dict[str, Any] | None:
    """The routine in progress as the page offers it: its label and the steps that remain, each
    with who does it unless the person changes it."""
    if not routine or not routine.get("remaining"):
        return None
    remaining = list(routine["remaining"])
    modes = list(routine.get("remaining_modes") or [])
    modes += [None] * (len(remaining) - len(modes))
    return {"key": routine["key"], "name": routine["name"], "steps_left": len(remaining),
            "label": words.routine(str(routine["name"]), len(remaining)),
            "steps": [_step(c, m, words) for c, m in zip(remaining, modes)]}


def why_not_said(task: str, latest: Mapping[str, Any] | None, answer: Mapping[str, Any], decision: Decision | None,
                 words: Words) -> str:
    """Why ``task`` is where it is, in one or two sentences that fit any task: its place in the
    latest ranking and its reason (the top one included), or that the robot cannot do it now;
    then, where the user chose something else since, what the user chose."""
    t = words.text
    ranking = (latest or {}).get("ranking") or []
    placed = next((r for r in ranking if r["task"] == task), None)
    if placed is None:
        unseen = next((r.get("object") for r in answer.get("reasons") or []
                       if r.get("reason") == "not_available" and r.get("why") == "object_not_perceived"), None)
        first = t["not_seen"].format(object=words.obj(unseen)) if unseen else t["not_now"]
    elif placed["rank"] == 1:
        first = f"{t['top']} {words.reason(placed)}"
    else:
        first = f"{t['placed'].format(rank=placed['rank'], n=len(ranking))} {words.reason(placed)}"
    if decision is not None and decision.task != task and (placed is None or placed["rank"] != 1):
        return f"{first} {t['you_chose'].format(at=words.clock(decision.at), task=words.said(decision.task))}"
    return first


def what_next_said(answer: Mapping[str, Any], decision: Decision | None, last_action: Mapping[str, Any] | None,
                   words: Words) -> str:
    """What the robot expects next, and whether the user's latest choice is still to be done
    (a choice made after the robot's latest action) or what the robot did last."""
    t = words.text
    chain = answer.get("chain") or []
    if not chain:
        return t["no_ranking"]
    said = t["next"].format(task=words.said(chain[0]["task"]))
    last_at = float(last_action["begin"]) if last_action and last_action.get("begin") is not None else None
    if decision is not None and (last_at is None or decision.at > last_at):
        return f"{said} {t['chosen_pending'].format(task=words.said(decision.task))}"
    if last_action and last_action.get("call"):
        return f"{said} {t['robot_did_at'].format(at=words.clock(last_at), task=words.said(last_action['call']))}"
    return said


def something_else_said(answer: Mapping[str, Any], words: Words) -> str:
    t = words.text
    alternatives = answer.get("alternatives") or []
    if not alternatives:
        return t["no_other"]
    current = answer.get("current")
    other = words.said(alternatives[0]["task"])
    return t["instead_of"].format(task=words.said(current), other=other) if current else t["next"].format(task=other)


def record_choice(session: NeemSession, calls: list[Any], at: Any, modes: Sequence[str] | None = None) -> dict[str, Any]:
    """Write the user's decision into the NEEM (one transaction), with who does each step
    (``modes``; None: who usually does each, else the robot); the choice as answered."""
    from oracle.errors import LoggingError
    from oracle.neem.decisions import record_decision
    from oracle.service.session import moment_of
    from oracle.timeline import Instant

    when = Instant.of(moment_of(at, "at")).seconds
    if modes is not None and len(modes) != len(calls):
        raise LoggingError(f"modes: {len(modes)} given for {len(calls)} step{'s' if len(calls) != 1 else ''};"
                           " give one per step (robot, user or together)")
    if modes is None:
        modes = [session.usual_mode(call, when) or DEFAULT_MODE for call in calls]
    else:
        modes = list(modes)
    made = record_decision(session.logger, calls, when, modes)
    session.logger.flush()
    return _choice(made)


def _choice(made: Decision) -> dict[str, Any]:
    return {"task": made.task, "workflow": made.workflow, "modes": list(made.modes) or None, "at": made.at,
            "decision": made.iri}


def recorded_choice(session: NeemSession) -> dict[str, Any] | None:
    """The user's latest decision as ``GET .../choice`` answers it (None: the NEEM holds none)."""
    decision_of(session)
    return session.choice


def decision_of(session: NeemSession) -> Decision | None:
    """The user's latest decision: the one this service recorded, else the NEEM's (read once
    per session, then kept as ``session.choice``; the NEEM has one writer, this service)."""
    from oracle.neem.decisions import latest_decision

    made = session.choice
    if made is None:
        logger = session.logger
        found = latest_decision(logger.store, logger.neem_id, logger.ns, logger.vocab.has_rank)
        if found is not None:
            session.choice = _choice(found)
        return found
    if made.get("decision") is None:
        return None
    return Decision(str(made["decision"]), float(made["at"]), tuple(made.get("workflow") or [made["task"]]),
                    tuple(made.get("modes") or ()))
