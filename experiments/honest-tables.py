"""Print the tables of docs/results.md, "Honest replay, learned baselines, chains" from the JSON
files of experiments/honest-replay.sh and experiments/normalized-distances.sh.

usage: python experiments/honest-tables.py OUT [targets [DEFAULT]|all|chains|normalized|online|pooled]
(``targets pooled``: the table with ``pooled`` as the default, from ``shards.py merge --against pooled``)
(``online``, ``pooled``: that predictor paired against the default and the learned baselines, from
``shards.py merge --against NAME``)
"""

from __future__ import annotations

import json
import sys
from collections.abc import Iterator
from pathlib import Path

SETS = (("persona", "Persona test split"), ("kasteren", "van Kasteren house A"), ("egtea", "EGTEA Gaze+"))
KS = (1, 3, 5)
#: predictors replayed beside the default that are candidates, not baselines
EXTRA = ("routine", "stacked", "online", "pooled")


def each(out: Path, prefix: str) -> Iterator[tuple[str, dict]]:
    """(label, summary) of every set whose ``OUT/PREFIX-SET.json`` exists."""
    for key, label in SETS:
        path = out / f"{prefix}-{key}.json"
        if path.exists():
            yield label, json.loads(path.read_text(encoding="utf-8"))


def targets(out: Path, default: str = "") -> None:
    """The default predictor (``default``: a method the JSON's ``against`` block pairs against
    every other one; none: the replay's first method) against every baseline."""
    print("| set | method | Top-1 | Top-3 | Top-5 | Top-3 minus the default [95 % CI] | cold start Top-1/3/5 |")
    print("| --- | --- | ---: | ---: | ---: | --- | --- |")
    for label, s in each(out, "i39"):
        ref = default or s["method"]
        paired = s["comparisons"]["methods"] if ref == s["method"] else s["against"]["methods"]
        cold = s["cold_start"]["methods"]
        shown = list(dict.fromkeys([ref, *EXTRA, "logit", "gbdt", "oracle"]))
        best = max((n for n in s["methods"] if n not in shown), key=lambda n: s["methods"][n]["top3"])
        for name in [*shown, best]:
            if name not in s["methods"]:
                continue
            m = s["methods"][name]
            d = paired.get(name, {}).get("top3")
            diff = f"{100 * d['difference']:+.1f} [{100 * d['low']:+.1f}, {100 * d['high']:+.1f}]" if d else "-"
            c = cold[name]
            tag = f"`{name}`" + (" (best other baseline on Top-3)" if name == best else "")
            print(f"| {label} | {tag} | {m['top1']:.3f} | {m['top3']:.3f} | {m['top5']:.3f} | {diff} | "
                  f"{c['top1']:.3f} / {c['top3']:.3f} / {c['top5']:.3f} |")
        others = [n for n in s["methods"] if n not in (ref, *EXTRA)]
        strongest = []
        for k in KS:
            top = max(others, key=lambda n: s["methods"][n][f"top{k}"])
            strongest.append(f"`{top}` {s['methods'][top][f'top{k}']:.3f}")
        ahead = all(s["methods"][ref][f"top{k}"] >= max(s["methods"][n][f"top{k}"] for n in others) for k in KS)
        print(f"| {label} | strongest baseline per k | {' | '.join(strongest)} | `{ref}` >= all three: "
              f"{'yes' if ahead else 'no'} | |")
        print(f"| {label} | chance | {s['chance']['top1']:.3f} | {s['chance']['top3']:.3f} | "
              f"{s['chance']['top5']:.3f} | {s['n_predictions']:,} predictions, {s['truth_not_offered']:,} "
              f"not offered | |")


def everything(out: Path) -> None:
    for label, s in each(out, "i39"):
        print(f"\n{label} (`{s['method']}` first; {s['mean_candidates']:.1f} candidates on average)\n")
        print("| method | Top-1 | Top-3 | Top-5 | ms / prediction |")
        print("| --- | ---: | ---: | ---: | ---: |")
        for name, m in s["methods"].items():
            print(f"| `{name}` | {m['top1']:.3f} | {m['top3']:.3f} | {m['top5']:.3f} | {m['ms_per_prediction']:.2f} |")


