"""The Python API (docs/python-api.md): every name at the package's top level, imported only on
first use, and the page's example runs as written."""

from __future__ import annotations

import json
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

import oracle

ROOT = Path(__file__).resolve().parents[1]
PAGE = ROOT / "docs" / "python-api.md"


def test_import_oracle_loads_nothing_heavy():
    script = ("import json, sys, oracle\n"
              "print(json.dumps([m for m in sys.modules if m.split('.')[0] in ('numpy', 'pyswip', 'rdflib', 'bson')"
              " or m.startswith(('oracle.store', 'oracle.ranking', 'oracle.bridge'))]))")
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, check=True)
    assert json.loads(done.stdout) == []


def test_every_name_of_the_api_is_what_its_module_defines():
    import importlib

    for name, module in oracle.API.items():
        assert getattr(oracle, name) is getattr(importlib.import_module(module), name), name
    assert sorted(oracle.API) == [n for n in dir(oracle) if n != "__version__"]
    with pytest.raises(AttributeError, match="no attribute 'nothing'"):
        oracle.nothing  # noqa: B018


def test_the_page_names_every_name_of_the_api():
    text = PAGE.read_text(encoding="utf-8")
    missing = [name for name in oracle.API if not re.search(rf"`{name}\b", text)]
    assert not missing, missing


@pytest.mark.skipif(shutil.which("swipl") is None, reason="SWI-Prolog (swipl) is not installed; run make setup")
def test_the_pages_example_runs(tmp_path, monkeypatch, capsys):
    (block,) = re.findall(r"```python\n(.*?)```", PAGE.read_text(encoding="utf-8"), re.S)
    monkeypatch.chdir(ROOT)
    monkeypatch.setenv("NEEM_ORACLE_CACHE", str(tmp_path / "cache"))
    exec(compile(block, str(PAGE), "exec"), {"__name__": "example"})
    out = capsys.readouterr().out
    assert out.startswith("16 rows, the last one pick(teapot)") and "next: pour(teapot, mug)" in out
