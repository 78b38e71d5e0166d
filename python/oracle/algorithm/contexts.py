"""Exact-context counts over one token stream and their PPM-C blend (docs/algorithm.md, "Routine predictor").

A token is an option id (>= 0) or ``IDLE``. ``ContextCounts`` counts, for every context of
1..``max_order`` tokens, which token followed it, and how often each action was done at all
(order 0). ``blend`` turns them into a distribution over candidates by PPM-C without exclusion
(or, with ``discount``, by interpolated absolute discounting), starting from a given base
distribution instead of the uniform one.

Why this module is large: the counts, their copy-on-write forks and the blend that reads them are
one structure (a level's tables, their owners and the blend's look-ups of the same contexts);
split, each part would reach into the others' attributes. The fork's layered view is its own
module (``layer``).
"""

from __future__ import annotations

import math
import weakref
from itertools import chain, islice
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from oracle.algorithm.layer import Layer

IDLE = -1      # the odb:IdleTask token
UNKNOWN = -3   # a candidate the history never saw (never counted)


@dataclass(slots=True)
class Blend:
    """The blended distribution and, per candidate, its longest exact context with a count (not
    frozen: a ranking builds some fifty of them, and a frozen one costs four times as much to make;
    nothing changes one once made)."""

    probabilities: np.ndarray
    order: np.ndarray      # longest n >= 1 whose context was followed by the candidate; 0: only done before; -1: never
    count: np.ndarray      # how often, at that order


#: Per (level, context): the candidates' follower counts, the distinct followers and the total,
#: or None for a context never followed (``_Level.apply``).
Memo = dict[tuple[int, tuple[int, ...]], "tuple[np.ndarray, int, int] | None"]


