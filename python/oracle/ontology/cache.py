"""The built ontology, cached on disk by a hash of everything the build reads.

A build parses the odb manifests, the mapping YAML and the upper TBox and generates a graph
(~150 ms of every ``why-not``, ``rank`` or ``import``); the cached copy loads in ~20 ms. The
key hashes the bytes of every input file and the source of the code that builds, so an edit
to any of them makes a new entry: an entry is never stale, only unused. Entries live in the
user's cache dir (0700, files 0600, written atomically); one that cannot be read is rebuilt.
"""

from __future__ import annotations

import hashlib
import sys
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import TYPE_CHECKING

from oracle.files import cached_plain

if TYPE_CHECKING:
    from oracle.ontology.inputs import BuildReport
    from oracle.ontology.model import OdbOntology

#: Bumped when the layout of an entry changes.
FORMAT = "4"
_CODE_DIR = Path(__file__).resolve().parent


def _input_files(odb_dir: Path, mapping: Path, soma_dir: Path | None, core_tbox: Path, official: tuple[str, ...]) -> Iterator[Path]:
    """Every file the build reads, in a fixed order (a file added to the odb changes the set)."""
    yield from sorted(odb_dir.glob("*/manifest.xml"))
    yield mapping
    if soma_dir is None:
        yield core_tbox
    else:
        yield from (soma_dir / name for name in official)
    yield from sorted(_CODE_DIR.glob("*.py"))
    yield _CODE_DIR.parent / "namespaces.py"


def build_key(odb_dir: Path, mapping: Path, soma_dir: Path | None, core_tbox: Path, official: tuple[str, ...]) -> str | None:
    """The hash of the inputs, or None when one cannot be read (the build then says why)."""

    digest = hashlib.sha256(f"neem-oracle ontology cache {FORMAT} {sys.version} {_rdflib_release()}\0".encode())
    # Read by the rule for handed files (oracle.handed): a FIFO, a device or a link out of the
    # odb folder is not read here either; the build that follows refuses it in one line.
    from oracle.errors import NeemOracleError
    from oracle.handed import OWL_LIMIT, Handed, read_handed

    try:
        for path in _input_files(odb_dir, mapping, soma_dir, core_tbox, official):
            inside = odb_dir if path.name == "manifest.xml" and path.parent.parent == odb_dir else None
            digest.update(str(path).encode() + b"\0")
            digest.update(hashlib.sha256(read_handed(path, Handed("input", NeemOracleError, inside), OWL_LIMIT)).digest())
    except (OSError, NeemOracleError):
        return None
    return digest.hexdigest()[:32]


def _rdflib_release() -> str:
    """The installed rdflib's distribution folder name (``rdflib-7.1.1.dist-info``), found
    without importing rdflib: a build made with another rdflib may differ, so its entry is another."""
    import importlib.util

    spec = importlib.util.find_spec("rdflib")
    if spec is None or spec.origin is None:
        return "none"
    package = Path(spec.origin).parent
    found = sorted(p.name for p in package.parent.glob("rdflib-*.dist-info"))
    return ",".join(found) or str(package)


def cached_build(
    key: str | None, directory: Path, build: Callable[[], tuple[OdbOntology, BuildReport]]
) -> tuple[OdbOntology, BuildReport]:
    """The entry for ``key`` when there is a good one, else ``build()`` saved under ``key``."""
    if key is None:
        return build()
    from oracle.ontology.plain import from_plain, to_plain

    return cached_plain(directory / f"ontology-{key}.json", key, build, to_plain, from_plain, "ontology-*.json",
                        former="ontology-*.pickle")  # the pickles kept until 2026-12-08 go
