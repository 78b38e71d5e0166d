"""Chain accuracy: how often the 2nd and 3rd predicted steps of the default predictor's chain are
the user's next actions, plain chaining against feasible chaining (docs/evaluation.md, "Chains").

At every decision t of the honest replay (``ReplayRules()``), the predictor ranks the offer; its
first option is taken as done (a copy of the model, ``partial_fit`` of that hypothetical step) and
the next step is ranked:
- tree: the forward tree of the first option (thesis Fig. 4.6, ``successors``): the options that
  followed its past situations, and for step 3 those under the tree's best child (the thesis
  oracle's chain, and the routine predictors' until 2026-12-06);
- plain: over the same offer (what the robot can offer now);
- feasible: over what was available after the same action before (the offer of the decision that
  followed the user's latest execution of that option: the task inference of a log without a world
  model; none, so the chain ends and its later steps count as misses, where no decision ever
  followed that option without a break), kept to the options the user did before when the data
  has no available sets (the replay's candidate rule): the routine predictors' chain in ``rank``,
  the service and the page, computed by the same code (``oracle.algorithm.chaining``);
- rules (with ``--world``, for data the kitchen world made): over what the world's task inference
  makes available once the predicted step is done (``World.apply``, then ``World.available``), from
  the world's state at the decision. That state is tracked by applying every action done, and
  taken afresh from the world's initial state (the kitchen tidied overnight) where the tracked
  state's available tasks are not the row's offer; a decision where neither matches has no rules
  chain (counted as ``rules_untracked``; its rules ranks count as misses).
Step 3 repeats this from the predicted step 2. Step k is scored at t only where actions t .. t+k-1
exist with no idle gap between (the chain is one activity); a hit at Top-j means the action t+k-1 is
among the first j options of the step's ranking. Intervals: the paired bootstrap of
``oracle.evaluation.statistics`` over users (blocks of one user's predictions on sets with few users).

usage: python experiments/chains.py CHAINS [--odb DIR --mapping YAML] [--users N] [--method NAME]
       [--world [FILE]] [--json OUT]
(``--method``: a predictor of the registry, by default the default predictor)
"""

from __future__ import annotations

import argparse
import json
import pickle
import sys
from collections import OrderedDict
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "python"))
from oracle.algorithm.chaining import Afterwards, rankings_ahead  # noqa: E402
from oracle.algorithm.params import Hyperparameters  # noqa: E402
from oracle.algorithm.predictors import DEFAULT  # noqa: E402
from oracle.algorithm.records import Option, Step  # noqa: E402
from oracle.evaluation.replay import KS, OracleMethod, Outcome, ReplayRules, load_users, replay  # noqa: E402
from oracle.evaluation.statistics import comparison_summary  # noqa: E402
from oracle.calls import option_of  # noqa: E402
from oracle.chains import TaskCall, parse_call  # noqa: E402
from oracle.errors import NeemOracleError  # noqa: E402
from oracle.ontology import build_ontology  # noqa: E402
from oracle.world.rules import World  # noqa: E402
from oracle.world.state import State  # noqa: E402
from oracle.world.worldfile import load_world  # noqa: E402


