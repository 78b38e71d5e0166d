"""A wheel carries its data: installed into a fresh venv, it runs the demo from outside the checkout."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import sysconfig
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

pytestmark = [pytest.mark.slow,
              pytest.mark.skipif(shutil.which("swipl") is None, reason="SWI-Prolog (swipl) is not installed")]


def _run(*argv: str | Path, **kw) -> subprocess.CompletedProcess:
    result = subprocess.run([str(a) for a in argv], capture_output=True, text=True, timeout=300, **kw)
    assert result.returncode == 0, result.stdout + result.stderr
    return result


def test_wheel_installs_and_runs_without_the_checkout(tmp_path):
    _run(sys.executable, "-m", "pip", "wheel", "--no-deps", "-q", "-w", tmp_path / "dist", ROOT)
    (wheel,) = (tmp_path / "dist").glob("neem_oracle-*.whl")
    names = zipfile.ZipFile(wheel).namelist()
    assert "oracle/_data/ontology/soma-core.ttl" in names and "oracle/_data/prolog/neem_store.pl" in names
    assert any(n.endswith(".dist-info/licenses/LICENSE") for n in names)
    assert any(n.endswith(".dist-info/licenses/NOTICE.md") for n in names)

    venv = tmp_path / "venv"
    _run(sys.executable, "-m", "venv", "--without-pip", venv)
    python = venv / "bin" / "python"
    site = Path(_run(python, "-c", "import sysconfig; print(sysconfig.get_path('purelib'))").stdout.strip())
    _run(sys.executable, "-m", "pip", "install", "-q", "--no-deps", "--no-index", "--target", site, wheel)
    # The dependencies come from this environment's site-packages, added as a plain path: its
    # editable-install hook (a .pth file there) is not run, so 'oracle' can only be the wheel's.
    (site / "deps.pth").write_text(sysconfig.get_path("purelib") + "\n")

    away = tmp_path / "elsewhere"
    away.mkdir()
    env = {k: v for k, v in os.environ.items() if k not in ("NEEM_ORACLE_HOME", "NEEM_MONGO_URI", "PYTHONPATH")}
    env["HOME"] = env["XDG_DATA_HOME"] = str(away)
    where = _run(python, "-c", "import oracle, oracle.paths as p; print(oracle.__file__); print(p.prolog_dir())",
                 cwd=away, env=env).stdout.split()
    assert where[0].startswith(str(site)) and where[1].startswith(str(site))
    demo = _run(python, "-m", "oracle", "demo", "--store", away / "demo.sqlite", cwd=away, env=env)
    assert "why not" in demo.stdout
    query = _run(python, "-m", "oracle", "prolog", "-q", "--store", away / "demo.sqlite", "-g",
                 "aggregate_all(count, is_action(_), N), N > 0", cwd=away, env=env)
    assert query.stderr == ""
