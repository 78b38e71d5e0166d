"""The attacks against a real ``serve`` process on loopback (subprocess, real uvicorn).

What a web page in the user's browser (DNS rebinding, framing), a flood and a crash can do:
nothing written or read through /api/prolog, foreign Host names refused before any handler,
the page unframeable, oversized and deep bodies refused without being read whole, the process
alive and small after floods, and no acknowledged situation lost to SIGKILL. Timing and memory
figures are in ``make bench`` (area security); these tests assert the behaviour.
"""

from __future__ import annotations

import os
import shutil
import signal
import socket
from collections.abc import Iterator
from pathlib import Path

import pytest

from oracle.benchmarks.security import ENDLESS_QUERY, Service, call, flood, post_oversized, start, stop
from tests.service.conftest import AVAILABLE, ROUTINE, at

pytestmark = pytest.mark.skipif(shutil.which("swipl") is None, reason="SWI-Prolog (swipl) is not installed; run make setup")
SECRET = "tuesday-secret-7f3a"


def count_triples(url: str) -> int:
    status, answer, _ = call(url, "/api/prolog", {"query": "aggregate_all(count, kb_call(triple(S, P, O)), N)", "neem": "ada"})
    assert status == 200, answer
    return int(answer["solutions"][0]["N"])


@pytest.fixture(scope="module")
def private_file(tmp_path_factory) -> Path:
    path = tmp_path_factory.mktemp("private") / "diary.ttl"
    path.write_text(f"<http://example.org/{SECRET}> <http://example.org/p> \"{SECRET}\" .\n")
    path.chmod(0o600)
    return path


@pytest.fixture(scope="module")
def served(tmp_path_factory) -> Iterator[Service]:
    # a long limit: the machine running the tests may be busy; the endless query asks for 3 s
    service = start(tmp_path_factory.mktemp("served") / "s.sqlite", "--query-seconds", "20")
    try:
        assert call(service.url, "/api/neems", {"user": "ada", "neem": "ada"})[0] == 201
        for i, action in enumerate(ROUTINE):
            assert call(service.url, "/api/neems/ada/situation", {"available": AVAILABLE, "at": at(0, 10 * i)})[0] == 200
            assert call(service.url, "/api/neems/ada/actions", {"call": action, "begin": at(0, 10 * i)})[0] == 200
        yield service
    finally:
        stop(service)


def test_nothing_is_written_or_read_through_api_prolog(served, private_file):
    before = count_triples(served.url)
    assert before > 0
    attacks = [
        "kb_unproject(triple(S, P, O))",
        "kb_project(triple(a, b, c))",
        "load_owl('/etc/hostname', [graph(odb)])",
        f"load_owl('{private_file}')",
        f"kb_call(load_owl('{private_file}'))",
        "assertz(neem_store:x)",
        "retractall(kb_subgraph:subgraph_of_(_, _))",
        "kb_subgraph:subgraph_reset",
        "neem_store:store_reset",
        "odb_names:odb_set_namespace('http://evil.example/')",
        f"read_file_to_string('{private_file}', S, [])",
        "shell('touch /tmp/pwned')",
        "findall(x, (member(G, [halt]), G), _)",
        "true. halt",
        "X = 1. kb_unproject(triple(S, P, O)).",
    ]
    for query in attacks:
        status, answer, _ = call(served.url, "/api/prolog", {"query": query, "neem": "ada"})
        assert status in (400, 403), (query, status, answer)
        assert "\n" not in answer["error"] and SECRET not in answer["error"]
    assert count_triples(served.url) == before
    status, answer, _ = call(served.url, "/api/prolog", {"query": f"kb_call(triple(S, P, \"{SECRET}\"))", "neem": "ada"})
    assert status == 200 and answer["solutions"] == []
    assert not Path("/tmp/pwned").exists()


def test_a_file_existence_probe_answers_the_same_for_both(served, private_file):
    answers = []
    for path in (private_file, private_file.with_name("missing.ttl"), "/etc/hostname", "/no/such/file"):
        for query in (f"load_owl('{path}')", f"exists_file('{path}')", f"kb_call(load_owl('{path}'))"):
            status, answer, _ = call(served.url, "/api/prolog", {"query": query, "neem": "ada"})
            answers.append((query.split("(")[0], status, answer["error"]))
    by_kind: dict[str, set] = {}
    for kind, status, error in answers:
        by_kind.setdefault(kind, set()).add((status, error))
    assert all(len(seen) == 1 for seen in by_kind.values()), by_kind