@dataclass
class _Level:
    """Follower counts of the contexts of one order, with its count-of-counts (for the discount)."""

    tables: dict[tuple[int, ...], dict[int, int]] = field(default_factory=dict)
    totals: dict[tuple[int, ...], int] = field(default_factory=dict)
    once: int = 0    # (context, follower) pairs seen exactly once
    twice: int = 0   # ... exactly twice
    #: the contexts whose follower table this level may change in place; None: all of them (no
    #: fork shares them, ``fork``)
    owned: set[tuple[int, ...]] | None = None
    #: the forks that read this level's tables through theirs (``fork``), while they live
    forks: list[weakref.ref[_Level]] = field(default_factory=list)

    def __getstate__(self) -> dict[str, object]:
        # an unpickled level shares nothing: a fork's layered tables are written out whole
        return {**self.__dict__, "tables": dict(self.tables.items()), "totals": dict(self.totals.items()),
                "owned": None, "forks": []}

    def __setstate__(self, state: dict[str, object]) -> None:
        self.__dict__.update(state)
        self.__dict__.setdefault("forks", [])  # a level pickled before forks were kept

    def plain_state(self) -> dict[str, object]:
        """The level as a few flat arrays (oracle.plainstate keeps a fit this way: one small
        object per context would cost it ten times pickle's time)."""
        contexts = list(self.tables)
        tables = list(self.tables.values())
        return {"lengths": np.fromiter(map(len, contexts), dtype=np.int64, count=len(contexts)),
                "contexts": np.fromiter(chain.from_iterable(contexts), dtype=np.int64),
                "totals": np.fromiter((self.totals.get(context, 0) for context in contexts), dtype=np.int64, count=len(contexts)),
                "sizes": np.fromiter(map(len, tables), dtype=np.int64, count=len(tables)),
                "followers": np.fromiter(chain.from_iterable(tables), dtype=np.int64),
                "counts": np.fromiter(chain.from_iterable(table.values() for table in tables), dtype=np.int64),
                "extra_totals": [[list(context), total] for context, total in self.totals.items() if context not in self.tables],
                "once": self.once, "twice": self.twice}

    @classmethod
    def from_plain_state(cls, state: dict[str, object]) -> _Level:
        """The level ``plain_state`` gave (its arrays checked against each other)."""
        lengths, flat, totals, sizes, followers, counts = (
            np.asarray(state[name], dtype=np.int64) for name in ("lengths", "contexts", "totals", "sizes", "followers", "counts"))
        if not (len(lengths) == len(totals) == len(sizes) and int(lengths.sum()) == len(flat)
                and int(sizes.sum()) == len(followers) == len(counts) and (lengths >= 0).all() and (sizes >= 0).all()):
            raise ValueError("a level whose arrays do not fit together")
        level = cls(once=int(state["once"]), twice=int(state["twice"]))  # type: ignore[call-overload]
        flat_list = flat.tolist()
        if len(lengths) and (lengths == lengths[0]).all():  # one order: tuples made at C speed
            tokens = iter(flat_list)
            contexts = list(zip(*[tokens] * int(lengths[0]))) if lengths[0] else [()] * len(lengths)
        else:
            ends = np.cumsum(lengths).tolist()
            contexts = [tuple(flat_list[end - length:end]) for end, length in zip(ends, lengths.tolist())]
        follower_iter, count_iter = iter(followers.tolist()), iter(counts.tolist())
        level.tables = {context: dict(zip(islice(follower_iter, size), islice(count_iter, size)))
                        for context, size in zip(contexts, sizes.tolist())}
        level.totals = dict(zip(contexts, totals.tolist()))
        for context, total in state["extra_totals"]:  # type: ignore[attr-defined]
            level.totals[tuple(context)] = int(total)
        return level

    def fork(self) -> _Level:
        """A copy that reads this level's tables through a layer of its own (``Layer``), so
        forking copies nothing: a table either of the two counts in next is copied first by
        it (copy on write), and before this level changes a context it hands its fork the
        context's entries as they were (``_hand_down``), so neither sees the other's counts."""
        if isinstance(self.tables, Layer):  # a fork of a fork: its own tables made whole first
            self.tables, self.totals = dict(self.tables.items()), dict(self.totals.items())
        self.owned = set()
        twin = _Level(Layer(self.tables), Layer(self.totals), self.once, self.twice, set())  # type: ignore[arg-type]
        self.forks = [ref for ref in self.forks if ref() is not None] + [weakref.ref(twin)]
        return twin

    def _hand_down(self, context: tuple[int, ...]) -> None:
        """Before ``context`` changes here: each living fork keeps its entries as they are now."""
        living = []
        for ref in self.forks:
            twin = ref()
            if twin is not None and isinstance(twin.tables, Layer) and isinstance(twin.totals, Layer):
                twin.tables.keep(context)
                twin.totals.keep(context)
                living.append(ref)
        self.forks = living

    def count(self, context: tuple[int, ...], token: int) -> None:
        if self.forks:
            self._hand_down(context)
        followers = self.tables.get(context)
        if followers is None:
            followers = self.tables[context] = {}
            self.totals[context] = 0
            if self.owned is not None:
                self.owned.add(context)
        elif self.owned is not None and context not in self.owned:
            followers = self.tables[context] = dict(followers)  # shared with a fork: copied first
            self.owned.add(context)
        seen = followers.get(token, 0)
        followers[token] = seen + 1
        self.totals[context] += 1
        if seen < 3:
            self.once += (seen == 0) - (seen == 1)
            self.twice += (seen == 1) - (seen == 2)

    def evidence(self) -> int:
        """The (context, follower) pairs the discount estimate rests on: those seen once or twice."""
        return self.once + self.twice

    def discount(self) -> float:
        """Ney-Essen-Kneser ``D = n1 / (n1 + 2 n2)`` of this order; 0.5 while no pair was seen exactly once."""
        if self.once == 0:
            return 0.5
        return self.once / (self.once + 2 * self.twice)

    def apply(self, context: tuple[int, ...], candidates: Sequence[int], probs: np.ndarray,
              discount: bool, exclude: bool = False, memo: Memo | None = None) -> tuple[np.ndarray, np.ndarray] | None:
        """The next blended distribution from ``probs`` and the candidates' counts, or None (unseen).
        With ``exclude`` the escape goes to the candidates this context was never followed by
        (PPM's exclusion), in proportion to ``probs``, while there are any with mass. ``memo``
        keeps the candidates' counts of a context for the other variants ranking the same
        candidates against the same counts (the counts must not change meanwhile)."""
        key = (id(self), context)
        if memo is not None and key in memo:
            counted = memo[key]
        else:
            followers = self.tables.get(context)
            counted = None if not followers else (
                np.array([followers.get(c, 0) for c in candidates], dtype=np.float64), len(followers),
                self.totals[context])
            if memo is not None:
                memo[key] = counted
        if counted is None:
            return None
        seen, kinds, total = counted
        if exclude:
            rest = np.where(seen > 0, 0.0, probs)
            mass = rest.sum(axis=-1, keepdims=True)
            probs = np.where(mass > 0, rest / np.where(mass > 0, mass, 1.0), probs)
        if discount:
            d = self.discount()
            return (np.maximum(seen - d, 0.0) + d * kinds * probs) / total, seen
        return (seen + kinds * probs) / (total + kinds), seen


