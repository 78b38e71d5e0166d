"""The user's own decisions in the NEEM: a confirmed choice on the tablet, written as KnowRob
models a mental act and read back after a restart (docs/service.md, "The user's choice").

A decision is a soma:MentalAction performed by the user (the NEEM's dul:NaturalPerson, never the
robot) executing a soma:MentalTask, with its time interval, and dul:isDescribedBy a soma:Order
whose soma:OrderedElements soma:encapsulate the chosen plans, step 1 first (one element for a
task, one per step for a workflow): the layout of the robot's preference order, so the same
plans (one per call, shared with imaginings and preferences) name what was chosen. What the
robot then executes is logged apart, as its action: the two are never confused.

Who does each chosen step (thesis 6.3: "I bring the cup, you pour") is kept on its element as
``odb:stepMode`` (robot, user or together; chains.MODES), as the routines keep their usual hour.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from oracle.chains import MODES, TaskCall, modes_error
from oracle.errors import LoggingError
from oracle.neem import terms as T
from oracle.neem.records import checked_instant, TripleBuffer
from oracle.neem.writer import NeemLogger
from oracle.namespaces import DUL_IRI, SOMA_IRI
from oracle.store import RDF_TYPE, Store
from oracle.store.model import decode_value

MENTAL_TASK = SOMA_IRI + "MentalTask"
#: The local name (in the odb namespace) of who does a chosen step.
STEP_MODE = "stepMode"
DESCRIBED_BY = DUL_IRI + "isDescribedBy"


@dataclass(frozen=True)
class Decision:
    """One decision read back: when it was made and the chosen calls, first step first."""

    iri: str
    at: float
    calls: tuple[str, ...]
    #: Who does each step (one per call; empty: a decision recorded without them).
    modes: tuple[str, ...] = ()

    @property
    def task(self) -> str:
        return self.calls[0]

    @property
    def workflow(self) -> list[str] | None:
        return list(self.calls) if len(self.calls) > 1 else None


def record_decision(logger: NeemLogger, calls: Sequence[TaskCall], at: float,
                    modes: Sequence[str] | None = None) -> Decision:
    """Buffer the user's decision for ``calls`` made at ``at`` (unix seconds) in the logger's
    transaction (the caller flushes), with who does each step (``modes``, one per call; None:
    not said). The calls and modes are checked first."""
    resolved = [logger.individuals.resolve(call) for call in calls]
    if modes is not None:
        if len(modes) != len(resolved):
            raise LoggingError(f"modes: {len(modes)} given for {len(resolved)} steps; give one per step")
        for mode in modes:
            if mode not in MODES:
                raise LoggingError(modes_error(mode))
    when = checked_instant(at)
    out = TripleBuffer()
    action = logger.individuals.mental(MENTAL_TASK, when, out, who="user")
    order = logger.individuals.event("Order")
    out.add(action, DESCRIBED_BY, order)
    out.add(order, RDF_TYPE, T.ORDER)
    for step, call in enumerate(resolved, start=1):
        element = f"{order}_{step}"
        out.add(element, RDF_TYPE, T.ORDERED_ELEMENT)
        out.add(order, T.ORDERS, element)
        out.add(element, T.ENCAPSULATES, logger.individuals.plan(call, out, when.seconds))
        out.add(element, logger.vocab.has_rank, step)
        if modes is not None:
            out.add(element, logger.ns + STEP_MODE, modes[step - 1])
    logger._write(out)
    return Decision(action, when.seconds, tuple(str(c) for c in resolved), tuple(modes or ()))


def latest_decision(store: Store, neem: str, ns: str, has_rank: str) -> Decision | None:
    """The user's latest decision in the NEEM (None when there is none); ``ns`` is the odb
    namespace the plans are named in, ``has_rank`` the ontology's rank property."""
    best: Decision | None = None
    for doc in store.find(neem, p=DESCRIBED_BY, exact=True):
        action, order = str(doc["s"]), str(doc["o"])
        if _one(store, neem, action, RDF_TYPE, T.MENTAL_ACTION) is None:
            continue
        interval = _one(store, neem, action, T.HAS_INTERVAL)
        begin = _one(store, neem, str(interval), T.BEGIN) if interval is not None else None
        if begin is None or (best is not None and float(begin) < best.at):
            continue
        steps: list[tuple[int, str, str | None]] = []
        for element in store.find(neem, s=order, p=T.ORDERS, exact=True):
            rank = _one(store, neem, str(element["o"]), has_rank)
            plan = _one(store, neem, str(element["o"]), T.ENCAPSULATES)
            mode = _one(store, neem, str(element["o"]), ns + STEP_MODE)
            if rank is not None and plan is not None:
                steps.append((int(rank), _call_of_plan(str(plan), ns), None if mode is None else str(mode)))
        if steps:
            steps.sort(key=lambda s: s[0])
            modes = tuple(str(m) for _, _, m in steps) if all(m is not None for _, _, m in steps) else ()
            best = Decision(action, float(begin), tuple(call for _, call, _ in steps), modes)
    return best


def _one(store: Store, neem: str, s: str, p: str, o: str | None = None) -> Any:
    """The object of the first asserted (s, p, o) triple, or None."""
    doc = next(store.find(neem, s=s, p=p, o=o, limit=1, exact=True), None)
    return None if doc is None else decode_value(doc["o"])


def _call_of_plan(plan: str, ns: str) -> str:
    """The call a plan IRI stands for: ``Plan_pour__beer_bottle__drinking_glass`` is
    ``pour(beer_bottle, drinking_glass)`` (odb names hold no double underscore)."""
    key = plan[len(ns) + len("Plan_"):] if plan.startswith(ns + "Plan_") else plan.rsplit("Plan_", 1)[-1]
    task, *args = key.split("__")
    return f"{task}({', '.join(args)})" if args else task