@pytest.mark.parametrize(("method", "path", "body"), [
    ("GET", "/api/neems", None),
    ("POST", "/api/neems/ada/choice", {"task": "pick(red_mug)"}),
    ("POST", "/api/prolog", {"query": "X = 1", "neem": "ada"}),
    ("GET", "/", None),
])
def test_a_foreign_host_is_refused_before_any_handler(served, method, path, body):
    evil = f"evil.example:{served.port}"
    status, answer, _ = call(served.url, path, body, headers={"Host": evil, "Origin": f"http://{evil}"})
    assert status == 421 and "Host" in answer["error"]
    for host in (f"127.0.0.1:{served.port}", f"localhost:{served.port}"):
        assert call(served.url, "/api/neems", headers={"Host": host})[0] == 200


def test_another_origin_cannot_change_state(served):
    status, answer, _ = call(served.url, "/api/neems/ada/choice", {"task": "pick(red_mug)"},
                             headers={"Origin": "http://evil.example"})
    assert status == 403 and "cross-origin" in answer["error"]


def test_the_page_cannot_be_framed_and_nothing_is_sniffed(served):
    for path in ("/", "/api/neems", "/no/such/path"):
        _, _, headers = call(served.url, path)
        assert headers["x-frame-options"] == "DENY"
        assert "frame-ancestors 'none'" in headers["content-security-policy"]
        assert headers["x-content-type-options"] == "nosniff"


@pytest.mark.parametrize("chunked", [False, True])
def test_a_50_mb_body_is_413_with_a_short_answer(served, chunked):
    answer = post_oversized(served.port, chunked=chunked)
    assert answer.status == 413 and len(answer.body) < 1024 and b"[[[" not in answer.body


def test_deep_json_is_400_not_500(served):
    deep: object = 1
    for _ in range(40):
        deep = [deep]
    status, answer, _ = call(served.url, "/api/prolog", {"query": "X = 1", "neem": "ada", "bindings": {"X": deep}})
    assert status == 400 and "nests deeper" in answer["error"]
    body = {"available": ["pick(red_mug)"] * 2000}
    assert call(served.url, "/api/neems/ada/situation", body)[0] == 422  # a list longer than its field allows


def test_floods_leave_the_process_answering(served):
    answers = flood(served.port, 4)
    assert [a.status for a in answers] == [413] * 4
    assert served.process.poll() is None
    assert call(served.url, "/api/health")[0] == 200


def test_one_query_at_a_time_and_each_stops_at_its_limit(served):
    import threading
    import time

    results: list[tuple[int, dict]] = []

    def slow() -> None:
        status, answer, _ = call(served.url, "/api/prolog", {"query": ENDLESS_QUERY, "neem": "ada", "timeout": 3})
        results.append((status, answer))

    thread = threading.Thread(target=slow)
    thread.start()
    try:
        time.sleep(0.5)  # the first query is running by now (it runs for the 3 s limit)
        status, refused, _ = call(served.url, "/api/prolog", {"query": "X = 1", "neem": "ada"})
        assert status == 429
        assert "another Prolog query" in refused["error"]
        # the robot is answered while the query runs (in the query process), not after it
        assert call(served.url, "/api/neems/ada/situation", {"available": AVAILABLE, "at": at(1, 0)})[0] == 200
        assert thread.is_alive()
        # a second query meanwhile is still refused
        status, answer, _ = call(served.url, "/api/prolog", {"query": "X = 1", "neem": "ada"})
        assert status == 429
    finally:
        thread.join(timeout=30)
    assert results and results[0][0] == 400 and "time limit" in results[0][1]["error"]
    status, answer, _ = call(served.url, "/api/prolog", {"query": "kb_call(is_action(A))", "neem": "ada", "limit": 1})
    assert status == 200, answer


def test_the_query_process_sees_every_acknowledged_write(served):
    before = count_triples(served.url)
    assert call(served.url, "/api/neems/ada/situation", {"available": AVAILABLE, "at": at(1, 5)})[0] == 200
    assert count_triples(served.url) > before


