"""neem_interface_python's ``NEEMInterface`` over this project: the same method names, driving
neem-interface.pl's predicates (``mem_episode_start/9``, ``add_subaction_with_task/3``, ...) in
process (``InProcess``: the Prolog bridge over a store) or reading a NEEM through ``serve``'s
JSON Prolog endpoint (``OverHttp``, which stands in for rosprolog; it answers read-only queries,
so the logging methods need ``InProcess``). A robot's Python code moves over by changing its
import and how it builds the interface. docs/prolog.md, "neem-interface".
"""

from __future__ import annotations

import re
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, Protocol

from oracle.errors import NeemOracleError

if TYPE_CHECKING:
    from oracle.bridge import Bridge


class NEEMError(NeemOracleError):
    """A query of the interface failed or found nothing (neem_interface_python's NEEMError)."""


class Prolog(Protocol):
    """Where the interface's queries go: every solution of a query text, as dicts."""

    def all_solutions(self, query: str) -> list[dict[str, Any]]: ...


class InProcess:
    """Queries through the Prolog bridge of this process, writes included."""

    def __init__(self, bridge: Bridge) -> None:
        self.bridge = bridge

    def all_solutions(self, query: str) -> list[dict[str, Any]]:
        return self.bridge.query(query)


class OverHttp:
    """Queries through ``serve``'s ``POST /api/prolog`` (read-only), paged until the last one.
    ``post`` (path, JSON body -> JSON answer) replaces the HTTP client, e.g. an in-process one."""

    def __init__(self, url: str, neem: str | None = None, token: str | None = None, page: int = 1000,
                 post: Callable[[str, dict[str, Any]], Any] | None = None) -> None:  # fmt: skip
        if post is None:
            from oracle.service.client import Client

            post = Client(url, token).post
        self.post, self.neem, self.page = post, neem, page

    def all_solutions(self, query: str) -> list[dict[str, Any]]:
        from oracle.service.client import ServiceError

        found: list[dict[str, Any]] = []
        while True:
            try:
                answer = self.post("/api/prolog", {"query": query, "neem": self.neem, "offset": len(found), "limit": self.page})
            except ServiceError as error:
                raise NEEMError(f"{query}: {error}") from None
            if "error" in answer:
                raise NEEMError(f"{query}: {answer['error']}")
            found.extend(answer["solutions"])
            if not answer.get("more"):
                return found


@dataclass(frozen=True)
class TfPoint:
    """One recorded pose for assert_tf_trajectory: ``frame`` (an object IRI) in ``reference_frame``."""

    frame: str
    reference_frame: str
    position: tuple[float, float, float]
    rotation: tuple[float, float, float, float]
    timestamp: float


_PREFIXED = re.compile(r"^[a-z][A-Za-z0-9_]*:'(?:[^'\\]|\\.)*'$")


def atom(text: str) -> str:
    """A Prolog atom for ``text``: a prefixed name such as ``soma:'Patient'`` as written, any
    other text quoted (neem_interface_python's ``atom``)."""
    if _PREFIXED.match(text):
        return text
    return "'" + text.replace("\\", "\\\\").replace("'", "\\'") + "'"


def _number(value: float) -> str:
    return repr(float(value))


