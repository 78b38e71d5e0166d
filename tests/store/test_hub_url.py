"""The hub registry entry's ``url`` and ``repo``: openEASE (ease-crc/openease ``neems/neem.py``)
keys a NEEM's overview page ``/overview/<repo path>`` by ``repo``, else the last part of ``url``,
and reads the page's README.md at ``url + '/-/raw/master/README.md'``; an empty ``url`` left the
export without a page. Default: the place the hub gives a NEEM of that name; ``export --url``."""

from __future__ import annotations

import pytest

from oracle.cli import main
from oracle.store.dump import export_neem, iter_bson
from oracle.store.meta import NEEMGIT, hub_document
from tests.store.test_hub_export import logged, onto  # noqa: F401  (the fixture)

pytest.importorskip("mongomock_ng")


def openease_repo_path(entry: dict) -> str:
    """neems/neem.py's ``neem_repo_path``, as openEASE computes it (its non-http prefixing aside)."""
    return entry["repo"] if "repo" in entry else entry["url"].split("/")[-1]


def test_the_default_url_is_the_hubs_place_for_the_neem(tmp_path, onto) -> None:
    store, neem_id = logged(tmp_path, onto)
    export_neem(store, neem_id, tmp_path / "dump", db_name="neems", hub_prefix=True)
    (entry,) = iter_bson(tmp_path / "dump" / "meta" / "neems" / "meta.bson")
    assert entry["url"] == f"{NEEMGIT}neems/breakfast" and entry["url"].startswith("http")
    assert openease_repo_path(entry) == "breakfast"
    store.close()


def test_export_url_names_the_repository(tmp_path, onto, capsys) -> None:
    store, neem_id = logged(tmp_path, onto)
    store.close()
    db, out = str(tmp_path / "s.sqlite"), tmp_path / "d"
    url = "https://neemgit.informatik.uni-bremen.de/neems/ada-breakfast-2024"
    assert main(["export", "--store", db, "--neem", neem_id, "--out", str(out), "--url", url]) == 0
    (entry,) = iter_bson(out / "meta" / "roslog" / "meta.bson")
    assert entry["url"] == url and openease_repo_path(entry) == "ada-breakfast-2024"
    # one URL for every NEEM of a store, or one openEASE cannot read: refused in one line, nothing written
    capsys.readouterr()
    assert main(["export", "--store", db, "--out", str(tmp_path / "e"), "--url", url]) != 0
    assert main(["export", "--store", db, "--neem", neem_id, "--out", str(tmp_path / "f"), "--url", "file:///x"]) != 0
    err = capsys.readouterr().err.strip().splitlines()
    assert [line.split(":")[0] for line in err] == ["error", "error"]
    assert not (tmp_path / "e").exists() and not (tmp_path / "f").exists()


def test_an_entry_with_its_own_url_and_repo_keeps_them() -> None:
    entry = hub_document({"name": "n", "url": "https://example.org/neems/x", "repo": "y"}, "n", visibility=False)
    assert (entry["url"], entry["repo"]) == ("https://example.org/neems/x", "y")
    assert hub_document({"name": "a b"}, "a b", visibility=False)["url"].endswith("/neems/a%20b")
