"""Faults from outside the program: a disk that fills up, a read-only file system, a second writer.

Each fault meets the real command in a subprocess; the promise checked is the store's (and the
dump folder's) state afterwards, and one line on stderr. A full disk is a file size limit
(RLIMIT_FSIZE, with SIGXFSZ ignored, so writes past it fail with EFBIG as they would with ENOSPC).
"""

from __future__ import annotations

import hashlib
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from oracle.store import open_store
from oracle.store.staging import drop_abandoned

ROOT = Path(__file__).resolve().parents[2]
SAMPLE = ROOT / "ontology" / "sample-chains.jsonl"

_LIMITED = """
import resource, signal, sys
signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
resource.setrlimit(resource.RLIMIT_FSIZE, (int(sys.argv[1]), int(sys.argv[1])))
from oracle.cli import main
sys.exit(main(sys.argv[2:]))
"""

# fault injection and whole-corpus runs: with the slow tests (CI, or make test SLOW=1)
pytestmark = pytest.mark.slow


def oracle(*argv: str, file_limit: int | None = None, env: dict[str, str] | None = None) -> subprocess.CompletedProcess[str]:
    prefix = ["-c", _LIMITED, str(file_limit)] if file_limit is not None else ["-m", "oracle"]
    return subprocess.run([sys.executable, *prefix, *argv], capture_output=True, text=True, timeout=300,
                          env={**os.environ, **(env or {})})  # fmt: skip


def one_line_error(done: subprocess.CompletedProcess[str]) -> str:
    assert done.returncode not in (0, -9), done
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), done.stderr
    return lines[0]


def listing(store: Path) -> list[dict]:
    done = oracle("neems", "--store", str(store), "--json")
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


def content(store: Path) -> dict[str, str]:
    """A digest of every document, per NEEM."""
    digests = {}
    with open_store(store, read_only=True) as s:
        for info in s.neems():
            digest = hashlib.sha256()
            for kind in ("triples", "annotations", "tf", "inferred"):
                for doc in s.read_documents(info.id, kind):
                    digest.update(repr(sorted(doc.items())).encode())
            digests[info.id] = digest.hexdigest()
    return digests


def folder_digest(folder: Path) -> dict[str, str]:
    return {str(p.relative_to(folder)): hashlib.sha256(p.read_bytes()).hexdigest() for p in sorted(folder.rglob("*")) if p.is_file()}


