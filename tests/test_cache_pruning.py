"""The user's caches keyed by content stay bounded: the entries used least recently go first."""

from __future__ import annotations

import os
import shutil

from oracle.files import MAX_CACHE_ENTRIES, prune_cache, used
from oracle.ontology import build_with_report
from oracle.ontology.inputs import DEFAULT_MAPPING, DEFAULT_ODB


def test_prune_keeps_the_most_recently_used_entries_files_and_folders(tmp_path):
    for i in range(6):
        path = tmp_path / f"e{i}"
        if i % 2:
            path.mkdir()
            (path / "inside").write_text("x")
        else:
            path.write_text("x")
        os.utime(path, (1000 + i, 1000 + i))
    os.utime(tmp_path / "e0", (5000, 5000))   # the oldest written, used last
    (tmp_path / "other").write_text("not an entry")
    prune_cache(tmp_path, "e*", keep=3)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["e0", "e4", "e5", "other"]


def test_used_marks_an_entry_and_ignores_a_missing_one(tmp_path):
    path = tmp_path / "entry"
    path.write_text("x")
    os.utime(path, (1000, 1000))
    used(path)
    assert path.stat().st_mtime > 1000
    used(tmp_path / "missing")  # no error


def test_the_ontology_cache_keeps_at_most_its_bound_and_the_entry_in_use(tmp_path):
    cache = tmp_path / "cache"
    odb = tmp_path / "odb"
    shutil.copytree(DEFAULT_ODB, odb)
    mapping = tmp_path / "mapping.yaml"
    base = DEFAULT_MAPPING.read_text()
    mapping.write_text(base)
    build_with_report(odb, mapping, cache_dir=cache)
    (kept,) = cache.glob("ontology-*.json")
    # the cache one entry short of its bound, the others copies of the entry (as if built from
    # other mappings), all used after the kept one: the rounds below then go past the bound with
    # 3 builds, not 35 (~5 s)
    for i in range(MAX_CACHE_ENTRIES - 2):
        other = cache / f"ontology-other{i:02d}.json"
        shutil.copy(kept, other)
        os.utime(other, (1e9 + 1 + i, 1e9 + 1 + i))
    assert len(list(cache.glob("ontology-*.json"))) == MAX_CACHE_ENTRIES - 1
    for i in range(3):
        os.utime(kept, (1e9, 1e9))                      # written long ago ...
        build_with_report(odb, mapping, cache_dir=cache)
        assert kept.exists()                            # ... but used on every round
        mapping.write_text(base + f"\n# edit {i}\n")
        build_with_report(odb, mapping, cache_dir=cache)
        mapping.write_text(base)
    assert len(list(cache.glob("ontology-*.json"))) == MAX_CACHE_ENTRIES
    assert kept.exists()


def test_a_new_entry_removes_the_former_formats_pickles(tmp_path):
    """Entries were pickles until 2026-12-08: nothing reads them now, so writing a new entry
    removes them rather than leaving them in the user's cache for ever."""
    cache = tmp_path / "cache"
    cache.mkdir(mode=0o700)
    for name in ("ontology-old1.pickle", "ontology-old2.pickle", "tbox-old.pickle"):
        (cache / name).write_bytes(b"\x80\x05old")
    odb = tmp_path / "odb"
    shutil.copytree(DEFAULT_ODB, odb)
    onto, _ = build_with_report(odb, DEFAULT_MAPPING, cache_dir=cache)
    assert not list(cache.glob("ontology-*.pickle")) and len(list(cache.glob("ontology-*.json"))) == 1
    from oracle.store.ontology_tbox import tbox_for

    tbox_for(onto)
    assert not list(cache.glob("tbox-*.pickle")) and len(list(cache.glob("tbox-*.json"))) == 1
