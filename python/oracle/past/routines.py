"""The user's routines mined from their own past: recurring chains of actions, each with a
readable name, its usual time and how many days it was seen; and the routine a chain in
progress belongs to.

A day's actions fall into episodes at the idle gaps (oracle.timeline's rule: the logger writes
an odb:IdleTask there). Episodes that share most of their steps (Jaccard similarity of their
sets of calls, averaged over the cluster's members) and begin within a few hours of each other
form a cluster; a cluster seen on enough different days is a routine. Its steps are those of
its most typical episode (the medoid), as the user did them.
"""

from __future__ import annotations

import statistics
from collections import Counter
from collections.abc import Sequence
from dataclasses import dataclass
from operator import attrgetter
from typing import TYPE_CHECKING

from oracle.chains import TaskCall, parse_call
from oracle.timeline import clock, is_idle_gap, time_of_day

if TYPE_CHECKING:
    from oracle.algorithm.records import Step
    from oracle.bridge import HistoryRow


@dataclass(frozen=True)
class Done:
    """One executed (non-idle) action: its begin and end in unix seconds, its call."""

    begin: float
    end: float
    call: str


@dataclass(frozen=True)
class Episode:
    """The actions between two idle gaps."""

    begin: float
    calls: tuple[str, ...]

    @property
    def hour(self) -> float:
        moment = clock(self.begin)
        return moment.hour + moment.minute / 60.0

    @property
    def day(self) -> str:
        return clock(self.begin).date().isoformat()


@dataclass(frozen=True)
class MiningSettings:
    """How alike episodes must be to be one routine, and how often it must recur."""

    min_similarity: float = 0.5  # mean Jaccard similarity of the call sets to the cluster's members
    max_hours: float = 2.0  # distance of an episode's start from the cluster's mean start
    min_days: int = 3  # days a routine is seen on, at least
    min_share: float = 0.4  # ... and at least this share of the days observed


@dataclass(frozen=True)
class Routine:
    """A recurring chain: its key (``r1``, ... by usual time), name, steps (the chain syntax),
    the days it was seen on, its usual start hour (median, wall clock) and part of the day,
    and the begins of its episodes (the evidence)."""

    key: str
    name: str
    steps: tuple[str, ...]
    days: int
    hour: float
    part: str
    begins: tuple[float, ...]
    episodes: tuple[tuple[str, ...], ...] = ()

    @property
    def usual_time(self) -> str:
        minutes = round(self.hour * 60)
        return f"{minutes // 60:02d}:{minutes % 60:02d}"

    def to_json(self) -> dict[str, object]:
        return {"key": self.key, "name": self.name, "steps": list(self.steps), "days": self.days,
                "episodes": len(self.begins), "usual_time": self.usual_time, "part_of_day": self.part,
                "begins": list(self.begins)}


def episodes_of(done: Sequence[Done]) -> list[Episode]:
    """The actions, by begin, cut into episodes at the idle gaps."""
    episodes: list[Episode] = []
    calls: list[str] = []
    begin = previous_end = None
    for action in sorted(done, key=lambda d: d.begin):
        if calls and is_idle_gap(previous_end, action.begin):
            episodes.append(Episode(float(begin), tuple(calls)))  # type: ignore[arg-type]
            calls = []
        if not calls:
            begin = action.begin
        calls.append(action.call)
        previous_end = action.end
    if calls:
        episodes.append(Episode(float(begin), tuple(calls)))  # type: ignore[arg-type]
    return episodes


def jaccard(a: Sequence[str], b: Sequence[str]) -> float:
    return _similarity(frozenset(a), frozenset(b))


def _similarity(sa: frozenset[str], sb: frozenset[str]) -> float:
    """The Jaccard similarity of two sets of calls (1 for two empty ones)."""
    return len(sa & sb) / len(sa | sb) if sa or sb else 1.0


def _hours_apart(a: float, b: float) -> float:
    gap = abs(a - b) % 24.0
    return min(gap, 24.0 - gap)


