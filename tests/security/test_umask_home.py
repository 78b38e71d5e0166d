"""Under umask 000, everything the tool creates in a fresh home is private (issue 54): the
default store's folders (~/.local/share/neem-oracle), the user's cache (~/.cache/neem-oracle:
compiled Prolog modules, ontology builds, distance matrices, kept fits) and what those hold.

A fresh process runs each command with HOME and the XDG folders in a temporary folder, so the
platform's defaults are what is exercised (no ``--store``, no ``$NEEM_ORACLE_CACHE``)."""

from __future__ import annotations

import os
import shutil
import stat
import subprocess
import sys
from pathlib import Path

import pytest

from tests.corpus.harness import sample_chains

pytestmark = pytest.mark.skipif(shutil.which("swipl") is None, reason="SWI-Prolog (swipl) is not installed; run make setup")


def run(home: Path, *argv: str) -> None:
    env = {k: v for k, v in os.environ.items() if not k.startswith(("XDG_", "NEEM_ORACLE_"))}
    env["HOME"] = str(home)
    done = subprocess.run([sys.executable, "-m", "oracle", *argv], env=env, capture_output=True, text=True, timeout=600,
                          preexec_fn=lambda: os.umask(0))
    assert done.returncode == 0, done.stderr[-2000:]


def test_a_fresh_home_under_umask_000_holds_only_private_folders_and_files(tmp_path):
    home = tmp_path / "home"
    home.mkdir(mode=0o700)
    chains = sample_chains(tmp_path / "good.jsonl", 8, users=1)
    run(home, "import", str(chains))
    run(home, "neems")
    run(home, "why-not", "pick(banana)", "--neem", "p000-tea-red-yogurt")
    made = [p for p in home.rglob("*")]
    assert any(p.name == "default.sqlite" for p in made)
    assert any(p.suffix == ".qlf" for p in made), "no compiled Prolog modules in the cache"
    loose = {str(p.relative_to(home)): oct(stat.S_IMODE(p.lstat().st_mode)) for p in made
             if not p.is_symlink() and stat.S_IMODE(p.lstat().st_mode) & 0o077}
    assert not loose, f"readable or writable by others: {loose}"
