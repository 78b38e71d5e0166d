"""The bad-input corpus on the MongoDB code path (a mongomock-ng server): the entries that write.

Every ``import``, ``load``, ``mapping`` and ``odb`` input (and the built ``import`` ones) runs
against one MongoStore holding two NEEMs; each must be refused in one line with a non-zero exit
and leave what a reader sees (the NEEM listing, every registry entry and document, and no hidden
staging NEEM) exactly as it was. Readers' inputs (settings, why-not text, options) never reach
a backend's write path and run on SQLite only (test_corpus.py).
"""

from __future__ import annotations

import hashlib
import json
from pathlib import Path

import bson
import mongomock_ng as mongomock
import pytest

from oracle.store import COLLECTION_KINDS
from oracle.store.mongo import MongoStore
from tests.corpus.built import BUILT
from tests.corpus.harness import assert_refused, run_cli, sample_chains
from tests.corpus.test_corpus import CASES, Case, _one_ontology  # noqa: F401 - a session fixture

WRITING = ("import", "load", "mapping", "odb")
MONGO_CASES = [c for c in CASES if c.entry in WRITING or (c.entry == "built" and c.name.startswith("import"))]
SPEC = "mongodb://corpus-test-double/roslog"

# fault injection and whole-corpus runs: with the slow tests (CI, or make test SLOW=1)
pytestmark = pytest.mark.slow


class _Shared(MongoStore):
    """A store on the one shared test server; closing it leaves the server up for the next case."""

    def close(self) -> None:
        pass


@pytest.fixture(scope="module")
def server(tmp_path_factory: pytest.TempPathFactory) -> dict[str, object]:
    from oracle.neem.importing import import_chains
    from oracle.ontology import build_ontology

    root = tmp_path_factory.mktemp("corpus-mongo")
    good = sample_chains(root / "good.jsonl", 8)
    client = mongomock.MongoClient()
    store = _Shared(client, "roslog")
    import_chains(store, build_ontology(), good, commit_every=50)
    dump = root / "dump"
    done = run_cli_on(client, ["export", "--store", SPEC, "--neem", "p001-coffee-green-fruit", "--out", str(dump)])
    assert done.code == 0, done
    return {"client": client, "good": good, "dump": dump, "listing": listing(client), "whole": state(client)}


def run_cli_on(client: object, argv: list[str]):  # noqa: ANN201 - the harness's Outcome
    import oracle.store

    real = oracle.store.open_mongo

    def on_test_double(uri: str, **kw: object) -> MongoStore:
        if uri != SPEC:
            return real(uri, **kw)  # type: ignore[arg-type]
        return _Shared(client, "roslog", location="mongodb://corpus-test-double/roslog")

    oracle.store.open_mongo = on_test_double  # type: ignore[assignment]
    try:
        return run_cli(argv)
    finally:
        oracle.store.open_mongo = real  # type: ignore[assignment]


def listing(client: object) -> str:
    """Cheap, per case: every collection with its size, and every registry entry (hidden ones too)."""
    db = client["roslog"]  # type: ignore[index]
    names = sorted(db.list_collection_names())
    entries = sorted(db["meta"].find({}), key=lambda doc: str(doc["_id"]))
    return json.dumps([[n, db[n].count_documents({})] for n in names] + [bson.encode(e).hex() for e in entries])


def state(client: object) -> str:
    """A digest of everything a reader of the database sees, hidden NEEMs included."""
    store = _Shared(client, "roslog")
    digest = hashlib.sha256()
    for info in [*store.neems(), *store.staging_neems()]:
        digest.update(bson.encode({"id": info.id, "meta": dict(info.meta)}))
        for kind in COLLECTION_KINDS:
            for doc in store.read_documents(info.id, kind):
                digest.update(bson.encode(doc))
    digest.update(json.dumps(sorted(store.db.list_collection_names())).encode())
    return digest.hexdigest()


@pytest.mark.parametrize("case", MONGO_CASES, ids=[f"{c.entry}/{c.name}" for c in MONGO_CASES])
def test_bad_input_changes_nothing_on_mongodb(case: Case, server, tmp_path: Path, monkeypatch):
    scratch = tmp_path / "scratch"
    scratch.mkdir()
    argv, expected = list(case.argv), case.expected
    if case.entry == "built":
        argv, expected = BUILT[case.name](scratch)
    while argv and argv[0].startswith("env:"):
        name, _, value = argv.pop(0)[4:].partition("=")
        monkeypatch.setenv(name, value)
    places = {"{store}": SPEC, "{good}": str(server["good"]), "{tmp}": str(scratch), "{dump}": str(server["dump"])}
    for key, value in places.items():
        argv = [a.replace(key, value) for a in argv]
    outcome = run_cli_on(server["client"], argv)

    assert_refused(outcome, expected)
    assert listing(server["client"]) == server["listing"], "the database changed"


def test_after_the_whole_corpus_every_document_is_as_it_was(server):
    # Run after the cases above (file order): one full comparison of every document.
    assert state(server["client"]) == server["whole"]
