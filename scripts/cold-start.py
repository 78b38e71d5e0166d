"""Cold start and step kinds: Top-1/3/5 of predictors over each user's first N actions, on first
uses and on the other steps, by replaying a chains file (docs/results.md).

usage: python scripts/cold-start.py CHAINS [--odb DIR --mapping FILE] [--first 30] [--methods routine,thesis] [--truncate]
"""

import argparse
from pathlib import Path

from oracle.evaluation.replay import OracleMethod, load_users, replay
from oracle.ontology import build_ontology
from oracle.algorithm.params import Hyperparameters

parser = argparse.ArgumentParser()
parser.add_argument("chains", type=Path)
parser.add_argument("--odb", type=Path)
parser.add_argument("--mapping", type=Path)
parser.add_argument("--first", type=int, default=30)
parser.add_argument("--methods", default="routine,thesis")
parser.add_argument("--truncate", action="store_true",
                    help="replay only each user's first N actions (the replay is causal: same figures for them)")
args = parser.parse_args()
ontology = build_ontology(args.odb, args.mapping, None)
users = load_users(args.chains)
if args.truncate:
    users = {user: rows[: args.first] for user, rows in users.items()}
methods = [OracleMethod(ontology, Hyperparameters(), method=name) for name in args.methods.split(",")]
result = replay(ontology, users, methods)
first_use = []
for rows in users.values():
    seen = set()
    for row in rows:
        first_use.append(row.action not in seen)
        seen.add(row.action)
groups = {f"first {args.first} actions of each user": [o.index < args.first for o in result.outcomes],
          "first uses": first_use, "all other steps": [not f for f in first_use]}
print(f"{'steps':40s} {'n':>6s} " + " ".join(f"{m.name + ' top' + str(k):>16s}" for m in methods for k in (1, 3, 5)))
for label, mask in groups.items():
    chosen = [o for o, keep in zip(result.outcomes, mask) if keep]
    rates = [sum(1 for o in chosen if o.ranks[m.name] is not None and o.ranks[m.name] <= k) / max(1, len(chosen))
             for m in methods for k in (1, 3, 5)]
    print(f"{label:40s} {len(chosen):6d} " + " ".join(f"{r:16.3f}" for r in rates))
