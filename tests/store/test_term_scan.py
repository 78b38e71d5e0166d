"""The term cache of a SQLite store (oracle.store.sqlite.terms) reads every term in one scan
while the table fits the cache; once a scan was thrown away because the table outgrew it, terms
are looked up one by one (many robots logging into one store had it scan the table over and
over)."""

from __future__ import annotations

from oracle.store import open_store
from oracle.store.sqlite import terms as terms_module


def test_a_table_that_outgrew_the_cache_is_no_longer_scanned(tmp_path, monkeypatch):
    monkeypatch.setattr(terms_module, "TERM_CACHE", 20)
    monkeypatch.setattr(terms_module, "TERM_SCAN_AFTER", 3)
    store = open_store(tmp_path / "s.sqlite")
    terms = store._terms
    with store.transaction():
        ids = terms.tids([f"https://example.org/t{i}" for i in range(40)])
    terms.forget()  # a fresh cache, as after opening the store
    assert terms.scan
    for value, tid in list(ids.items())[:5]:
        assert terms.value(tid) == value
    assert terms.all_read  # misses past TERM_SCAN_AFTER: one scan read the whole table
    with store.transaction():
        terms.tids(["https://example.org/new"])  # more than the cache holds: forgotten
    assert not terms.scan and not terms.all_read
    for value, tid in list(ids.items())[10:20]:
        assert terms.value(tid) == value  # looked up one by one, right all the same
    assert not terms.all_read and len(terms.values) <= 11
    store.close()
