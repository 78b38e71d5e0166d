"""Files the tool writes hold a person's routine or names: 0600 in 0700 folders, even under umask 000."""

from __future__ import annotations

import os
import stat
from collections.abc import Iterator
from pathlib import Path

import pytest

from oracle.cli import main

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture()
def open_umask() -> Iterator[None]:
    old = os.umask(0)
    try:
        yield
    finally:
        os.umask(old)


def modes(folder: Path) -> dict[str, int]:
    return {str(p.relative_to(folder)): stat.S_IMODE(p.stat().st_mode) for p in folder.rglob("*")}


def assert_private(folder: Path) -> None:
    found = modes(folder)
    assert found, "nothing was written"
    loose = {name: oct(mode) for name, mode in found.items() if mode & 0o077}
    assert not loose, f"readable or writable by others: {loose}"


def test_generate_evaluate_and_ontology_build_write_private_files(tmp_path, open_umask):
    bench = tmp_path / "bench" / "out"
    assert main(["generate", "--personas", "2", "--days", "2", "--out", str(bench)]) == 0
    assert_private(tmp_path / "bench")
    chains = next(bench.glob("*.jsonl"))
    reports = tmp_path / "reports" / "deep"
    assert main(["evaluate", str(chains), "--json", str(reports / "s.json"), "--report", str(reports / "r.md"),
                 "--plots", str(reports / "plots")]) == 0
    assert_private(tmp_path / "reports")
    assert (reports / "plots").is_dir() and any((reports / "plots").iterdir())
    built = tmp_path / "onto" / "kitchen.owl"
    assert main(["ontology", "build", "--out", str(built)]) == 0
    assert_private(tmp_path / "onto")
