import shutil

import pytest

from oracle.cli import main
from oracle.store import open_store

pytestmark = pytest.mark.skipif(shutil.which("swipl") is None, reason="SWI-Prolog (swipl) is not installed; run make setup")


def test_demo_logs_ranks_writes_back_and_answers(tmp_path, capsys):
    store = tmp_path / "demo.sqlite"
    assert main(["demo", "--store", str(store), "--days", "3"]) == 0
    out = capsys.readouterr().out
    assert "ranking written back as" in out and "why not" in out and "predicted chain:" in out
    (first,) = [(n.id, n.meta["alias"]) for n in open_store(store).neems()]
    assert first[1] == "demo"
    # running it again replaces the demo NEEM (same id, same name) instead of piling up copies
    assert main(["demo", "--store", str(store), "--days", "2"]) == 0
    assert [(n.id, n.meta["alias"]) for n in open_store(store).neems()] == [first]
