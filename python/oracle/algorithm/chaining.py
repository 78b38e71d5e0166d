"""The predicted chain by re-ranking (thesis 6.4, "Improving the predictions of a further future"):
the best option taken as done, then the best of what is feasible after it, ranked by the model as
it would be once that step is learnt, and so on.

What is feasible after an option is the task inference of a log without a world model: the offer
of the decision that followed the user's latest execution of that option (``Afterwards``); the
chain ends at an option that no decision ever followed without a break (never done, or the end of
an activity each time): there is no evidence of what would come next. The step
taken as done is learnt by a copy of the fitted model (``partial_fit``), so the model itself is
never changed; the copy is made once per chain, and shares the model's option tables until it
interns an option of its own (``RoutineOracle.hypothetical``). The thesis oracle keeps its own chain, the
forward tree of Fig. 4.6 (``Ranking.chain``); the routine predictors chain by re-ranking
(``reranks``). docs/algorithm.md, "The predicted chain", has the evidence and the cost.
"""

from __future__ import annotations

import pickle
from collections.abc import Iterable, Sequence
from typing import Any, TypeGuard

from oracle.algorithm.records import Option, Ranking, Step
from oracle.algorithm.routine import RoutineOracle


class Afterwards:
    """Per option done: the offer of the decision that followed its latest execution (no entry
    when a break followed it, or nothing has yet)."""

    def __init__(self, steps: Iterable[Step] = ()) -> None:
        self.after: dict[Option, tuple[Option, ...]] = {}
        self.previous: Option | None = None
        for step in steps:
            self.add(step)

    def add(self, step: Step) -> None:
        """One more step of the history, in order (an idle step ends what is "after")."""
        if step.idle:
            self.previous = None
            return
        if self.previous is not None and step.options:
            self.after[self.previous] = step.options
        self.previous = step.option

    def feasible(self, option: Option) -> tuple[Option, ...]:
        """What is likely feasible once ``option`` is done: the offer that followed it last time;
        nothing when no decision ever followed it without a break (the chain ends there)."""
        return self.after.get(option, ())


def reranks(model: Any) -> TypeGuard[RoutineOracle]:
    """Whether ``model`` chains by re-ranking (the routine predictors) rather than by its forward
    tree (the thesis oracle, as the thesis defines it)."""
    return isinstance(model, RoutineOracle)


def rankings_ahead(model: Any, ranking: Ranking, offer: Sequence[Option], afterwards: Afterwards,
                   time_of_day: str | None, at: float | None, length: int) -> list[Ranking]:
    """The rankings of the steps after ``ranking``'s best, at most ``length - 1``: each over
    ``afterwards.feasible`` after the step before (that ranking's best), by a copy of ``model``
    that has learnt the steps before it as done (from the offer each was chosen from, at
    ``time_of_day`` and ``at``, the decision's). It ends early where nothing is known to be
    feasible."""
    return _ahead(model, ranking, offer, afterwards, time_of_day, at, length, True)


def _ahead(model: Any, ranking: Ranking, offer: Sequence[Option], afterwards: Afterwards,
           time_of_day: str | None, at: float | None, length: int, explain: bool) -> list[Ranking]:
    """``rankings_ahead``; without ``explain`` a routine predictor's rankings carry their order
    alone (``RoutineOracle.rank``), all the chain reads of them."""
    rankings: list[Ranking] = []
    if not ranking.tasks:
        return rankings
    step, offer, ahead = ranking.tasks[0].option, tuple(offer), None
    while len(rankings) < length - 1:
        feasible = afterwards.feasible(step)
        if not feasible:
            break
        if ahead is None:
            ahead = model.hypothetical() if reranks(model) else pickle.loads(pickle.dumps(model, protocol=pickle.HIGHEST_PROTOCOL))
        ahead.partial_fit(Step(step.task, step.target, step.reference, offer, time_of_day, False, str(step), at))
        offer = feasible
        following: Ranking = (ahead.rank(list(offer), time_of_day, tree_roots=0, at=at) if explain or not reranks(ahead)
                              else ahead.rank(list(offer), time_of_day, tree_roots=0, at=at, explain=False))
        if not following.tasks:
            break
        rankings.append(following)
        step = following.tasks[0].option
    return rankings


def chain_ahead(model: Any, ranking: Ranking, offer: Sequence[Option], afterwards: Afterwards,
                time_of_day: str | None, at: float | None, length: int) -> tuple[Option, ...]:
    """The predicted chain of at most ``length`` options: ``ranking``'s best, then the best of
    each of ``rankings_ahead`` (ranked without their explanations: the same order, for less)."""
    if not ranking.tasks or length < 1:
        return ()
    later = _ahead(model, ranking, offer, afterwards, time_of_day, at, length, False)
    return (ranking.tasks[0].option, *(following.tasks[0].option for following in later))
