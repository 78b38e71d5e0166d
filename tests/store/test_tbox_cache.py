"""The TBox a NEEM stores is kept in the user's cache beside the built ontology: an import or a
session with a cached ontology then never loads rdflib; a damaged or foreign entry is made again."""

from __future__ import annotations

import stat
import subprocess
import sys
from dataclasses import replace
from pathlib import Path

from oracle.ontology import build_ontology
from oracle.store import ontology_tbox as tbox_module
from oracle.store.ontology_tbox import tbox_for


def _entries(cache: Path) -> list[Path]:
    return sorted(cache.glob("tbox-*.json"))


def test_the_second_tbox_is_the_cached_one_and_equal(tmp_path, monkeypatch):
    cache = tmp_path / "cache"
    onto = build_ontology(cache_dir=cache)
    first = tbox_for(onto)
    (entry,) = _entries(cache)
    assert stat.S_IMODE(entry.stat().st_mode) == 0o600

    def refuse(_onto):
        raise AssertionError("converted again although the cache holds it")

    monkeypatch.setattr(tbox_module, "_converted", refuse)
    again = tbox_for(build_ontology(cache_dir=cache))
    assert again == first and again.triples and again.markers


def test_a_cached_tbox_needs_no_rdflib(tmp_path):
    cache = tmp_path / "cache"
    tbox_for(build_ontology(cache_dir=cache))
    probe = (
        "import sys, pathlib\n"
        "from oracle.ontology import build_ontology\n"
        "from oracle.store.ontology_tbox import tbox_for\n"
        f"tbox = tbox_for(build_ontology(cache_dir=pathlib.Path({str(cache)!r})))\n"
        "print(len(tbox.triples) > 0, 'rdflib' in sys.modules)\n"
    )
    out = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, check=True).stdout.split()
    assert out == ["True", "False"]


def test_an_ontology_from_no_cached_build_is_converted_each_time(tmp_path):
    cache = tmp_path / "cache"
    onto = replace(build_ontology(cache_dir=cache), cache_key=None)
    onto.cache_dir = cache
    assert tbox_for(onto).triples and not _entries(cache)


def test_a_damaged_or_foreign_entry_is_made_again(tmp_path):
    cache = tmp_path / "cache"
    onto = build_ontology(cache_dir=cache)
    good = tbox_for(onto)
    (entry,) = _entries(cache)
    for damage in (b"not an entry", entry.read_bytes()[:1000], b""):
        entry.write_bytes(damage)
        assert tbox_for(onto) == good
        assert entry.stat().st_size > 1000
    entry.chmod(0o666)  # anyone could have replaced it: made again, not read
    assert tbox_for(onto) == good and stat.S_IMODE(entry.stat().st_mode) == 0o600
