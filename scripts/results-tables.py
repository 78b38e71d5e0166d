"""Print the markdown tables of docs/results.md from the JSON files scripts/make-results.sh wrote."""

import json
import sys
from pathlib import Path

OUT = Path(sys.argv[1] if len(sys.argv) > 1 else "out")
ONLY = set(sys.argv[2:])  # names to print (default: all)


def table(name: str, label: str) -> None:
    data = json.loads((OUT / f"{name}.json").read_text())
    users = len(next(iter(data["methods"].values()))["per_user"])
    print(f"**{label}** ({data['n_predictions']} predictions, {users} users, "
          f"{data['mean_candidates']:.1f} candidates on average, replay {data['replay_seconds']:.0f} s)\n")
    print("| method | Top-1 | Top-3 | Top-5 | ms/prediction |\n| --- | ---: | ---: | ---: | ---: |")
    for method, entry in data["methods"].items():
        print(f"| {method} | {entry['top1']:.3f} | {entry['top3']:.3f} | {entry['top5']:.3f} | {entry['ms_per_prediction']:.2f} |")
    c = data["chance"]
    print(f"| chance | {c['top1']:.3f} | {c['top3']:.3f} | {c['top5']:.3f} | |\n")
    if "ablations" in data:
        base = data["ablations"]["A"]["settings"]
        print("| setting | change | Top-1 | Top-3 | Top-5 | p(Top-5 vs A) | ms/prediction |")
        print("| --- | --- | ---: | ---: | ---: | ---: | ---: |")
        for letter, row in data["ablations"].items():
            change = ", ".join(f"{k} = {v:g}" for k, v in row["settings"].items() if v != base[k]) or "recommended"
            print(f"| {letter} | {change} | {row['top1']:.3f} | {row['top3']:.3f} | {row['top5']:.3f} | "
                  f"{row['p_top5']:.2g} | {row['ms_per_prediction']:.2f} |")
        print()


for name, label in [("persona-recommended", "Persona test split, recommended settings (thesis Table 4.2)"),
                    ("persona-tuned", "Persona test split, settings tuned on the tuning split (top-1)"),
                    ("kasteren-recommended", "van Kasteren house A, recommended settings"),
                    ("kasteren-tuned-top1", "van Kasteren house A, persona-tuned settings"),
                    ("egtea-recommended", "EGTEA Gaze+, recommended settings"),
                    ("egtea-tuned-top1", "EGTEA Gaze+, persona-tuned settings")]:
    if (OUT / f"{name}.json").exists() and (not ONLY or name in ONLY):
        table(name, label)
