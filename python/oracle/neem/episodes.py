"""The recording sessions of the NEEM a ``NeemLogger`` writes (oracle.neem.writer): one soma:Episode
each, the setting for a top-level action whose constituents the session's actions are, opened and
closed as neem-interface's ``mem_episode_start`` and ``mem_episode_stop`` write them."""

from __future__ import annotations

from dataclasses import dataclass
from datetime import datetime, timezone

from oracle.neem import terms as T
from oracle.neem.individuals import Individuals
from oracle.neem.records import TripleBuffer
from oracle.store import RDF_TYPE
from oracle.store.model import INFINITY, USER_GRAPH
from oracle.timeline import Instant


@dataclass(frozen=True)
class _Episode:
    """The recording session being written: its soma:Episode, the top-level action it is the
    setting for (whose constituents the logged actions are), that action's interval and the
    latest end logged in it (the interval's end, written when the session closes)."""

    key: str
    iri: str
    top: str
    interval: str
    end: float
    #: The session's actions, written as the top-level action's constituents when it closes.
    members: tuple[str, ...] = ()


class Episodes:
    """The open recording session of one logger, and the triples that open and close one."""

    def __init__(self, individuals: Individuals) -> None:
        self.individuals = individuals
        #: The open recording session (None before the first action of this logger's run).
        self.current: _Episode | None = None

    def constituent(self, action: str, start: Instant, stop: Instant, session: str | None, out: TripleBuffer,
                    begin: Instant | None = None) -> None:  # fmt: skip
        """``action`` (which starts at ``begin``, default ``start``) a constituent of the session
        of ``start``; a session of another key (a new day, another name) first closes the open
        one and opens its own."""
        if session is not None:
            key = session
        elif not self.individuals.clocked:
            key = "sequence"
        else:
            key = datetime.fromtimestamp(start.seconds, timezone.utc).date().isoformat()
        episode = self.current
        if episode is not None and episode.key != key:
            self.end(out)
            episode = None
        if episode is None:
            episode = self._open(key, start if begin is None else begin, out)
        self.current = _Episode(episode.key, episode.iri, episode.top, episode.interval, max(episode.end, stop.seconds),
                                (*episode.members, action))  # fmt: skip

    def _open(self, key: str, start: Instant, out: TripleBuffer) -> _Episode:
        """neem-interface's ``mem_episode_start``: an episode that is the setting for a top-level
        action executing a physical task, performed by the robot, which plays an agent role."""
        made = self.individuals
        episode, top, task, role = (made.named(c) for c in (T.EPISODE, T.PHYSICAL_ACTION, T.PHYSICAL_TASK, T.AGENT_ROLE))
        interval = made.event("TimeInterval")
        robot = made.agent("robot", out)
        for iri, cls_iri in ((episode, T.EPISODE), (top, T.PHYSICAL_ACTION), (task, T.PHYSICAL_TASK), (role, T.AGENT_ROLE)):
            out.add(iri, RDF_TYPE, cls_iri)
            out.add(iri, RDF_TYPE, T.NAMED_INDIVIDUAL)
        out.add(interval, RDF_TYPE, T.TIME_INTERVAL)  # typed as the actions' intervals are
        out.add(episode, T.INCLUDES_ACTION, top)
        out.add(top, T.EXECUTES, task)
        out.add(top, T.PERFORMED_BY, robot)
        out.add(task, T.IS_TASK_OF, role)
        out.add(role, T.CLASSIFIES, robot)
        out.add(top, T.HAS_INTERVAL, interval)
        out.add(interval, T.BEGIN, start.seconds)
        return _Episode(key, episode, top, interval, start.seconds)

    def end(self, out: TripleBuffer) -> None:
        """neem-interface's ``mem_episode_stop``: the session's actions become constituents of its
        top-level action, whose interval ends with the latest end logged in the session.

        Written together when the session closes, not one by one: a triple whose subject is an
        earlier individual (the top-level action) would make every later history read whole
        (oracle.historycache keeps a history only while every added subject is new)."""
        episode = self.current
        if episode is not None:
            out.extend([(episode.top, T.HAS_CONSTITUENT, member, USER_GRAPH, 0.0, INFINITY) for member in episode.members])
            out.add(episode.interval, T.END, episode.end)
            self.current = None
