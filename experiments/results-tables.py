"""Print the markdown tables of docs/results.md from the JSON files experiments/make-results.sh wrote.

usage: python experiments/results-tables.py [OUT] [NAME ...]   (OUT defaults to out/; NAMEs default to all)
Per evaluation: accuracy of every method and its paired difference to the first method (the one
the run scored first, named in the column header) with the 95 % bootstrap interval and the
Holm-corrected Wilcoxon p; the cold start; with ablations the Fig. 5.5 table against A.
Then, over the three sets, the targets of the default predictor (ahead of the best baseline on
Top-1/3/5 with the Top-3 interval above zero; cold start at least as good as the thesis oracle)
and its self-tuning ablations.
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


SETS = [("persona", "Persona test split"), ("kasteren", "van Kasteren house A"), ("egtea", "EGTEA Gaze+")]


def points(entry: dict, flip: bool = True) -> str:
    """Reference minus method (flip) in points with the 95 % interval."""
    sign = -1 if flip else 1
    low, high = sorted((sign * entry["low"], sign * entry["high"]))
    return f"{100 * sign * entry['difference']:+.1f} [{100 * low:+.1f}, {100 * high:+.1f}]"


def targets() -> None:
    """Per set: the default predictor against the best baseline per k, and the cold start."""
    rows = []
    for tag, label in SETS:
        path = OUT / f"{tag}-recommended.json"
        if not path.exists():
            continue
        data = json.loads(path.read_text())
        paired, ref = data["comparisons"], data["comparisons"]["reference"]
        baselines = [m for m in paired["methods"] if m != "oracle"]
        cells, met = [], True
        for k in KS:
            best = max(baselines, key=lambda m: data["methods"][m][f"top{k}"])
            entry = paired["methods"][best][f"top{k}"]
            ours = data["methods"][ref][f"top{k}"]
            met &= ours > data["methods"][best][f"top{k}"] and (k != 3 or -entry["high"] > 0)
            cells.append(f"{ours:.3f} vs `{best}` {data['methods'][best][f'top{k}']:.3f}: {points(entry)}")
        cold = data["cold_start"]
        ahead = all(cold["methods"][ref][f"top{k}"] >= cold["methods"]["oracle"][f"top{k}"] for k in KS)
        cold_cell = " / ".join(f"{cold['methods'][ref][f'top{k}']:.3f} vs {cold['methods']['oracle'][f'top{k}']:.3f}"
                               for k in KS)
        rows.append(f"| {label} | {' | '.join(cells)} | {'yes' if met else 'no'} | {cold_cell} | "
                    f"{'yes' if ahead else 'no'} |")
    if not rows:
        return
    print("**Targets of the default predictor** (`routine` minus the strongest baseline per k, in points, "
          "with the 95 % bootstrap interval; cold start: Top-1 / Top-3 / Top-5 of `routine` vs the thesis "
          "oracle over each user's first 30 predictions)\n")
    print("| set | Top-1 | Top-3 | Top-5 | ahead, Top-3 interval above 0 | cold start | cold start >= thesis |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    print("\n".join(rows) + "\n")


def self_tuning() -> None:
    """The routine predictor with its self-tuning (leader), its first variant alone, and the mixture."""
    rows = []
    for tag, label in SETS:
        files = {"routine (leader)": (OUT / f"{tag}-recommended.json", "routine"),
                 "routine-fixed": (OUT / f"{tag}-routine-fixed.json", "routine-fixed"),
                 "routine-mixture": (OUT / f"{tag}-routine-mixture.json", "routine-mixture")}
        if not all(path.exists() for path, _ in files.values()):
            continue
        for name, (path, key) in files.items():
            entry = json.loads(path.read_text())["methods"][key]
            rows.append(f"| {label} | {name} | {entry['top1']:.3f} | {entry['top3']:.3f} | {entry['top5']:.3f} | "
                        f"{entry['ms_per_prediction']:.2f} |")
    if rows:
        print("**Self-tuning of the routine predictor**\n")
        print("| set | tuning | Top-1 | Top-3 | Top-5 | ms/prediction |\n| --- | --- | ---: | ---: | ---: | ---: |")
        print("\n".join(rows) + "\n")


for name, label in [("persona-recommended", "Persona test split, recommended settings (thesis Table 4.2)"),
                    ("persona-tuned", "Persona test split, settings tuned on the tuning split (top-1)"),
                    ("kasteren-recommended", "van Kasteren house A, recommended settings"),
                    ("kasteren-tuned-top1", "van Kasteren house A, persona-tuned settings"),
                    ("egtea-recommended", "EGTEA Gaze+, recommended settings"),
                    ("egtea-tuned-top1", "EGTEA Gaze+, persona-tuned settings")]:
    if (OUT / f"{name}.json").exists() and (not ONLY or name in ONLY):
        table(name, label)
if not ONLY or "targets" in ONLY:
    targets()
if not ONLY or "self-tuning" in ONLY:
    self_tuning()
