"""Derive the condition-matched development sets of a chains file (docs/algorithm.md, "Selection protocol").

usage: python experiments/dev-conditions.py CHAINS OUT
writes OUT/open/NAME and OUT/clockless/NAME (NAME: the file name of CHAINS): the same rows without
the available sets, and without the available sets and the clock.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "python"))
from oracle.errors import ChainSyntaxError  # noqa: E402
from oracle.evaluation.conditions import write_conditions  # noqa: E402


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("chains")
    parser.add_argument("out")
    args = parser.parse_args()
    try:
        written = write_conditions(args.chains, args.out)
    except (ChainSyntaxError, OSError) as error:
        print(f"dev-conditions: {error}", file=sys.stderr)
        return 1
    for condition, path in written.items():
        print(f"{condition}: {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
