"""The user's decisions in the NEEM: written as the user's mental act, read back, on SQLite and
on the MongoDB layout (mongomock-ng)."""

from __future__ import annotations

from datetime import datetime, timezone

import pytest

from oracle.errors import LoggingError
from oracle.neem import terms as T
from oracle.neem.decisions import DESCRIBED_BY, latest_decision, record_decision
from oracle.neem.writer import NeemLogger
from tests.store.conftest import make_store

T0 = datetime(2024, 5, 6, 8, 30, tzinfo=timezone.utc).timestamp()


@pytest.fixture(scope="module")
def onto():
    from oracle.ontology import build_ontology

    return build_ontology()


@pytest.mark.parametrize("kind", ["sqlite", "mongomock"])
def test_the_latest_decision_is_the_users_and_reads_back_in_order(kind, tmp_path, onto):
    store = make_store(kind, tmp_path)
    log = NeemLogger.create(store, onto, user="ada")
    log.action("pick(red_mug)", T0, T0 + 5)  # the robot's action: never read as a decision
    assert latest_decision(store, log.neem_id, log.ns, log.vocab.has_rank) is None
    first = record_decision(log, ["open(fridge)"], T0 + 10)
    flow = record_decision(log, ["open(small_drawer)", "pick(red_mug)", "close(small_drawer)"], T0 + 20)
    log.flush()
    back = latest_decision(store, log.neem_id, log.ns, log.vocab.has_rank)
    assert back == flow and back.calls == ("open(small_drawer)", "pick(red_mug)", "close(small_drawer)")
    assert back.workflow == list(back.calls) and first.workflow is None and first.task == "open(fridge)"
    performer = next(store.find(log.neem_id, s=flow.iri, p=T.PERFORMED_BY, exact=True))["o"]
    assert performer.endswith("ada") and "robot" not in performer
    assert sum(1 for _ in store.find(log.neem_id, p=DESCRIBED_BY, exact=True)) == 2
    store.close()


def test_a_decision_for_an_unknown_task_writes_nothing(tmp_path, onto):
    store = make_store("sqlite", tmp_path)
    log = NeemLogger.create(store, onto, user="ada")
    before = store.count(log.neem_id)
    with pytest.raises(LoggingError, match="fly"):
        record_decision(log, ["open(fridge)", "fly(away)"], T0)
    log.flush()
    assert store.count(log.neem_id) == before
    store.close()
