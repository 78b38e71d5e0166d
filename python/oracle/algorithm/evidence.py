"""The routine predictor's evidence about each offered option, as one feature row per option.

One home for the features that the learned rankers (``stacked``, the default's combination, and
the ``logit`` and ``gbdt`` baselines of the evaluation) read: every column is something the
routine predictor already computes from the user's own history (docs/algorithm.md, "Stacked
predictor"). Nothing here changes the model.
"""

from __future__ import annotations

import math
from bisect import bisect_right
from collections.abc import Sequence
from typing import Any

import numpy as np

from oracle.algorithm.records import Option, Step
from oracle.algorithm.selftune import FLOOR
from oracle.timeline import IDLE_THRESHOLD_S, TIME_OF_DAY_NAMES, part_of_day_at

_TOD = {name: code for code, name in enumerate(TIME_OF_DAY_NAMES)}
#: exact-context orders whose follower counts are columns
CONTEXT_ORDERS = (1, 2, 3)


def feature_names(model: Any) -> tuple[str, ...]:
    """The column names of ``features`` for a fitted ``RoutineOracle``, in order."""
    variants = tuple(f"logp[{'/'.join(str(part) for part in v)}]" for v in model.variants_)
    contexts = tuple(name for n in CONTEXT_ORDERS for name in (f"share{n}", f"count{n}"))
    buckets = tuple(f"since<{edge:g}s" for edge in model.recency) + (f"since>={model.recency[-1]:g}s" if
                                                                       model.recency else "since", "never-since")
    return (variants + contexts + ("count0", "never", "share-part-of-day", "in-hand", "newly-offered",
                                   "resumed", "nearest") + buckets + ("no-clock",))


def features(model: Any, offered: Sequence[Option], time_of_day: str | None, at: float | None) -> np.ndarray:
    """Per offered option (rows, in the order given), the routine predictor's evidence (columns,
    ``feature_names``): the log-probability every variant gives it (with the lifts of the objects
    in hand, newly offered options and resumption), the share and log count of its followings of
    the current exact contexts of orders 1-3, its log count of uses, whether it was never done,
    its share of the uses at this part of day, the three lifts' flags, its nearest Algorithm 2
    distance to a past action, and the bucket of the time since it was last done (``at``; a
    column "no clock" when there is none)."""
    found = model._evidence(offered, time_of_day)
    ids = found.ids
    size = len(offered)
    edges = tuple(model.recency)
    n_variants = len(found.probabilities)
    out = np.zeros((size, n_variants + 2 * len(CONTEXT_ORDERS) + 7 + len(edges) + 3))
    out[:, :n_variants] = np.log(np.maximum(np.asarray(found.probabilities), FLOOR)).T
    at_column = n_variants
    counts = model._streams[model.streams[0]].counts
    for n in CONTEXT_ORDERS:
        context = counts.context(n) if n <= counts.max_order else None
        followers = counts.levels[n].tables.get(context) if context is not None else None
        if followers:  # share and log count of the followings (columns of zeros otherwise)
            seen = np.array([followers.get(i, 0) for i in ids], dtype=np.float64)
            out[:, at_column] = seen / counts.levels[n].totals[context]
            out[:, at_column + 1] = np.log1p(seen)
        at_column += 2
    done = counts.levels[0].tables.get(()) or {}
    uses = np.array([done.get(i, 0) for i in ids], dtype=np.float64)
    out[:, at_column] = np.log1p(uses)
    out[:, at_column + 1] = uses == 0
    part = _TOD.get(time_of_day or "", -1)
    timed = counts.timed[0].tables.get((part,)) if part >= 0 else None
    if timed:
        out[:, at_column + 2] = np.array([timed.get(i, 0) for i in ids], dtype=np.float64) / counts.timed[0].totals[(part,)]
    for column, flags in enumerate((found.inside, found.new, found.resumed), start=at_column + 3):
        if flags is not None:
            out[:, column] = flags
    cand = found.distances
    nearest = cand.min(axis=1) if cand.shape[1] else np.full(size, math.inf)
    out[:, at_column + 6] = np.minimum(nearest, 2 * model.penalty + model.task_factor)
    at_column += 7
    last = model.clock_.last
    if at is not None:
        for row, i in enumerate(ids):
            t = last.get(i)
            out[row, at_column + (len(edges) + 1 if t is None else bisect_right(edges, at - t))] = 1.0
    else:
        out[:, -1] = 1.0
    return out


class DecisionClock:
    """When each past decision was taken, as its history shows it (the replay's rule, never the
    action's own start): the previous action's start, 20 s later after an idle gap; and that
    moment's part of day. Without a clock: the step's own part of day, as recorded. Feed it every
    step, idle ones included, after reading the step's moment (``decided``, then ``passed``)."""

    def __init__(self) -> None:
        self.last: float | None = None   # the last action's start
        self.paused = False              # an idle step since

    def moment(self) -> float | None:
        """When the next decision is taken, as the history will show it (None: no clock yet)."""
        if self.last is None:
            return None
        return self.last + IDLE_THRESHOLD_S if self.paused else self.last

    def decided(self, step: Step) -> tuple[float | None, str | None]:
        if step.time is None:
            return None, step.time_of_day
        when = self.moment()
        return (when, part_of_day_at(when)) if when is not None else (None, None)

    def fork(self) -> DecisionClock:
        """A copy."""
        twin = DecisionClock()
        twin.last, twin.paused = self.last, self.paused
        return twin

    def passed(self, step: Step) -> None:
        if step.idle:
            self.paused = True
        else:
            self.last, self.paused = step.time, False
