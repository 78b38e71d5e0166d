"""Progressive replay: before each action, every method ranks that step's candidates using only
the user's earlier actions (thesis 5.3); then the action joins the history.

The ``ReplayRules`` say what a decision may know (docs/evaluation.md, "Replay"). By default
(honest): a row without an ``available`` set is offered the distinct actions its user did before
it (``candidates="history"``; the old rule, every action of the user anywhere in the file, is
``"vocabulary"``), and the decision is taken at the end of the previous action, or, when the user
paused for an idle gap, at the moment that gap became one (``decision="previous-end"``; the true
start is ``"start"``). Candidate sets are shuffled with a generator seeded by user and position,
identically for every method. A gap of ``oracle.timeline.IDLE_THRESHOLD_S`` or more between one
action's end (its start when the row has no end) and the next start inserts an odb:IdleTask step
into the history (it is a chain delimiter, never a prediction target).
"""

from __future__ import annotations

import hashlib
import random
import sys
import time
from collections import OrderedDict
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Protocol

from oracle.algorithm.params import Hyperparameters
from oracle.algorithm.predictors import DEFAULT, THESIS, make_predictor
from oracle.algorithm.records import Option, Step
from oracle.chains import ChainRow, TaskCall, read_chains
from oracle.errors import ChainSyntaxError
from oracle.evaluation.baselines import BASELINES, chance_hit
from oracle.ontology import OdbOntology
from oracle.calls import check_call, idle_step, opening_tasks, option_of
from oracle.timeline import IDLE_THRESHOLD_S, clock, is_idle_gap, seconds_of, time_of_day

KS = (1, 3, 5)
CANDIDATE_RULES = ("history", "vocabulary")
DECISION_RULES = ("previous-end", "start")


@dataclass(frozen=True)
class ReplayRules:
    """What a replayed decision may know. ``candidates``: for a row without ``available``,
    "history" (the user's distinct actions before it) or "vocabulary" (every action of the user
    in the input, future ones included); ``decision``: the time the decision is ranked at,
    "previous-end" (the previous action's end, or the moment an idle gap became one) or "start"
    (the true action's start); ``served``: a predictor with ``extend`` is kept as ``rank`` keeps it
    (``fit(history)``: self-tuning on the latest window), not by ``partial_fit``."""

    candidates: str = "history"
    decision: str = "previous-end"
    served: bool = True

    def __post_init__(self) -> None:
        if self.candidates not in CANDIDATE_RULES:
            raise ValueError(f"candidates must be one of {', '.join(CANDIDATE_RULES)}, got {self.candidates!r}")
        if self.decision not in DECISION_RULES:
            raise ValueError(f"decision must be one of {', '.join(DECISION_RULES)}, got {self.decision!r}")


#: The protocol of the first published results: future actions offered, decisions at the true start.
LEGACY = ReplayRules("vocabulary", "start", False)


def decision_time(previous_end: float | None, start: float | None, rule: str) -> float | None:
    """The unix seconds a decision is ranked at. "previous-end": the previous action's end, or
    ``previous_end + IDLE_THRESHOLD_S`` when the user paused longer (the moment the logger writes
    the idle step: all a live system knows then is that nothing began before it); None for a
    user's first action. "start": the true start."""
    if rule == "start" or start is None:
        return start
    if previous_end is None:
        return None
    return previous_end + IDLE_THRESHOLD_S if is_idle_gap(previous_end, start) else previous_end


class Method(Protocol):
    name: str

    def reset(self) -> None: ...

    def rank(self, candidates: Sequence[Option], time_of_day: str | None = None,
             at: float | None = None) -> list[Option]: ...

    def observe(self, step: Step) -> None: ...