def mine_routines(done: Sequence[Done], settings: MiningSettings | None = None) -> list[Routine]:
    """The routines of a user's actions, by usual time."""
    clustering = Clustering(settings or MiningSettings())
    for episode in episodes_of(done):
        clustering.add(episode)
    return clustering.routines()


class Clustering:
    """``mine_routines``'s clustering of episodes, one at a time in order (each joins the cluster
    it is most like, or starts one), so that a caller may keep it and add the episodes that come
    later (the service, oracle.service.warm): the routines are those of mining them all at once."""

    def __init__(self, settings: MiningSettings) -> None:
        self.settings = settings
        self.episodes: list[Episode] = []
        self.clusters: list[list[Episode]] = []
        self.sets: list[list[frozenset[str]]] = []  # each member's set of calls, made once
        self.hours: list[float] = []  # the sum of the members' start hours
        # the routine of a cluster by its index, size, last member and key (a cluster only grows, so
        # they name its members; copies share it)
        self._made: dict[tuple[int, int, Episode, str], Routine] = {}

    def copy(self) -> Clustering:
        """A copy to add episodes to (this one stays as it is)."""
        twin = object.__new__(Clustering)
        twin.settings, twin.episodes, twin._made = self.settings, list(self.episodes), self._made
        twin.clusters, twin.sets, twin.hours = [list(c) for c in self.clusters], [list(s) for s in self.sets], list(self.hours)
        return twin

    def add(self, episode: Episode) -> None:
        """The next episode (by begin)."""
        settings, clusters, sets, hours = self.settings, self.clusters, self.sets, self.hours
        self.episodes.append(episode)
        mine = frozenset(episode.calls)
        best, best_score = None, settings.min_similarity
        for index, cluster in enumerate(clusters):
            if _hours_apart(episode.hour, hours[index] / len(cluster)) > settings.max_hours:
                continue
            # (fmean of a list, not of a generator: the same sum, without counting it item by item)
            score = statistics.fmean([_similarity(mine, other) for other in sets[index]])
            if score >= best_score:
                best, best_score = index, score
        if best is None:
            clusters.append([episode])
            sets.append([mine])
            hours.append(episode.hour)
        else:
            clusters[best].append(episode)
            sets[best].append(mine)
            hours[best] += episode.hour

    def routines(self) -> list[Routine]:
        """The routines of the episodes added, by usual time."""
        clusters, sets = self.clusters, self.sets
        observed = len({e.day for e in self.episodes})
        needed = max(self.settings.min_days, self.settings.min_share * observed)
        kept = [i for i, c in enumerate(clusters) if len({e.day for e in c}) >= needed]
        kept.sort(key=lambda i: statistics.median(e.hour for e in clusters[i]))
        routines = []
        if len(self._made) > MADE:
            self._made.clear()
        for n, i in enumerate(kept, start=1):
            key = (i, len(clusters[i]), clusters[i][-1], f"r{n}")
            made = self._made.get(key)
            if made is None:
                made = self._made[key] = _routine(key[3], clusters[i], sets[i])
            routines.append(made)
        return _distinct_names(routines)


#: How many routines a clustering and its copies keep made, at most.
MADE = 1024


def _routine(key: str, cluster: list[Episode], sets: list[frozenset[str]]) -> Routine:
    """The routine of a cluster whose members' sets of calls are ``sets``: its medoid's steps."""
    typical = [statistics.fmean([_similarity(mine, other) for other in sets]) for mine in sets]
    medoid = max(zip(typical, cluster), key=lambda pair: (pair[0], -pair[1].begin))[1]
    hour = statistics.median(e.hour for e in cluster)
    return Routine(key, name_of(medoid.calls), medoid.calls, len({e.day for e in cluster}), hour, time_of_day(hour),
                   tuple(e.begin for e in cluster), tuple(e.calls for e in cluster))


