"""A NEEM remembers the ontology it was logged with: commands use it by default, refuse another."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest

from oracle.store.ids import resolve_neem
from oracle.cli import main
from oracle.paths import data_dir
from oracle.store import open_store

pytestmark = pytest.mark.skipif(shutil.which("swipl") is None, reason="SWI-Prolog (swipl) is not installed")

CHAIN = ["open(small_drawer)", "pick(red_mug)", "place(red_mug, counter_top)", "close(small_drawer)"]


def _chains(tmp_path: Path) -> Path:
    rows = [{"user": "ada", "time": f"2026-03-0{2 + day}T08:00:{8 * i:02d}", "duration": 5, "action": a,
             "available": sorted(set(CHAIN + ["pick(banana)"]))}
            for day in range(3) for i, a in enumerate(CHAIN)]
    path = tmp_path / "c.jsonl"
    path.write_text("".join(json.dumps(r) + "\n" for r in rows))
    return path


@pytest.fixture()
def own_ontology(tmp_path, capsys) -> Path:
    """The sample odb under another namespace: a user's own ontology, whose IRIs the sample lacks."""
    mapping = tmp_path / "mine.yaml"
    text = (data_dir() / "mapping.yaml").read_text()
    mapping.write_text(text.replace("namespace: https://ontology.dlr.de/soma/odb", "namespace: https://example.org/mine"))
    owl = tmp_path / "mine.owl"
    assert main(["ontology", "build", "--mapping", str(mapping), "--out", str(owl)]) == 0
    capsys.readouterr()
    return owl


def _neem_state(path: Path) -> tuple[int, dict]:
    with open_store(path) as store:
        ada = resolve_neem(store, "ada")
        return store.count(ada), dict(store.neem(ada).meta)


def test_commands_use_the_ontology_the_neem_was_logged_with(tmp_path, own_ontology, capsys):
    store = tmp_path / "s.sqlite"
    assert main(["import", str(_chains(tmp_path)), "--store", str(store), "--ontology", str(own_ontology)]) == 0
    assert _neem_state(store)[1]["ontology"]["owl"] == str(own_ontology.resolve())
    capsys.readouterr()
    assert main(["rank", "--store", str(store), "--json", "--no-write"]) == 0
    assert json.loads(capsys.readouterr().out)["history"] > 0
    assert main(["rank", "--store", str(store), "--json", "--no-write", "--ontology", str(own_ontology)]) == 0
    assert main(["why-not", "pick(banana)", "--store", str(store)]) == 0


def test_another_ontology_is_an_error_and_writes_nothing(tmp_path, own_ontology, capsys):
    store = tmp_path / "s.sqlite"
    assert main(["import", str(_chains(tmp_path)), "--store", str(store), "--ontology", str(own_ontology)]) == 0
    before = _neem_state(store)
    capsys.readouterr()
    sample = ["--odb", str(data_dir() / "kitchen-odb"), "--mapping", str(data_dir() / "mapping.yaml")]
    for command in (["rank"], ["why-not", "pick(banana)"], ["what-next"]):
        assert main([*command, "--store", str(store), *sample]) == 1
        err = capsys.readouterr().err
        assert "NEEM 'ada' was logged with --ontology" in err and str(own_ontology.resolve()) in err
    assert _neem_state(store) == before


def test_a_recorded_ontology_that_is_gone_is_an_error_naming_it(tmp_path, own_ontology, capsys):
    store = tmp_path / "s.sqlite"
    assert main(["import", str(_chains(tmp_path)), "--store", str(store), "--ontology", str(own_ontology)]) == 0
    own_ontology.unlink()
    capsys.readouterr()
    assert main(["rank", "--store", str(store)]) == 1
    assert str(own_ontology.resolve()) in capsys.readouterr().err


def test_the_sample_kitchen_is_recorded_portably(tmp_path, capsys):
    store = tmp_path / "s.sqlite"
    assert main(["import", str(_chains(tmp_path)), "--store", str(store)]) == 0
    recorded = _neem_state(store)[1]["ontology"]
    assert recorded["odb"] is None and recorded["mapping"] is None and recorded["owl"] is None
    assert main(["rank", "--store", str(store), "--no-write"]) == 0


def test_with_several_neems_a_read_command_asks_for_neem(tmp_path, capsys):
    store = tmp_path / "s.sqlite"
    chains = _chains(tmp_path)
    bob = tmp_path / "bob.jsonl"
    bob.write_text(chains.read_text().replace('"ada"', '"bob"'))
    assert main(["import", str(chains), "--store", str(store)]) == 0
    assert main(["import", str(bob), "--store", str(store)]) == 0
    before = _neem_state(store)
    capsys.readouterr()
    for command in (["why-not", "pick(banana)"], ["rank"], ["what-next"], ["something-else"]):
        assert main([*command, "--store", str(store)]) == 1
        err = capsys.readouterr().err
        assert "holds 2 NEEMs (ada, bob); choose one with --neem" in err
    assert _neem_state(store) == before
    assert main(["why-not", "pick(banana)", "--store", str(store), "--neem", "ada"]) == 0
