"""Each per-process limit of guard.Limits, in-process (the real-server attacks are test_attacks.py)."""

from __future__ import annotations

import shutil
from collections.abc import Iterator

import pytest

from oracle.algorithm.params import Hyperparameters
from oracle.service.guard import Limits

pytestmark = pytest.mark.skipif(shutil.which("swipl") is None, reason="SWI-Prolog (swipl) is not installed; run make setup")


@pytest.fixture()
def limited(tmp_path, request) -> Iterator:
    """A client of a service with the limits the test gives (indirect parameter)."""
    from fastapi.testclient import TestClient

    from oracle.ontology import build_ontology
    from oracle.service import build_context
    from oracle.service.app import create_app

    limits = Limits(**request.param)
    ctx = build_context(str(tmp_path / "s.sqlite"), build_ontology(), Hyperparameters(), limits=limits)
    try:
        with TestClient(create_app(ctx), base_url="http://127.0.0.1", raise_server_exceptions=False) as client:
            yield client
    finally:
        ctx.thread.close()


@pytest.mark.parametrize("limited", [dict(new_neems=1)], indirect=True)
def test_neems_made_per_process(limited):
    assert limited.post("/api/neems", json={"user": "ada"}).status_code == 201
    refused = limited.post("/api/neems", json={"user": "bea"})
    assert refused.status_code == 429 and "limit" in refused.json()["error"]
    assert [n["user"] for n in limited.get("/api/neems").json()] == ["ada"]


@pytest.mark.parametrize("limited", [dict(sessions=1)], indirect=True)
def test_live_sessions_per_process(limited):
    assert limited.post("/api/neems", json={"user": "ada"}).status_code == 201
    refused = limited.post("/api/neems", json={"user": "bea"})
    assert refused.status_code == 503 and "open" in refused.json()["error"]


@pytest.mark.parametrize("limited", [dict(subscribers=0)], indirect=True)
def test_event_stream_subscribers(limited):
    refused = limited.get("/api/events")
    assert refused.status_code == 503 and "event streams" in refused.json()["error"]


@pytest.mark.parametrize("limited", [dict(in_flight=0)], indirect=True)
def test_requests_in_flight(limited):
    refused = limited.get("/api/neems")
    assert refused.status_code == 503 and refused.headers["retry-after"] == "1"


@pytest.mark.parametrize("limited", [dict(body_bytes=1024, json_depth=3)], indirect=True)
def test_body_size_and_depth(limited):
    big = limited.post("/api/neems", content=b'{"user": "' + b"a" * 2000 + b'"}', headers={"content-type": "application/json"})
    assert big.status_code == 413 and len(big.content) < 200 and b"aaaa" not in big.content
    deep = limited.post("/api/prolog", json={"query": "X = 1", "bindings": {"X": [[[1]]]}})
    assert deep.status_code == 400 and "nests deeper than 3" in deep.json()["error"]
    strings = limited.post("/api/prolog", json={"query": "X = '[[[[[['", "neem": "none"})
    assert strings.status_code == 404  # brackets inside strings nest nothing


@pytest.mark.parametrize("limited", [dict()], indirect=True)
def test_hosts(limited):
    assert limited.get("/api/neems", headers={"host": "evil.example"}).status_code == 421
    assert limited.get("/api/neems", headers={"host": "[::1]:8765"}).status_code == 200
    assert limited.get("/api/neems", headers={"host": "LOCALHOST"}).status_code == 200