def _distinct_names(routines: list[Routine]) -> list[Routine]:
    """Two routines of the same name get their part of the day (then their time) added."""
    from dataclasses import replace

    names = [r.name for r in routines]
    out = []
    for routine in routines:
        name = routine.name
        if names.count(name) > 1:
            name = f"{name} ({routine.part.lower()})"
            if sum(1 for r in routines if r.name == routine.name and r.part == routine.part) > 1:
                name = f"{routine.name} ({routine.usual_time})"
        out.append(replace(routine, name=name))
    return out


# -- names ----------------------------------------------------------------------------------------
#: What a poured or switched-on object makes, in a name; other objects are named by their words.
CONTENTS = {"thermos": "hot water", "coffee_machine": "coffee", "instant_coffee": "instant coffee",
            "milk_carton": "milk", "cereal_box": "cereal", "water_bottle": "water", "beer_bottle": "beer",
            "tap": "water", "juice": "juice", "yogurt": "yogurt"}
#: Objects that hold food or drink (a name says "in the ...").
VESSELS = ("mug", "cup", "glass", "bowl")


def _words(name: str) -> str:
    if name.endswith("_tea_bag"):
        return name[: -len("_tea_bag")].replace("_", " ") + " tea"
    return CONTENTS.get(name, name.replace("_", " "))


def _unique(items: list[str]) -> list[str]:
    return list(dict.fromkeys(items))


def _and(items: list[str]) -> str:
    return items[0] if len(items) == 1 else ", ".join(items[:-1]) + " and " + items[-1]


def name_of(steps: Sequence[str]) -> str:
    """A readable name from a chain's steps and objects: what is drunk from which vessel, what
    is eaten ("Coffee in the red mug", "Cereal and milk in the cereal bowl", "Bread and cucumber
    with water in the drinking glass"); failing both, its first task and most used object."""
    calls = [parse_call(s) for s in steps]
    vessels = _unique([c.args[0] for c in calls if c.task == "drink_from" and c.args])
    foods = _unique([c.args[-1] for c in calls if c.task in ("eat", "eat_with", "cut") and c.args])
    drink = ", ".join(_drink(calls, vessel) for vessel in vessels[:2])
    food = _and([_words(f) for f in foods]) if foods else ""
    if food and drink:
        text = f"{food} with {drink}"
    else:
        text = food or drink
    if not text:
        objects = [a for c in calls for a in c.args]
        common = max(_unique(objects), key=objects.count) if objects else ""
        text = f"{calls[0].task.replace('_', ' ')} {_words(common)}".strip() if calls else "nothing"
    return text[0].upper() + text[1:]


def _drink(calls: list[TaskCall], vessel: str) -> str:
    """What was drunk from ``vessel``: what was poured or steeped in it, what a switched-on
    machine made; from a bottle, the bottle's drink."""
    poured = _unique([c.args[0] for c in calls if c.task in ("pour", "place") and len(c.args) == 2 and c.args[1] == vessel
                      and (c.task == "pour" or c.args[0].endswith("_tea_bag"))])
    switched = _unique([c.args[0] for c in calls if c.task == "turn_on" and c.args and c.args[0] in CONTENTS])
    made = _unique([_words(x) for x in switched + poured])
    if any(w.endswith(" tea") or w in ("coffee", "instant coffee") for w in made):
        made = [w for w in made if w != "hot water"]  # the water is part of the tea or coffee
    if made:
        return f"{_and(made)} in the {vessel.replace('_', ' ')}"
    if not any(v in vessel for v in VESSELS):
        return f"{_words(vessel)} from the bottle"
    return f"a drink from the {vessel.replace('_', ' ')}"


# -- in progress ----------------------------------------------------------------------------------
@dataclass(frozen=True)
class InProgress:
    """The routine a chain in progress belongs to: how many of its steps are done, which remain."""

    routine: Routine
    done: int
    remaining: tuple[str, ...]
    score: float

    def to_json(self) -> dict[str, object]:
        return {"key": self.routine.key, "name": self.routine.name, "done": self.done,
                "remaining": list(self.remaining), "score": round(self.score, 3)}


