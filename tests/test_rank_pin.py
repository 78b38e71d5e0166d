"""The ranking ``rank`` writes back on a 10,000-action NEEM, pinned to what the implementation
before the speed work wrote (a digest it produced, stored below): a faster history read, store
projection or fit must not change a single call, rank, score or predicted chain.

The NEEM is one simulated persona (``generate --seed 3``), cut at 10,000 actions and imported
through the CLI as a user would; the ranking is read back from the store through Prolog.
"""

from __future__ import annotations

import hashlib
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

pytestmark = [pytest.mark.slow,
              pytest.mark.skipif(shutil.which("swipl") is None, reason="SWI-Prolog (swipl) is not installed; run make setup")]

ACTIONS = 10_000
#: sha256 of ``ranking_digest_text`` as the implementation of commit 4f2f506 wrote it, renewed when
#: the routine predictor's default changed on purpose (part-of-day contexts and the leader's
#: switch margin; then absolute discounting from order 2 once 100 pairs back it; then the objects
#: in hand, which also add the JSON field ``focus``; then the newly offered options and the lift
#: after a break, which add the fields ``new`` and ``resumed``; docs/algorithm.md). With
#: ``focus=0`` and that field dropped the code of the objects in hand gave the digest before it,
#: 77aa1b49...; with ``fresh=False`` and ``new`` dropped the code of the newly offered options
#: gave the one before it, ac2327a9...; with ``resume=False`` and ``resumed`` dropped the code of
#: the lift after a break gives the newly offered options' one, 8193c57e... The clock (how long
#: ago each option was last done, behind its Top-1 gate) adds the field ``since``; on this NEEM
#: its gate stays shut, and with ``since`` dropped the code gives the digest before it, 6e082cec...
#: The tuning window of 500 steps (1,000 before; docs/algorithm.md, "Tuning window") renewed it:
#: with ``tuning_window=1000`` and ``online_window=1000`` the code gives the one before, 2d72e897...
#: The predicted chain re-ranked after each step taken as done (docs/algorithm.md, "The predicted
#: chain") renewed both: only the field ``chain`` moved; with it dropped, the texts of the code
#: before (7c8c3cd9... and 521a6a27...) and after are equal, the ranking read back included.
#: ``python tests/test_rank_pin.py`` prints it.
EXPECTED = "c4691709fa52cb411227f4286e690e4e15173d46c38524ea59c3bef05c0c1e0d"
#: the same for the default, ranked right after on the same NEEM. For ``pooled`` (the default
#: before issue 56) it was the routine predictor's text but for ``"method": "pooled"`` (its gate
#: stays shut here), 7c31cb02...; the default ``personal`` (no prior: a per-user logit over the
#: routine predictor's evidence) keeps the routine predictor's explanations and chain and gives
#: its own probabilities and order from the 8th option on.
EXPECTED_DEFAULT = "1a7a2933363465de762b1c06fd4196030c1f1a0e4f9b512cd36b68e0e6bbdcf9"


def _oracle(*argv: str, env: dict[str, str]) -> str:
    done = subprocess.run([sys.executable, "-m", "oracle", *argv], check=True, capture_output=True, text=True, env=env)
    return done.stdout


def ranking_digest_texts(tmp: Path) -> tuple[str, str]:
    """What the pins hash, for the routine predictor and then the default on the same imported
    NEEM: rank's JSON without its timing and the written individual's random id, then the ranking
    as Prolog reads it back from the store (call, rank, score)."""
    env = {**os.environ, "NEEM_ORACLE_CACHE": str(tmp / "cache")}
    gen = tmp / "gen"
    _oracle("generate", "--personas", "1", "--days", str(ACTIONS // 35 + 30), "--seed", "3", "--out", str(gen), env=env)
    rows = [json.loads(line) for name in ("tune.jsonl", "test.jsonl") for line in (gen / name).read_text().splitlines() if line]
    assert len(rows) >= ACTIONS
    chains = tmp / "u.jsonl"
    chains.write_text("".join(json.dumps({**row, "user": "u"}) + "\n" for row in rows[:ACTIONS]))
    store = tmp / "s.sqlite"
    imported = _oracle("import", str(chains), "--store", str(store), "--commit-every", "1000", env=env)
    neem_id, name, _ = imported.strip().split("\t")
    return tuple(_ranked(store, neem_id, name, method, env) for method in (["--method", "routine"], []))  # type: ignore[return-value]


def _ranked(store: Path, neem_id: str, name: str, method: list[str], env: dict[str, str]) -> str:
    ranked = json.loads(_oracle("rank", "--store", str(store), "--neem", "u", "--json", *method, env=env))
    assert ranked["written"] and ranked["note"] is None
    # the NEEM's id is a fresh ObjectId: the pin keeps its name, as before ids were ObjectIds
    assert name == "u" and ranked["neem"] == neem_id
    ranked["neem"] = name
    for key in ("ms", "written"):
        ranked.pop(key)
    # who usually does each task (docs/beyond.md, "Autonomy mode") is beside the ranking, not part
    # of it: the pin holds the ranking unchanged by it (every row of this NEEM is the robot's)
    assert ranked.pop("chain_modes") == ["robot"] * len(ranked["chain"])
    for entry in ranked["ranking"]:
        assert entry.pop("mode") in ("robot", None)
        entry.pop("mode_support")
    goal = "odb_decisions:latest_preference(_, B, R), format('~q~n', [B-R])"
    back = _oracle("prolog", "--store", str(store), "--neem", "u", "-g", goal, env=env)
    return json.dumps(ranked, sort_keys=True) + "\n" + back


def test_the_ranking_written_back_at_10k_actions_is_the_one_before_the_speed_work(tmp_path):
    routine, default = ranking_digest_texts(tmp_path)
    assert hashlib.sha256(routine.encode()).hexdigest() == EXPECTED, routine[:2000]
    assert hashlib.sha256(default.encode()).hexdigest() == EXPECTED_DEFAULT, default[:2000]


if __name__ == "__main__":  # print the digest of the implementation on sys.path
    import tempfile

    with tempfile.TemporaryDirectory() as tmp_name:
        texts = ranking_digest_texts(Path(tmp_name))
    for text in texts:
        print(text)
        print(hashlib.sha256(text.encode()).hexdigest())
