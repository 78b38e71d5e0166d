"""The compiled Prolog modules are cached per user and keyed by content: a second process loads
the cached compilation, an edited module gets a new entry (never the stale one), and a damaged
entry falls back to the sources."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from oracle.modulecache import modules_key
from oracle.paths import project_home

pytestmark = pytest.mark.skipif(shutil.which("swipl") is None, reason="SWI-Prolog (swipl) is not installed")

#: Whether the loaded odb_history module holds the probe/1 fact an edit adds (and its exports).
PROBE = ("from oracle.bridge import engine; engine.ensure_loaded();"
         " assert engine.run('current_predicate(odb_history:situation_history/1)');"
         " print(engine.run('catch(odb_history:probe(_), _, fail)') != [])")


def _home_copy(tmp_path: Path) -> Path:
    home = tmp_path / "home"
    for name in ("ontology", "prolog"):
        shutil.copytree(project_home() / name, home / name)
    return home


def _probe(home: Path, cache: Path) -> str:
    env = {**os.environ, "NEEM_ORACLE_HOME": str(home), "NEEM_ORACLE_CACHE": str(cache)}
    done = subprocess.run([sys.executable, "-c", PROBE], capture_output=True, text=True, env=env, check=True)
    return done.stdout.strip()


def _entries(cache: Path) -> list[Path]:
    return sorted((cache / "prolog").glob("*/modules.qlf"))


def test_the_key_follows_every_source_and_the_version(tmp_path):
    home = _home_copy(tmp_path)
    folder = home / "prolog"
    key = modules_key(folder, "90004")
    assert modules_key(folder, "90004") == key and modules_key(folder, "90205") != key
    module = folder / "odb" / "history.pl"
    module.write_text(module.read_text() + "\n% an edit\n")
    assert modules_key(folder, "90004") != key


def test_a_second_process_loads_the_cached_modules_and_an_edit_compiles_anew(tmp_path):
    home, cache = _home_copy(tmp_path), tmp_path / "cache"
    assert _probe(home, cache) == "False"
    first = _entries(cache)
    assert len(first) == 1 and oct(first[0].stat().st_mode & 0o777) == "0o600"
    assert _probe(home, cache) == "False" and _entries(cache) == first
    module = home / "prolog" / "odb" / "history.pl"
    module.write_text(module.read_text() + "\nprobe(edited).\n")
    assert _probe(home, cache) == "True"  # the edited module, not the cached one
    assert len(_entries(cache)) == 2


def test_a_damaged_entry_falls_back_to_the_sources(tmp_path):
    home, cache = _home_copy(tmp_path), tmp_path / "cache"
    _probe(home, cache)
    (entry,) = _entries(cache)
    entry.write_bytes(b"not a qlf")
    assert _probe(home, cache) == "False"  # loaded from the sources (probe/1 is not there)
    assert _entries(cache) == [] or _entries(cache)[0].read_bytes() != b"not a qlf"


def test_publishing_an_entry_prunes_the_least_recently_used_beyond_the_bound(tmp_path):
    from oracle import modulecache

    root = tmp_path / "prolog"
    for i in range(modulecache.KEPT + 2):
        entry = root / f"{i:024x}"
        entry.mkdir(parents=True)
        (entry / modulecache.COMPILED).write_text("old")
        os.utime(entry, (1000 + i, 1000 + i))
    modulecache.loaded(root / f"{0:024x}" / modulecache.COMPILED)  # the oldest, just used
    compiled = root / ("f" * 24) / modulecache.COMPILED
    loader = modulecache.prepare(compiled, [], str)
    loader.with_name(modulecache.COMPILED).write_text("new")
    modulecache.publish(loader, compiled)
    names = sorted(p.name for p in root.iterdir())
    assert len(names) == modulecache.KEPT and compiled.is_file()
    assert f"{0:024x}" in names and f"{1:024x}" not in names and f"{2:024x}" not in names