class OracleMethod:
    """A predictor of the registry (``oracle.algorithm.predictors``) behind the replay's Method
    interface; ``method`` names it (default: the thesis oracle, with ``settings``), ``name`` is the
    column it gets in the summary (default: the method's name; "oracle" for the thesis)."""

    def __init__(self, ontology: OdbOntology, settings: Hyperparameters, name: str | None = None,
                 method: str = THESIS, served: bool = False) -> None:
        self.method = method
        self.served = served
        self.name = name if name is not None else ("oracle" if method == THESIS else method)
        self.settings = settings
        self.distances = ontology.distances()
        self.opening = opening_tasks(ontology)
        self.prior: Any = None
        self.reset()

    def use_prior(self, prior: Any) -> None:
        """The shared prior the next user's predictor ranks with (None: none; --population)."""
        self.prior = prior

    def reset(self) -> None:
        self.model = make_predictor(self.method, self.distances, self.opening, self.settings).fit([])
        use = getattr(self.model, "use_prior", None)
        if use is not None:
            use(self.prior)
        self.history: list[Step] = []

    def rank(self, candidates: Sequence[Option], time_of_day: str | None = None, at: float | None = None) -> list[Option]:
        return list(self.model.rank(list(candidates), time_of_day, tree_roots=0, at=at).options())

    def observe(self, step: Step) -> None:
        extend = getattr(self.model, "extend", None)
        if self.served and extend is not None:
            # as rank serves it: the model fit(history) gives, self-tuned on the latest window
            self.history.append(step)
            extend(self.history)
        else:
            self.model.partial_fit(step)


@dataclass(frozen=True)
class Outcome:
    """One prediction: where each method put the truth (1-based rank, None if not offered)."""

    user: str
    index: int
    n_candidates: int
    truth_offered: bool
    ranks: dict[str, int | None]
    seconds: dict[str, float]


@dataclass
class ReplayResult:
    outcomes: list[Outcome] = field(default_factory=list)

    def methods(self) -> list[str]:
        return list(self.outcomes[0].ranks) if self.outcomes else []


def load_users(path: Path | str) -> OrderedDict[str, list[ChainRow]]:
    """Rows of a JSONL file, or of every ``*.jsonl`` in a folder, grouped by user in file order."""
    path = Path(path)
    files = sorted(path.glob("*.jsonl")) if path.is_dir() else [path]
    if not files:
        raise ChainSyntaxError(f"{path}: no *.jsonl chain files found")
    users: OrderedDict[str, list[ChainRow]] = OrderedDict()
    for file in files:
        for row in read_chains(file):
            users.setdefault(row.user, []).append(row)
    if not users:
        raise ChainSyntaxError(f"{path}: no actions found")
    return users


def check_users(ontology: OdbOntology, users: dict[str, list[ChainRow]], source: str) -> None:
    """Fail early, naming file line and name, when a chain uses an unknown task or object."""
    for rows in users.values():
        for row in rows:
            where = f"{source}:{row.line}" if row.line else source
            check_call(ontology, row.action, where)
            for call in row.available or ():
                check_call(ontology, call, where)


def _rng(user: str, index: int, seed: int) -> random.Random:
    digest = hashlib.sha256(f"{seed}:{user}:{index}".encode()).digest()
    return random.Random(int.from_bytes(digest[:8], "big"))


def replay(
    ontology: OdbOntology,
    users: dict[str, list[ChainRow]],
    methods: Sequence[Method],
    seed: int = 0,
    progress: Callable[[int, int, str], None] | None = None,
    protocol: ReplayRules = ReplayRules(),
    priors: Callable[[str], Any] | None = None,
) -> ReplayResult:
    """``priors``: each user's shared prior (built without them, oracle.evaluation.population),
    given to every method that takes one before it meets the user."""
    result = ReplayResult()
    known: dict[TaskCall, Option] = {}

    def convert(call: TaskCall) -> Option:
        option = known.get(call)
        if option is None:
            option = known[call] = option_of(ontology, call)
        return option

    for number, (user, rows) in enumerate(users.items(), start=1):
        if progress is not None:
            progress(number, len(users), user)
        vocabulary = list(OrderedDict.fromkeys(option_of(ontology, row.action) for row in rows))
        done: OrderedDict[Option, None] = OrderedDict()  # the user's actions so far, in first-use order
        prior = priors(user) if priors is not None else None
        for method in methods:
            use = getattr(method, "use_prior", None)
            if use is not None:
                use(prior)
            method.reset()
        previous_end: float | None = None
        for index, row in enumerate(rows):
            start_s = seconds_of(row.time) if row.time is not None else None
            at = decision_time(previous_end, start_s, protocol.decision)
            if start_s is not None and is_idle_gap(previous_end, start_s):
                idle = idle_step(ontology, clock(at) if at is not None else row.time)
                for method in methods:
                    method.observe(idle)
            if row.time is not None:
                previous_end = seconds_of(row.end if row.end is not None else row.time)
            truth = convert(row.action)
            if row.available is not None:
                candidates = list(OrderedDict.fromkeys(convert(call) for call in row.available))
            elif protocol.candidates == "history":
                candidates = list(done)
            else:
                candidates = list(vocabulary)
            _rng(user, index, seed).shuffle(candidates)
            tod = time_of_day(clock(at)) if at is not None else None
            ranks: dict[str, int | None] = {}
            seconds: dict[str, float] = {}
            offered = truth in candidates
            for method in methods:
                begin = time.perf_counter()
                order = method.rank(candidates, tod, at) if candidates else []
                seconds[method.name] = time.perf_counter() - begin
                ranks[method.name] = order.index(truth) + 1 if offered else None
            result.outcomes.append(Outcome(user, index, len(candidates), offered, ranks, seconds))
            # the step joins the history as it happened: when it began, at its own part of day
            observed = Step(truth.task, truth.target, truth.reference, tuple(candidates),
                            time_of_day(row.time) if row.time is not None else None, False, str(row.action), start_s)
            done[truth] = None
            for method in methods:
                method.observe(observed)
    return result