def differs(part: dict[int, int], overall: dict[int, int], critical: float) -> bool:
    """Whether the followers of a context at one part of day differ from its followers at the other
    parts beyond sampling noise: the G-test of independence of the 2 x k table (this part, the
    others) x follower exceeds ``critical`` standard normal units, by the Wilson-Hilferty
    approximation of the chi-square quantile with k - 1 degrees of freedom (k: the followers seen).
    No evidence (the context was followed only at this part of day, or by one token) is no difference."""
    n_part = sum(part.values())
    n_all = sum(overall.values())
    n_rest = n_all - n_part
    k = len(overall)
    if n_part == 0 or n_rest == 0 or k < 2:
        return False
    g = 0.0
    for token, total in overall.items():
        here = part.get(token, 0)
        rest = total - here
        if here:
            g += here * math.log(here * n_all / (n_part * total))
        if rest:
            g += rest * math.log(rest * n_all / (n_rest * total))
    df = k - 1
    quantile = df * (1 - 2 / (9 * df) + critical * math.sqrt(2 / (9 * df))) ** 3
    return 2 * g > quantile


class ContextCounts:
    """Follower counts of every context of 1..max_order tokens, kept incrementally.

    With ``timed_from`` >= 0, every context of that order or more is counted a second time keyed
    by the part of day of the token that followed it (``(part,) + context``), so that ``blend`` can
    put "this context at this part of day" right above "this context"; at order 0 the part-of-day
    counts replace the overall ones (``blend``).
    """

    def __init__(self, max_order: int, timed_from: int = -1) -> None:
        self.max_order = max_order
        self.timed_from = timed_from
        self.tokens: list[int] = []
        self.levels = [_Level() for _ in range(max_order + 1)]
        self.timed = [_Level() for _ in range(max_order + 1)]

    def fork(self) -> ContextCounts:
        """A copy that counts on its own while sharing what neither changes (``_Level.fork``)."""
        twin = ContextCounts(0, self.timed_from)
        twin.max_order, twin.tokens = self.max_order, list(self.tokens)
        twin.levels = [level.fork() for level in self.levels]
        twin.timed = [level.fork() for level in self.timed]
        return twin

    def add(self, token: int, part: int = -1) -> None:
        """Count ``token`` after every current context; ``part`` is its part of day (-1 unknown)."""
        history = self.tokens
        size = len(history)
        timed_from = self.timed_from if part >= 0 else size + 1  # past every order: no timed count
        levels, timed = self.levels, self.timed
        for n in range(0 if token != IDLE else 1, min(self.max_order, size) + 1):  # idle: no order-0 count
            context = tuple(history[size - n:]) if n else ()
            levels[n].count(context, token)
            if n >= timed_from >= 0:
                timed[n].count((part, *context), token)
        history.append(token)

    def context(self, n: int) -> tuple[int, ...] | None:
        """The current context of order n, or None when the stream is shorter."""
        if n == 0:
            return ()
        return tuple(self.tokens[-n:]) if len(self.tokens) >= n else None

    def blend(self, candidates: Sequence[int], base: np.ndarray, max_order: int, min_order: int = 0,
              part: int = -1, discount: bool = False, gate: float | None = None,
              exclusion: bool = False, novelty: bool = False, memo: Memo | None = None,
              discount_from: int = 0, discount_evidence: int = 0, timed_discount_from: int | None = None,
              timed_shrink: bool = False, timed_to: int | None = None) -> Blend:
        """One variant's blend: ``blends`` with the one stop ``max_order`` (documented there)."""
        return self.blends(candidates, base, (max_order,), min_order, part, discount, gate, exclusion, novelty,
                           memo, discount_from, discount_evidence, timed_discount_from, timed_shrink,
                           timed_to)[max_order]

    def blends(self, candidates: Sequence[int], base: np.ndarray, max_orders: Sequence[int], min_order: int = 0,
               part: int = -1, discount: bool = False, gate: float | None = None,
               exclusion: bool = False, novelty: bool = False, memo: Memo | None = None,
               discount_from: int = 0, discount_evidence: int = 0,
               timed_discount_from: int | None = None, timed_shrink: bool = False,
               timed_to: int | None = None) -> dict[int, Blend]:
        """``P_n(c) = (n(ctx_n, c) + u_n P_{n-1}(c)) / (N(ctx_n) + u_n)`` from ``P_{-1} = base`` up to
        ``max_order``; an unseen context leaves the distribution as it is (PPM-C, no exclusion).
        With ``discount``: ``P_n(c) = (max(n(ctx_n, c) - D_n, 0) + D_n u_n P_{n-1}(c)) / N(ctx_n)`` at
        the orders ``n >= discount_from`` (their part-of-day levels too), PPM-C below, and only once
        the order's estimate ``D_n`` rests on ``discount_evidence`` pairs seen once or twice.
        When ``part`` is known (>= 0) and the counts are timed from order ``t``, the level
        ``(part,) + ctx_n`` follows each level ``ctx_n``, n >= max(t, 1), in the same way; at order 0
        (t = 0) it replaces the level ``()`` unless nothing was done at this part of day yet. The
        explanation (``order``, ``count``) keeps the untimed levels. With ``gate`` (a standard normal
        quantile) a part-of-day level is used only where its followers ``differs`` from those of
        the same context at the other parts of day. With ``exclusion`` the lowest level applied
        escapes only to the candidates it did not count (``_Level.apply``): the options never done
        (at order 0) share the estimate ``u / (N + u)`` of a novel action by ``base``. With
        ``novelty`` the order-0 stage is two-staged: a novel action (one never done) comes next with
        the PPM-C estimate ``q = u_0 / (N_0 + u_0)`` and is then chosen by ``base`` among the
        never-done candidates; otherwise (``1 - q``) the order-0 level ranks the done candidates,
        escaping to ``base`` restricted to them (below the order-1 contexts when the order-0
        level is not used). With ``timed_shrink`` a part-of-day level of order n >= 1 escapes as
        often as the context has distinct followers at any part of day (``u_n``, not its own
        ``u_t``): its estimate ``R`` becomes ``a R + (1 - a) P_n`` with ``a = (N_t + u_t) / (N_t +
        u_n)``, which under PPM-C is ``(n_t(c) + u_n P_n(c)) / (N_t + u_n)``; a context split four
        ways by the clock then moves the untimed estimate only as far as its few timed counts
        warrant. With ``timed_to`` k the part-of-day levels stop at order k (the higher orders
        are untimed). The blend of each of ``max_orders`` (variants that differ in their
        maximum order only), computed once up to the highest: a lower one is the state the
        higher one's blend passes through. ``base`` may also be a stack of distributions (one
        per row, variants that differ in their base only): each row is blended as it would be
        alone, with the same operations, so its result is bit for bit the same."""
        return self.lane_blends(candidates, [(base, min_order, novelty)], max_orders, part, discount, gate, exclusion,
                                memo, discount_from, discount_evidence, timed_discount_from, timed_shrink,
                                timed_to)[0]

    def lane_blends(self, candidates: Sequence[int], lanes: Sequence[tuple[np.ndarray, int, bool]],
                    max_orders: Sequence[int], part: int = -1, discount: bool = False, gate: float | None = None,
                    exclusion: bool = False, memo: Memo | None = None, discount_from: int = 0,
                    discount_evidence: int = 0, timed_discount_from: int | None = None,
                    timed_shrink: bool = False, timed_to: int | None = None) -> list[dict[int, Blend]]:
        """``blends`` of each lane ``(base, min_order, novelty)``, in one pass: the lanes differ only
        below order 1 (the order-0 level and the novelty split are worked out per lane), so from
        order 1 on their rows are stacked and go through each level together, each row with the
        operations it would meet alone (element by element), so every result is bit for bit
        that of ``blends`` on the lane alone. With ``exclusion`` the lowest level applied differs
        by lane, and so do the levels a lane of ``min_order`` 2 or more skips: then each lane is
        blended alone."""
        if len(lanes) > 1 and (exclusion or any(min_order > 1 for _, min_order, _ in lanes)):
            return [self.lane_blends(candidates, [lane], max_orders, part, discount, gate, exclusion, memo,
                                     discount_from, discount_evidence, timed_discount_from, timed_shrink, timed_to)[0]
                    for lane in lanes]
        done = self._done_mask(candidates) if any(novelty for _, _, novelty in lanes) else None
        states = [_Lane.start(self, len(candidates), base, min_order, done if novelty else None)
                  for base, min_order, novelty in lanes]
        stack: _Stack | None = None
        for n in range(min(lane.min_order for lane in states), min(max(max_orders), self.max_order) + 1):
            for lane in states:
                lane.reached(n, max_orders)
            context = self.context(n)
            if context is None:
                break
            followers = self.levels[n].tables.get(context)
            if not followers:
                continue
            timed = part >= 0 and 0 <= self.timed_from <= n and (timed_to is None or n <= timed_to)
            if timed and gate is not None:
                timed = differs(self.timed[n].tables.get((part, *context), {}), followers, gate)
            discounted = discount and n >= discount_from and self.levels[n].evidence() >= discount_evidence
            if n == 0:
                # order 0 at a known part of day: the user's counts at this part of day replace the
                # overall counts (Q already lends evidence across parts of day), unless there are none
                replace_zero = timed and bool(self.timed[0].tables.get((part,)))
                for lane in states:
                    if lane.min_order == 0:
                        lane.order_zero(self, candidates, part, discounted, replace_zero, exclusion, memo)
                continue
            if stack is None:  # from order 1 on every lane takes part (min_order 0 or 1, or one lane)
                stack = _Stack.of(states)
            lowest = exclusion and not states[0].applied  # excluding: one lane alone
            states[0].applied = True
            plain = self.levels[n].apply(context, candidates, stack.probs, discounted, lowest, memo)
            assert plain is not None
            seen = plain[1]
            hit = seen > 0
            counted = seen[hit].astype(np.int64)
            for lane in states:
                lane.order[hit] = n
                lane.count[hit] = counted
            probs = plain[0]
            if timed:
                timed_discounted = discounted if timed_discount_from is None else (
                    discount and n >= timed_discount_from and self.timed[n].evidence() >= discount_evidence)
                key = (part, *context)
                refined = self.timed[n].apply(key, candidates, probs, timed_discounted, memo=memo)
                if refined is not None and timed_shrink:
                    n_t, u_t = self.timed[n].totals[key], len(self.timed[n].tables[key])
                    share = (n_t + u_t) / (n_t + len(followers))
                    probs = share * refined[0] + (1.0 - share) * probs
                elif refined is not None:
                    probs = refined[0]
            stack.update(probs)
        for lane in states:
            lane.reached(math.inf, max_orders)  # the order-0 level never reached leaves the novelty split as it is
        return [lane.done for lane in states]

    def _done_mask(self, candidates: Sequence[int]) -> np.ndarray | None:
        """Per candidate: was it ever done? None unless both kinds are offered (no novelty split)."""
        done = self.levels[0].tables.get(())
        if not done:
            return None
        mask = np.array([c in done for c in candidates], dtype=bool)
        return None if mask.all() or not mask.any() else mask

    def _novelty(self, base: np.ndarray, mask: np.ndarray) -> tuple[np.ndarray, np.ndarray, float]:
        """``base`` restricted to the done candidates (``mask``, ``_done_mask``), ``q * base``
        restricted to the never-done ones, and ``1 - q``."""
        kinds = len(self.levels[0].tables[()])
        q = kinds / (self.levels[0].totals[()] + kinds)
        return _within(base, mask), q * _within(base, ~mask), 1.0 - q


