"""A NEEM's fits with the routine predictor: their digest (to show a faster fit is the same fit)
and what the whole fit costs.

Usage: python experiments/fit-check.py STORE NEEM [--runs 3] [--params JSON]
Reads the NEEM's history as `rank` does, fits the default predictor and four other settings
(novelty only, timed_shrink, timed and untimed variants, exclusion) on its first 40, 700 and
3,000 steps, ranks the next 30 situations of each, and prints the SHA-256 of the variant
weights and every ranked option's probability, context order, count and situations; then the
CPU seconds of fitting the default on the whole history, each run, and how many kinds of past
action (predecessors and part of day) its similarity level holds. ``--params`` adds the same
constructor parameters to every setting (``'{"focus": 0}'``: the predictor before the objects in
hand, whose digest docs/prolog.md quotes).
"""

from __future__ import annotations

import argparse
import hashlib
import json
import time
from typing import Any

import numpy as np

from oracle.calls import steps_before
from oracle.commands.common import connect
from oracle.ranking import DEFAULT, make_predictor
from oracle.algorithm.params import Hyperparameters

SETTINGS: tuple[dict[str, Any], ...] = ({}, {"novelty": (True,), "lowest_orders": (1,)}, {"timed_shrink": True},
                                        {"timed": (True, False)}, {"exclusion": True})
CUTS = (40, 700, 3000)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("store")
    parser.add_argument("neem")
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--params", type=json.loads, default={}, help="JSON object of parameters added to every setting")
    args = parser.parse_args()
    target = argparse.Namespace(store=args.store, neem=args.neem, odb=None, mapping=None, soma=None, ontology=None)
    bridge, onto = connect(target, write=False)
    steps = steps_before(onto, bridge.history(), float("inf"))

    def model(**settings: Any) -> Any:
        made = make_predictor(onto, Hyperparameters(), DEFAULT)
        settings = {**settings, **args.params}
        return made.set_params(**settings) if settings else made

    digest = hashlib.sha256()
    for settings in SETTINGS:
        for cut in CUTS:
            fitted = model(**settings).fit(steps[:cut])
            digest.update(np.asarray(fitted.weights_.weights(fitted.tuning, fitted.switch_margin)).tobytes())
            for step in steps[cut:cut + 30]:
                if step.idle or not step.options:
                    continue
                for task in fitted.rank(step):
                    digest.update(repr((task.option, task.probability, task.order, task.n_similar,
                                        task.situations)).encode())
    print(f"{len(steps)} steps; fits digest {digest.hexdigest()}")
    for _ in range(args.runs):
        cpu = time.process_time()
        whole = model().fit(steps)
        print(f"fit of the whole history: {time.process_time() - cpu:.3f} s CPU")
    if args.runs:  # the kinds of past situations the similarity level works out once each
        print("kinds of past actions per stream: " + ", ".join(
            f"{name} {len(stream.past.kinds)}" for name, stream in whole._streams.items()))


if __name__ == "__main__":
    main()
