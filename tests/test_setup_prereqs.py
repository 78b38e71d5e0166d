"""`make setup` on a fresh Debian: installs the missing packages as root or with sudo, else says
exactly what to run. The system tools are replaced by small scripts on PATH that record calls."""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import pytest

SCRIPT = Path(__file__).resolve().parents[1] / "scripts" / "setup-prereqs.sh"
SH = shutil.which("sh")


def _tools(tmp_path: Path, *, uid: int, sudo: bool, venv: bool, swipl: bool) -> Path:
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    log = tmp_path / "calls.log"
    tools = {
        "id": f'echo {uid}',
        "apt-get": f'echo "apt-get $*" >> {log}',
        "python3": 'case "$*" in *ensurepip*) exit ' + ("0" if venv else "1") + ';; esac',
    }
    if sudo:
        tools["sudo"] = f'echo "sudo" >> {log}; "$@"'
    if swipl:
        tools["swipl"] = "exit 0"
    for name, body in tools.items():
        (bin_dir / name).write_text(f"#!{SH}\n{body}\n")
        (bin_dir / name).chmod(0o755)
    return bin_dir


def _run(tmp_path: Path, **kw) -> tuple[subprocess.CompletedProcess, str]:
    bin_dir = _tools(tmp_path, **kw)
    env = {"PATH": f"{bin_dir}:/nonexistent"}
    done = subprocess.run([SH, str(SCRIPT)], env=env, capture_output=True, text=True, timeout=30)
    log = tmp_path / "calls.log"
    return done, log.read_text() if log.exists() else ""


pytestmark = pytest.mark.skipif(SH is None, reason="no sh")


def test_nothing_missing_installs_nothing(tmp_path):
    done, calls = _run(tmp_path, uid=1000, sudo=False, venv=True, swipl=True)
    assert done.returncode == 0 and calls == ""


def test_root_installs_what_is_missing(tmp_path):
    done, calls = _run(tmp_path, uid=0, sudo=False, venv=False, swipl=False)
    assert done.returncode == 0, done.stderr
    assert "apt-get install -y --no-install-recommends python3-venv swi-prolog-nox" in calls
    assert "sudo" not in calls


def test_a_user_with_sudo_installs_through_sudo(tmp_path):
    done, calls = _run(tmp_path, uid=1000, sudo=True, venv=False, swipl=True)
    assert done.returncode == 0, done.stderr
    assert calls.splitlines()[0] == "sudo" and "install -y --no-install-recommends python3-venv" in calls


def test_a_user_without_sudo_is_told_exactly_what_to_run(tmp_path):
    done, calls = _run(tmp_path, uid=1000, sudo=False, venv=False, swipl=False)
    assert done.returncode == 1 and calls == ""
    assert done.stderr.strip() == ("make setup: missing Debian packages: python3-venv swi-prolog-nox; as root run: "
                                   "apt-get update && apt-get install -y --no-install-recommends python3-venv swi-prolog-nox")
