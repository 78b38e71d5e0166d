"""What a situation's answer derives from the NEEM's history alone, kept per session until the
history changes (nothing that can wait belongs on the answer's path).

- The autonomy-mode logit (oracle.past.modelogit.fit_modes) changes only when an action is
  counted: fitted once per count, not once per situation.
- The routines mined from the actions done (oracle.past.routines), the episode in progress and
  the routine it continues, likewise; only "has the user been idle since" depends on the
  situation's time.

- The workflows stored in the NEEM (the names the user gave routines: one Prolog query, and a
  switch of the one Prolog bridge to the NEEM, which with many robots is most of its cost), read
  again after an action is answered once ``STORED_S`` have passed since the last read; a
  situation reads them itself only when none were read yet. A workflow saved by another process
  meanwhile names the routine from the first action after that on.

The actions done are named by the ranker's steps: their number and the last step itself (a step is
replaced, never changed, so ``is`` tells a new one). The engine refreshes both right after an
action is answered (``warm``), off the answer's path; a situation that comes first fits them
itself, with the same result.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from oracle.past.modelogit import ModeLogit, fit_modes
from oracle.past.routines import Clustering, Done, Episode, InProgress, MiningSettings, Routine, begun_by
from oracle.past.routines import done_from_steps, episodes_of, recognise
from oracle.timeline import is_idle_gap

if TYPE_CHECKING:
    from oracle.ranking import NeemRanker


#: The stored workflows are read again after an action at most this often (seconds).
STORED_S = 10.0


def _version(ranker: NeemRanker) -> tuple[int, object]:
    steps = ranker.steps
    return len(steps), steps[-1] if steps else None


def _same(a: tuple[int, object] | None, b: tuple[int, object]) -> bool:
    return a is not None and a[0] == b[0] and a[1] is b[1]


@dataclass
class _Mined:
    """The actions done by a time, the routines mined from them, and the routine the last
    episode continues (before the idle test)."""

    done: list[Done]
    routines: list[Routine]
    latest_end: float | None
    found: InProgress | None


@dataclass
class Warm:
    """One session's kept derivations (module docstring)."""

    _modes: tuple[int, int, ModeLogit] | None = None
    _done: tuple[tuple[int, object], float | None, list[Done]] | None = None
    _mined: dict[int, _Mined] = field(default_factory=dict)
    _stored: list[dict[str, Any]] | None = None
    _stored_at: float = 0.0  # when they were read (time.monotonic)
    _clustering: Clustering | None = None  # the episodes' clustering but for the last (``_mine``)
    _cut: tuple[int, Done, list[Episode]] | None = None  # the episodes but the last (``_episodes``)

    def stored(self, read: Callable[[], list[dict[str, Any]]]) -> list[dict[str, Any]]:
        """The workflows stored in the NEEM as last read (``read``: the read, made now if none was)."""
        if self._stored is None:
            self._stored, self._stored_at = read(), time.monotonic()
        return self._stored

    def modes(self, ranker: NeemRanker) -> ModeLogit:
        """``fit_modes(ranker.modes)``, fitted once per history."""
        counts = ranker.modes
        # every action counted adds one to exactly one task's counts: their sum names the counts
        total = sum(sum(counted.values()) for key, counted in counts.counts.items() if key[0] == "t")
        if self._modes is None or self._modes[0] != id(counts) or self._modes[1] != total:
            self._modes = (id(counts), total, fit_modes(counts))
        return self._modes[2]

    def done(self, ranker: NeemRanker) -> list[Done]:
        """``done_from_steps`` of the ranker's steps (do not change the list)."""
        version = _version(ranker)
        kept = self._done
        if kept is None or not _same(kept[0], version) or kept[1] != ranker.last_end:
            kept = self._done = (version, ranker.last_end, _done_since(kept, ranker))
            self._mined.clear()
        return kept[2]

    def mined(self, ranker: NeemRanker, at: float) -> _Mined:
        """The actions begun by ``at``, their routines and the routine their last episode continues."""
        done = begun_by(self.done(ranker), at)
        kept = self._mined.get(len(done))
        if kept is None:
            episodes = self._episodes(done)
            routines = self._mine(episodes)
            found = None
            if done:
                current = episodes[-1]
                found = recognise(routines, current.calls, current.hour)
            kept = _Mined(done, routines, max(done, key=lambda d: d.begin).end if done else None, found)
            self._mined = {len(done): kept}  # one time at once: the situation's
        return kept

    def _episodes(self, done: list[Done]) -> list[Episode]:
        """``episodes_of(done)``: the episodes before the last are kept with the actions they were
        cut from, and only the actions from the last episode's first on are cut again, while the
        actions before are the same (the same objects: ``done`` is made so) and all are in order
        of begin (else the whole list is cut afresh)."""
        kept = self._cut
        if kept is not None:
            first, before, complete = kept
            rest = done[first:]
            if 0 < first <= len(done) and done[first - 1] is before and _in_order([before, *rest]):
                episodes = complete + episodes_of(rest)
                self._keep_cut(done, episodes)
                return episodes
        episodes = episodes_of(done)
        self._cut = None
        if _in_order(done):
            self._keep_cut(done, episodes)
        return episodes

    def _keep_cut(self, done: list[Done], episodes: list[Episode]) -> None:
        """Keep the episodes but the last and the action before the last (``done`` in order of begin)."""
        first = len(done) - len(episodes[-1].calls) if episodes else 0
        self._cut = (first, done[first - 1], episodes[:-1]) if first > 0 else None

    def _mine(self, episodes: list[Episode]) -> list[Routine]:
        """``mine_routines`` of the actions cut into ``episodes``: the clustering of every episode
        but the last (which the next action may still extend) is kept and grown, and a copy of it
        takes the last one."""
        base = self._clustering
        complete = episodes[:-1]
        if base is None or base.episodes != complete[:len(base.episodes)]:
            base = self._clustering = Clustering(MiningSettings())
        for episode in complete[len(base.episodes):]:
            base.add(episode)
        clustering = base.copy()
        for episode in episodes[len(complete):]:
            clustering.add(episode)
        return clustering.routines()

    def in_progress(self, ranker: NeemRanker, at: float, stored: list[dict[str, Any]]) -> tuple[list[Routine], InProgress | None]:
        """The routines (with the names the user gave, oracle.past.workflows) and the one in
        progress at ``at``: oracle.past.routines.in_progress over ``mined``."""
        from oracle.past.workflows import keep_user_names

        mined = self.mined(ranker, at)
        routines, _ = keep_user_names(mined.routines, stored)
        if mined.latest_end is None or is_idle_gap(mined.latest_end, at):
            return routines, None
        found = mined.found
        if found is None or not found.remaining:
            return routines, None
        return routines, _renamed(found, routines)

    def warm(self, ranker: NeemRanker, at: float | None,
             read: Callable[[], list[dict[str, Any]]] | None = None) -> None:
        """Fit what the next situation needs now (after an action was answered); ``read``: the
        stored workflows' read, made again if ``STORED_S`` have passed since the last."""
        if read is not None and (self._stored is None or time.monotonic() - self._stored_at >= STORED_S):
            self._stored, self._stored_at = read(), time.monotonic()
        self.modes(ranker)
        if ranker.clocked and at is not None:
            self.mined(ranker, at)


def _in_order(done: list[Done]) -> bool:
    return all(a.begin <= b.begin for a, b in zip(done, done[1:]))


def _done_since(kept: tuple[tuple[int, object], float | None, list[Done]] | None, ranker: NeemRanker) -> list[Done]:
    """``done_from_steps`` of the ranker's steps, from the ``kept`` list when the steps only grew
    since it was made (its last step still where it was): only the last action of the kept list
    (the step after it sets its end) and the actions after it are made again."""
    steps, begins, end = ranker.steps, ranker.begins, ranker.last_end
    if kept is not None:
        (counted, last), _, done = kept
        if 0 < counted <= len(steps) and steps[counted - 1] is last:
            head = done if steps[counted - 1].idle else done[:-1]
            return head + done_from_steps(steps[counted - 1:], begins[counted - 1:], end)
    return done_from_steps(steps, begins, end)


def _renamed(found: InProgress, routines: list[Routine]) -> InProgress:
    """``found`` with its routine as ``keep_user_names`` named it (same key)."""
    import dataclasses

    for routine in routines:
        if routine.key == found.routine.key:
            return dataclasses.replace(found, routine=routine)
    return found
