"""``python -m oracle evaluate`` and ``python -m oracle tune``: replay chains and score methods."""

from __future__ import annotations

import argparse
import json
import shlex
import sys
import time
from pathlib import Path

from oracle.commands.common import ONTOLOGY_OPTIONS, SETTINGS, add_options, ontology_from, settings_from
from oracle.errors import NeemOracleError


def register(subparsers: argparse._SubParsersAction) -> None:
    evaluate = subparsers.add_parser("evaluate", help="replay chains and score the oracle against baselines")
    evaluate.add_argument("chains", type=Path, help="chains JSONL file or a folder of them")
    add_options(evaluate, *ONTOLOGY_OPTIONS, SETTINGS)
    evaluate.add_argument("--baselines", action="store_true", help="also run most-frequent, bigram and n-gram")
    evaluate.add_argument("--ablations", action="store_true", help="also replay the thesis Fig. 5.5 settings A-N")
    evaluate.add_argument("--json", type=Path, metavar="OUT", help="write the summary JSON here")
    evaluate.add_argument("--report", type=Path, metavar="FILE.md", help="write a markdown report here")
    evaluate.add_argument("--plots", type=Path, metavar="DIR", help="write PNG plots into DIR")
    evaluate.add_argument("--seed", type=int, default=0, help="seed of the candidate shuffling (default 0)")
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
    from oracle.evaluation.replay import check_users, load_users, make_methods, replay, stderr_progress, summarize

    ontology = ontology_from(args)
    settings = settings_from(args.settings)
    users = load_users(args.chains)
    check_users(ontology, users, str(args.chains))
    started = time.perf_counter()
    result = replay(ontology, users, make_methods(ontology, settings, args.baselines), args.seed, stderr_progress)
    summary = summarize(result)
    summary["settings"] = settings.to_dict()
    summary["replay_seconds"] = time.perf_counter() - started
    command = "python -m oracle " + " ".join(shlex.quote(a) for a in sys.argv[1:]) if sys.argv[1:2] == ["evaluate"] else "python -m oracle evaluate"
    if args.ablations:
        from oracle.evaluation.ablations import run_ablations

        summary["ablations"] = run_ablations(ontology, users, args.seed,
                                             lambda letter: print(f"ablation {letter}", file=sys.stderr))
    _print_table(summary)
    if args.json is not None:
        _write(args.json, json.dumps(summary, indent=1) + "\n")
    if args.report is not None:
        from oracle.evaluation.report import markdown

        _write(args.report, markdown(summary, command))
    if args.plots is not None:
        from oracle.evaluation import plots

        args.plots.mkdir(parents=True, exist_ok=True)
        made = [plots.box_plots(summary, args.plots), plots.learning_curves(result, args.plots)]
        if args.ablations:
            made.append(plots.ablation_plot(summary["ablations"], args.plots))
        print("plots: " + ", ".join(str(p) for p in made))
    return 0


def _print_table(summary: dict) -> None:
    print(f"{summary['n_predictions']} predictions, {summary['mean_candidates']:.1f} candidates each on average")
    print(f"{'method':16s} {'top1':>7s} {'top3':>7s} {'top5':>7s} {'ms/pred':>8s}")
    for name, entry in summary["methods"].items():
        print(f"{name:16s} {entry['top1']:7.3f} {entry['top3']:7.3f} {entry['top5']:7.3f} {entry['ms_per_prediction']:8.2f}")
    chance = summary["chance"]
    print(f"{'chance':16s} {chance['top1']:7.3f} {chance['top3']:7.3f} {chance['top5']:7.3f}")
    for letter, row in summary.get("ablations", {}).items():
        print(f"  {letter}: top1 {row['top1']:.3f} top3 {row['top3']:.3f} top5 {row['top5']:.3f} "
              f"p(top5 vs A) {row['p_top5']:.3g} {row['ms_per_prediction']:.2f} ms")


def _write(path: Path, text: str) -> None:
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text, encoding="utf-8")
    except OSError as error:
        raise NeemOracleError(f"{path}: cannot write ({error.strerror})") from None


def run_tune(args: argparse.Namespace) -> int:
    from oracle.algorithm.params import save_settings
    from oracle.evaluation.replay import check_users, load_users
    from oracle.evaluation.tuning import tune

    ontology = ontology_from(args)
    users = load_users(args.chains)
    check_users(ontology, users, str(args.chains))

    def show(step, candidate) -> None:
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
