from pathlib import Path

import pytest

from oracle.ontology import build_with_report

SHARED_SOMA = Path(__file__).resolve().parents[3] / "shared" / "soma"


@pytest.fixture(scope="session")
def kitchen():
    """The shipped sample kitchen built on the core TBox, with its build report."""
    return build_with_report()


@pytest.fixture(scope="session")
def soma_dir():
    if not (SHARED_SOMA / "SOMA.owl").exists():
        pytest.skip(f"official SOMA/DUL files not found at {SHARED_SOMA}")
    return SHARED_SOMA


def write_manifest(root: Path, name: str, body: str) -> Path:
    folder = root / name
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / "manifest.xml"
    path.write_text(body)
    return path


def manifest(name: str, parents=(), snippets=()) -> str:
    derive = "".join(f"<derive>{p}</derive>" for p in parents)
    logic = "".join(f"<code_snippet>{s}</code_snippet>" for s in snippets)
    return f"<object><name>{name}</name>{derive}<logic>{logic}</logic></object>"
