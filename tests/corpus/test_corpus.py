"""The bad-input corpus: every input is refused with one line, a non-zero exit, and no change.

For each input in ``tests/corpus/<entry>/cases.tsv`` (and each one ``built.py`` makes) the
command runs in-process against a copy of a small store holding two NEEMs, and must: not raise
(no traceback), exit non-zero, print exactly one line on stderr containing the expected
fragment, leak no password, and leave the store's bytes as they were.
"""

from __future__ import annotations

import os
import shlex
import shutil
import sys
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import pytest

from tests.corpus.built import BUILT, corrupt
from tests.corpus.harness import assert_refused, run_cli, sample_chains, store_state

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]

#: How each entry's input reaches the program; ``{input}`` is the corpus file or folder.
COMMANDS = {
    "import": ["import", "{input}", "--store", "{store}"],
    "settings": ["rank", "--store", "{store}", "--neem", "p000-tea-red-yogurt", "--settings", "{input}"],
    "mapping": ["import", "{good}", "--store", "{store}", "--mapping", "{input}"],
    "odb": ["import", "{good}", "--store", "{store}", "--odb", "{input}"],
    "prolog": ["why-not", "{text}", "--store", "{store}", "--neem", "p000-tea-red-yogurt"],
    "load": ["load", "{input}", "--store", "{store}"],
    "cli": ["{args}"],
}


@dataclass(frozen=True)
class Case:
    entry: str
    name: str
    argv: tuple[str, ...]
    expected: str
    input: Path | None = None


def corpus_cases() -> Iterator[Case]:
    for entry, template in COMMANDS.items():
        for line in (HERE / entry / "cases.tsv").read_text(encoding="utf-8").splitlines():
            if line.startswith("#") or not line.strip():
                continue
            file, extra, expected = line.split("\t")
            path = HERE / entry / file
            argv: list[str] = []
            for part in template:
                if part == "{args}":
                    argv += shlex.split(path.read_text(encoding="utf-8"))
                elif part == "{text}":
                    argv.append(path.read_text(encoding="utf-8").rstrip("\n"))
                else:
                    argv.append(part.replace("{input}", str(path)))
            yield Case(entry, file, tuple(argv + shlex.split(extra)), expected, path)
    for name, _builder in BUILT.items():
        yield Case("built", name, (), "")


CASES = list(corpus_cases())


def test_the_corpus_is_large_enough():
    by_entry: dict[str, int] = {}
    for case in CASES:
        by_entry[case.entry] = by_entry.get(case.entry, 0) + 1
    assert sum(by_entry.values()) >= 500, by_entry
    assert all(count >= 7 for count in by_entry.values()), by_entry


@pytest.fixture(scope="session")
def world(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Path]:
    """A store with two NEEMs of 25 actions each, a valid chains file and a dump of one NEEM."""
    root = tmp_path_factory.mktemp("corpus")
    good = sample_chains(root / "good.jsonl", 25)
    store = root / "base.sqlite"
    done = run_cli(["import", str(good), "--store", str(store)])
    assert done.code == 0, done
    dump = root / "dump"
    done = run_cli(["export", "--store", str(store), "--neem", "p001-coffee-green-fruit", "--out", str(dump)])
    assert done.code == 0, done
    return {"store": store, "good": good, "dump": dump}


@pytest.fixture(scope="module", autouse=True)
def _one_ontology():
    """Build the default ontology once per module instead of once per command (a speed-up only:
    the ontology every command builds from the shipped files is the same). Module-scoped: a
    session-scoped patch stayed on for every test the worker ran after the corpus (test_tbox_cache's
    and the cache's tests among them) and answered their builds from this list."""
    import oracle.ontology
    import oracle.store.tbox

    build, tbox_of = oracle.ontology.build_ontology, oracle.store.tbox.tbox_from_graph
    built_default: list[object] = []
    tboxes: dict[int, object] = {}

    def cached_build(odb=None, mapping=None, soma=None, *rest, **kw):  # noqa: ANN001, ANN202
        if odb is None and mapping is None and soma is None and not rest and not kw:
            if not built_default:
                built_default.append(build())
            return built_default[0]
        return build(odb, mapping, soma, *rest, **kw)

    def cached_tbox(graph, *rest, **kw):  # noqa: ANN001, ANN202
        if rest or kw:
            return tbox_of(graph, *rest, **kw)
        if id(graph) not in tboxes:
            tboxes[id(graph)] = (graph, tbox_of(graph))
        return tboxes[id(graph)][1]

    patched = []
    for module in list(sys.modules.values()):
        for name, original, replacement in (("build_ontology", build, cached_build), ("tbox_from_graph", tbox_of, cached_tbox)):
            if getattr(module, name, None) is original:
                setattr(module, name, replacement)
                patched.append((module, name, original))
    yield
    for module, name, original in patched:
        setattr(module, name, original)


@pytest.fixture(scope="session")
def states_seen() -> dict[str, tuple[str, dict[str, int]]]:
    """The logical state of each store met, by the digest of its bytes (store_state): nearly every
    load case starts from the same bytes (a copy of the world's store), whose rows are read once
    rather than before each case (~45 ms each)."""
    return {}


