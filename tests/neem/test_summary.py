"""The registry keeps each NEEM's summary (actions, begin, end): ``neems`` reads no triples
when it is current, and recomputes it once when a write the logger did not make moved the store."""

from __future__ import annotations

from datetime import datetime, timedelta

import pytest

from oracle.neem.query import count_actions, summarize_neem
from oracle.neem.writer import NeemLogger
from oracle.store import Triple
from oracle.store.base import SUMMARY_KEY
from oracle.store.dump import export_neem, load_dump
from tests.neem.test_logger import onto, small_tbox, tbox, tbox_for  # noqa: F401 - shared fixtures
from tests.store.conftest import backend, make_store, store  # noqa: F401

T0 = datetime(2024, 5, 6, 8, 30)


def _log(store, onto, tbox, commit_every: int = 1) -> NeemLogger:
    logger = NeemLogger.create(store, onto, user="alice", tbox=tbox, commit_every=commit_every)
    logger.available(["pick(green_mug)", "pour(thermos, green_mug)"], T0)
    logger.action("pick(green_mug)", T0, T0 + timedelta(seconds=5))
    logger.action("pour(thermos, green_mug)", T0 + timedelta(seconds=90), T0 + timedelta(seconds=100),
                  available=["pick(green_mug)"])  # fmt: skip  (an idle action fills the gap)
    logger.preference([("pick(green_mug)", 0.5)], T0 + timedelta(seconds=200))
    logger.flush()
    return logger


def _no_triple_reads(store, monkeypatch) -> None:
    def refuse(*args, **kwargs):
        raise AssertionError("the listing read triples")

    monkeypatch.setattr(store, "find", refuse)
    monkeypatch.setattr(store, "match", refuse)


@pytest.mark.parametrize("commit_every", [1, 3])
def test_the_kept_summary_is_what_the_triples_say(store, onto, tbox_for, commit_every):
    neem = _log(store, onto, tbox_for, commit_every).neem_id
    actions, begin, end = count_actions(store, neem)
    assert actions == 3  # pick, idle, pour; the mental actions are not counted
    kept = store.neem(neem).meta[SUMMARY_KEY]
    assert (kept["actions"], kept["begin"], kept["end"]) == (actions, begin, end)


def test_a_current_summary_is_listed_without_reading_triples(store, onto, tbox_for, monkeypatch):
    neem = _log(store, onto, tbox_for).neem_id
    expected = count_actions(store, neem)
    _no_triple_reads(store, monkeypatch)
    row = summarize_neem(store, neem)
    assert (row.actions, row.begin, row.end) == expected


def test_a_write_the_logger_did_not_make_is_counted_once(store, onto, tbox_for, monkeypatch):
    logger = _log(store, onto, tbox_for)
    neem = logger.neem_id
    act = f"{logger.ns}Action_bare"
    store.insert(neem, [Triple(act, "http://www.w3.org/1999/02/22-rdf-syntax-ns#type",
                               "http://www.ontologydesignpatterns.org/ont/dul/DUL.owl#Action")])  # fmt: skip
    assert summarize_neem(store, neem).actions == 4
    _no_triple_reads(store, monkeypatch)  # kept again: the second listing reads no triples
    assert summarize_neem(store, neem).actions == 4


def test_a_store_without_summaries_lists_correctly(store, onto, tbox_for):
    neem = _log(store, onto, tbox_for).neem_id
    store.update_meta(neem, **{SUMMARY_KEY: None})  # as an older version left it: nothing kept
    assert summarize_neem(store, neem).actions == 3
    assert store.neem(neem).meta[SUMMARY_KEY]["actions"] == 3


def test_a_dump_carries_no_summary_and_its_load_lists_correctly(tmp_path, onto, tbox):
    source = make_store("sqlite", tmp_path / "a")
    neem = _log(source, onto, tbox).neem_id
    export_neem(source, neem, tmp_path / "dump")
    assert SUMMARY_KEY not in (tmp_path / "dump" / "meta.json").read_text()
    target = make_store("sqlite", tmp_path / "b")
    (loaded,) = load_dump(target, tmp_path / "dump")
    assert summarize_neem(target, loaded).actions == 3
