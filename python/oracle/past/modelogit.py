"""Who usually performs an action, learned across tasks (thesis 6.3, autonomy mode): a multinomial
logit of the mode over four kinds of evidence, fitted to the user's own counts.

The counts of ``oracle.past.autonomy`` judge each task on its own actions. What makes a person do
something by hand is partly shared between tasks (tired in the evening, a heavy object, a weak
grip), and a per-task count cannot carry that across: the logit can. Its features are one-hot:
a bias, the task, the call (task with its objects) and the part of the day, each with a weight
per mode; the weights minimise the counts' negative log-likelihood plus ``SHRINK / 2`` times
their squared norm (L2), so a call seen once stays close to its task and its task close to the
bias. The fit is to the counts of each (call, part of the day, mode), not to the order of the
actions: the same history gives the same weights however it was read, and a kept history can be
extended and fitted again. The settings (features and shrink) were chosen on the persona tune
split, docs/beyond.md ("Autonomy mode").

The loss is smooth and strictly convex, so any solver that converges finds the same weights; this
one is a small limited-memory BFGS (numpy only; scipy costs 0.2-0.5 s to import on the ranking
path).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import numpy as np

from oracle.chains import parse_call
from oracle.past.autonomy import NO_PART, TIE_ORDER, ModeCounts, UsualMode

#: The L2 weight on the logit's weights (chosen on the persona tune split).
SHRINK = 10.0
#: Iterations of the solver at most, and the gradient norm (per count) it stops at.
ITERATIONS, TOLERANCE = 200, 1e-6
#: A call done the same way this many times or more keeps that mode (chosen on the tune split).
OWN = 3
#: Scores closer than this are a tie (far below any difference the counts can make).
TIE = 1e-4

Loss = Callable[[np.ndarray], tuple[float, np.ndarray]]


@dataclass(frozen=True)
class ModeLogit:
    """The fitted weights (one row per feature, one column per mode of TIE_ORDER) and each
    feature's row: ``b`` the bias, ``t:<task>``, ``c:<call>``, ``p:<part>``."""

    weights: np.ndarray
    rows: dict[str, int]
    #: The calls' tasks as the counts parsed them (ModeCounts.tasks), shared, not copied.
    tasks: dict[str, str] = field(default_factory=dict, repr=False, compare=False)

    def scores(self, call: str, part: str) -> np.ndarray:
        """The mode's scores for ``call`` in ``part`` (features never seen add nothing)."""
        total = np.zeros(len(TIE_ORDER))
        task = self.tasks.get(call) or parse_call(call).task
        for name in _features(call, task, part):
            row = self.rows.get(name)
            if row is not None:
                total += self.weights[row]
        return total

    def predict(self, call: str, part: str) -> str:
        """The likeliest mode; a tie (scores within TIE of the best: the solver's precision) to the
        first of TIE_ORDER (the user)."""
        scores = self.scores(call, part)
        return TIE_ORDER[int(np.argmax(scores >= scores.max() - TIE))]  # the first of the best


def ranked_modes(counts: ModeCounts, calls: Sequence[str], chain: Sequence[str], part: str | None,
                 model: ModeLogit | None = None) -> tuple[list[UsualMode], list[str | None]]:
    """The usual mode of each ranked call and of each step of the predicted chain, in ``part``
    of the day (None: a NEEM without a clock): the logit's, with the counts of the most specific
    context that has any as its support (ModeCounts.usual). A call none of whose task's actions
    is known has no usual mode (None); one done the same way every time, at least OWN times (in
    this part of the day, or else at all), keeps that mode. ``model``: ``fit_modes(counts)`` when
    the caller kept it (the service fits it once per history, oracle.service.warm)."""
    at = part or NO_PART
    logit = fit_modes(counts) if model is None else model

    def usual(call: str) -> UsualMode:
        counted = counts.usual(call, at)
        if counted.mode is None or _kept(counted):
            return counted
        return UsualMode(logit.predict(call, at), counted.context, counted.counts)

    known = {call: usual(call) for call in {*calls, *chain}}  # the chain's steps are mostly ranked calls
    return [known[call] for call in calls], [known[call].mode for call in chain]


