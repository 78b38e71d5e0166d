"""Markdown report of an evaluation summary: accuracies, paired differences, ablations."""

from __future__ import annotations

from typing import Any


def _pct(value: float) -> str:
    return f"{100 * value:.1f}"


def _p(value: float) -> str:
    return f"{value:.2g}" if value >= 1e-4 else "<1e-4"


def paired_cell(entry: dict[str, Any]) -> str:
    """'+1.2 [+0.4, +2.0] p 0.003': difference in points, 95 % interval, Holm-adjusted p."""
    return (f"{100 * entry['difference']:+.1f} [{100 * entry['low']:+.1f}, {100 * entry['high']:+.1f}] "
            f"p {_p(entry['p_holm'])}")


def paired_caption(block: dict[str, Any]) -> str:
    return (f"Paired differences against `{block['reference']}` in percentage points (method minus "
            f"{block['reference']}), with the {100 * block['level']:.0f} % bootstrap interval over "
            f"{block['units']} resampled units ({block['unit']}; {block['resamples']} resamples, seed "
            f"{block['seed']}) and p: {block['test']}.")


def markdown(summary: dict[str, Any], command: str, title: str = "Evaluation") -> str:
    users = len(next(iter(summary["methods"].values()))["per_user"])
    lines = [f"# {title}", "", f"Command: `{command}`", "",
             f"{summary['n_predictions']} predictions, {users} users, "
             f"{summary['mean_candidates']:.1f} candidates per prediction on average"
             + (f", truth not among the candidates in {summary['truth_not_offered']}" if summary.get("truth_not_offered") else "")
             + ".", "",
             "| method | Top-1 % | Top-3 % | Top-5 % | ms/prediction |", "| --- | ---: | ---: | ---: | ---: |"]
    for name, entry in summary["methods"].items():
        lines.append(f"| {name} | {_pct(entry['top1'])} | {_pct(entry['top3'])} | {_pct(entry['top5'])} | "
                     f"{entry['ms_per_prediction']:.2f} |")
    chance = summary["chance"]
    lines.append(f"| chance | {_pct(chance['top1'])} | {_pct(chance['top3'])} | {_pct(chance['top5'])} | |")
    if summary.get("comparisons"):
        block = summary["comparisons"]
        lines += ["", paired_caption(block), "",
                  "| method | Top-1 | Top-3 | Top-5 |", "| --- | ---: | ---: | ---: |"]
        for name, entry in block["methods"].items():
            lines.append(f"| {name} | " + " | ".join(paired_cell(entry[f"top{k}"]) for k in (1, 3, 5)) + " |")
    if summary.get("cold_start", {}).get("comparisons"):
        cold = summary["cold_start"]
        block = cold["comparisons"]
        lines += ["", f"## Cold start: each user's first {cold['first_predictions']} predictions", "",
                  f"{cold['n_predictions']} predictions. " + paired_caption(block), "",
                  "| method | Top-1 % | Top-3 % | Top-5 % | Top-1 | Top-3 | Top-5 |",
                  "| --- | ---: | ---: | ---: | ---: | ---: | ---: |"]
        for name, entry in cold["methods"].items():
            versus = block["methods"].get(name)
            cells = [paired_cell(versus[f"top{k}"]) if versus else "" for k in (1, 3, 5)]
            lines.append(f"| {name} | {_pct(entry['top1'])} | {_pct(entry['top3'])} | {_pct(entry['top5'])} | "
                         + " | ".join(cells) + " |")
    if summary.get("ablations"):
        ablations = summary["ablations"]
        rows = ablations["settings"]
        base = rows["A"]["settings"]
        lines += ["", "## Ablations (thesis Fig. 5.5 settings)", "",
                  f"Accuracy in %, and the paired difference to A (points, 95 % bootstrap interval over "
                  f"{ablations['units']} units, {ablations['unit']}; p: {ablations['test']}).", "",
                  "| setting | change | Top-1 % | Top-3 % | Top-5 % | Top-1 vs A | Top-5 vs A | ms/prediction |",
                  "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: |"]
        for letter, row in rows.items():
            change = ", ".join(f"{k}={v:g}" for k, v in row["settings"].items() if v != base[k]) or "recommended"
            versus = [paired_cell(row["vs_A"][f"top{k}"]) if "vs_A" in row else "" for k in (1, 5)]
            lines.append(f"| {letter} | {change} | {_pct(row['top1'])} | {_pct(row['top3'])} | {_pct(row['top5'])} | "
                         f"{versus[0]} | {versus[1]} | {row['ms_per_prediction']:.2f} |")
    lines.append("")
    return "\n".join(lines)