@pytest.fixture(scope="module")
def base(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A store holding the three sample NEEMs, checkpointed (no -wal left)."""
    store = tmp_path_factory.mktemp("faults") / "base.sqlite"
    assert oracle("import", str(SAMPLE), "--store", str(store)).returncode == 0
    return store


@pytest.fixture()
def store(base: Path, tmp_path: Path) -> Path:
    copy = tmp_path / "store.sqlite"
    shutil.copy(base, copy)
    return copy


def test_a_disk_that_fills_up_during_import_replace_leaves_every_neem_as_it_was(store, tmp_path):
    before, data = listing(store), content(store)
    done = oracle("import", str(SAMPLE), "--store", str(store), "--replace", file_limit=store.stat().st_size + 64 * 1024,
                  env={"XDG_CACHE_HOME": str(tmp_path / "cache")})  # fmt: skip
    one_line_error(done)
    # Users whose rows ended before the disk filled are replaced whole (their NEEM lists the same
    # actions as before: same rows); the user in flight, and every later one, keeps the old NEEM.
    assert listing(store) == before
    after = content(store)
    assert after.keys() == data.keys()
    kept = [neem for neem in data if after[neem] == data[neem]]
    assert kept and kept == sorted(data)[len(data) - len(kept) :], (kept, done.stdout)
    with open_store(store) as s:  # the next writer finds a sound file, and drops what was left hidden
        drop_abandoned(s)
        assert s.staging_neems() == []


def test_a_disk_that_fills_up_during_load_replace_leaves_the_old_neem(store, tmp_path):
    dump = tmp_path / "dump"
    assert oracle("export", "--store", str(store), "--neem", "p002-tea-red-cereal", "--out", str(dump)).returncode == 0
    before, data = listing(store), content(store)
    # The write-ahead log, where the new NEEM goes first, may not grow past 256 KiB: less than it needs.
    done = oracle("load", str(dump), "--store", str(store), "--replace", file_limit=256 * 1024)
    one_line_error(done)
    assert listing(store) == before and content(store) == data


def test_an_export_that_runs_out_of_space_leaves_the_earlier_dump_whole(store, tmp_path):
    out = tmp_path / "dump"
    assert oracle("export", "--store", str(store), "--neem", "p002-tea-red-cereal", "--out", str(out)).returncode == 0
    before = folder_digest(out)
    triples = (out / "triples" / "roslog" / "triples.bson").stat().st_size
    # a file-size limit stops writes past it, not reads: half the triples file cannot be written
    done = oracle("export", "--store", str(store), "--neem", "p002-tea-red-cereal", "--out", str(out),
                  file_limit=triples // 2)  # fmt: skip
    assert "nothing was replaced" in one_line_error(done)
    assert folder_digest(out) == before  # no .part files left either


@pytest.fixture()
def read_only_copy(base: Path, tmp_path: Path):
    """``base`` in a folder bind-mounted read-only (root only; otherwise a 0500 folder, which
    root would write through)."""
    source, mounted = tmp_path / "src", tmp_path / "ro"
    source.mkdir()
    mounted.mkdir()
    shutil.copy(base, source / "store.sqlite")
    if os.geteuid() != 0:
        os.chmod(source, 0o500)
        yield source
        os.chmod(source, 0o700)
        return
    made = subprocess.run(["mount", "--bind", str(source), str(mounted)], capture_output=True)
    if made.returncode != 0:
        pytest.skip(f"cannot bind-mount here: {made.stderr.decode().strip()}")
    try:
        if subprocess.run(["mount", "-o", "remount,ro,bind", str(mounted)], capture_output=True).returncode != 0:
            pytest.skip("cannot remount read-only here")
        yield mounted
    finally:
        subprocess.run(["umount", str(mounted)], capture_output=True)


def test_a_store_on_a_read_only_file_system_is_read_and_never_written(read_only_copy, base, tmp_path):
    store = read_only_copy / "store.sqlite"
    assert listing(store) == listing(base)
    done = oracle("why-not", "pick(banana)", "--neem", "p000-tea-red-yogurt", "--store", str(store))
    assert done.returncode == 0, done.stderr
    assert oracle("export", "--store", str(store), "--out", str(tmp_path / "out")).returncode == 0
    for argv in (["import", str(SAMPLE)], ["load", str(tmp_path / "out")], ["export", "--out", str(read_only_copy / "x")]):
        one_line_error(oracle(*argv, "--store", str(store) if argv[0] != "export" else str(base)))
    assert sorted(p.name for p in read_only_copy.iterdir()) == ["store.sqlite"]


def test_two_imports_into_one_store_at_once_both_land_whole(tmp_path):
    store = tmp_path / "s.sqlite"
    users = {}
    for line in SAMPLE.read_text().splitlines():
        users.setdefault(json.loads(line)["user"], []).append(line)
    names = sorted(users)[:2]
    files = []
    for name in names:
        files.append(tmp_path / f"{name}.jsonl")
        files[-1].write_text("\n".join(users[name]) + "\n")
    running = [subprocess.Popen([sys.executable, "-m", "oracle", "import", str(f), "--store", str(store), "--commit-every", "1"],
                                stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True) for f in files]  # fmt: skip
    for process in running:
        _, err = process.communicate(timeout=300)
        assert process.returncode == 0, err
    alone = tmp_path / "alone.sqlite"
    for f in files:
        assert oracle("import", str(f), "--store", str(alone)).returncode == 0
    # ids are ObjectIds, in the order the imports created them: compare by name
    assert sorted((n["name"], n["actions"]) for n in listing(store)) == sorted((n["name"], n["actions"]) for n in listing(alone))
