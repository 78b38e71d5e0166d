"""Importing users who already have a NEEM: refused by default, replaced or added
when asked, and a NEEM cut by a stopped import is named incomplete and replaced next time."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from oracle.cli import main
from oracle.neem.importing import INCOMPLETE_KEY, import_chains
from oracle.store import open_store


def rows(user: str, n: int, minute: int = 0) -> list[dict]:
    """10 s apart: no idle actions between them, so actions == rows."""
    return [{"user": user, "time": f"2025-03-03T08:{minute + i // 6:02d}:{i % 6 * 10:02d}",
             "action": "open(fridge)" if i % 2 == 0 else "close(fridge)"} for i in range(n)]  # fmt: skip


def write(path: Path, lines: list[dict]) -> Path:
    path.write_text("".join(json.dumps(line) + "\n" for line in lines))
    return path


def listed(store: Path, capsys) -> list[dict]:
    capsys.readouterr()
    assert main(["neems", "--store", str(store), "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def test_a_user_with_a_neem_is_refused_with_one_line_and_the_others_import(tmp_path, capsys):
    store = tmp_path / "s.sqlite"
    assert main(["import", str(write(tmp_path / "a.jsonl", rows("ada", 4))), "--store", str(store)]) == 0
    before = listed(store, capsys)
    both = write(tmp_path / "ab.jsonl", rows("ada", 6) + rows("bob", 3, minute=30))
    assert main(["import", str(both), "--store", str(store)]) == 1
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "'ada'" in err[0] and "--replace" in err[0] and "--as-new" in err[0]
    after = {row["user"]: row for row in listed(store, capsys)}
    assert set(after) == {"ada", "bob"} and after["ada"] == before[0]  # ada untouched, bob imported
    assert after["bob"]["actions"] == 3


@pytest.mark.parametrize(("flag", "neems", "actions"), [("--replace", 1, 6), ("--as-new", 2, 6)])
def test_replace_and_as_new(tmp_path, capsys, flag, neems, actions):
    store = tmp_path / "s.sqlite"
    assert main(["import", str(write(tmp_path / "a.jsonl", rows("ada", 4))), "--store", str(store)]) == 0
    assert main(["import", str(write(tmp_path / "b.jsonl", rows("ada", 6))), "--store", str(store), flag]) == 0
    found = listed(store, capsys)
    assert len(found) == neems and max(row["actions"] for row in found) == actions
    assert not any(row["incomplete"] for row in found)


def test_a_cut_import_is_named_incomplete_and_the_next_import_replaces_it(tmp_path, capsys):
    from oracle.ontology import build_ontology

    onto = build_ontology()
    chains = write(tmp_path / "a.jsonl", rows("ada", 8))
    path = tmp_path / "s.sqlite"
    seen = [0]

    def stop() -> bool:  # stopped between two rows, after two commits of two rows
        seen[0] += 1
        return seen[0] > 5

    with open_store(str(path)) as store, pytest.raises(KeyboardInterrupt):
        import_chains(store, onto, chains, commit_every=2, stop=stop)
    (cut,) = listed(path, capsys)
    assert cut["incomplete"] and 0 < cut["actions"] < 8
    assert main(["neems", "--store", str(path)]) == 0
    assert "INCOMPLETE" in capsys.readouterr().out
    assert main(["import", str(chains), "--store", str(path)]) == 0  # no flag needed: it was cut
    (whole,) = listed(path, capsys)
    assert not whole["incomplete"] and whole["actions"] == 8 and whole["name"] == cut["name"]
    with open_store(str(path), read_only=True) as store:
        assert not store.neems()[0].meta.get(INCOMPLETE_KEY)
