"""The routine predictor (the default): exact-context counts of the user's own actions, backed off
to ontology similarity of past situations, self-tuned on the user's own history.

For each variant ``v = (stream, order, tau, n0, timed, discount, novelty)`` the probability of a candidate
is PPM-C over the user's exact contexts (and the same contexts at this part of day) whose lowest
level is the similarity distribution ``Q`` of ``kernel``, reweighted by the objects in hand (and, right after
a break, by what followed the last action), and whose result is reweighted by the user's odds of
taking a newly offered option; the predictor ranks with the variant
that predicted the user's past steps best (``selftune``). docs/algorithm.md, "Routine predictor",
gives every formula and the reasons.

Why this module is large: it is one estimator whose fit, scoring of the user's past steps and
ranking read and write the same private state (the streams' counts, the interned options, the
self-tuning's scores, the latest evidence); split across modules, each half would reach into the
other's attributes. The formulas themselves live in the modules it imports.
"""

from __future__ import annotations

import math
import pickle
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from itertools import product
from typing import Any, cast

import numpy as np

from oracle.algorithm.clock import EDGES, ClockGate, SinceDone, reweighted
from oracle.algorithm.contexts import IDLE, UNKNOWN, Blend, ContextCounts, Memo
from oracle.algorithm.focus import (FeatureLift, NewOffers, Resumption, combined, decision, held_objects, in_focus,
                                   split_weights, tells_apart)
from oracle.algorithm.params import THESIS_DEFAULTS, EstimatorParams
from oracle.algorithm.kernel import START, PastSituations, Rows, context_distance, normalised, similarity_mass
from oracle.algorithm.reference import offered_options
from oracle.algorithm.routine_settings import check_settings
from oracle.algorithm.selftune import VariantWeights, mixed_distribution
from oracle.algorithm.similarity import Offers, OptionTable, class_rows
from oracle.algorithm.support import followed_at
from oracle.algorithm.records import Option, Ranking, RoutineTask, Step, TreeNode, is_unix_seconds
from oracle.algorithm.tree import Successions, TreeShape, successor_tree
from oracle.errors import SettingsError
from oracle.timeline import TIME_OF_DAY_NAMES

_TOD = {name: code for code, name in enumerate(TIME_OF_DAY_NAMES)}
#: ``fit`` scores the variants on at most this many latest steps by default (``tuning_window``;
#: ``partial_fit`` scores every step). 1,000 until 2026-12-06: 500 halves the scored part of a fit
#: for at most a tenth of a Top-3 point on the development sets of long histories (docs/algorithm.md,
#: "Tuning window").
TUNING_WINDOW = 500


class _Stream:
    """One token stream: its context counts and each past action's predecessor tokens."""

    def __init__(self, max_order: int, depth: int, timed_from: int) -> None:
        self.counts = ContextCounts(max_order, timed_from)
        self.depth = depth
        self.past = PastSituations(depth)  # per past action: its predecessors and their kind

    def forked(self, past: PastSituations) -> _Stream:
        """A stream with forked counts (``ContextCounts.fork``) and the given copy of ``past``."""
        twin = object.__new__(_Stream)
        twin.counts, twin.depth, twin.past = self.counts.fork(), self.depth, past
        return twin

    def recent(self) -> tuple[int, ...]:
        tokens = self.counts.tokens
        return tuple(tokens[-n] if len(tokens) >= n else START for n in range(1, self.depth + 1))


@dataclass
class Evidence:
    """What every variant says about one offer (``RoutineOracle._evidence``): the options' interned
    ids, the lifts' flags (None where a lift is off or does not apply), each variant's distribution
    and the candidates' Algorithm 2 distances to every interned option."""

    ids: list[int]
    inside: np.ndarray | None
    new: np.ndarray | None
    resumed: np.ndarray | None
    probabilities: list[np.ndarray]
    distances: np.ndarray
    #: each variant's blend (its distribution with the context order and count behind each option)
    blends: list[Blend]


