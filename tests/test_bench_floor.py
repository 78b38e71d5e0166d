"""The bench's floors. The SQL floor of the history read reads every row that read needs, wherever the store
keeps it: an imagining's plans are in the NEEM's side table (docs/store.md), and a floor that
looked for them in the triples table read none of them and made the history read look 4.2x its
floor at 10,000 actions instead of 2.3x."""

from __future__ import annotations

from pathlib import Path

from oracle.algorithm.records import Option
from oracle.algorithm.routine import RoutineOracle
from oracle.benchmarks.algorithm import fit_floor_ms, floor_counts, history
from oracle.benchmarks.prolog import _neem
from oracle.benchmarks.readfloor import sql_floor as _sql_floor
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


def test_the_fit_floor_counts_what_the_routine_predictor_counts_at_order_3() -> None:
    """The fits' floor does real work: its order-3 counts are the routine predictor's, token for
    token (the two intern actions in different orders, so both are compared as actions)."""
    matrix, steps = history(400, seed=5)
    ids, counts = floor_counts(steps)
    model = RoutineOracle(matrix).fit(steps)
    level = model._streams["idle"].counts.levels[3].tables

    def as_actions(tables: dict[tuple[int, ...], dict[int, int]],
                   options: list[Option]) -> dict[tuple[Option | None, ...], dict[Option | None, int]]:
        def named(token: int) -> Option | None:
            return None if token < 0 else options[token]
        return {tuple(map(named, context)): {named(t): n for t, n in followers.items()}
                for context, followers in tables.items() if len(context) == 3}

    ours = as_actions(counts, list(ids))
    assert ours == as_actions(level, model.options_) and sum(map(len, ours.values())) > 100
    assert fit_floor_ms(steps, runs=1) > 0
