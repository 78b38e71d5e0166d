"""Replay chains with the stacked or online predictor, the routine predictor, the learned baselines and a
few token baselines under the honest replay rules; print Top-1/3/5 and the paired Top-3
difference of the first method against each other one (95 % bootstrap interval), then each
method's Top-1/3/5 over each user's first 30 predictions (the cold start).

usage: python experiments/learned-dev.py CHAINS [--odb DIR --mapping YAML] [--users N]
       [--methods stacked,routine,logit,gbdt,kn3,ngram] [--stacked NAME=JSON] [--online NAME=JSON]
       [--pooled NAME=JSON]
Development use only (docs/algorithm.md, "Stacked predictor" and "Online predictor": the selection protocol).
"""

from __future__ import annotations

import argparse
import json
import sys
from collections import OrderedDict
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "python"))
from oracle.algorithm.params import Hyperparameters  # noqa: E402
from oracle.algorithm.online import OnlineOracle  # noqa: E402
from oracle.algorithm.pooled import PooledOracle  # noqa: E402
from oracle.algorithm.stacked import StackedOracle  # noqa: E402
from oracle.calls import opening_tasks  # noqa: E402
from oracle.ontology import build_ontology  # noqa: E402
from oracle.evaluation.baselines import BASELINES  # noqa: E402
from oracle.evaluation.learned import Evidence, Gbdt, OnlineLogit  # noqa: E402
from oracle.evaluation.replay import OracleMethod, ReplayRules, load_users, replay, summarize  # noqa: E402
from oracle.evaluation.statistics import cold_start_summary, comparison_summary  # noqa: E402


class Configured(OracleMethod):
    """The stacked (or online) predictor with settings given as JSON."""

    def __init__(self, ontology, name: str, settings: dict, cls: type = StackedOracle) -> None:
        self.extra = settings
        self.cls = cls
        super().__init__(ontology, Hyperparameters(), name=name, method="stacked", served=True)

    def reset(self) -> None:
        self.model = self.cls(self.distances, opening_tasks=self.opening, **self.extra).fit([])
        self.history = []


def main() -> int:
    parser = argparse.ArgumentParser()
    parser.add_argument("chains")
    parser.add_argument("--odb")
    parser.add_argument("--mapping")
    parser.add_argument("--users", type=int, default=0)
    parser.add_argument("--methods", default="stacked,routine,logit,gbdt,kn3,ngram")
    parser.add_argument("--stacked", action="append", default=[], help="NAME=JSON settings of another stacked row")
    parser.add_argument("--online", action="append", default=[], help="NAME=JSON settings of another online row")
    parser.add_argument("--pooled", action="append", default=[], help="NAME=JSON settings of another pooled row")
    args = parser.parse_args()
    ontology = build_ontology(args.odb, args.mapping)
    users = load_users(args.chains)
    if args.users:
        users = OrderedDict(list(users.items())[:args.users])
    evidence = Evidence(ontology.distances(), opening_tasks(ontology))
    methods = []
    for name in args.methods.split(","):
        if name in ("stacked", "online", "pooled", "routine", "routine-fixed", "thesis"):
            methods.append(OracleMethod(ontology, Hyperparameters(), method=name, served=True))
        elif name == "logit":
            methods.append(OnlineLogit(evidence))
        elif name == "gbdt":
            methods.append(Gbdt(evidence))
        else:
            methods.append(BASELINES[name]())
    for spec in args.stacked:
        label, _, text = spec.partition("=")
        methods.append(Configured(ontology, label, json.loads(text)))
    for spec in args.online:
        label, _, text = spec.partition("=")
        methods.append(Configured(ontology, label, json.loads(text), OnlineOracle))
    for spec in args.pooled:
        label, _, text = spec.partition("=")
        methods.append(Configured(ontology, label, json.loads(text), PooledOracle))
    result = replay(ontology, users, methods, 0, None, ReplayRules())
    summary = summarize(result)
    names = result.methods()
    paired = comparison_summary(result.outcomes, names[0], names[1:], 0)["methods"]
    print(f"{args.chains}: {summary['n_predictions']} predictions, {len(users)} users")
    for name in names:
        m = summary["methods"][name]
        line = f"{name:24s} {m['top1']:.3f} {m['top3']:.3f} {m['top5']:.3f} {m['ms_per_prediction']:6.2f} ms"
        if name in paired:
            d = paired[name]["top3"]
            line += f"  top3 {names[0]} - this: {-100 * d['difference']:+.2f} [{-100 * d['high']:+.2f}, {-100 * d['low']:+.2f}]"
        print(line)
    cold = cold_start_summary(result)
    print(f"cold start (each user's first {cold['first_predictions']} predictions, {cold['n_predictions']} in all):")
    for name in names:
        c = cold["methods"][name]
        print(f"  {name:22s} {c['top1']:.3f} {c['top3']:.3f} {c['top5']:.3f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
