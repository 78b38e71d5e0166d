"""Per-user and read-only tokens (``serve --tokens FILE``, oracle.service.access) against a real
``serve`` process: a token limited to one user reaches that user's NEEMs only (another's is 404,
listings hold only theirs, the whole-store doors are closed), a read-only token writes nothing,
and no token is ever printed to stdout."""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import pytest

from oracle.benchmarks.security import Service, call, free_port, stop
from tests.service.conftest import AVAILABLE, at

pytestmark = pytest.mark.skipif(shutil.which("swipl") is None, reason="SWI-Prolog (swipl) is not installed; run make setup")

ADMIN, ADA, ADA_READS, ALL_READS = "admin-Q7x2Lp9vR4", "ada-Hc8Tn3Wq5Zk1", "ada-ro-Bm6Ys2Jd8", "carer-ro-Fv3Nk7Gt1"
TOKENS = f"""# the care home's hub
{ADMIN}
{ADA} user=ada
{ADA_READS} user=ada read-only   # her daughter's tablet
{ALL_READS} read-only
"""


def as_(token: str) -> dict[str, str]:
    return {"Authorization": f"Bearer {token}"}


def start(store: Path, tokens: Path) -> Service:
    """``serve --tokens`` (its /api/health needs a token too, so benchmarks.security.start's wait
    cannot be used)."""
    import tempfile
    import time

    port = free_port()
    log = tempfile.TemporaryFile()
    process = subprocess.Popen([sys.executable, "-m", "oracle", "serve", "--store", str(store), "--port", str(port),
                                "--tokens", str(tokens)], stdout=subprocess.DEVNULL, stderr=log)
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline and process.poll() is None:
        try:
            if call(f"http://127.0.0.1:{port}", "/api/health", headers=as_(ADMIN), timeout=2)[0] == 200:
                return Service(process, port, log)
        except OSError:
            time.sleep(0.2)
    process.kill()
    raise RuntimeError("the service did not start")


@pytest.fixture(scope="module")
def served(tmp_path_factory) -> Iterator[Service]:
    folder = tmp_path_factory.mktemp("access")
    tokens = folder / "tokens"
    tokens.write_text(TOKENS)
    tokens.chmod(0o600)
    service = start(folder / "s.sqlite", tokens)
    try:
        for user in ("ada", "bob"):
            assert call(service.url, "/api/neems", {"user": user, "neem": user}, as_(ADMIN))[0] == 201
            assert call(service.url, f"/api/neems/{user}/situation", {"available": AVAILABLE, "at": at(0, 0)}, as_(ADMIN))[0] == 200
        yield service
    finally:
        stop(service)


def test_a_users_token_reaches_only_that_users_neems(served):
    status, listed, _ = call(served.url, "/api/neems", headers=as_(ADA))
    assert status == 200 and [n["user"] for n in listed] == ["ada"]
    assert call(served.url, "/api/neems/ada/situation", headers=as_(ADA))[0] == 200
    status, answer, _ = call(served.url, "/api/neems/bob/situation", headers=as_(ADA))
    assert status == 404 and answer == {"error": "no NEEM 'bob' in the store"}  # as a NEEM that does not exist
    assert call(served.url, "/api/neems/nobody/situation", headers=as_(ADA))[1] == {"error": "no NEEM 'nobody' in the store"}
    assert call(served.url, "/api/neems/bob/situation", {"available": AVAILABLE, "at": at(0, 5)}, as_(ADA))[0] == 404
    assert call(served.url, "/api/neems", {"user": "bob", "neem": "bob2"}, as_(ADA))[0] == 403
    assert call(served.url, "/api/prolog", {"query": "X = 1", "neem": "ada"}, as_(ADA))[0] == 403
    assert call(served.url, "/api/events", headers=as_(ADA))[0] == 403
    assert call(served.url, "/", headers=as_(ADA))[0] == 200  # her newest NEEM
    status, page, _ = call(served.url, "/?neem=bob", headers=as_(ADA))
    assert status == 404


