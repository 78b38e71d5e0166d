"""experiments/chains.py with the kitchen world's rules (``--world``): on data the world made, the
world's state is tracked at every decision (the row's offer is what the tracked state makes
available), and the rules chain ranks only what the world allows after the predicted step."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def _run(*argv: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, *argv], capture_output=True, text=True, cwd=ROOT, check=False)


def test_the_rules_chain_tracks_the_world_on_every_decision(tmp_path: Path) -> None:
    made = _run("-m", "oracle", "generate", "--personas", "2", "--days", "2", "--seed", "4", "--out", str(tmp_path / "p"))
    assert made.returncode == 0, made.stderr
    out = tmp_path / "chains.json"
    done = _run("experiments/chains.py", str(tmp_path / "p" / "tune.jsonl"), "--users", "1", "--world", "--json", str(out))
    assert done.returncode == 0, done.stderr
    report = json.loads(out.read_text())
    assert report["decisions"] > 20 and report["rules_untracked"] == 0
    for depth in (2, 3):
        step = report[f"step{depth}"]
        assert step["n"] > 0 and set(step) >= {"plain", "feasible", "tree", "rules", "rules_minus_plain", "rules_minus_feasible"}
        # the world's rules know what becomes possible: never below ranking the stale offer
        assert step["rules"]["top3"] >= step["plain"]["top3"]


def test_without_the_world_there_is_no_rules_chain(tmp_path: Path) -> None:
    made = _run("-m", "oracle", "generate", "--personas", "2", "--days", "1", "--seed", "4", "--out", str(tmp_path / "p"))
    assert made.returncode == 0, made.stderr
    out = tmp_path / "chains.json"
    done = _run("experiments/chains.py", str(tmp_path / "p" / "tune.jsonl"), "--users", "1", "--json", str(out))
    assert done.returncode == 0, done.stderr
    report = json.loads(out.read_text())
    assert "rules_untracked" not in report and "rules" not in report["step2"]