@pytest.mark.parametrize("case", CASES, ids=[f"{c.entry}/{c.name}" for c in CASES])
def test_bad_input_is_refused_in_one_line_and_changes_nothing(case: Case, world, states_seen, tmp_path: Path, monkeypatch):
    store = tmp_path / "store.sqlite"
    shutil.copy(world["store"], store)
    scratch = tmp_path / "scratch"
    scratch.mkdir()
    argv, expected = list(case.argv), case.expected
    if case.entry == "built":
        argv, expected = BUILT[case.name](scratch)
    corrupted = any(a.startswith("corrupt:") for a in argv)  # a damaged store: compared byte for byte
    for token in [a for a in argv if a.startswith("corrupt:")]:
        argv.remove(token)
        corrupt(store, int(token.split(":")[1]))
    while argv and argv[0].startswith("env:"):
        name, _, value = argv.pop(0)[4:].partition("=")
        monkeypatch.setenv(name, value)
    places = {"{store}": str(store), "{good}": str(world["good"]), "{tmp}": str(scratch), "{dump}": str(world["dump"])}
    for key, value in places.items():
        argv = [a.replace(key, value) for a in argv]
    # A refused load may have written and dropped a hidden staging NEEM: its pages differ, so
    # for loads the store's content (every NEEM's registry entry and documents) is compared.
    logical = case.entry == "load" or (argv[:1] == ["load"] and not corrupted)
    before_bytes = store_state(store)
    if logical and before_bytes not in states_seen:
        states_seen[before_bytes] = logical_state(store)
    before = states_seen[before_bytes] if logical else before_bytes

    outcome = run_cli(argv)

    assert "Traceback" not in outcome.stderr
    assert_refused(outcome, expected)
    after_bytes = store_state(store)
    # the same bytes hold the same rows: the rows are read again only where the bytes changed
    if isinstance(before, tuple) and after_bytes != before_bytes:
        assert logical_state(store, before[1]) == before, "the store changed"
    else:
        assert after_bytes == before_bytes, "the store changed"


#: The store's shared dictionaries (interned terms, closures), with their key column: a refused
#: load may leave entries there that nothing refers to; the rows that were there stay as they were.
DICTIONARIES = {"terms": "id", "closure": "cid", "closure_member": "cid"}


def logical_state(path: Path, bounds: dict[str, int] | None = None) -> tuple[str, dict[str, int]]:
    """What the store holds, row by row: every table's and index's definition and every row of
    every table (SQLite's own bookkeeping aside), and of the dictionaries the rows up to
    ``bounds`` (their largest keys now where None). Equal to the store's bytes but for free pages
    and page order, which a dropped staging NEEM changes, and for dictionary entries nothing refers
    to; a row, a table or an index a refused load left behind changes it."""
    import hashlib
    import sqlite3

    digest = hashlib.sha256()
    connection = sqlite3.connect(f"file:{path}?mode=ro", uri=True)
    try:
        schema = connection.execute("SELECT type, name, sql FROM sqlite_master WHERE name NOT LIKE 'sqlite_%' ORDER BY name").fetchall()
        digest.update(repr(schema).encode())
        if bounds is None:
            bounds = {name: connection.execute(f'SELECT coalesce(max("{key}"), 0) FROM "{name}"').fetchone()[0]  # noqa: S608
                      for name, key in DICTIONARIES.items() if any(name == row[1] for row in schema)}  # fmt: skip
        for kind, name, _sql in schema:
            if kind != "table":
                continue
            digest.update(name.encode())
            if name in DICTIONARIES:  # names from sqlite_master and DICTIONARIES, never from input
                rows = connection.execute(f'SELECT * FROM "{name}" WHERE "{DICTIONARIES[name]}" <= ?', (bounds.get(name, 0),))  # noqa: S608
            else:
                rows = connection.execute(f'SELECT * FROM "{name}"')  # noqa: S608
            for row in rows:
                digest.update(repr(row).encode())
    finally:
        connection.close()
    return digest.hexdigest(), bounds


@pytest.mark.parametrize("seed", range(5))
@pytest.mark.parametrize(
    "command", [["export", "--out", "{tmp}/out"], ["neems"], ["why-not", "pick(banana)", "--neem", "p000-tea-red-yogurt"]]
)
def test_a_damaged_store_gives_readers_an_error_or_an_answer_never_a_traceback(seed, command, world, tmp_path):
    # Readers do not check the whole file (that would cost them a full read); a damaged page
    # they meet is a one-line error, a page they do not need does not stop them.
    store = tmp_path / "store.sqlite"
    shutil.copy(world["store"], store)
    corrupt(store, seed)
    argv = [a.replace("{tmp}", str(tmp_path)) for a in command] + ["--store", str(store)]
    outcome = run_cli(argv)
    assert outcome.crash is None, outcome.crash
    if outcome.code != 0:
        assert len(outcome.stderr.strip().splitlines()) == 1, outcome.stderr