def chains(out: Path) -> None:
    """Plain, forward-tree and feasible chains per set and step; the world's rules where the set
    was replayed with them (``chains.py --world``; "-" elsewhere)."""
    print("| set | step | n | plain Top-1/3/5 | forward tree Top-1/3/5 | feasible Top-1/3/5 | "
          "feasible minus plain, Top-3 [95 % CI] | feasible minus tree, Top-3 | world's rules Top-1/3/5 | "
          "rules minus plain, Top-3 [95 % CI] | rules minus feasible, Top-3 [95 % CI] |")
    print("| --- | ---: | ---: | --- | --- | --- | --- | ---: | --- | --- | --- |")
    for label, c in each(out, "i39-chains"):
        for depth in (2, 3):
            e = c[f"step{depth}"]
            cells = [" / ".join(f"{e[kind][f'top{k}']:.3f}" for k in KS) if kind in e else "-"
                     for kind in ("plain", "tree", "feasible", "rules")]
            d = e["feasible_minus_plain"]["top3"]
            tree = 100 * (e["feasible"]["top3"] - e["tree"]["top3"])
            rules = [f"{100 * r['difference']:+.1f} [{100 * r['low']:+.1f}, {100 * r['high']:+.1f}]" if r else "-"
                     for r in (e.get(f"rules_minus_{other}", {}).get("top3") for other in ("plain", "feasible"))]
            print(f"| {label} | {depth} | {e['n']:,} | {cells[0]} | {cells[1]} | {cells[2]} | "
                  f"{100 * d['difference']:+.1f} [{100 * d['low']:+.1f}, {100 * d['high']:+.1f}] | {tree:+.1f} | "
                  f"{cells[3]} | {rules[0]} | {rules[1]} |")


def normalized(out: Path) -> None:
    print("| set | thesis Top-1/3/5 | thesis-normalized Top-1/3/5 | Top-3 difference [95 % CI] |")
    print("| --- | --- | --- | --- |")
    for label, s in each(out, "i39-normalized"):
        a, b = s["methods"]["oracle"], s["methods"]["thesis-normalized"]
        d = s["comparisons"]["methods"]["thesis-normalized"]["top3"]
        print(f"| {label} | {a['top1']:.3f} / {a['top3']:.3f} / {a['top5']:.3f} | "
              f"{b['top1']:.3f} / {b['top3']:.3f} / {b['top5']:.3f} | "
              f"{100 * d['difference']:+.1f} [{100 * d['low']:+.1f}, {100 * d['high']:+.1f}] |")


def against(out: Path, name: str) -> None:
    """Predictor ``name`` paired against the default and the learned baselines (``shards.py merge
    --against NAME``)."""
    print(f"| set | `{name}` minus | Top-1 [95 % CI] | Top-3 [95 % CI] | Top-5 [95 % CI] |")
    print("| --- | --- | --- | --- | --- |")
    for label, s in each(out, "i39"):
        paired = s.get("against", {}).get("methods", {})
        for other in ("routine", "logit", "gbdt"):
            if other in paired:
                # the block pairs each method against NAME: its sign turned, NAME minus the method
                cells = [f"{-100 * d['difference']:+.1f} [{-100 * d['high']:+.1f}, {-100 * d['low']:+.1f}]"
                         for d in (paired[other][f"top{k}"] for k in KS)]
                print(f"| {label} | `{other}` | {' | '.join(cells)} |")


def main() -> int:
    out = Path(sys.argv[1] if len(sys.argv) > 1 else "out")
    which = sys.argv[2] if len(sys.argv) > 2 else "targets"
    if which == "targets":
        targets(out, sys.argv[3] if len(sys.argv) > 3 else "")
    elif which in ("online", "pooled"):
        against(out, which)
    else:
        {"all": everything, "chains": chains, "normalized": normalized}[which](out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
