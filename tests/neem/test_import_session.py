"""Privacy (thesis 3.5): session imports are temporary until persisted, and the next session wipes them."""

import json

from oracle.cli import main
from oracle.store import open_store


def chains(tmp_path, user):
    path = tmp_path / f"{user}.jsonl"
    path.write_text(json.dumps({"user": user, "time": "2026-01-01T08:00:00", "action": "pick(apple)"}) + "\n")
    return path


def test_next_session_wipes_unpersisted_neems(tmp_path, capsys):
    store = tmp_path / "s.sqlite"
    assert main(["import", str(chains(tmp_path, "ada")), "--store", str(store), "--session"]) == 0
    first = capsys.readouterr().out.split("\t")[0]
    assert [(n.id, n.temporary) for n in open_store(store).neems()] == [(first, True)]
    assert main(["persist", "--neem", first, "--as", "kept", "--store", str(store)]) == 0
    assert main(["import", str(chains(tmp_path, "bo")), "--store", str(store), "--session"]) == 0
    second = capsys.readouterr().out.strip().splitlines()[-1].split("\t")[0]
    assert main(["import", str(chains(tmp_path, "cy")), "--store", str(store), "--session"]) == 0
    ids = {n.id: n.temporary for n in open_store(store).neems()}
    assert ids.get("kept") is False and second not in ids  # kept survives, the unpersisted one is wiped
    assert sum(ids.values()) == 1  # only the newest session remains temporary
