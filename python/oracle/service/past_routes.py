"""The HTTP routes of the questions about the past and the state summary (docs/beyond.md).

Each reads the NEEM through the engine's one bridge, on the engine thread; nothing is fitted
and nothing written, so an answer costs its few Prolog queries (tens of milliseconds).
"""

from __future__ import annotations

from typing import Any

from fastapi import APIRouter, Query, Request

router = APIRouter(tags=["answers"])


def _seconds(at: str | None) -> float | None:
    from oracle.service.session import moment_of
    from oracle.timeline import Instant

    if at is None:
        return None
    try:
        value: float | str = float(at)
    except ValueError:
        value = at
    return Instant.of(moment_of(value, "at")).seconds


def _ask(engine: Any, neem: str, question: str, at: str | None) -> dict[str, Any]:
    from oracle.past.ask import ask
    from oracle.timeline import has_clock

    bridge = engine.bridge(engine.resolve(neem))
    clocked = has_clock(engine.store.neem(bridge.neem_id).meta)
    answer: dict[str, Any] = ask(bridge, engine.ontology, question, _seconds(at), clocked).to_json()
    return answer


def _summary(engine: Any, neem: str, at: str | None) -> dict[str, Any]:
    from oracle.past.summary import state_summary
    from oracle.timeline import has_clock

    bridge = engine.bridge(engine.resolve(neem))
    return state_summary(bridge, _seconds(at), has_clock(engine.store.neem(bridge.neem_id).meta))


@router.get("/api/neems/{neem}/ask")
async def ask_route(neem: str, request: Request,
                    q: str = Query(min_length=1, max_length=500, description="a question, e.g. when did I last open the fridge?"),
                    at: str | None = Query(None, description="as of this time (default: the NEEM's latest event)")) -> dict[str, Any]:
    """A question about the past, answered in its language (English or German) with the evidence."""
    ctx = request.app.state.ctx
    return await ctx.thread.run(_ask, ctx.engine, neem, q, at)


@router.get("/api/neems/{neem}/summary")
async def summary_route(neem: str, request: Request,
                        at: str | None = Query(None, description="as of this time (default: the NEEM's latest event)")) -> dict[str, Any]:
    """The NEEM's state summary: recent actions, the latest and what usually follows it, the predicted chain."""
    ctx = request.app.state.ctx
    return await ctx.thread.run(_summary, ctx.engine, neem, at)
