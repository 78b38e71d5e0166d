"""KnowRob master's 245 non-ROS exports probed here (tools/knowrob_api.py), and the generated
table docs/knowrob-api.md kept up to date. Skips when no KnowRob source is found."""

from __future__ import annotations

import importlib.util
import shutil
import sys
from pathlib import Path

import pytest

TOOL = Path(__file__).resolve().parents[2] / "tools" / "knowrob_api.py"


def _tool():
    spec = importlib.util.spec_from_file_location("knowrob_api", TOOL)
    assert spec and spec.loader
    module = importlib.util.module_from_spec(spec)
    sys.modules["knowrob_api"] = module
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def probed():
    if shutil.which("swipl") is None:
        pytest.skip("needs swipl")
    tool = _tool()
    texts = tool.knowrob_sources()
    if texts is None:
        pytest.skip("no KnowRob source (KNOWROB_SRC or the git mirror at KNOWROB_GIT)")
    return tool, tool.probe(tool.knowrob_exports(texts))


def test_knowrob_exports_245_predicates(probed):
    _, rows = probed
    assert len(rows) == 245
    assert len({(r.module, r.key) for r in rows}) == 245


def test_present_predicates(probed):
    _, rows = probed
    present = [r for r in rows if r.status != "absent"]
    print(f"{len(present)} of {len(rows)} present")
    assert len(present) >= 229


def test_every_note_names_a_predicate_knowrob_exports(probed):
    tool, rows = probed
    assert set(tool.NOTES) <= {r.key for r in rows}


def test_committed_table_is_up_to_date(probed):
    tool, rows = probed
    assert tool.TABLE.read_text(encoding="utf-8") == tool.render(rows), "run python tools/knowrob_api.py --write"