class Chaining(OracleMethod):
    """The predictor, recording at each decision its plain and feasible 2nd and 3rd steps (and,
    with ``world``, the chain the world's rules allow)."""

    def __init__(self, ontology: Any, settings: Hyperparameters, method: str, world: World | None = None) -> None:
        self.world = world
        self.ontology = ontology
        self.untracked = 0
        super().__init__(ontology, settings, method=method, served=True)

    def reset(self) -> None:
        super().reset()
        self.chains: list[dict[str, list[list[Option]]]] = getattr(self, "chains", [])
        self.afterwards = Afterwards()   # option -> the offer of the decision after it (the product's rule)
        self.state: State | None = None if self.world is None else self.world.initial_state()

    def _calls(self, state: State) -> dict[Option, TaskCall]:
        """What the world makes available in ``state``, as options with their calls (two calls of
        one option, objects of one class: the one listed last)."""
        assert self.world is not None
        return {option_of(self.ontology, call): call for call in self.world.available(state)}

    def _tracked(self, offer: set[Option]) -> State | None:
        """The world's state at this decision: the tracked one, or the initial one, whichever makes
        the row's offer available; None when neither does."""
        assert self.world is not None
        for state in (self.state, self.world.initial_state()):
            if state is not None and set(self._calls(state)) == offer:
                self.state = state
                return state
        self.state = None
        return None

    def rank(self, candidates: Any, time_of_day: str | None = None, at: float | None = None) -> list[Option]:
        ranking = self.model.rank(list(candidates), time_of_day, tree_roots=1, at=at)
        order = list(ranking.options())
        record: dict[str, list[list[Option]]] = {"plain": [], "feasible": [], "tree": []}
        state = self._tracked(set(candidates)) if self.world is not None else None
        if self.world is not None:
            record["rules"] = [[], []]
            self.untracked += state is None
        # the forward tree of the first option (thesis Fig. 4.6): what followed its past situations
        children = ranking.tasks[0].successors if ranking.tasks else ()
        record["tree"] = [[n.option for n in children], [n.option for n in children[0].children] if children else []]
        # feasible: the product's predicted chain (oracle.algorithm.chaining), its rankings at steps 2 and 3
        record["feasible"] = [list(r.options()) for r in rankings_ahead(
            self.model, ranking, list(candidates), self.afterwards, time_of_day, at, 3)]
        record["feasible"] += [[]] * (2 - len(record["feasible"]))
        for kind in ("plain",) if state is None else ("plain", "rules"):
            model, offer, first = self.model, list(candidates), order[0] if order else None
            record[kind] = []
            for _ in range(2):
                if first is None:
                    record[kind].append([])
                    continue
                model = pickle.loads(pickle.dumps(model))
                model.partial_fit(Step(first.task, first.target, first.reference, tuple(offer), time_of_day, False,
                                       str(first), at))
                if kind == "rules":
                    assert self.world is not None and state is not None
                    state = self.world.apply(state, self._calls(state)[first])
                    offer = list(self._calls(state))
                nxt = list(model.rank(offer, time_of_day, tree_roots=0, at=at).options()) if offer else []
                record[kind].append(nxt)
                first = nxt[0] if nxt else None
        self.chains.append(record)
        return order

    def observe(self, step: Step) -> None:
        self.afterwards.add(step)
        if not step.idle and self.world is not None and self.state is not None:
            try:
                self.state = self.world.apply(self.state, parse_call(step.label))
            except NeemOracleError:  # not feasible in the tracked state: tracked afresh at the next decision
                self.state = None
        super().observe(step)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("chains")
    parser.add_argument("--odb")
    parser.add_argument("--mapping")
    parser.add_argument("--users", type=int, default=0)
    parser.add_argument("--method", default=DEFAULT, help=f"predictor (default {DEFAULT})")
    parser.add_argument("--world", nargs="?", const="", default=None, metavar="FILE",
                        help="also chain by the kitchen world's rules (FILE: a world file; none: the shipped one)")
    parser.add_argument("--json", type=Path)
    args = parser.parse_args()
    world = None if args.world is None else load_world(args.world or None)
    ontology = build_ontology(args.odb, args.mapping)
    users = load_users(args.chains)
    if args.users:
        users = OrderedDict(list(users.items())[:args.users])
    method = Chaining(ontology, Hyperparameters(), args.method, world)
    kinds = ("plain", "feasible", "tree") + (("rules",) if world is not None else ())
    result = replay(ontology, users, [method], 0, None, ReplayRules())
    # which decisions were ranked (a decision with no candidates is not), in replay order
    ranked = iter(method.chains)
    chains = [next(ranked) if o.n_candidates else None for o in result.outcomes]
    outcomes: list[Outcome] = []
    by_user: dict[str, list[int]] = {}
    for i, o in enumerate(result.outcomes):
        by_user.setdefault(o.user, []).append(i)
    for user, positions in by_user.items():
        rows_of = users[user]
        for j, i in enumerate(positions):
            record = chains[i]
            if record is None:
                continue
            for depth in (2, 3):
                later = j + depth - 1
                if later >= len(positions) or _gap(rows_of, j, later):
                    continue
                truth = option_of(ontology, rows_of[later].action)
                ranks: dict[str, int | None] = {}
                for kind in kinds:
                    listed = record.get(kind, [[], []])[depth - 2]  # no rules chain: a miss
                    ranks[kind] = listed.index(truth) + 1 if truth in listed else None
                outcomes.append(Outcome(f"{user}", depth * 1_000_000 + j, 0, True, ranks, dict.fromkeys(ranks, 0.0)))
    report: dict[str, Any] = {"set": args.chains, "method": args.method, "users": len(users)}
    if world is not None:
        report["rules_untracked"] = method.untracked
        report["decisions"] = len(method.chains)
    for depth in (2, 3):
        chosen = [o for o in outcomes if o.index // 1_000_000 == depth]
        entry: dict[str, Any] = {"n": len(chosen)}
        for kind in kinds:
            entry[kind] = {f"top{k}": sum(1 for o in chosen if (r := o.ranks[kind]) is not None and r <= k)
                           / max(1, len(chosen)) for k in KS}
        paired = comparison_summary(chosen, "plain", [kind for kind in kinds if kind != "plain"], 0)["methods"]
        entry["feasible_minus_plain"], entry["tree_minus_plain"] = paired["feasible"], paired["tree"]
        if "rules" in paired:
            entry["rules_minus_plain"] = paired["rules"]
            entry["rules_minus_feasible"] = comparison_summary(chosen, "feasible", ["rules"], 0)["methods"]["rules"]
        report[f"step{depth}"] = entry
        print(f"step {depth} ({len(chosen)} predictions): " + "; ".join(
            f"top{k} plain {entry['plain'][f'top{k}']:.3f} feasible {entry['feasible'][f'top{k}']:.3f} "
            f"tree {entry['tree'][f'top{k}']:.3f} "
            f"diff {100 * entry['feasible_minus_plain'][f'top{k}']['difference']:+.2f} "
            f"[{100 * entry['feasible_minus_plain'][f'top{k}']['low']:+.2f}, "
            f"{100 * entry['feasible_minus_plain'][f'top{k}']['high']:+.2f}]"
            + (f" rules {entry['rules'][f'top{k}']:.3f}" if "rules" in entry else "") for k in KS))
    if args.json is not None:
        args.json.write_text(json.dumps(report, indent=1) + "\n", encoding="utf-8")
    return 0


def _gap(rows: list[Any], first: int, last: int) -> bool:
    """Whether an idle gap lies between rows ``first`` and ``last`` (the chain ended)."""
    from oracle.timeline import is_idle_gap, seconds_of

    for a, b in zip(rows[first:last], rows[first + 1:last + 1]):
        if a.time is not None and b.time is not None and is_idle_gap(
                seconds_of(a.end if a.end is not None else a.time), seconds_of(b.time)):
            return True
    return False


if __name__ == "__main__":
    sys.exit(main())
