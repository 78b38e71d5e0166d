"""The bench's SQL floor of the history read reads every row that read needs, wherever the store
keeps it: an imagining's plans are in the NEEM's side table (docs/store.md), and a floor that
looked for them in the triples table read none of them and made the history read look 4.2x its
floor at 10,000 actions instead of 2.3x."""

from __future__ import annotations

from pathlib import Path

from oracle.benchmarks.prolog import _neem, _sql_floor
from oracle.ontology import build_ontology
from oracle.store import open_store
from oracle.store.ids import resolve_neem


def test_the_floor_reads_every_imagined_task(tmp_path: Path) -> None:
    path = tmp_path / "floor.sqlite"
    store = open_store(path)
    _neem(store, build_ontology(), 30, "floor")   # an imagining of 3 available tasks every 10 actions
    neem_id = resolve_neem(store, "floor")
    store.close()
    actions, interval_types, imagined = _sql_floor(path, neem_id)
    assert imagined == 3 * 3
    assert actions > 0 and interval_types > 0
