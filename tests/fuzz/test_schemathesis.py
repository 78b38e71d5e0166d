"""schemathesis against a live ``serve`` from its own /openapi.json: at least 1,000 generated
requests in CI (500 in a developer's make test), no server error (5xx), no status, content type
or body outside what the document says (``make fuzz`` runs more: NEEM_SCHEMATHESIS_EXAMPLES)."""

from __future__ import annotations

import importlib.util
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from oracle.benchmarks.security import call, start, stop
from tests.service.conftest import AVAILABLE, ROUTINE, at

CONFIG = Path(__file__).with_name("schemathesis.toml")
#: Examples per operation and phase (20 operations: about 1,000 requests in all at 25, as CI
#: runs it; about 600 at 8, as a developer's make test does, kept within its 3 minutes).
EXAMPLES = int(os.environ.get("NEEM_SCHEMATHESIS_EXAMPLES") or (25 if os.environ.get("CI") else 8))
#: The generated requests a run must reach: CI's run at least 1,000.
AT_LEAST = 1000 if EXAMPLES >= 25 else 500
CHECKS = "not_a_server_error,status_code_conformance,content_type_conformance,response_schema_conformance"

pytestmark = [
    pytest.mark.skipif(shutil.which("swipl") is None, reason="SWI-Prolog (swipl) is not installed; run make setup"),
    pytest.mark.skipif(importlib.util.find_spec("schemathesis") is None,
                       reason="schemathesis is not installed (make setup installs the dev extra)"),
]


def test_generated_requests_get_no_server_error_and_only_documented_answers(tmp_path):
    service = start(tmp_path / "s.sqlite")
    try:
        # the NEEM schemathesis.toml names, with a routine, so requests reach the handlers
        assert call(service.url, "/api/neems", {"user": "ada", "neem": "ada"})[0] == 201
        for i, action in enumerate(ROUTINE):
            assert call(service.url, "/api/neems/ada/situation", {"available": AVAILABLE, "at": at(0, 10 * i)})[0] == 200
            assert call(service.url, "/api/neems/ada/actions", {"call": action, "begin": at(0, 10 * i)})[0] == 200
        cli = Path(sys.executable).with_name("schemathesis")
        run = subprocess.run([str(cli), "--config-file", str(CONFIG), "run", f"{service.url}/openapi.json", "--checks", CHECKS,
                              "--max-examples", str(EXAMPLES), "--workers", "1", "--no-color"],
                             cwd=tmp_path, capture_output=True, text=True, timeout=900)  # fmt: skip
    finally:
        stop(service)
    found = re.search(r"(\d+) generated.*", run.stdout)
    print(found.group(0) if found else "no count in schemathesis' output")  # pytest -s shows it
    assert run.returncode == 0, run.stdout[-8000:] + run.stderr[-2000:]
    assert found is not None and int(found.group(1)) >= AT_LEAST, run.stdout[-3000:]
