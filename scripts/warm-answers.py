"""What `why_not` and `what_next` cost in a process that has answered before (as the service
answers): CPU milliseconds of the two together, each run, fastest first.

Usage: python scripts/warm-answers.py STORE NEEM [--task pick --args banana] [--runs 7]
"""

from __future__ import annotations

import argparse
import time

from oracle.commands.common import connect


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("store")
    parser.add_argument("neem")
    parser.add_argument("--task", default="pick")
    parser.add_argument("--args", nargs="*", default=["banana"])
    parser.add_argument("--runs", type=int, default=7)
    args = parser.parse_args()
    target = argparse.Namespace(store=args.store, neem=args.neem, odb=None, mapping=None, soma=None, ontology=None)
    bridge, _ = connect(target, write=False)
    bridge.why_not(args.task, args.args)   # the first answer of a process is not what is timed
    spent = []
    for _ in range(args.runs):
        cpu = time.process_time()
        bridge.why_not(args.task, args.args)
        bridge.what_next()
        spent.append(time.process_time() - cpu)
    print(" ".join(f"{s * 1000:.0f}" for s in sorted(spent)), "ms CPU")


if __name__ == "__main__":
    main()