def test_read_only_tokens_write_nothing(served):
    assert call(served.url, "/api/neems/ada/situation", {"available": AVAILABLE, "at": at(0, 9)}, as_(ADA_READS))[0] == 403
    assert call(served.url, "/api/neems", {"user": "ada", "neem": "ada3"}, as_(ALL_READS))[0] == 403
    assert call(served.url, "/api/neems/ada/situation", headers=as_(ADA_READS))[0] == 200
    status, listed, _ = call(served.url, "/api/neems", headers=as_(ALL_READS))
    assert status == 200 and sorted(n["user"] for n in listed) == ["ada", "bob"]
    assert call(served.url, "/api/prolog", {"query": "X = 1", "neem": "bob"}, as_(ALL_READS))[0] == 200


def test_the_service_token_and_no_token(served):
    status, listed, _ = call(served.url, "/api/neems", headers=as_(ADMIN))
    assert status == 200 and len(listed) == 2
    assert call(served.url, "/api/neems")[0] == 401
    assert call(served.url, "/api/neems", headers=as_("not-a-token-at-all"))[0] == 401


@pytest.mark.parametrize(("text", "mode", "said"), [
    (f"{ADA} user=ada extra\n", 0o600, ":1: 'extra' is neither user=ID nor read-only"),
    ("short user=ada\n", 0o600, ":1: the token has 5 characters"),
    (f"{ADA}\n{ADA} read-only\n", 0o600, ":2: the same token is on an earlier line"),
    (f"{ADA}\n", 0o644, "others can read it"),
    ("# nothing\n", 0o600, "holds no token"),
])
def test_a_bad_token_file_is_one_line_before_the_service_starts(tmp_path, text, mode, said):
    tokens = tmp_path / "tokens"
    tokens.write_text(text)
    tokens.chmod(mode)
    done = subprocess.run([sys.executable, "-m", "oracle", "serve", "--store", str(tmp_path / "s.sqlite"), "--port", "1",
                           "--tokens", str(tokens)], capture_output=True, text=True, timeout=120)
    lines = done.stderr.strip().splitlines()
    assert done.returncode != 0 and len(lines) == 1 and lines[0].startswith("error: ") and said in lines[0], done.stderr
    assert ADA not in done.stderr + done.stdout



def test_the_rosbridge_door_takes_the_services_tokens_only(served):
    websockets_sync = pytest.importorskip("websockets.sync.client", reason="the websockets client (make setup) is not installed")
    from websockets.exceptions import InvalidStatus

    url = f"ws://127.0.0.1:{served.port}/rosbridge"
    for token in (ADA, ADA_READS, ALL_READS):  # a user's or a read-only token: refused before the upgrade
        with pytest.raises(InvalidStatus):
            websockets_sync.connect(url, additional_headers={"Authorization": f"Bearer {token}"}, open_timeout=30)
    with websockets_sync.connect(url, additional_headers={"Authorization": f"Bearer {ADMIN}"}, open_timeout=30) as socket:
        socket.send(json.dumps({"op": "call_service", "id": "q", "service": "rosprolog/query",
                                "args": {"id": "q", "query": "X = 1", "mode": 1}}))
        assert json.loads(socket.recv(timeout=60))["result"] is True


def test_the_explorer_opens_the_users_own_newest_neem(served):
    """/explore with a user's token names that user's newest NEEM, never another's (bob's is newer)."""
    ids = {n["user"]: n["id"] for n in call(served.url, "/api/neems", headers=as_(ADMIN))[1]}
    status, page, _ = call(served.url, "/explore", headers=as_(ADA))
    assert status == 200 and f'"neem": "{ids["ada"]}"' in page["text"] and ids["bob"] not in page["text"]
    assert call(served.url, "/explore?neem=bob", headers=as_(ADA))[0] == 404
    assert call(served.url, "/explore/api/neems/bob/timeline", headers=as_(ADA))[0] == 404
    status, page, _ = call(served.url, "/explore", headers=as_(ADMIN))
    assert status == 200 and f'"neem": "{ids["bob"]}"' in page["text"]
