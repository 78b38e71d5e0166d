"""Where the routine predictor's clock gate ends for each user of a chains file, after replaying
the whole history (docs/algorithm.md, "How long ago").

usage: python scripts/clock-gate.py CHAINS [--odb DIR --mapping YAML]
Per user: the gate's lead (Top-1 hits with the clock's odds minus without, over the scored
steps), its standard error (the root of the summed squared differences) and whether the gate is
open at the end (lead > recency_gate x standard error).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "python"))
from oracle.algorithm.routine import RoutineOracle  # noqa: E402
from oracle.algorithm.params import Hyperparameters  # noqa: E402
from oracle.evaluation.replay import OracleMethod, load_users, replay  # noqa: E402
from oracle.ontology import build_ontology  # noqa: E402


class Gates(OracleMethod):
    """The default routine predictor, noting its gate each time the replay moves to the next user."""

    def __init__(self, *args: object, **kwargs: object) -> None:
        self.ends: list[tuple[float, float, bool]] = []
        super().__init__(*args, **kwargs)  # type: ignore[arg-type]

    def reset(self) -> None:
        model = getattr(self, "model", None)
        if isinstance(model, RoutineOracle) and model.n_steps_:
            gate = model.gate_
            self.ends.append((gate.lead, gate.spread ** 0.5, gate.open(model.recency_gate)))
        super().reset()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("chains")
    parser.add_argument("--odb")
    parser.add_argument("--mapping")
    args = parser.parse_args()
    ontology = build_ontology(args.odb, args.mapping, None)
    users = load_users(args.chains)
    method = Gates(ontology, Hyperparameters(), method="routine")
    replay(ontology, users, [method], 0)
    method.reset()  # the last user's gate
    for user, (lead, error, is_open) in zip(users, method.ends):
        print(f"{user}: lead {lead:+.0f}, standard error {error:.1f}, {'open' if is_open else 'shut'}")
    print(f"{sum(end[2] for end in method.ends)} of {len(method.ends)} users' gates open at the end")


if __name__ == "__main__":
    main()
