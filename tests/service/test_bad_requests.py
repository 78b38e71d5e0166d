"""The service's share of the bad-input corpus: every bad request is a one-line 4xx that changes nothing.

Bodies from the same families as tests/corpus (broken JSON, NaN and huge numbers, times out of
range, odd strings, deep nesting, wrong types, ids that are no NEEM id), sent to every endpoint
that writes. After each one the store holds exactly the documents it held before and the
service still answers; no request may end in a 500 (a bug) or echo more than one line.
"""

from __future__ import annotations

import json

import pytest

from tests.service.conftest import at

NEEM = "ada"
DEEP = "[" * 100_000
HUGE = 10**400

#: (path, raw body) pairs; a str body is sent as is, anything else as JSON.
BODIES: list[tuple[str, object]] = []


def bodies(path: str, *items: object) -> None:
    BODIES.extend((path, item) for item in items)


_TIMES = [float("nan"), float("inf"), float("-inf"), 1e308, -1e308, 1e20, -1.0, "9999-12-31T23:59:59-12:00",
          "0001-01-01T00:00:00+05:00", "yesterday", "", "2026-02-30T08:00:00", True, [1], {"$gt": 0}]  # fmt: skip
_CALLS = ["fly(red_mug)", "pick(red_mug", "pick(unicorn)", "", " ", "\ud800", "pick(" + "a" * 100_000 + ")", "pick(red_mug))",
          "pick()", 5, None, ["pick(red_mug)"], {"$where": "1"}, "pick(red_mug, red_mug, red_mug, red_mug)"]  # fmt: skip

bodies(f"/api/neems/{NEEM}/situation",
       *({"available": ["pick(red_mug)"], "at": t} for t in _TIMES),
       *({"available": [c]} for c in _CALLS),
       {"available": []}, {"available": "pick(red_mug)"}, {"available": ["pick(red_mug)"] * 1001}, {}, [], None, 5,
       "{", "}", DEEP, '{"available": ["pick(red_mug)"], "at": 1e400}', b"\xff\xfe{".decode("latin-1"),
       '{"available": ["pick(red_mug)"], "at": NaN}', '{"available": ["pick(red_mug)"], "at": ' + str(HUGE) + "}")  # fmt: skip
bodies(f"/api/neems/{NEEM}/actions",
       *({"call": "pick(apple)", "begin": t} for t in _TIMES),
       *({"call": c} for c in _CALLS),
       {"call": "pick(apple)", "begin": at(1, 9), "end": at(1, 1)}, {"phase": "end", "id": "nothing-open"},
       {"phase": "begin"}, {"phase": "later", "call": "pick(apple)"}, {"call": "pick(apple)", "performed_by": "cat"},
       {"call": "pick(apple)", "id": "x" * 101}, {"call": "pick(apple)", "begin": at(0, 0) - 3600},
       DEEP, "[]", '{"call": "pick(apple)", "begin": Infinity}')  # fmt: skip
bodies(f"/api/neems/{NEEM}/perception",
       *({"objects": [{"name": "banana"}], "at": t} for t in _TIMES),
       {"objects": []}, {"objects": [{"name": "unicorn"}]}, {"objects": [{"name": "banana", "pose": [1, 2]}]},
       {"objects": [{"name": "banana", "pose": [float("nan"), 0, 0]}]}, {"objects": [{"name": 5}]},
       {"objects": [{"name": "\ud800"}]}, {"objects": [{"name": "banana"}] * 1001}, DEEP)  # fmt: skip
bodies(f"/api/neems/{NEEM}/choice", {"task": "fly(away)"}, {"task": ""}, {"task": 5}, {"task": "pick(unicorn)"},
       {"task": "pick(red_mug)", "workflow": ["fly(away)"]}, {"task": "pick(red_mug)", "workflow": "pick(red_mug)"}, DEEP)  # fmt: skip
