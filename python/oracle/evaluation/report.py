"""Markdown report of an evaluation summary (and of ablations when present)."""

from __future__ import annotations

def _pct(value: float) -> str:
    return f"{100 * value:.1f}"


def markdown(summary: dict, command: str, title: str = "Evaluation") -> str:
    lines = [f"# {title}", "", f"Command: `{command}`", "",
             f"{summary['n_predictions']} predictions, {len(next(iter(summary['methods'].values()))['per_user'])} users, "
             f"{summary['mean_candidates']:.1f} candidates per prediction on average"
             + (f", truth not among the candidates in {summary['truth_not_offered']}" if summary.get("truth_not_offered") else "")
             + ".", "",
             "| method | Top-1 % | Top-3 % | Top-5 % | ms/prediction |", "| --- | ---: | ---: | ---: | ---: |"]
    for name, entry in summary["methods"].items():
        lines.append(f"| {name} | {_pct(entry['top1'])} | {_pct(entry['top3'])} | {_pct(entry['top5'])} | "
                     f"{entry['ms_per_prediction']:.2f} |")
    chance = summary["chance"]
    lines.append(f"| chance | {_pct(chance['top1'])} | {_pct(chance['top3'])} | {_pct(chance['top5'])} | |")
    if summary.get("ablations"):
        lines += ["", "## Ablations (thesis Fig. 5.5 settings; p: Mann-Whitney U of per-user accuracy against A)", "",
                  "| setting | change | Top-1 % | Top-3 % | Top-5 % | p (Top-5) | ms/prediction |",
                  "| --- | --- | ---: | ---: | ---: | ---: | ---: |"]
        base = summary["ablations"]["A"]["settings"]
        for letter, row in summary["ablations"].items():
            change = ", ".join(f"{k}={v:g}" for k, v in row["settings"].items() if v != base[k]) or "recommended"
            lines.append(f"| {letter} | {change} | {_pct(row['top1'])} | {_pct(row['top3'])} | {_pct(row['top5'])} | "
                         f"{row['p_top5']:.3g} | {row['ms_per_prediction']:.2f} |")
    lines.append("")
    return "\n".join(lines)