def stderr_progress(done: int, total: int, user: str) -> None:
    """A bar redrawn in place on a terminal; on a log file, one line per tenth of the users."""
    if not sys.stderr.isatty():
        if done == total or done % max(1, total // 10) == 0:
            sys.stderr.write(f"replay {done}/{total} users\n")
        return
    width = 30
    filled = int(width * done / total)
    sys.stderr.write(f"\rreplay [{'#' * filled}{'.' * (width - filled)}] {done}/{total} {user[:24]:24s}")
    if done == total:
        sys.stderr.write("\n")
    sys.stderr.flush()


def make_methods(ontology: OdbOntology, settings: Hyperparameters, baselines: bool,
                 method: str = DEFAULT, served: bool = True) -> list[Method]:
    """The predictor ``method``; with ``baselines`` also the thesis oracle (when it is not the one
    chosen) and every baseline (``served``: predictors kept as ``rank`` keeps them, ``ReplayRules``)."""
    methods: list[Method] = [OracleMethod(ontology, settings, method=method, served=served)]
    if baselines:
        if method != THESIS:
            methods.append(OracleMethod(ontology, settings, method=THESIS, served=served))
        methods.extend(cls() for cls in BASELINES.values())
        from oracle.evaluation.learned import learned_baselines

        methods.extend(learned_baselines(ontology.distances(), opening_tasks(ontology)))
        from oracle.evaluation.population import PopPPM

        methods.append(PopPPM())
    return methods


def summarize(result: ReplayResult) -> dict[str, Any]:
    """The JSON summary of the issue: accuracies as fractions, per user and overall."""
    methods = result.methods()
    out: dict[str, Any] = {"methods": {}, "n_predictions": len(result.outcomes)}
    users = list(OrderedDict.fromkeys(o.user for o in result.outcomes))
    for name in methods:
        entry: dict[str, Any] = {}
        for k in KS:
            entry[f"top{k}"] = _rate(result.outcomes, name, k)
        entry["ms_per_prediction"] = 1000 * sum(o.seconds[name] for o in result.outcomes) / max(1, len(result.outcomes))
        entry["per_user"] = {
            user: {f"top{k}": _rate([o for o in result.outcomes if o.user == user], name, k) for k in KS}
            for user in users
        }
        out["methods"][name] = entry
    out["chance"] = {f"top{k}": sum(chance_hit(k, o.n_candidates, o.truth_offered) for o in result.outcomes)
                     / max(1, len(result.outcomes)) for k in KS}
    out["mean_candidates"] = sum(o.n_candidates for o in result.outcomes) / max(1, len(result.outcomes))
    out["truth_not_offered"] = sum(1 for o in result.outcomes if not o.truth_offered)
    return out


def _rate(outcomes: Iterable[Outcome], name: str, k: int) -> float:
    outcomes = list(outcomes)
    hits = sum(1 for o in outcomes if (rank := o.ranks[name]) is not None and rank <= k)
    return hits / len(outcomes) if outcomes else 0.0


__all__ = ["CANDIDATE_RULES", "DECISION_RULES", "KS", "LEGACY", "Method", "OracleMethod", "Outcome", "ReplayResult",
           "ReplayRules", "check_users", "decision_time",
           "load_users", "make_methods", "opening_tasks", "replay", "stderr_progress", "summarize"]
