"""The HTTP routes of the questions about the past, the state summary and the routines (docs/beyond.md).

Each reads the NEEM through the engine's one bridge, on the engine thread; nothing is fitted
and nothing written, so an answer costs its few Prolog queries (tens of milliseconds). What
they read of the NEEM's whole history (its actions, its routines) the engine keeps while the
NEEM is unchanged (oracle.past.kept).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, Literal

from fastapi import APIRouter, Query, Request

from oracle.service import schemas as S

if TYPE_CHECKING:
    from oracle.service.app import Context

router = APIRouter(tags=["answers"], responses=S.ERRORS)


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
    answer: dict[str, Any] = ask(bridge, engine.ontology, question, _seconds(at), clocked, engine.past).to_json()
    return answer


def _summary(engine: Any, neem: str, at: str | None) -> dict[str, Any]:
    from oracle.past.summary import state_summary
    from oracle.timeline import has_clock

    bridge = engine.bridge(engine.resolve(neem))
    return state_summary(bridge, _seconds(at), has_clock(engine.store.neem(bridge.neem_id).meta), engine.past)


def _routines(engine: Any, neem: str, at: str | None) -> dict[str, Any]:
    from oracle.past.mine import neem_routines

    return neem_routines(engine.bridge(engine.resolve(neem)), _seconds(at), kept=engine.past).to_json()


@router.get("/api/neems/{neem}/ask", response_model=S.PastAnswer)
async def ask_route(neem: str, request: Request,
                    q: str = Query(min_length=1, max_length=500, description="a question, e.g. when did I last open the fridge?"),
                    at: str | None = Query(None, description="as of this time (default: the NEEM's latest event)")) -> dict[str, Any]:
    """A question about the past, answered in its language (English or German) with the evidence."""
    ctx: Context = request.app.state.ctx
    return await ctx.thread.run(_ask, ctx.engine, neem, q, at)


@router.get("/api/neems/{neem}/summary", response_model=S.StateSummary)
async def summary_route(neem: str, request: Request,
                        at: str | None = Query(None, description="as of this time (default: the NEEM's latest event)")) -> dict[str, Any]:
    """The NEEM's state summary: recent actions, the latest and what usually follows it, the predicted chain."""
    ctx: Context = request.app.state.ctx
    return await ctx.thread.run(_summary, ctx.engine, neem, at)


@router.get("/api/neems/{neem}/routines", response_model=S.RoutinesAnswer)
async def routines_route(neem: str, request: Request,
                         at: str | None = Query(None, description="as of this time (default: the NEEM's latest action)")) -> dict[str, Any]:
    """The user's routines mined from the NEEM (names the user gave kept) and the one in progress."""
    ctx: Context = request.app.state.ctx
    return await ctx.thread.run(_routines, ctx.engine, neem, at)


def _prepare(engine: Any, neem: str, part: str | None, at: str | None) -> dict[str, Any]:
    from oracle.past.mine import neem_preparation

    return neem_preparation(engine.bridge(engine.resolve(neem)), part, _seconds(at), engine.past)


@router.get("/api/neems/{neem}/prepare", response_model=S.PrepareAnswer)
async def prepare_route(neem: str, request: Request,
                        part: Literal["Morning", "Midday", "Evening", "Night"] | None = Query(
                            None, alias="for", description="the part of the day (default: the part after now's)"),
                        at: str | None = Query(None, description="as of this time (default: the NEEM's latest event)")) -> dict[str, Any]:
    """The objects worth preparing now for the user's routines of the coming part of the day, with reasons."""
    ctx: Context = request.app.state.ctx
    return await ctx.thread.run(_prepare, ctx.engine, neem, part, at)
