"""Mean absolute-discount estimate ``D_n = n1 / (n1 + 2 n2)`` per context order at the end of each user's history.

usage: python scripts/discount-estimates.py CHAINS [CHAINS ...]
Counts each user's actions (in file order; idle gaps are not tokens here) into
``ContextCounts(5)`` and prints the mean over users of ``levels[n].discount()`` for n = 1, 2, 3, 5:
near 1 when a history's pairs at that order are mostly seen once (docs/algorithm.md, "Third round").
"""

from __future__ import annotations

import argparse
import sys
from collections import defaultdict
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "python"))
from oracle.algorithm.contexts import ContextCounts  # noqa: E402
from oracle.chains import read_chains  # noqa: E402
from oracle.errors import NeemOracleError  # noqa: E402

ORDERS = (1, 2, 3, 5)


def estimates(path: str) -> tuple[int, dict[int, float]]:
    """Users and the mean estimate per order of one chains file."""
    actions: dict[str, list[str]] = defaultdict(list)
    for row in read_chains(path):
        actions[row.user].append(str(row.action))
    found: dict[int, list[float]] = defaultdict(list)
    for acts in actions.values():
        ids: dict[str, int] = {}
        counts = ContextCounts(max(ORDERS))
        for act in acts:
            counts.add(ids.setdefault(act, len(ids)))
        for n in ORDERS:
            found[n].append(counts.levels[n].discount())
    return len(actions), {n: sum(v) / len(v) for n, v in found.items()}


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("chains", nargs="+")
    args = parser.parse_args()
    for path in args.chains:
        try:
            users, means = estimates(path)
        except (NeemOracleError, OSError) as error:
            print(f"discount-estimates: {error}", file=sys.stderr)
            return 1
        shown = "  ".join(f"D_{n} {means[n]:.2f}" for n in ORDERS)
        print(f"{path}: {users} users  {shown}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
