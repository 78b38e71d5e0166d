"""How often a user's next action uses an object of their latest actions, or was newly offered,
against the offer.

usage: python scripts/focus-rates.py CHAINS [CHAINS ...] [--depth M] [--feature hand|new|episode]

For each chains file, over every step with objects in hand (the objects of the latest M actions,
default 3): the share of steps whose action uses one of them, and the mean share of the offered
options that do (the row's ``available``, or every distinct action of the user in the file, as
the replay offers). Both for first uses (among the options never done before) and for the other
steps (among the options done before). With ``--feature new`` the feature is "not offered at the
previous step" instead, over the steps whose options of that kind hold some newly offered and some
not; with ``--feature episode`` "done since the last idle gap" (the replay's gap rule; a file
without times has one episode per user), over the steps whose options of that kind hold some of
each. docs/algorithm.md, "Sixth round" to "Ninth round", reads it. Calls are parsed as text
(``task(object, object)``): no ontology is needed.
"""

from __future__ import annotations

import argparse
import json
import sys
from collections import OrderedDict
from dataclasses import dataclass
from datetime import datetime
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "python"))
from oracle.timeline import is_idle_gap, seconds_of  # noqa: E402


def objects(call: str) -> frozenset[str]:
    """The objects named in ``task(a, b)``."""
    inner = call.partition("(")[2].rpartition(")")[0]
    return frozenset(name.strip() for name in inner.split(",") if name.strip())


@dataclass
class Rates:
    steps: int = 0
    uses: int = 0          # steps whose action uses an object in hand
    offered: float = 0.0   # sum over steps of the share of the options that do

    def text(self) -> str:
        if not self.steps:
            return "no steps"
        return f"{self.steps} steps: action {self.uses / self.steps:.3f}, offer {self.offered / self.steps:.3f}"


def rates(path: Path, depth: int, feature: str = "hand") -> dict[str, Rates]:
    users: OrderedDict[str, list[dict]] = OrderedDict()
    for line in path.read_text().splitlines():
        if line.strip():
            row = json.loads(line)
            users.setdefault(row["user"], []).append(row)
    out = {"first": Rates(), "again": Rates()}
    for rows in users.values():
        every = list(OrderedDict.fromkeys(row["action"] for row in rows))
        done: set[str] = set()
        recent: list[str] = []
        previous: set[str] = set()
        episode: set[str] = set()
        last_end: float | None = None
        for row in rows:
            action = row["action"]
            if row.get("time"):
                begin = seconds_of(datetime.fromisoformat(row["time"]))
                if is_idle_gap(last_end, begin):
                    episode = set()
                last_end = seconds_of(datetime.fromisoformat(row["end"])) if row.get("end") else begin
            offer = row.get("available") or every
            held = frozenset().union(*(objects(call) for call in recent[-depth:]))
            first = action not in done
            pool = [c for c in offer if (c not in done) == first]
            if feature == "new":
                has = [c not in previous for c in pool]
                counted = any(has) and not all(has) and action in pool
                hit = action not in previous
            elif feature == "episode":
                has = [c in episode for c in pool]
                counted = any(has) and not all(has) and action in pool
                hit = action in episode
            else:
                has = [bool(objects(c) & held) for c in pool]
                counted = bool(held and pool)
                hit = bool(objects(action) & held)
            if counted:
                r = out["first" if first else "again"]
                r.steps += 1
                r.uses += hit
                r.offered += sum(has) / len(pool)
            done.add(action)
            recent.append(action)
            episode.add(action)
            previous = set(offer)
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("chains", nargs="+", type=Path)
    parser.add_argument("--depth", type=int, default=3)
    parser.add_argument("--feature", choices=("hand", "new", "episode"), default="hand")
    args = parser.parse_args()
    for path in args.chains:
        found = rates(path, args.depth, args.feature)
        print(f"{path}: first uses {found['first'].text()}; other steps {found['again'].text()}")


if __name__ == "__main__":
    main()
