"""/api/prolog's limits hold for what a stack limit does not bound (issue 54): a query that
builds a 2 GiB atom, one whose answer is 12 million characters, one that fills the stack. Each
is one JSON error, the service keeps answering, and the next query runs. The memory and time
figures are in ``make bench`` (area querylimits)."""

from __future__ import annotations

import shutil
from collections.abc import Iterator

import pytest

from oracle.benchmarks.querylimits import doubling, rss_mb
from oracle.benchmarks.security import Service, call, start, stop

pytestmark = pytest.mark.skipif(shutil.which("swipl") is None, reason="SWI-Prolog (swipl) is not installed; run make setup")


@pytest.fixture(scope="module")
def served(tmp_path_factory) -> Iterator[Service]:
    service = start(tmp_path_factory.mktemp("limits") / "s.sqlite", "--query-seconds", "20")
    try:
        assert call(service.url, "/api/neems", {"user": "ada", "neem": "ada"})[0] == 201
        yield service
    finally:
        stop(service)


def ask(service: Service, query: str) -> tuple[int, dict]:
    status, answer, _ = call(service.url, "/api/prolog", {"query": query, "neem": "ada", "timeout": 5})
    assert isinstance(answer, dict), answer
    return status, answer


@pytest.mark.parametrize(("query", "said"), [
    (doubling(31), "the query"),  # past the child's address space: it ends, the query gets an error
    (doubling(22, answer=True), "more than a service query may return"),
    (doubling(25, answer=True), "more memory than a service query may use"),
])
def test_a_query_past_a_limit_is_one_json_error_and_the_next_runs(served, query, said):
    before = rss_mb(served.process.pid)
    status, answer = ask(served, query)
    assert status == 400 and set(answer) == {"error"} and said in answer["error"], answer
    assert ask(served, "X = 1") == (200, {"solutions": [{"X": 1}], "more": False, "offset": 0})
    # the answer never reached the service: its memory is what it was, give or take its own work
    assert rss_mb(served.process.pid) - before < 50


def test_an_answer_under_the_limit_is_whole(served):
    status, answer = ask(served, doubling(18, answer=True))
    assert status == 200 and len(answer["solutions"][0]["Big"]) == 2 ** 18
