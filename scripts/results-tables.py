"""Print the markdown tables of docs/results.md from the JSON files scripts/make-results.sh wrote.

usage: python scripts/results-tables.py [OUT] [NAME ...]   (OUT defaults to out/; NAMEs default to all)
Per evaluation: accuracy of every method and its paired difference to the first method (the one
the run scored first, named in the column header) with the 95 % bootstrap interval and the
Holm-corrected Wilcoxon p; the cold start; with ablations the Fig. 5.5 table against A.
"""

import json
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "python"))
from oracle.evaluation.report import paired_caption, paired_cell  # noqa: E402

OUT = Path(sys.argv[1] if len(sys.argv) > 1 else "out")
ONLY = set(sys.argv[2:])  # names to print (default: all)
KS = (1, 3, 5)


def methods_table(methods: dict, paired: dict | None, chance: dict, timing: bool) -> None:
    """Accuracy per method and, with ``paired``, its difference to the reference per k."""
    head = "| method | Top-1 | Top-3 | Top-5 |" + (" ms/prediction |" if timing else "")
    rule = "| --- | ---: | ---: | ---: |" + (" ---: |" if timing else "")
    if paired:
        head += "".join(f" Top-{k} vs {paired['reference']} |" for k in KS)
        rule += " ---: | ---: | ---: |"
    print(head + "\n" + rule)
    for method, entry in methods.items():
        line = f"| {method} | {entry['top1']:.3f} | {entry['top3']:.3f} | {entry['top5']:.3f} |"
        line += f" {entry['ms_per_prediction']:.2f} |" if timing else ""
        if paired:
            versus = paired["methods"].get(method)
            line += "".join(f" {paired_cell(versus[f'top{k}']) if versus else ''} |" for k in KS)
        print(line)
    blank = (" |" if timing else "") + (" | | |" if paired else "")
    print(f"| chance | {chance['top1']:.3f} | {chance['top3']:.3f} | {chance['top5']:.3f} |{blank}\n")


def table(name: str, label: str) -> None:
    data = json.loads((OUT / f"{name}.json").read_text())
    users = len(next(iter(data["methods"].values()))["per_user"])
    print(f"**{label}** ({data['n_predictions']} predictions, {users} users, "
          f"{data['mean_candidates']:.1f} candidates on average, replay {data['replay_seconds']:.0f} s)\n")
    paired = data.get("comparisons")
    methods_table(data["methods"], paired, data["chance"], timing=True)
    if paired:
        print(paired_caption(paired) + "\n")
        strongest = []
        for k in KS:
            best = max(paired["methods"], key=lambda m: data["methods"][m][f"top{k}"])
            strongest.append(f"Top-{k} `{best}` {data['methods'][best][f'top{k}']:.3f} "
                             f"({paired_cell(paired['methods'][best][f'top{k}'])})")
        print(f"Strongest method other than `{paired['reference']}`: " + "; ".join(strongest) + ".\n")
    cold = data.get("cold_start")
    if cold and cold.get("comparisons"):
        print(f"Cold start, each user's first {cold['first_predictions']} predictions ({cold['n_predictions']} "
              f"predictions; intervals over {cold['comparisons']['units']} units, {cold['comparisons']['unit']}):\n")
        methods_table(cold["methods"], cold["comparisons"], cold["chance"], timing=False)
    if "ablations" in data:
        ablations = data["ablations"]
        rows = ablations["settings"]
        base = rows["A"]["settings"]
        print("| setting | change | Top-1 | Top-3 | Top-5 | Top-1 vs A | Top-3 vs A | Top-5 vs A | ms/prediction |")
        print("| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
        for letter, row in rows.items():
            change = ", ".join(f"{k} = {v:g}" for k, v in row["settings"].items() if v != base[k]) or "recommended"
            versus = "".join(f" {paired_cell(row['vs_A'][f'top{k}']) if 'vs_A' in row else ''} |" for k in KS)
            print(f"| {letter} | {change} | {row['top1']:.3f} | {row['top3']:.3f} | {row['top5']:.3f} |{versus} "
                  f"{row['ms_per_prediction']:.2f} |")
        print(f"\nDifferences to A in points with the 95 % bootstrap interval over {ablations['units']} units "
              f"({ablations['unit']}); p: {ablations['test']}.\n")


for name, label in [("persona-recommended", "Persona test split, recommended settings (thesis Table 4.2)"),
                    ("persona-tuned", "Persona test split, settings tuned on the tuning split (top-1)"),
                    ("kasteren-recommended", "van Kasteren house A, recommended settings"),
                    ("kasteren-tuned-top1", "van Kasteren house A, persona-tuned settings"),
                    ("egtea-recommended", "EGTEA Gaze+, recommended settings"),
                    ("egtea-tuned-top1", "EGTEA Gaze+, persona-tuned settings")]:
    if (OUT / f"{name}.json").exists() and (not ONLY or name in ONLY):
        table(name, label)
