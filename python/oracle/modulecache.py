"""Where the compiled Prolog modules are cached: one SWI-Prolog ``.qlf`` of the product's modules
per user, keyed by the content of every Prolog source under ``prolog/``, where they are, and the
SWI-Prolog version. An edited module changes the key, so a stale compilation is never loaded; the
entries used least recently beyond ``KEPT`` are removed when a new one is published.
The bridge compiles and loads (oracle.bridge.engine.ensure_loaded).
"""

from __future__ import annotations

import hashlib
import os
import shutil
from collections.abc import Callable, Sequence
from pathlib import Path

from oracle.files import private_folder, prune_cache, used, write_private_bytes
from oracle.files import default_cache_dir

#: The cache's sub-folder; each entry is a folder named by its key.
FOLDER = "prolog"
LOADER = "modules.pl"
COMPILED = "modules.qlf"
#: Compiled entries kept (one per checkout and SWI-Prolog version in use).
KEPT = 8


def modules_key(folder: Path, swipl_version: str) -> str:
    """A digest of every ``*.pl`` file under ``folder`` (path and content), of the folder's
    location and of the SWI-Prolog version: what a compilation of the modules depends on."""
    digest = hashlib.sha256()
    digest.update(f"{swipl_version}\0{folder.resolve()}\0".encode())
    for path in sorted(folder.rglob("*.pl")):
        digest.update(f"{path.relative_to(folder)}\0".encode())
        digest.update(path.read_bytes())
        digest.update(b"\0")
    return digest.hexdigest()[:24]


def compiled_path(folder: Path, swipl_version: str, cache_dir: Path | None = None) -> Path:
    """The ``.qlf`` of the modules under ``folder`` (it may not exist yet)."""
    root = cache_dir if cache_dir is not None else default_cache_dir()
    return root / FOLDER / modules_key(folder, swipl_version) / COMPILED


def prepare(compiled: Path, sources: Sequence[Path], quote: Callable[[str], str]) -> Path:
    """A private scratch folder beside ``compiled``'s entry with a loader file that loads
    ``sources`` in order (``quote`` makes a Prolog atom of a path); returns the loader's path.
    SWI-Prolog's qcompile writes the ``.qlf`` beside it."""
    scratch = compiled.parent.with_name(f".{compiled.parent.name}.{os.getpid()}.tmp")
    shutil.rmtree(scratch, ignore_errors=True)
    private_folder(scratch)  # it and each missing folder above it 0700 whatever the umask
    os.chmod(scratch.parent, 0o700)
    loader = scratch / LOADER
    write_private_bytes(loader, "".join(f":- use_module({quote(str(path))}).\n" for path in sources).encode())
    return loader


def publish(loader: Path, compiled: Path) -> None:
    """Move the scratch folder holding a finished ``.qlf`` to its entry (another process may
    have published the same entry first: then the scratch folder is dropped)."""
    qlf = loader.with_name(COMPILED)
    try:
        os.chmod(qlf, 0o600)
        os.rename(loader.parent, compiled.parent)
    except OSError:
        pass
    shutil.rmtree(loader.parent, ignore_errors=True)
    prune_cache(compiled.parent.parent, "[0-9a-f]*", KEPT)


def loaded(compiled: Path) -> None:
    """Note that an entry was just loaded (pruning keeps the entries used last)."""
    used(compiled.parent)


def discard(compiled: Path) -> None:
    """Remove an entry that would not load."""
    shutil.rmtree(compiled.parent, ignore_errors=True)
