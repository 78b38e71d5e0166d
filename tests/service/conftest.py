"""A live service over a temporary SQLite store, driven in-process through Starlette's client."""

from __future__ import annotations

import shutil
from collections.abc import Iterator
from datetime import datetime, timezone

import pytest

from oracle.algorithm.params import Hyperparameters
from oracle.ontology import build_ontology

pytestmark = pytest.mark.skipif(shutil.which("swipl") is None, reason="SWI-Prolog (swipl) is not installed; run make setup")

#: Two mornings of one small routine; the third morning is what the tests rank.
ROUTINE = ["open(small_drawer)", "pick(red_mug)", "place(red_mug, counter_top)", "close(small_drawer)",
           "pick(thermos)", "pour(thermos, red_mug)", "place(thermos, counter_top)"]
AVAILABLE = sorted(set(ROUTINE + ["pick(banana)", "open(fridge)"]))


def at(day: int, second: int) -> float:
    return datetime(2026, 3, 2 + day, 8, 0, tzinfo=timezone.utc).timestamp() + second


@pytest.fixture(scope="session")
def onto():
    return build_ontology()


@pytest.fixture()
def ctx(tmp_path, onto) -> Iterator:
    from oracle.service import build_context

    context = build_context(str(tmp_path / "s.sqlite"), onto, Hyperparameters())
    yield context
    context.thread.close()


@pytest.fixture()
def client(ctx) -> Iterator:
    from fastapi.testclient import TestClient

    from oracle.service.app import create_app

    with TestClient(create_app(ctx), base_url="http://127.0.0.1") as test_client:
        yield test_client


def drive(client, neem: str, days: int = 2) -> None:
    """The robot's loop for ``days`` mornings: situation, then the action done, for each step."""
    for day in range(days):
        drive_day(client, neem, day)


def drive_day(client, neem: str, day: int) -> None:
    """One morning of the routine: situation, then the action done, for each step."""
    for i, call in enumerate(ROUTINE):
        begin = at(day, 10 * i)
        assert client.post(f"/api/neems/{neem}/situation", json={"available": AVAILABLE, "at": begin}).status_code == 200
        response = client.post(f"/api/neems/{neem}/actions", json={"call": call, "begin": begin, "end": begin + 5})
        assert response.status_code == 200, response.text