def _lcs(a: Sequence[str], b: Sequence[str]) -> tuple[int, int]:
    """The length of the longest common subsequence of a and b, and the position in b after the
    last matched element of the longest one that ends earliest in b."""
    rows = [[0] * (len(b) + 1) for _ in range(len(a) + 1)]
    for i, x in enumerate(a, 1):
        for j, y in enumerate(b, 1):
            rows[i][j] = rows[i - 1][j - 1] + 1 if x == y else max(rows[i - 1][j], rows[i][j - 1])
    best = rows[len(a)][len(b)]
    end = next(j for j in range(len(b) + 1) if rows[len(a)][j] == best)
    return best, end


def recognise(routines: Sequence[Routine], prefix: Sequence[str], hour: float, *, min_score: float = 0.5,
              max_hours: float = 3.0) -> InProgress | None:
    """The routine the calls so far (``prefix``, since the last idle gap, begun at ``hour``)
    belong to: the one whose episodes (their first steps) share the most of the prefix in
    order, among those usually begun within ``max_hours``; None below ``min_score``."""
    if not prefix:
        return None
    best: tuple[float, float, InProgress] | None = None
    for routine in routines:
        distance = _hours_apart(hour, routine.hour)
        if distance > max_hours:
            continue
        window = len(prefix) + 2
        score = max(_lcs(prefix, episode[:window])[0] for episode in (routine.episodes or (routine.steps,))) / len(prefix)
        if score < min_score:
            continue
        _, end = _lcs(prefix, routine.steps)
        found = InProgress(routine, end, routine.steps[end:], score)
        if best is None or (score, -distance) > (best[0], best[1]):
            best = (score, -distance, found)
    return best[2] if best else None


def done_from_history(rows: Sequence[HistoryRow]) -> list[Done]:
    """The non-idle actions of ``Bridge.history()`` rows."""
    return [Done(float(r["begin"]), float(r["end"]), str(parse_call(r["call"]))) for r in rows if r["call"] != "idle"]


def begun_by(done: list[Done], at: float | None) -> list[Done]:
    """The actions begun by ``at`` (all of them for None; then the list itself)."""
    return done if at is None else [d for d in done if d.begin <= at]


def done_from_steps(steps: Sequence[Step], begins: Sequence[float], last_end: float | None) -> list[Done]:
    """The non-idle actions of the predictor's steps (``NeemRanker.steps`` and ``.begins``), with
    no read of the NEEM: an action followed by an idle step ends where the idle step begins (the
    logger dates the idle action from the end before it), one followed by an action where that
    begins (no idle gap: the logger wrote none), the last at ``last_end``. So the episodes are
    cut where the NEEM's idle actions stand, as ``done_from_history`` cuts them."""
    done = []
    for index, step in enumerate(steps):
        if step.idle:
            continue
        after = index + 1
        end = begins[after] if after < len(steps) else (last_end if last_end is not None else begins[index])
        done.append(Done(float(begins[index]), float(end), step.label))
    return done


def follows(done: Sequence[Done], call: str) -> tuple[int, list[tuple[str, int]]]:
    """How often ``call`` was done, and what the next action was after it (by begin), with how
    often: most often first, ties by the call's text. The same rule as prolog/odb/past.pl's
    usual_after/3, held equal to it by tests/past/test_follows.py."""
    calls = [d.call for d in sorted(done, key=attrgetter("begin", "call"))]  # C-made keys: 10,000 actions in ms
    nexts = Counter(b for a, b in zip(calls, calls[1:]) if a == call)
    return calls.count(call), sorted(nexts.items(), key=lambda item: (-item[1], item[0]))


def in_progress(routines: Sequence[Routine], done: Sequence[Done], now: float) -> InProgress | None:
    """The routine the user is in at ``now``: the actions since the last idle gap, unless the
    user has been idle since the last one; None when they match no routine or it is done."""
    if not done:
        return None
    latest = max(done, key=lambda d: d.begin)
    if is_idle_gap(latest.end, now):
        return None
    current = episodes_of(done)[-1]
    found = recognise(routines, current.calls, current.hour)
    return found if found is not None and found.remaining else None