def _within(probs: np.ndarray, mask: np.ndarray) -> np.ndarray:
    """``probs`` (each row of it) restricted to ``mask`` and normalised (uniform there when the
    row has no mass)."""
    part = np.where(mask, probs, 0.0)
    mass = part.sum(axis=-1, keepdims=True)
    uniform = mask / float(mask.sum())
    return np.where(mass > 0, part / np.where(mass > 0, mass, 1.0), uniform)


@dataclass
class _Lane:
    """One lane's blend in progress (``ContextCounts.lane_blends``): its distribution (one row,
    or a stack of rows), the candidates' longest counted orders and counts, the novelty split
    still to merge, and the blends of the maximum orders passed."""

    probs: np.ndarray
    order: np.ndarray
    count: np.ndarray
    min_order: int
    novel_part: np.ndarray | None = None
    done_share: float = 1.0
    applied: bool = False
    done: dict[int, Blend] = field(default_factory=dict)

    @classmethod
    def start(cls, counts: ContextCounts, size: int, base: np.ndarray, min_order: int,
              done: np.ndarray | None) -> _Lane:
        """A lane over ``size`` candidates from ``base``; ``done``: which were ever done, for the
        novelty split (None: no split)."""
        lane = cls(base.astype(np.float64, copy=True), np.full(size, -1, dtype=np.int64),
                   np.zeros(size, dtype=np.int64), min_order)
        if done is not None:
            lane.probs, lane.novel_part, lane.done_share = counts._novelty(lane.probs, done)
            if min_order > 0:
                lane.probs = lane.done_share * lane.probs + lane.novel_part
                lane.novel_part = None
        return lane

    def reached(self, below: float, max_orders: Sequence[int]) -> None:
        """The blends of every maximum order below ``below``."""
        for stop in max_orders:
            if stop < below and stop not in self.done:
                final = self.probs if self.novel_part is None else self.done_share * self.probs + self.novel_part
                self.done[stop] = Blend(final, self.order.copy(), self.count.copy())

    def order_zero(self, counts: ContextCounts, candidates: Sequence[int], part: int, discounted: bool,
                   replace_zero: bool, exclusion: bool, memo: Memo | None) -> None:
        """The order-0 level: the user's action counts (at this part of day when ``replace_zero``)."""
        lowest = exclusion and not self.applied
        self.applied = True
        plain = counts.levels[0].apply((), candidates, self.probs, discounted, lowest and not replace_zero, memo)
        assert plain is not None
        seen = plain[1]
        hit = seen > 0
        self.order[hit] = 0
        self.count[hit] = seen[hit].astype(np.int64)
        if replace_zero:
            refined = counts.timed[0].apply((part,), candidates, self.probs, discounted, lowest, memo)
            assert refined is not None
            self.probs = refined[0]
        else:
            self.probs = plain[0]
        if self.novel_part is not None:
            self.probs = self.done_share * self.probs + self.novel_part
            self.novel_part = None


@dataclass
class _Stack:
    """The lanes' rows stacked for the levels from order 1 on; each lane's ``probs`` is kept a
    view of its rows."""

    probs: np.ndarray
    lanes: list[_Lane]
    spans: list[tuple[int, int, bool]]   # per lane: first row, end row, whether it is one flat row

    @classmethod
    def of(cls, lanes: list[_Lane]) -> _Stack:
        if len(lanes) == 1:  # a lane alone keeps its shape
            return cls(lanes[0].probs, lanes, [])
        spans, rows, at = [], [], 0
        for lane in lanes:
            block = np.atleast_2d(lane.probs)
            rows.append(block)
            spans.append((at, at + block.shape[0], lane.probs.ndim == 1))
            at += block.shape[0]
        return cls(np.concatenate(rows), lanes, spans)

    def update(self, probs: np.ndarray) -> None:
        self.probs = probs
        if not self.spans:
            self.lanes[0].probs = probs
        for lane, (lo, hi, flat) in zip(self.lanes, self.spans):
            lane.probs = probs[lo] if flat else probs[lo:hi]