class NEEMInterface:
    """Logging and reading NEEMs with neem-interface.pl's predicates (code-iai/neem-interface,
    consulted unchanged from ``neem_interface_pl`` when given)."""

    def __init__(self, prolog: Prolog, neem_interface_pl: str | Path | None = None) -> None:
        self.prolog = prolog
        if neem_interface_pl is not None:
            self._once(f"consult({atom(str(neem_interface_pl))})")

    def _all(self, query: str) -> list[dict[str, Any]]:
        return self.prolog.all_solutions(query)

    def _once(self, query: str) -> dict[str, Any]:
        found = self._all(f"once(({query}))")
        if not found:
            raise NEEMError(f"no solution: {query}")
        return found[0]

    # -- creation ---------------------------------------------------------------------------
    def start_episode(self, task_type: str, env_owl: str, env_owl_ind_name: str, env_urdf: str, env_urdf_prefix: str,
                      agent_owl: str, agent_owl_ind_name: str, agent_urdf: str, start_time: float | None = None) -> str:
        """mem_episode_start/9; the top-level action's task also typed ``task_type``. Returns the
        top-level action."""
        begin = time.time() if start_time is None else start_time
        args = ", ".join(atom(a) for a in (env_owl, env_owl_ind_name, env_urdf, env_urdf_prefix, agent_owl,
                                            agent_owl_ind_name, agent_urdf))  # fmt: skip
        action = str(self._once(f"mem_episode_start(Action, {args}, {_number(begin)})")["Action"])
        self._once(f"kb_call(executes_task({atom(action)}, Task)), kb_project(has_type(Task, {atom(task_type)}))")
        return action

    def stop_episode(self, neem_path: str, end_time: float | None = None) -> None:
        """mem_episode_stop/2: the top-level action ends, the NEEM is memorized below ``neem_path``."""
        end = time.time() if end_time is None else end_time
        self._once(f"mem_episode_stop({atom(neem_path)}, {_number(end)})")

    def add_subaction_with_task(self, parent_action: str, sub_action_type: str = "dul:'Action'",
                                task_type: str = "dul:'Task'", start_time: float | None = None,
                                end_time: float | None = None) -> str:  # fmt: skip
        """add_subaction_with_task/3, the sub-action also typed ``sub_action_type`` and given the
        interval [start_time, end_time] when both are given. Returns the sub-action."""
        sub = str(self._once(f"add_subaction_with_task({atom(parent_action)}, Sub, {atom(task_type)})")["Sub"])
        self._once(f"kb_project(has_type({atom(sub)}, {atom(sub_action_type)}))")
        if start_time is not None and end_time is not None:
            self._once(f"kb_project(event_interval({atom(sub)}, {_number(start_time)}, {_number(end_time)}))")
        return sub

    def add_participant_with_role(self, action: str, participant: str, role_type: str = "dul:'Role'") -> None:
        """add_participant_with_role/3 (the action needs its interval: the role holds during it)."""
        self._once(f"add_participant_with_role({atom(action)}, {atom(participant)}, {atom(role_type)})")

    def set_succeeded(self, action: str) -> None:
        """mem_event_set_succeeded/1."""
        self._once(f"mem_event_set_succeeded({atom(action)})")

    def assert_tf_trajectory(self, points: Sequence[TfPoint]) -> None:
        """mem_tf_set/5 for each point."""
        for p in points:
            pos = ", ".join(_number(v) for v in p.position)
            rot = ", ".join(_number(v) for v in p.rotation)
            self._once(f"mem_tf_set({atom(p.frame)}, {atom(p.reference_frame)}, [{pos}], [{rot}], {_number(p.timestamp)})")

    # -- reading ----------------------------------------------------------------------------
    def load_neem(self, neem_path: str) -> None:
        """mem_clear_memory, remember/1 (in process)."""
        self._once(f"mem_clear_memory, remember({atom(neem_path)})")

    def get_all_actions(self, action_type: str | None = None) -> list[str]:
        """Every action (of ``action_type``), each once."""
        query = "kb_call(is_action(Action))"
        if action_type is not None:
            query = f"kb_call((is_action(Action), instance_of(Action, {atom(action_type)})))"
        found = sorted({str(row["Action"]) for row in self._all(query)})
        if not found:
            raise NEEMError("Failed to find any actions")
        return found

    def get_tasks_for_action(self, action: str) -> list[str]:
        """The tasks the action executes."""
        return sorted({str(row["Task"]) for row in self._all(f"kb_call(executes_task({atom(action)}, Task))")})

    def get_interval_for_event(self, event: str) -> tuple[float, float] | None:
        """event_interval/3, or None when the event has no (closed) interval."""
        found = self._all(f"once(kb_call(event_interval({atom(event)}, Begin, End)))")
        return (float(found[0]["Begin"]), float(found[0]["End"])) if found else None

    def get_tf_trajectory(self, obj: str, start_timestamp: float, end_timestamp: float) -> list[tuple[float, Any]]:
        """tf_mng_trajectory/4: ``(stamp, [ref, position, rotation])`` in time order."""
        query = (f"tf_mng_trajectory({atom(obj)}, {_number(start_timestamp)}, {_number(end_timestamp)}, T),"
                 " findall([S, P], member(S-P, T), Trajectory)")
        return [(float(stamp), pose) for stamp, pose in self._once(query)["Trajectory"]]