bodies("/api/neems",
       {"user": ""}, {"user": "x" * 201}, {"user": 5}, {"user": "bo", "neem": "a_b"}, {"user": "bo", "neem": "../etc"},
       {"user": "bo", "neem": NEEM}, {"user": "bo", "neem": "x" * 65}, {"user": "bo", "neem": "$where"},
       {"user": "bo", "neem": {"$gt": ""}}, {}, DEEP, "{")  # fmt: skip
bodies("/api/prolog",
       {"query": "halt", "neem": NEEM}, {"query": "kb_call(halt)", "neem": NEEM}, {"query": "member(X, [a", "neem": NEEM},
       {"query": "", "neem": NEEM}, {"query": "true", "neem": NEEM, "limit": 0}, {"query": "true", "neem": NEEM, "offset": -1},
       {"query": "true", "neem": NEEM, "timeout": float("nan")}, {"query": "true", "neem": NEEM, "timeout": 1e400},
       {"query": "true", "neem": NEEM, "offset": HUGE}, {"query": "true", "neem": "nobody"},
       {"query": "shell('touch /tmp/owned')", "neem": NEEM}, {"query": "X = " + "[" * 20_000, "neem": NEEM},
       {"query": "true", "neem": NEEM, "bindings": {"X": {"$where": "1"}}}, {"query": "x" * 10_001, "neem": NEEM})  # fmt: skip
for path in ("/api/neems/nobody/situation", "/api/neems/a_b/actions", "/api/neems/%2e%2e/perception"):
    bodies(path, {"available": ["pick(red_mug)"], "call": "pick(apple)", "objects": [{"name": "banana"}]})


def _encoded(body: object) -> bytes:
    if isinstance(body, str):
        return body.encode("utf-8", "surrogatepass")
    return json.dumps(body).encode("utf-8", "surrogatepass")


def _state(ctx) -> list[tuple[str, dict[str, int]]]:
    def read() -> list[tuple[str, dict[str, int]]]:
        store = ctx.engine.store
        kinds = ("triples", "annotations", "tf", "inferred")
        return [(info.id, {k: store.count(info.id, k) for k in kinds}) for info in [*store.neems(), *store.staging_neems()]]

    return ctx.thread.call(read)


def test_the_service_corpus_is_large_enough():
    assert len(BODIES) >= 140


@pytest.fixture()
def served(ctx):
    from fastapi.testclient import TestClient

    from oracle.service.app import create_app

    with TestClient(create_app(ctx), raise_server_exceptions=False, base_url="http://127.0.0.1") as client:
        yield _driven(client)


def _driven(client):  # noqa: ANN001, ANN202
    made = client.post("/api/neems", json={"user": "Ada", "neem": NEEM})
    assert made.status_code == 201, made.text
    for i, call in enumerate(["pick(apple)", "place(apple, counter_top)"]):
        done = client.post(f"/api/neems/{NEEM}/actions", json={"call": call, "begin": at(0, 10 * i), "end": at(0, 10 * i + 5)})
        assert done.status_code == 200, done.text
    return client


def test_every_bad_request_is_a_one_line_4xx_and_changes_nothing(served, ctx):
    failures = []
    before = _state(ctx)
    for path, body in BODIES:
        response = served.post(path, content=_encoded(body), headers={"content-type": "application/json"})
        text = response.text
        try:
            error = response.json().get("error", "")
        except (ValueError, AttributeError):
            error = None
        if not 400 <= response.status_code < 500 or not isinstance(error, str) or not error or "\n" in error:
            failures.append(f"{path} {str(body)[:80]!r}: {response.status_code} {text[:200]}")
            before = _state(ctx)
        elif _state(ctx) != before:
            failures.append(f"{path} {str(body)[:80]!r}: the store changed")
            before = _state(ctx)
    assert not failures, f"{len(failures)} of {len(BODIES)} bad requests:\n" + "\n".join(failures)
    assert served.get("/api/health").status_code == 200