def _kept(counted: UsualMode) -> bool:
    """The call's own counts are unanimous over OWN actions or more."""
    total = sum(counted.counts.values())
    return counted.context in ("call and part", "call") and total >= OWN and max(counted.counts.values()) == total


def _features(call: str, task: str, part: str) -> tuple[str, ...]:
    return ("b", f"t:{task}", f"c:{call}", f"p:{part}")


def fit_modes(counts: ModeCounts, shrink: float = SHRINK) -> ModeLogit:
    """The logit fitted to the counts of each call in each part of the day (ModeCounts' most
    specific context)."""
    cells = [(key[1], key[2], counted) for key, counted in counts.counts.items() if key[0] == "cp"]
    rows: dict[str, int] = {}
    index = np.zeros((len(cells), 4), dtype=np.intp)
    seen = np.zeros((len(cells), len(TIE_ORDER)))
    for i, (call, part, counted) in enumerate(cells):
        for j, name in enumerate(_features(call, counts.task_of(call), part)):
            index[i, j] = rows.setdefault(name, len(rows))
        seen[i] = [counted.get(mode, 0) for mode in TIE_ORDER]
    width = (len(rows), len(TIE_ORDER))
    if not cells:
        return ModeLogit(np.zeros(width), rows, counts.tasks)
    totals = seen.sum(axis=1, keepdims=True)

    def loss(flat: np.ndarray) -> tuple[float, np.ndarray]:
        weights = flat.reshape(width)
        scores = weights[index].sum(axis=1)
        scores -= scores.max(axis=1, keepdims=True)
        log_p = scores - np.log(np.exp(scores).sum(axis=1, keepdims=True))
        value = float(-(seen * log_p).sum() + 0.5 * shrink * (flat @ flat))
        residual = np.exp(log_p) * totals - seen
        grad = shrink * weights
        for j in range(index.shape[1]):
            np.add.at(grad, index[:, j], residual)
        return value, grad.ravel()

    flat = _minimise(loss, np.zeros(width[0] * width[1]), TOLERANCE * float(totals.sum()))
    return ModeLogit(flat.reshape(width), rows, counts.tasks)


def _minimise(loss: Loss, start: np.ndarray, tolerance: float, memory: int = 8) -> np.ndarray:
    """Limited-memory BFGS with a backtracking (Armijo) line search, from ``start`` until the
    gradient's norm is below ``tolerance`` or ITERATIONS have passed."""
    x = start
    value, grad = loss(x)
    steps: list[tuple[np.ndarray, np.ndarray, float]] = []
    for _ in range(ITERATIONS):
        if float(np.linalg.norm(grad)) <= tolerance:
            break
        direction = _direction(grad, steps)
        slope = float(grad @ direction)
        if slope >= 0.0:  # not a descent direction: start the memory afresh
            steps.clear()
            direction, slope = -grad, -float(grad @ grad)
        size = 1.0
        while True:
            moved = x + size * direction
            new_value, new_grad = loss(moved)
            if new_value <= value + 1e-4 * size * slope or size < 1e-10:
                break
            size /= 2.0
        s, y = moved - x, new_grad - grad
        sy = float(s @ y)
        if sy > 1e-12:
            steps.append((s, y, 1.0 / sy))
            del steps[:-memory]
        x, value, grad = moved, new_value, new_grad
    return x


def _direction(grad: np.ndarray, steps: list[tuple[np.ndarray, np.ndarray, float]]) -> np.ndarray:
    """The two-loop recursion: minus the inverse-Hessian estimate times the gradient."""
    q = grad.copy()
    alphas = []
    for s, y, rho in reversed(steps):
        alpha = rho * float(s @ q)
        alphas.append(alpha)
        q -= alpha * y
    if steps:
        s, y, _ = steps[-1]
        q *= float(s @ y) / float(y @ y)
    for (s, y, rho), alpha in zip(steps, reversed(alphas)):
        beta = rho * float(y @ q)
        q += (alpha - beta) * s
    return -q
