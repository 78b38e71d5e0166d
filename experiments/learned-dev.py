"""Replay chains with the stacked or online predictor, the routine predictor, the learned baselines and a
few token baselines under the honest replay rules; print Top-1/3/5 and the paired Top-3
difference of the first method against each other one (95 % bootstrap interval), then each
method's Top-1/3/5 over each user's first 30 predictions (the cold start).

usage: python experiments/learned-dev.py CHAINS [--odb DIR --mapping YAML] [--users N]
       [--methods stacked,routine,logit,gbdt,kn3,ngram] [--stacked NAME=JSON] [--online NAME=JSON]
       [--pooled NAME=JSON] [--batch NAME=JSON] [--digits 3]
Development use only (docs/algorithm.md, "Stacked predictor" and "Online predictor": the selection protocol).
"""

from __future__ import annotations

import argparse
import json
import sys
from collections import OrderedDict
from pathlib import Path

import numpy as np
from scipy.optimize import minimize

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


class BatchLogit(OnlineLogit):
    """A conditional logit refitted to all the user's decisions (or the latest ``window``) with
    L2 strength ``l2`` by L-BFGS, at the 16th decision and every ``every``-th after it, warm
    started; the online ``logit`` ranks until its first fit. A development trial only: whether
    a fully fitted logit on the same evidence ranks better than the online one."""

    def __init__(self, evidence: Evidence, name: str, l2: float = 1.0, every: int = 32, window: int = 0) -> None:
        self.name, self.l2_batch, self.every, self.window = name, l2, every, window
        super().__init__(evidence)

    def reset(self) -> None:
        super().reset()
        self.decisions: list[tuple[np.ndarray, int]] = []
        self.fitted: np.ndarray | None = None

    def scores(self, x: np.ndarray) -> np.ndarray:
        return x @ self.fitted if self.fitted is not None else super().scores(x)

    def learn(self, x: np.ndarray, truth: int) -> None:
        super().learn(x, truth)
        self.decisions.append((x, truth))
        n = len(self.decisions)
        if n == 16 or (n > 16 and n % self.every == 0):
            self.refit()

    def refit(self) -> None:
        decisions = self.decisions[-self.window:] if self.window else self.decisions
        x = np.concatenate([rows for rows, _ in decisions])
        sizes = np.array([len(rows) for rows, _ in decisions])
        starts = np.concatenate([[0], np.cumsum(sizes)[:-1]])
        segment = np.repeat(np.arange(len(decisions)), sizes)
        done = x[starts + np.array([truth for _, truth in decisions])].sum(axis=0)
        l2 = self.l2_batch

        def loss(w: np.ndarray) -> tuple[float, np.ndarray]:
            u = x @ w
            top = np.maximum.reduceat(u, starts)
            e = np.exp(u - top[segment])
            total = np.add.reduceat(e, starts)
            p = e / total[segment]
            return (float(-(done @ w - (top + np.log(total)).sum()) + 0.5 * l2 * w @ w),
                    p @ x - done + l2 * w)

        start = self.fitted if self.fitted is not None else (self.w if self.w is not None else np.zeros(x.shape[1]))
        self.fitted = minimize(loss, start, jac=True, method="L-BFGS-B", options={"maxiter": 200}).x


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
    parser.add_argument("--digits", type=int, default=3, help="decimals of each Top-k figure")
    parser.add_argument("--batch", action="append", default=[], help="NAME=JSON settings (l2, every, window) of a "
                        "batch-refitted logit row")
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
    for spec in args.batch:
        label, _, text = spec.partition("=")
        methods.append(BatchLogit(evidence, label, **json.loads(text)))
    result = replay(ontology, users, methods, 0, None, ReplayRules())
    summary = summarize(result)
    names = result.methods()
    paired = comparison_summary(result.outcomes, names[0], names[1:], 0)["methods"]
    print(f"{args.chains}: {summary['n_predictions']} predictions, {len(users)} users")
    for name in names:
        m = summary["methods"][name]
        tops = " ".join(f"{m[f'top{k}']:.{args.digits}f}" for k in (1, 3, 5))
        line = f"{name:24s} {tops} {m['ms_per_prediction']:6.2f} ms"
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
