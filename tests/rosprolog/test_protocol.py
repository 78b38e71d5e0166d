"""rosprolog's protocol over a stand-in Prolog: ids, modes, statuses, finish, pages."""

from __future__ import annotations

import json
import threading

import pytest

from oracle.rosprolog.protocol import (ALL_SOLUTIONS, INCREMENTAL, NO_SOLUTION, OK, QUERY_FAILED, WRONG_ID, DoorError, Page,
                                       Queries, QueryFailed, page_of, request)


class Counting:
    """Answers ``between(1, N, X)`` for N = the text's length; records every page asked."""

    def __init__(self) -> None:
        self.asked: list[tuple[str, int, int]] = []

    def __call__(self, text: str, offset: int, limit: int) -> Page:
        self.asked.append((text, offset, limit))
        if text == "fail":
            raise QueryFailed("unknown predicate fail/0")
        rows = [json.dumps({"X": i}) for i in range(1, len(text) + 1)]
        return Page(rows[offset:offset + limit], offset + limit < len(rows))


def drain(queries: Queries, id: str) -> list[tuple[int, str]]:
    steps = []
    while True:
        steps.append(queries.next_solution(id))
        if steps[-1][0] != OK:
            return steps


def test_incremental_asks_one_then_the_rest_in_one_page():
    ask = Counting()
    queries = Queries(ask, page=100)
    assert queries.query("q", "x" * 13, INCREMENTAL) == (True, "")
    steps = drain(queries, "q")
    assert [json.loads(s)["X"] for status, s in steps if status == OK] == list(range(1, 14))
    assert steps[-1] == (NO_SOLUTION, "")
    assert ask.asked == [("x" * 13, 0, 1), ("x" * 13, 1, 100)]


def test_all_solutions_in_pages():
    ask = Counting()
    queries = Queries(ask, page=5)
    queries.query("q", "x" * 12, ALL_SOLUTIONS)
    assert len([s for s in drain(queries, "q") if s[0] == OK]) == 12
    assert [(offset, limit) for _, offset, limit in ask.asked] == [(0, 5), (5, 5), (10, 5)]


def test_once_runs_nothing_beyond_the_first_solution():
    ask = Counting()
    queries = Queries(ask)
    queries.query("q", "x" * 13, INCREMENTAL)
    assert queries.next_solution("q")[0] == OK
    queries.finish("q")
    assert len(ask.asked) == 1 and queries.next_solution("q") == (WRONG_ID, "")


def test_failure_told_on_next_solution():
    queries = Queries(Counting())
    assert queries.query("q", "fail", INCREMENTAL) == (True, "")
    assert queries.next_solution("q") == (QUERY_FAILED, "unknown predicate fail/0")
    assert queries.next_solution("q") == (QUERY_FAILED, "unknown predicate fail/0")


def test_ids_taken_finish_all_and_the_open_limit():
    queries = Queries(Counting(), max_open=2)
    assert queries.query("a", "x", INCREMENTAL)[0] and queries.query("b", "x", INCREMENTAL)[0]
    assert queries.query("a", "x", INCREMENTAL) == (False, "Another query is already being processed with id a.")
    assert not queries.query("c", "x", INCREMENTAL)[0]
    queries.finish("*")
    assert queries.open_ids() == [] and queries.query("c", "x", INCREMENTAL)[0]
    queries.finish("never-opened")  # no error, as rosprolog


def test_call_by_service_name_checks_fields():
    queries = Queries(Counting())
    assert queries.call("query", {"id": "q", "query": "xx", "mode": 1}) == {"ok": True, "message": ""}
    assert queries.call("next_solution", {"id": "q"}) == {"status": OK, "solution": json.dumps({"X": 1})}
    assert queries.call("finish", {"id": "q"}) == {}
    assert queries.call("simple_query", {"id": "old", "query": "x"}) == {"ok": True, "message": ""}  # json_prolog's name
    for service, args in (("query", {"id": 1, "query": "x"}), ("query", {"id": "q", "query": "x", "mode": "1"}),
                          ("next_solution", {}), ("simple_query", {"id": "q"})):
        with pytest.raises(DoorError):
            queries.call(service, args)


def test_clients_at_once_each_get_their_own_solutions():
    queries = Queries(Counting(), page=3)
    results: dict[int, list[int]] = {}

    def client(i: int) -> None:
        queries.query(f"c{i}", "x" * (i + 1), i % 2)
        results[i] = [json.loads(s)["X"] for status, s in drain(queries, f"c{i}") if status == OK]
        queries.finish(f"c{i}")

    threads = [threading.Thread(target=client, args=(i,)) for i in range(20)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert results == {i: list(range(1, i + 2)) for i in range(20)}
    assert queries.open_ids() == []


def test_the_client_text_is_a_binding_never_pasted():
    query, bindings = request("X = 1), halt, (true", writes=False)
    assert "halt" not in query and bindings == {"_Q": "X = 1), halt, (true"}
    assert request("X = 1", writes=True)[0].startswith("rosprolog_json:rosprolog_solution_writing(")
    assert page_of({"solutions": [{"S": "{\"X\":1}"}], "more": True}) == Page(["{\"X\":1}"], True)