def test_weak_token_files_are_refused(tmp_path):
    import subprocess
    import sys

    weak = tmp_path / "weak"
    weak.write_text("ab\n")
    weak.chmod(0o600)
    repeated = tmp_path / "repeated"
    repeated.write_text("aaaaaaaaaaaaaaaaaaaaaaaa\n")
    repeated.chmod(0o600)
    for token_file, needle in ((weak, "at least 12"), (repeated, "different characters")):
        result = subprocess.run([sys.executable, "-m", "oracle", "serve", "--host", "0.0.0.0", "--token-file", str(token_file),
                                 "--store", str(tmp_path / "s.sqlite")], capture_output=True, text=True, timeout=60)
        assert result.returncode == 1 and needle in result.stderr and len(result.stderr.strip().splitlines()) == 1
    result = subprocess.run([sys.executable, "-m", "oracle", "serve", "--allow-prolog-writes", "--store", str(tmp_path / "s.sqlite")],
                            capture_output=True, text=True, timeout=60)
    assert result.returncode == 1 and "needs --token-file" in result.stderr


@pytest.mark.slow
def test_no_acknowledged_situation_is_lost_over_20_sigkills(tmp_path):
    """Each round restarts the service, checks that the situation the last one acknowledged is
    the NEEM's latest, posts a new one and SIGKILLs the process the moment the answer is read."""
    store = tmp_path / "s.sqlite"
    service = start(store)
    assert call(service.url, "/api/neems", {"user": "kim", "neem": "kim"})[0] == 201
    assert call(service.url, "/api/neems/kim/actions", {"call": "open(fridge)", "begin": at(0, 0)})[0] == 200
    acknowledged = None
    lost = []
    for kill in range(20):
        if kill:
            service = start(store)
            status, latest, _ = call(service.url, "/api/neems/kim/situation")
            assert status == 200
            if latest.get("at") != acknowledged:
                lost.append((acknowledged, latest.get("at")))
        when = at(0, 10 + kill)
        status, _, _ = call(service.url, "/api/neems/kim/situation", {"available": AVAILABLE, "at": when})
        assert status == 200
        acknowledged = when
        os.kill(service.process.pid, signal.SIGKILL)
        service.process.wait()
    service = start(store)
    try:
        last = call(service.url, "/api/neems/kim/situation")[1].get("at")
        if last != acknowledged:
            lost.append((acknowledged, last))
    finally:
        stop(service)
    assert lost == []


@pytest.mark.deadline
def test_clients_that_send_nothing_or_a_trickle_are_closed(served):
    """A socket that sends nothing, and one that sends a header line a second, are closed by the
    header deadline (5 s, Limits.header_seconds) rather than held for ever (slowloris)."""
    import threading
    import time

    closed_after: dict[str, float] = {}

    def hold(name: str, trickle: bool) -> None:
        started = time.monotonic()
        with socket.create_connection(("127.0.0.1", served.port), timeout=40) as sock:
            sock.sendall(b"GET /api/health HTTP/1.1\r\nHost: 127.0.0.1\r\n" if trickle else b"")
            try:
                while time.monotonic() - started < 35:
                    if trickle:
                        sock.sendall(b"X-Slow: 1\r\n")
                    sock.settimeout(1.0)
                    try:
                        if sock.recv(1024) == b"":
                            break
                    except TimeoutError:
                        continue
            except (BrokenPipeError, ConnectionResetError):
                pass
        closed_after[name] = time.monotonic() - started

    threads = [threading.Thread(target=hold, args=(name, trickle)) for name, trickle in (("silent", False), ("trickle", True))]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert closed_after["silent"] < 30 and closed_after["trickle"] < 30, closed_after


@pytest.mark.deadline
def test_keep_alive_connections_are_closed_when_idle(served):
    """An idle client does not hold its socket for ever (uvicorn's timeout_keep_alive)."""
    import time

    with socket.create_connection(("127.0.0.1", served.port), timeout=30) as sock:
        sock.sendall(b"GET /api/health HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n")
        time.sleep(0.2)
        assert sock.recv(4096).startswith(b"HTTP/1.1 200")
        started = time.monotonic()
        assert sock.recv(4096) == b""  # closed by the server
        assert time.monotonic() - started < 20
