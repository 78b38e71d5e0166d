"""``python -m oracle evaluate`` and ``python -m oracle tune``: replay chains and score methods."""

from __future__ import annotations

import argparse
import json
import shlex
import sys
import time
from pathlib import Path
from typing import TYPE_CHECKING, Any

from oracle.commands.common import (
    METHOD, ONTOLOGY_OPTIONS, SETTINGS, add_options, method_from, ontology_from, settings_from,
)
from oracle.errors import NeemOracleError

if TYPE_CHECKING:
    from oracle.algorithm.params import Hyperparameters
    from oracle.evaluation.tuning import TuningStep


def register(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    evaluate = subparsers.add_parser("evaluate", help="replay chains and score the oracle against baselines")
    evaluate.add_argument("chains", type=Path, help="chains JSONL file or a folder of them")
    add_options(evaluate, *ONTOLOGY_OPTIONS, METHOD, SETTINGS)
    evaluate.add_argument("--baselines", action="store_true",
                          help="also run the thesis oracle (unless it is --method) and every history-only "
                               "baseline (docs/evaluation.md), compared pairwise with --method")
    evaluate.add_argument("--also", default="", metavar="NAME[,NAME]",
                          help="also replay these predictors of the registry (e.g. stacked), compared with --method")
    evaluate.add_argument("--ablations", action="store_true", help="also replay the thesis Fig. 5.5 settings A-N")
    evaluate.add_argument("--json", type=Path, metavar="OUT", help="write the summary JSON here")
    evaluate.add_argument("--report", type=Path, metavar="FILE.md", help="write a markdown report here")
    evaluate.add_argument("--plots", type=Path, metavar="DIR", help="write PNG plots into DIR")
    evaluate.add_argument("--seed", type=int, default=0, help="seed of the candidate shuffling (default 0)")
    evaluate.add_argument("--candidates", choices=("history", "vocabulary"), default="history",
                          help="a row without available options is offered the user's actions before it "
                               "(history, default) or every action of the user in the file (vocabulary: "
                               "future ones too, the rule of the first published results)")
    evaluate.add_argument("--decision", choices=("previous-end", "start"), default="previous-end",
                          help="rank each decision at the previous action's end, or when an idle gap became one "
                               "(default), or at the true start (the rule of the first published results)")
    evaluate.add_argument("--every-step", action="store_true",
                          help="keep predictors by partial_fit (self-tuning on every step) instead of as rank "
                               "serves them (fit on the history: the latest tuning window)")
    evaluate.add_argument("--population", choices=("none", "loo"), default="none",
                          help="the shared prior each user's predictor ranks with: none, or loo (built from the "
                               "other users of the file only, with --k, --epsilon and --clip; docs/evaluation.md)")
    evaluate.add_argument("--k", type=int, default=5, help="a prior keeps a count only when >= K users gave it (5)")
    evaluate.add_argument("--epsilon", type=float, default=None, help="Laplace noise for epsilon-DP counts (none)")
    evaluate.add_argument("--clip", type=int, default=3, help="at most this much of each count from one user (3)")
    evaluate.set_defaults(handler=run_evaluate)

    tune = subparsers.add_parser("tune", help="tune the hyperparameters by coordinate search (thesis 4.5)")
    tune.add_argument("chains", type=Path, help="tuning chains JSONL file or folder")
    add_options(tune, *ONTOLOGY_OPTIONS)
    tune.add_argument("--metric", choices=("top1", "top3", "top5"), default="top5")
    tune.add_argument("--budget", type=int, default=40, help="number of replays to spend (default 40)")
    tune.add_argument("--start", default="recommended", help="settings YAML or preset to start from")
    tune.add_argument("--out", type=Path, required=True, help="settings YAML to write")
    tune.add_argument("--seed", type=int, default=0)
    tune.set_defaults(handler=run_tune)


def run_evaluate(args: argparse.Namespace) -> int:
    from oracle.evaluation.replay import OracleMethod, ReplayRules, check_users, load_users, make_methods, replay, summarize
    from oracle.progress import bar

    method = method_from(args)
    ontology = ontology_from(args)
    settings = settings_from(args.settings)
    users = load_users(args.chains)
    check_users(ontology, users, str(args.chains))
    started = time.perf_counter()
    rules = ReplayRules(args.candidates, args.decision, not args.every_step)
    methods = make_methods(ontology, settings, args.baselines, method, rules.served)
    for name in (n.strip() for n in args.also.split(",") if n.strip()):
        methods.insert(1, OracleMethod(ontology, settings, method=method_from(argparse.Namespace(method=name)),
                                       served=rules.served))
    priors = None
    if args.population == "loo":
        from oracle.algorithm.prior_counts import check_privacy
        from oracle.evaluation.population import leave_one_out

        check_privacy(args.k, args.epsilon, args.clip)
        priors = leave_one_out(ontology, users, args.k, args.epsilon, args.clip, args.seed)
    with bar("replay", "users", len(users)) as tick:
        result = replay(ontology, users, methods, args.seed, lambda done, total, user: tick(done, total), rules, priors)
    summary = summarize(result)
    summary["protocol"] = {"candidates": rules.candidates, "decision": rules.decision, "served": rules.served}
    summary["method"] = methods[0].name
    names = result.methods()
    if len(names) > 1:
        from oracle.evaluation.statistics import cold_start_summary, comparison_summary

        summary["comparisons"] = comparison_summary(result.outcomes, names[0], names[1:], args.seed)
        summary["cold_start"] = cold_start_summary(result, args.seed)
        summary["first"] = {str(n): cold_start_summary(result, args.seed, n) for n in (50, 200)}
    summary["population"] = {"kind": args.population, "k": args.k, "epsilon": args.epsilon, "clip": args.clip}
    summary["settings"] = settings.to_dict()
    summary["replay_seconds"] = time.perf_counter() - started
    command = "python -m oracle evaluate"
    if sys.argv[1:2] == ["evaluate"]:
        command = "python -m oracle " + " ".join(shlex.quote(a) for a in sys.argv[1:])
    if args.ablations:
        from oracle.evaluation.ablations import run_ablations

        with bar("ablations A-N", "users", len(users)) as tick:
            summary["ablations"] = run_ablations(ontology, users, args.seed, lambda done, total, user: tick(done, total))
    _print_table(summary)
    if args.json is not None:
        _write(args.json, json.dumps(summary, indent=1) + "\n")
    if args.report is not None:
        from oracle.evaluation.report import markdown

        _write(args.report, markdown(summary, command))
    if args.plots is not None:
        from oracle.evaluation import plots

        from oracle.files import private_folder

        private_folder(args.plots)
        made = [plots.box_plots(summary, args.plots), plots.learning_curves(result, args.plots, methods[0].name)]
        if "comparisons" in summary:
            made.append(plots.differences(summary, args.plots))
        if args.ablations:
            made.append(plots.ablation_plot(summary["ablations"], args.plots))
        print("plots: " + ", ".join(str(p) for p in made))
    return 0


def _print_table(summary: dict[str, Any]) -> None:
    print(f"{summary['n_predictions']} predictions, {summary['mean_candidates']:.1f} candidates each on average")
    paired = summary.get("comparisons", {}).get("methods", {})
    extra = f" {'top3 - ' + summary['comparisons']['reference'] + ' [95% CI]':>28s} {'p(Holm)':>8s}" if paired else ""
    print(f"{'method':16s} {'top1':>7s} {'top3':>7s} {'top5':>7s} {'ms/pred':>8s}{extra}")
    for name, entry in summary["methods"].items():
        line = f"{name:16s} {entry['top1']:7.3f} {entry['top3']:7.3f} {entry['top5']:7.3f} {entry['ms_per_prediction']:8.2f}"
        if name in paired:
            d = paired[name]["top3"]
            line += f" {d['difference']:+9.3f} [{d['low']:+.3f}, {d['high']:+.3f}] {d['p_holm']:8.2g}"
        print(line)
    for n, block in summary.get("first", {}).items():
        vs = block.get("comparisons", {}).get("methods", {})
        cells = []
        for name, entry in block["methods"].items():
            d = vs.get(name, {}).get("top3")
            cells.append(f"{name} {entry['top3']:.3f}" + (f" ({d['difference']:+.3f} [{d['low']:+.3f}, {d['high']:+.3f}])"
                                                          if d else ""))
        print(f"first {n} per user, top3: " + "; ".join(cells))
    chance = summary["chance"]
    print(f"{'chance':16s} {chance['top1']:7.3f} {chance['top3']:7.3f} {chance['top5']:7.3f}")
    for letter, row in summary.get("ablations", {}).get("settings", {}).items():
        versus = row.get("vs_A", {}).get("top5")
        tail = (f" top5 - A {versus['difference']:+.3f} [{versus['low']:+.3f}, {versus['high']:+.3f}] "
                f"p(Holm) {versus['p_holm']:.2g}") if versus else ""
        print(f"  {letter}: top1 {row['top1']:.3f} top3 {row['top3']:.3f} top5 {row['top5']:.3f} "
              f"{row['ms_per_prediction']:.2f} ms{tail}")


def _write(path: Path, text: str) -> None:
    try:
        from oracle.files import private_file

        with private_file(path) as handle:  # a report names the users: 0600
            handle.write(text)
    except OSError as error:
        raise NeemOracleError(f"{path}: cannot write ({error.strerror})") from None


def run_tune(args: argparse.Namespace) -> int:
    from oracle.algorithm.params import save_settings
    from oracle.evaluation.replay import check_users, load_users
    from oracle.evaluation.tuning import tune
    from oracle.progress import bar, shown

    ontology = ontology_from(args)
    users = load_users(args.chains)
    check_users(ontology, users, str(args.chains))

    with bar("tuning", "replays", args.budget) as tick:
        drawn = shown()

        def show(step: TuningStep, candidate: Hyperparameters) -> None:
            tick(step.evaluation, args.budget)
            if not drawn:  # a log gets one line per replay; a terminal the bar with its rate and ETA
                mark = "kept" if step.kept else "    "
                print(f"[{step.evaluation:3d}/{args.budget}] {step.parameter:30s} = {step.value:<8.4g} "
                      f"{args.metric} {step.score:.4f} {mark}", file=sys.stderr)

        best, score, history = tune(ontology, users, args.metric, args.budget, settings_from(args.start), args.seed, show)
    save_settings(best, args.out)
    print(f"best {args.metric} on {args.chains}: {score:.4f} after {history[-1].evaluation} replays "
          f"(start {history[0].score:.4f}); settings written to {args.out}")
    for name, value in best.to_dict().items():
        print(f"  {name:30s} {value:g}")
    return 0
