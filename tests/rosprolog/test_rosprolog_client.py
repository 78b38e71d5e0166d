"""knowrob/rosprolog's own Python client, unchanged, against the ROS door.

The client is fetched at test time from GitHub (never copied into this project); where GitHub
cannot be reached the test skips saying so. ``ROSPROLOG_CLIENT_PY`` names a local copy of the
same file instead (a machine without GitHub access that has a checkout)."""

from __future__ import annotations

import json
import os
import subprocess
import urllib.request
from pathlib import Path

import pytest

from tests.rosprolog.conftest import ROS_PYTHON, needs_ros, needs_swipl

pytestmark = [needs_swipl, needs_ros]
URL = "https://raw.githubusercontent.com/knowrob/rosprolog/master/src/rosprolog_client/rosprolog_client.py"
SCRIPT = Path(__file__).with_name("knowrob_client.py")


@pytest.fixture()
def client_source() -> str:
    """The client's text (asked before the door starts: a skip costs nothing)."""
    local = os.environ.get("ROSPROLOG_CLIENT_PY")
    if local:
        return Path(local).read_text(encoding="utf-8")
    try:
        with urllib.request.urlopen(URL, timeout=15) as response:
            return str(response.read().decode("utf-8"))
    except OSError as error:
        pytest.skip(f"GitHub unreachable ({URL}: {error})")


def test_knowrob_rosprolog_client_unchanged(client_source, door, tmp_path):
    folder = tmp_path / "client"
    folder.mkdir()
    (folder / "rosprolog_client.py").write_text(client_source, encoding="utf-8")
    env = {**door, "PYTHONPATH": f"{folder}:{door['PYTHONPATH']}"}
    done = subprocess.run([ROS_PYTHON, str(SCRIPT)], env=env, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    out = json.loads(done.stdout.strip().splitlines()[-1])
    assert [s["X"] for s in out["all"]] == ["a", 1, 2.5, "\"s\"", ["b"]]
    assert out["once"]["A"].startswith("http") and out["once"]["T"].startswith("http")
    assert out["none"] == []  # rosprolog_client's once: [] when there is no solution
    assert out["term"] == {"X": {"term": ["foo", "a", [1, 2.5], "\"str\""]}, "Y": "_"}
    assert out["incremental"] == list(range(1, 14))
    assert out["finished_after_3"] == [1, 2, 3]
    assert out["failure"].startswith("Prolog query failed: ") and "no_such_predicate/1" in out["failure"]