def _forked(value: Any) -> Any:
    """``value`` as a hypothetical copy of a model holds it (``RoutineOracle.hypothetical``): a
    value that is replaced, never changed in place (a number, a string, a tuple: the parameters,
    the latest evidence), shared; an array copied; a part of the state with a ``fork`` of its own
    forked; anything else copied whole."""
    if value is None or isinstance(value, (int, float, str, frozenset, tuple)):
        return value
    if isinstance(value, np.ndarray):
        return value.copy()
    fork = getattr(value, "fork", None)
    if fork is not None:
        return fork()
    return pickle.loads(pickle.dumps(value, protocol=pickle.HIGHEST_PROTOCOL))


class RoutineOracle(EstimatorParams):
    """The routine predictor, with the estimator contract of the thesis oracle (style.md).

    ``distances`` is the DistanceMatrix; ``task_factor``, ``object_factor``, ``penalty`` and
    ``time_of_day_penalty`` are the thesis's Table 4.2 values, used in the same roles;
    ``orders``, ``temperatures``, ``lowest_orders``, ``timed`` (part-of-day contexts from order
    ``timed_from``; with ``timed_gate`` only where they differ beyond noise), ``discounts``
    (absolute discounting from order ``discount_from`` once ``discount_evidence`` pairs back an
    order's estimate; the part-of-day levels from ``timed_discount_from``, None: as the rest;
    ``timed_shrink``: a part-of-day level escapes as often as its context has distinct followers
    at any time of day) and
    ``streams`` span the variants that ``tuning`` weighs (``timed_blend``: a timed variant averaged
    with its untimed twin); ``focus`` reweights ``Q`` (``focus_level`` "top": each variant's
    blend) by the user's own lift of the options that use an object of the latest ``focus``
    actions (``focus_odds``: and of those that do not); ``fresh`` reweights each variant's blend
    (``fresh_level`` "base": ``Q``) by the user's own odds of taking an option that was not
    offered at the previous decision; ``resume`` reweights ``Q``, right after an idle gap, by
    the user's own odds of taking an option that once followed the last action; ``recency``
    (bucket edges, seconds) reweights the final ranking by the user's odds per bucket of the time
    since each option was last done, once they lead on Top-1 by ``recency_gate`` standard errors
    (``clock.py``); ``exclusion`` lets the lowest counted
    level escape only to the options it did not count; ``novelty`` (variants) gives the never-done
    options together the PPM-C estimate of a novel action
    ("leader": the best so far that leads the first variant by ``switch_margin`` standard errors,
    "mixture": posterior weights, "fixed": the first variant), which ``fit`` scores on the
    latest ``tuning_window`` steps (``extend`` continues a fit exactly).
    """

    _param_names: tuple[str, ...] = ("distances", "opening_tasks", "orders", "temperatures", "lowest_orders", "timed", "timed_from",
                    "discounts", "discount_from", "discount_evidence", "timed_discount_from", "timed_shrink", "timed_to",
                    "timed_blend", "focus", "focus_level", "focus_odds", "fresh", "fresh_level", "resume", "recency", "recency_gate",
                    "streams",
                    "timed_gate",
                    "exclusion", "novelty",
                    "context_depth", "switch_margin", "context_decay", "tuning", "tuning_window", "task_factor", "object_factor",
                    "penalty",
                    "time_of_day_penalty", "event_horizon_forward")

    def __init__(self, distances: Any = None, *, opening_tasks: frozenset[str] = frozenset(),
                 orders: tuple[int, ...] = (3, 5), temperatures: tuple[float, ...] = (0.5, 2.0),
                 lowest_orders: tuple[int, ...] = (0, 1), timed: tuple[bool, ...] = (True,),
                 timed_from: int = 0, discounts: tuple[bool, ...] = (True,), discount_from: int = 2,
                 discount_evidence: int = 100, timed_discount_from: int | None = None, timed_shrink: bool = False,
                 timed_to: int | None = None, timed_blend: float | None = None,
                 focus: int = 3, focus_level: str = "base", focus_odds: bool = True, fresh: bool = True,
                 fresh_level: str = "top", resume: bool = True,
                 recency: tuple[float, ...] = EDGES, recency_gate: float = 2.0,
                 streams: tuple[str, ...] = ("idle",), timed_gate: float | None = None,
                 exclusion: bool = False,
                 novelty: tuple[bool, ...] = (False, True),
                 context_depth: int = 3, context_decay: float = 0.5,
                 tuning: str = "leader", tuning_window: int = TUNING_WINDOW, switch_margin: float = 2.0,
                 task_factor: float = THESIS_DEFAULTS.task_factor,
                 object_factor: float = THESIS_DEFAULTS.object_factor, penalty: float = THESIS_DEFAULTS.penalty,
                 time_of_day_penalty: float = THESIS_DEFAULTS.time_of_day_penalty,
                 event_horizon_forward: int = THESIS_DEFAULTS.event_horizon_forward) -> None:
        self.distances = distances
        self.opening_tasks = opening_tasks
        self.orders = orders
        self.temperatures = temperatures
        self.lowest_orders = lowest_orders
        self.timed = timed
        self.timed_from = timed_from
        self.discounts = discounts
        self.discount_from = discount_from
        self.discount_evidence = discount_evidence
        self.timed_discount_from = timed_discount_from
        self.timed_shrink = timed_shrink
        self.timed_to = timed_to
        self.timed_blend = timed_blend
        self.focus = focus
        self.focus_level = focus_level
        self.focus_odds = focus_odds
        self.fresh = fresh
        self.fresh_level = fresh_level
        self.resume = resume
        self.recency = recency
        self.recency_gate = recency_gate
        self.streams = streams
        self.timed_gate = timed_gate
        self.exclusion = exclusion
        self.novelty = novelty
        self.context_depth = context_depth
        self.context_decay = context_decay
        self.tuning = tuning
        self.tuning_window = tuning_window
        self.switch_margin = switch_margin
        self.task_factor = task_factor
        self.object_factor = object_factor
        self.penalty = penalty
        self.time_of_day_penalty = time_of_day_penalty
        self.event_horizon_forward = event_horizon_forward

    # -- learning -------------------------------------------------------------------------

    def fit(self, history: Iterable[Step]) -> RoutineOracle:
        check_settings(self)
        self._raw_params = tuple(self.get_params().values())
        self.variants_ = tuple(product(self.streams, self.orders, self.temperatures, self.lowest_orders,
                                      self.timed, self.discounts, self.novelty))
        self.weights_ = VariantWeights(len(self.variants_), keep=True)
        self._known = OptionTable(self.distances, self.task_factor, self.object_factor, self.penalty)
        self.options_: list[Option] = self._known.options
        self._streams = {s: _Stream(max(self.orders), self.context_depth,
                                        self.timed_from if any(self.timed) else -1) for s in self.streams}
        self._executed = Rows(1)        # per past action: option id
        self._tod = Rows(1)             # per past action: time-of-day code, -1 unknown
        self._position = Rows(1)        # per past action: its position in the history
        self._next = Rows(1)            # per history position: successor position, -1 none or idle
        self._step_ids = Rows(1)        # per history position: option id, -1 idle
        self.hand_ = FeatureLift()
        self.fresh_ = NewOffers()
        self.resume_ = Resumption()
        self.clock_ = SinceDone(tuple(self.recency))
        self.gate_ = ClockGate(kept=[])
        self.n_steps_ = 0
        self.fitted_steps_: int | None = 0  # the length of the history fit() saw; None once partial_fit
        self._evidence_at: tuple[Any, ...] | None = None  # _evidence's latest answers: key, evidence, ...
        self._grow(list(history))
        return self

    def extend(self, history: Sequence[Step]) -> RoutineOracle:
        """The model ``fit(history)`` gives, from this one, fitted by ``fit`` on the first
        ``fitted_steps_`` steps of ``history`` (the caller vouches for that prefix; the fitted-
        model cache compares digests): the later steps are added, and the variants' scores
        re-cut to the latest ``tuning_window`` steps, bit for bit as a fresh fit would count them."""
        self._check()
        if self.fitted_steps_ is None:
            raise SettingsError("a model changed by partial_fit does not extend; call fit(history)")
        if len(history) < self.fitted_steps_:
            raise SettingsError(f"extend: {len(history)} steps, fewer than the {self.fitted_steps_} fitted")
        self._grow(history)
        return self

    def _grow(self, steps: Sequence[Step]) -> None:
        # scoring a step costs one rank: only the latest tuning_window steps tune a long history
        first_scored = len(steps) - self.tuning_window
        offers: Offers = {}  # a history's steps share a few hundred offers: each interned once
        for position in range(self.n_steps_, len(steps)):
            self._add(steps[position], score=position >= first_scored, offers=offers)
        self.weights_.keep_from(first_scored)
        self.gate_.keep_from(first_scored)
        self.fitted_steps_ = len(steps)

    def partial_fit(self, step: Step) -> RoutineOracle:
        if not hasattr(self, "variants_"):
            return self.fit([step])
        self._check()
        self.fitted_steps_ = None
        self.weights_.kept = None  # every later step is scored: nothing is re-cut
        self.gate_.kept = None
        self._add(step, score=True)
        return self

    def hypothetical(self) -> RoutineOracle:
        """A copy of the fitted model to learn steps that were not done (the predicted chain,
        oracle.algorithm.chaining): what it learns never reaches this model, and it ranks as a
        pickled copy would. Nothing is pickled: the interned options' tables and the context
        counts, most of a model's bytes, are shared until one of the two would change them
        (``OptionTable.fork``, ``ContextCounts.fork``), the rest is copied by each part's own
        ``fork`` (``_forked``)."""
        if not hasattr(self, "variants_"):
            return cast(RoutineOracle, pickle.loads(pickle.dumps(self, protocol=pickle.HIGHEST_PROTOCOL)))
        twin = object.__new__(type(self))
        twin.__dict__.update({name: self._fork_part(name, value) for name, value in self.__dict__.items()
                              if name not in ("_known", "options_", "_streams")})
        twin._known = self._known.fork()
        twin.options_ = twin._known.options
        twin._streams = {name: stream.forked(stream.past.fork()) for name, stream in self._streams.items()}
        return twin

    def _fork_part(self, name: str, value: Any) -> Any:
        """The attribute ``name`` as the hypothetical copy holds it: the settings (the distance
        matrix among them) shared, learning never changes them; the rest ``_forked``."""
        return value if name in self._param_names else _forked(value)

    def _check(self) -> None:
        if not hasattr(self, "variants_"):
            raise SettingsError(f"{type(self).__name__} is not fitted; call fit(history) first")
        if tuple(self.get_params().values()) != self._raw_params:
            raise SettingsError("parameters changed since fit; call fit(history) again")

    def _add(self, step: Step, score: bool, offers: Offers | None = None) -> None:
        """Count a step (``score``: after the variants ranked its offer); ``offers`` keeps the
        interned ids of each offer met (by identity: an option keeps its id once interned)."""
        if not isinstance(step, Step):
            raise TypeError(f"history entries must be Step records, got {type(step).__name__}")
        scored = score and self.tuning != "fixed" and not step.idle and bool(step.options)  # "fixed" needs no scores
        if scored:
            offered, _ = offered_options(step, None)
            if step.option in offered:
                seen = self._evidence(offered, step.time_of_day)
                ids, probabilities = seen.ids, seen.probabilities
                truth = offered.index(step.option)
                clock = self.clock_.weights(self.clock_.buckets(ids, step.time))
                if clock is not None:  # the clock's gate: Top-1 with its odds against without
                    plain = mixed_distribution(self.weights_.weights(self.tuning, self.switch_margin), probabilities)
                    self.gate_.update(plain, reweighted(plain, clock), truth, self.n_steps_)
                self.weights_.update(probabilities, truth, self.n_steps_)
        position = self.n_steps_
        ids, offer = self._known.offer(step.options, offers)
        option = None if step.idle else step.option  # made once: a Step makes a new Option each time
        found = None if option is None else self._known.ids.get(option)
        if option is not None and ids:
            counted = decision(ids, found, offer)
            if counted is not None:
                self._observe(*counted, step.time)
            self.fresh_.offer = offer
        if option is None:
            token = IDLE
        else:
            token = self._known.intern(option) if found is None else found
            if position > 0 and self._step_ids.view[position - 1, 0] != IDLE:
                self._next.view[position - 1, 0] = position
            code = _TOD.get(step.time_of_day or "", -1)
            for stream in self._streams.values():
                stream.past.add(stream.recent(), code)
            self._executed.append(token)
            self._tod.append(code)
            self._position.append(position)
            self.resume_.follow(token)
            self.clock_.done(token, step.time)
        part = _TOD.get(step.time_of_day or "", -1)
        for name, stream in self._streams.items():
            if name == "idle" or token != IDLE:
                stream.counts.add(token, part)
        self._step_ids.append(token)
        self._next.append(-1)
        self.n_steps_ = position + 1

    # -- ranking --------------------------------------------------------------------------

    def _evidence(self, offered: Sequence[Option], now: str | None) -> Evidence:
        """Every variant's distribution over ``offered`` at part of day ``now`` in the model's
        present state, with what it rests on; the latest answer is kept, since scoring a step and
        the learned rankers' evidence of the same decision (``evidence.features``) ask for it in
        the same state (the number of steps counted is part of the key: nothing else changes the
        counts, and ``fit`` starts afresh)."""
        key = (tuple(offered), now, self.n_steps_)
        kept = self.__dict__.get("_evidence_at")
        if kept is not None:
            # the latest two answers: learning a decision asks for its evidence at the part of day
            # it will be learnt at and at the one it was ranked at (the predicted chain's first step)
            for at in (0, 2):
                if len(kept) > at and kept[at] == key:
                    return cast(Evidence, kept[at + 1])
        ids = self._offer_ids(offered)
        inside = self._in_focus(offered, ids=ids) if self.focus else None
        new, resumed = self._offer_flags(ids)
        probabilities, blends, cand = self._variant_probabilities(offered, ids, now, None, inside, new, resumed)
        seen = Evidence(ids, inside, new, resumed, probabilities, cand, blends)
        self._evidence_at = (key, seen) if kept is None or kept[0][2] != key[2] else (key, seen, *kept[:2])
        return seen

    def _in_focus(self, offered: Sequence[Option], held: frozenset[str] | None = None,
                  ids: Sequence[int] | None = None) -> np.ndarray:
        """Per offered option: does it use an object of the latest ``focus`` actions (``held``)?
        ``ids``: their interned ids (``_offer_ids``), whose objects are kept."""
        objects = self._known.objects
        used = ((option.objects() for option in offered) if ids is None else
                (objects[i] if i >= 0 else option.objects() for i, option in zip(ids, offered)))
        return in_focus(self._held() if held is None else held, used)

    def _observe(self, offered: list[int], truth: int, now: float | None) -> None:
        """Count a decision (interned ids offered, the index of the option done, its time) for the lifts."""
        self.clock_.observe(self.clock_.buckets(offered, now), truth)
        if self.focus:
            held, objects = self._held(), self._known.objects
            self.hand_.observe([not held.isdisjoint(objects[i]) for i in offered], truth)
        if self.fresh:
            self.fresh_.observe(offered, truth)
        if self.resume and self._paused():
            self.resume_.observe(offered, truth)

    def _offer_ids(self, offered: Sequence[Option]) -> list[int]:
        """The interned id of each offered option (UNKNOWN for one never met)."""
        return [self._known.ids.get(option, UNKNOWN) for option in offered]

    def _paused(self) -> bool:
        """Whether the history ends with an idle gap (the user paused right before now)."""
        return self.n_steps_ > 0 and self._step_ids.view[self.n_steps_ - 1, 0] == IDLE

    def _offer_flags(self, ids: list[int]) -> tuple[np.ndarray | None, np.ndarray | None]:
        """Per offered option (interned ids): was it not offered at the latest decision (None
        without ``fresh``), and, right after a gap, did it ever follow the last action (None otherwise)?"""
        return (self.fresh_.which(ids) if self.fresh else None,
                self.resume_.which(ids, self._paused()) if self.resume else None)

    def _held(self) -> frozenset[str]:
        """The objects of the latest ``focus`` actions (idle gaps skipped), worked out once per
        state of the history."""
        kept: tuple[int, frozenset[str]] | None = self.__dict__.get("_held_at")
        if kept is not None and kept[0] == self._executed.size:
            return kept[1]
        recent = self._executed.view[-self.focus:, 0].tolist() if self.focus and self._executed.size else []
        held = held_objects(self._known.objects[t] for t in recent)
        self._held_at = (self._executed.size, held)
        return held

    def _variant_probabilities(self, offered: Sequence[Option], ids: list[int], now: str | None,
                               which: Sequence[int] | None = None, inside: np.ndarray | None = None,
                               new: np.ndarray | None = None, resumed: np.ndarray | None = None
                               ) -> tuple[list[np.ndarray], list[Blend], np.ndarray]:
        """The distribution over ``offered`` (``ids``: their interned ids, ``_offer_ids``) and the
        blend of each variant in ``which`` (default: all), and the candidates' Algorithm 2
        distances to every interned option (``inside``:
        which offered options are in focus, None without focus; ``new``: which were not offered
        at the previous decision, None without ``fresh``; ``resumed``: after a gap, which once
        followed the last action, None otherwise)."""
        count = len(self.options_)
        known = UNKNOWN not in ids
        if known:
            cand = self._known.table[ids, :count]
        else:
            cand = self._known.distances(class_rows(self.distances, offered), self._known.classes[:count])
        executed = self._executed.view[:, 0]
        now_code = _TOD.get(now, -1) if now is not None else -1
        table = self._known.table[:count, :count]
        chosen = [self.variants_[v] for v in (range(len(self.variants_)) if which is None else which)]
        # per stream, per kind of past action: its context distance and whether its part of day differs
        context = {name: context_distance(table, s.recent(), s.past.kind_before.view, self.penalty, self.context_decay)
                   for name, s in self._streams.items() if any(v[0] == name for v in chosen)}
        differs = {name: self._streams[name].past.differs(now_code) for name in context}
        base: dict[tuple[str, float], np.ndarray] = {}
        focus, top = split_weights(self.hand_.weights(inside, self.focus_odds), self.fresh_.lift.weights(new, True),
                                   self.fresh_level == "top")
        focus = combined(focus, self.resume_.lift.weights(resumed, True))
        blends: dict[tuple[str, int, float, int, bool, bool, bool], Blend] = {}
        probabilities = []
        memo: Memo = {}  # the counts' look-ups, shared by the variants (same candidates, same counts)
        # variants alike but for the order, the temperature, the lowest order and the novelty:
        # one blend pass (orders as stops; per lowest order and novelty a lane of bases as rows)
        groups: dict[tuple[str, bool, bool], dict[tuple[int, bool], tuple[list[int], list[float]]]] = {}
        blended = self.timed_blend is not None and now_code >= 0
        for stream, order, tau, lowest, timed, discount, novel in chosen:
            # with timed_blend a timed variant also needs its untimed twin
            for clocked in ((timed, False) if timed and blended else (timed,)):
                stops, taus = groups.setdefault((stream, clocked, discount), {}).setdefault((lowest, novel), ([], []))
                if order not in stops:
                    stops.append(order)
                if tau not in taus:
                    taus.append(tau)
        for (stream, timed, discount), lanes in groups.items():
            stops = sorted({order for lane_stops, _ in lanes.values() for order in lane_stops})
            for _, taus in lanes.values():
                for tau in taus:
                    if (stream, tau) not in base:
                        mass = similarity_mass(cand, executed, context[stream], differs[stream], tau,
                                               self.time_of_day_penalty, self._streams[stream].past.kind_of.view[:, 0],
                                               self._known.decayed(tau)[ids] if known else None)
                        if focus is not None and self.focus_level == "base":
                            mass = normalised(mass) * focus
                        base[stream, tau] = normalised(mass)
            found = self._streams[stream].counts.lane_blends(
                ids, [(np.stack([base[stream, tau] for tau in taus]), lowest, novel)
                      for (lowest, novel), (_, taus) in lanes.items()],
                stops, now_code if timed else -1, discount, self.timed_gate, self.exclusion, memo,
                self.discount_from, self.discount_evidence, self.timed_discount_from, self.timed_shrink, self.timed_to)
            for ((lowest, novel), (lane_stops, taus)), lane in zip(lanes.items(), found):
                for order in lane_stops:
                    rows = lane[order]
                    for row, tau in enumerate(taus):
                        blends[stream, order, tau, lowest, timed, discount, novel] = Blend(
                            rows.probabilities[row], rows.order, rows.count)
        if blended:  # a timed variant: its chain and the untimed twin's, averaged
            weight = float(self.timed_blend)  # type: ignore[arg-type]
            for variant in chosen:
                if variant[4]:
                    twin = blends[variant[:4] + (False,) + variant[5:]]
                    timed_blend = blends[variant]
                    blends[variant] = Blend((1 - weight) * timed_blend.probabilities + weight * twin.probabilities,
                                            timed_blend.order, timed_blend.count)
        if focus is not None and self.focus_level == "top":
            for variant in chosen:
                b = blends[variant]
                blends[variant] = Blend(b.probabilities * focus, b.order, b.count)
        if top is not None:
            for variant in chosen:
                b = blends[variant]
                blends[variant] = Blend(b.probabilities * top, b.order, b.count)
        for variant in chosen:
            probabilities.append(blends[variant].probabilities)
        return probabilities, [blends[v] for v in chosen], cand

    def rank(self, current: Step | Iterable[Option], time_of_day: str | None = None, *,
             tree_roots: int | None = 3, present_objects: Iterable[str] | None = None,
             at: float | None = None, explain: bool = True) -> Ranking:
        """Rank the available options of ``current`` (a Step, or options plus ``time_of_day``;
        ``at``: the decision's unix seconds, default the Step's ``time``), most probable first
        (ties: the order offered); the model is not changed. Without ``explain`` the ranking is
        the same but its tasks carry no support (context, situations, trees, lifts): what the
        predicted chain reads of its hypothetical steps is their order alone."""
        self._check()
        offered, now = offered_options(current, time_of_day)
        when = at if at is not None else current.time if isinstance(current, Step) else None
        if when is not None and not is_unix_seconds(when):
            raise SettingsError(f"rank: at must be finite unix seconds or None, got {when!r}")
        if not offered:
            return Ranking(())
        weights = self.weights_.weights(self.tuning, self.switch_margin)
        used = np.flatnonzero(weights > 0).tolist()  # the leader alone, unless mixing
        if not explain:  # every variant's distributions, as scoring this offer next will read them
            seen = self._evidence(offered, now)
            _, mixed = self._mixed(weights, used, [seen.probabilities[v] for v in used], seen.ids, when)
            order = sorted(range(len(offered)), key=lambda i: (-mixed[i], i))
            return Ranking(tuple(RoutineTask(rank, -math.log2(mixed[i]) if mixed[i] > 0 else math.inf, offered[i], 0,
                                             math.inf, (), float(mixed[i])) for rank, i in enumerate(order, start=1)))
        held = self._held()
        ids = self._offer_ids(offered)
        inside = self._in_focus(offered, held, ids) if self.focus else None
        new, resumed = self._offer_flags(ids)
        lifted, goes_on = tells_apart(new), tells_apart(resumed)
        probabilities, blends, cand = self._used_evidence(offered, ids, now, used, inside, new, resumed)
        clock, mixed = self._mixed(weights, used, probabilities, ids, when)
        ago = self.clock_.ages(ids, when, clock is not None)
        lead = int(np.argmax(weights[used]))
        leading = blends[lead]
        stream = self._streams[self.variants_[used[lead]][0]]
        order = sorted(range(len(offered)), key=lambda i: (-mixed[i], i))
        nearest = cand.min(axis=1) if cand.shape[1] else np.full(len(offered), math.inf)
        present = frozenset(present_objects) if present_objects is not None else frozenset(
            obj for option in offered for obj in option.objects())
        tasks = []
        for rank, i in enumerate(order, start=1):
            option, n = offered[i], int(leading.order[i])
            context = stream.counts.context(n) if n > 0 else ()
            situations = self._support(stream, self._known.ids.get(option, UNKNOWN), context or (), n)
            successors: tuple[TreeNode, ...] = ()
            if situations and (tree_roots is None or rank <= tree_roots):
                successors = successor_tree(
                    np.array(situations, dtype=np.int64), np.ones(len(situations)),
                    Successions(self._next.view[:, 0], np.maximum(self._step_ids.view[:, 0], 0), self.options_),
                    TreeShape(self.event_horizon_forward, 1.0, present, frozenset(self.opening_tasks)),
                    option.task not in self.opening_tasks)
            probability = float(mixed[i])
            tasks.append(RoutineTask(
                rank, -math.log2(probability) if probability > 0 else math.inf, option,
                int(leading.count[i]) if n >= 0 else 0, float(nearest[i]), successors, probability, n,
                tuple(self._label(t) for t in context or ()), tuple(situations[-5:]) if n >= 0 else (),
                tuple(obj for obj in option.objects() if obj in held) if inside is not None else (),
                lifted and bool(new[i]), goes_on and bool(resumed[i]), ago[i]))  # type: ignore[index]
        return Ranking(tuple(tasks))

    def _used_evidence(self, offered: Sequence[Option], ids: list[int], now: str | None, used: list[int],
                       inside: np.ndarray | None, new: np.ndarray | None, resumed: np.ndarray | None
                       ) -> tuple[list[np.ndarray], list[Blend], np.ndarray]:
        """What ``rank`` reads of the ``used`` variants (``_variant_probabilities`` of those alone);
        a subclass that reads every variant's evidence of the same offer anyway takes them from
        there (each variant's distribution is the same computed alone or with the others)."""
        return self._variant_probabilities(offered, ids, now, used, inside, new, resumed)

    def _mixed(self, weights: np.ndarray, used: list[int], probabilities: list[np.ndarray], ids: list[int],
               when: float | None) -> tuple[np.ndarray | None, np.ndarray]:
        """The clock's weights (None where they do not weigh) and ``P(c | offered)``: the ``used``
        variants' distributions mixed by ``weights``, reweighted by the clock's odds once its gate is open."""
        mixed = mixed_distribution(weights[used], probabilities)
        clock = self.clock_.weights(self.clock_.buckets(ids, when)) if self.gate_.open(self.recency_gate) else None
        if clock is not None:
            mixed = reweighted(mixed, clock)
        return clock, mixed

    def _support(self, stream: _Stream, option_id: int, context: tuple[int, ...], n: int) -> list[int]:
        """History positions where ``option_id`` followed ``context`` (all its uses when n is 0)."""
        positions = self._position.view[:, 0]
        index = np.arange(self._executed.size) if stream is self._streams.get("through") else positions
        return followed_at(self._executed.view[:, 0], positions, stream.past.before.view, stream.counts.tokens, index,
                           option_id, context, n)

    def _label(self, token: int) -> str:
        return "idle" if token == IDLE else str(self.options_[token])
