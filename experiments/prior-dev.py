"""Development runs of issue 56 (never reported): the personal predictor against the per-user logit,
the pooled predictor, pop_ppm and ngram on one chains file, with or without leave-one-out priors.

usage: python experiments/prior-dev.py CHAINS [--odb DIR --mapping YAML] [--population loo|none]
       [--k 5] [--epsilon E] [--clip 3] [--methods personal,pooled] [--no-baselines]
Prints overall Top-1/3/5 and each user's first 50 and 200 predictions (Top-3), with the paired
difference against ``logit`` and its 95 % interval.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from oracle.algorithm.params import Hyperparameters
from oracle.commands.common import ONTOLOGY_OPTIONS, add_options, ontology_from
from oracle.evaluation.baselines import NGram
from oracle.evaluation.learned import learned_baselines
from oracle.evaluation.population import PopPPM, leave_one_out
from oracle.evaluation.replay import OracleMethod, ReplayResult, check_users, load_users, replay, summarize
from oracle.evaluation.statistics import compare
from oracle.calls import opening_tasks


def main() -> int:
    parser = argparse.ArgumentParser()
    parser.add_argument("chains", type=Path)
    add_options(parser, *ONTOLOGY_OPTIONS)
    parser.add_argument("--population", default="loo")
    parser.add_argument("--k", type=int, default=5)
    parser.add_argument("--epsilon", type=float, default=None)
    parser.add_argument("--clip", type=int, default=3)
    parser.add_argument("--methods", default="personal")
    parser.add_argument("--no-baselines", action="store_true")
    parser.add_argument("--set", action="append", default=[], metavar="METHOD:NAME=VALUE",
                        help="a predictor parameter for one method column (e.g. personal:routine_start=1)")
    args = parser.parse_args()
    ontology = ontology_from(args)
    users = load_users(args.chains)
    check_users(ontology, users, str(args.chains))
    methods: list = []
    for column in args.methods.split(","):
        method = column.split("@")[0]
        made = OracleMethod(ontology, Hyperparameters(), name=column, method=method, served=True)
        params = {name: float(value) for item in args.set for target, _, pair in [item.partition(":")]
                  if target == column for name, _, value in [pair.partition("=")]}
        if params:
            build = made.reset

            def reset(build=build, made=made, params=params) -> None:
                build()
                made.model.set_params(**params).fit([])
                use = getattr(made.model, "use_prior", None)
                if use is not None:
                    use(made.prior)
            made.reset = reset  # type: ignore[method-assign]
            made.reset()
        methods.append(made)
    if not args.no_baselines:
        methods += [learned_baselines(ontology.distances(), opening_tasks(ontology))[0], PopPPM(), NGram()]
    priors = leave_one_out(ontology, users, args.k, args.epsilon, args.clip) if args.population == "loo" else None
    result = replay(ontology, users, methods, 0, None, priors=priors)
    names = result.methods()
    reference = "logit" if "logit" in names else names[-1]
    for label, outcomes in (("all", result.outcomes), ("first50", [o for o in result.outcomes if o.index < 50]),
                            ("first200", [o for o in result.outcomes if o.index < 200])):
        summary = summarize(ReplayResult(outcomes))
        _, found = compare(outcomes, reference, [n for n in names if n != reference], 0, (3,))
        diffs = {c.method: c for c in found}
        print(f"{label} ({summary['n_predictions']} predictions)")
        for name in names:
            m = summary["methods"][name]
            c = diffs.get(name)
            tail = f"  top3-{reference} {c.difference:+.3f} [{c.low:+.3f}, {c.high:+.3f}]" if c else ""
            print(f"  {name:10s} {m['top1']:.3f} {m['top3']:.3f} {m['top5']:.3f}{tail}")
    sys.stdout.flush()
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
