"""The history view ``import`` builds as it writes (oracle.writtenview) equals the Prolog read of
the NEEM it wrote: idle gaps, parts of the day, who performed each action, rows without an
available set, several users interleaved, the sequence clock. Where the rules are not mirrored
(two rows of one begin) it says so and the import reads the NEEM as before. The CLI's import
keeps it, so that the first rank reads nothing through Prolog."""

from __future__ import annotations

import json
import random
from datetime import datetime, timedelta
from pathlib import Path

import pytest

from oracle.bridge import Bridge
from oracle.chains import read_chains
from oracle.historycache import HistoryCache
from oracle.neem.importing import import_chains
from oracle.store import open_store
from oracle.writtenview import WrittenView, views_of_import

CALLS = ["pick(apple)", "pour(thermos, green_mug)", "pick(banana)", "open(fridge)", "close(fridge)",
         "place(apple, kitchen_table)"]


def _rows(seed: int, n: int, users: tuple[str, ...] = ("ann", "bob"), clock: bool = True) -> list[dict[str, object]]:
    rng = random.Random(seed)
    t = {user: datetime(2024, 5, 1, 6, 0) for user in users}
    rows: list[dict[str, object]] = []
    for _ in range(n):
        user = rng.choice(users)
        t[user] += timedelta(seconds=rng.choice([1, 7, 40, 2000, 5 * 3600]))  # idle gaps, parts of the day
        duration = timedelta(seconds=rng.choice([2, 30]))
        row: dict[str, object] = {"user": user, "action": rng.choice(CALLS)}
        if clock:
            row["time"] = t[user].isoformat()
            row["end"] = (t[user] + duration).isoformat()
        if rng.random() < 0.8:
            row["available"] = rng.sample(CALLS, rng.randint(1, len(CALLS)))
        if rng.random() < 0.3:
            row["performed_by"] = rng.choice(["user", "robot", "together"])
        t[user] += duration
        rows.append(row)
    return rows


def _write(path: Path, rows: list[dict[str, object]]) -> Path:
    path.write_text("".join(json.dumps(row) + "\n" for row in rows))
    return path


def _compare(tmp_path: Path, onto, rows: list[dict[str, object]], no_clock: bool = False) -> int:
    chains = _write(tmp_path / "chains.jsonl", rows)
    store = open_store(tmp_path / "s.sqlite")
    written: dict[str, WrittenView] = {}  # as the import builds it while it logs
    import_chains(store, onto, chains, commit_every=50, no_clock=no_clock, views=written)
    views = views_of_import(read_chains(chains), no_clock=no_clock)
    compared = 0
    for info in store.neems():
        bridge = Bridge(store, info.id, onto)
        try:
            want = bridge.history_view()
        finally:
            bridge.close()
        for view in (views, written):
            got = view[info.user].view()
            assert got is not None
            assert got.rows == want.rows
            assert got.latest == want.latest
        compared += len(want.rows)
    store.close()
    return compared


@pytest.mark.parametrize("seed", [1, 2])
def test_the_written_view_equals_the_read(tmp_path, onto, seed):
    rows = _rows(seed, 160)
    assert _compare(tmp_path, onto, rows) > 160  # the idle rows too


def test_on_the_sequence_clock(tmp_path, onto):
    assert _compare(tmp_path, onto, _rows(3, 80, clock=False), no_clock=True) == 80


def test_rows_of_one_begin_are_not_mirrored(tmp_path, onto):
    rows = _rows(4, 10, users=("ann",))
    rows[5]["time"] = rows[4]["time"]  # same begin: Prolog orders them by IRI
    rows[5]["end"] = rows[4]["end"]
    views = views_of_import(read_chains(_write(tmp_path / "c.jsonl", rows)))
    assert views["ann"].view() is None


def test_the_import_keeps_it_and_the_first_rank_reads_nothing(tmp_path, onto, monkeypatch):
    from oracle.cli import main

    chains = _write(tmp_path / "c.jsonl", _rows(5, 120, users=("ann",)))
    store_path = tmp_path / "s.sqlite"
    calls: list[object] = []
    real = Bridge.history_view

    def counted(self, after=None):
        calls.append(after)
        return real(self, after)

    monkeypatch.setattr(Bridge, "history_view", counted)
    assert main(["import", str(chains), "--store", str(store_path)]) == 0
    assert calls == []  # nothing read back through Prolog
    store = open_store(store_path)
    (info,) = store.neems()
    bridge = Bridge(store, info.id, onto)
    try:
        kept = HistoryCache.default().view(bridge)
        assert calls == []  # the kept entry is at the store's mark
        monkeypatch.setattr(Bridge, "history_view", real)
        assert kept == bridge.history_view()
    finally:
        bridge.close()
        store.close()
