"""Bad inputs that are built at test time: too large to commit, or not files at all.

Each builder gets a scratch folder and returns the extra command-line arguments and the
expected fragment of the error; ``{store}`` in them is the corpus store.
"""

from __future__ import annotations

import os
from collections.abc import Callable
from pathlib import Path

GOOD_ROW = '{"user": "alice", "time": "2025-03-03T08:00:00", "action": "open(fridge)"}'

Builder = Callable[[Path], tuple[list[str], str]]
BUILT: dict[str, Builder] = {}


def built(name: str) -> Callable[[Builder], Builder]:
    def register(function: Builder) -> Builder:
        BUILT[name] = function
        return function

    return register


@built("import-dev-zero")
def _dev_zero(tmp: Path) -> tuple[list[str], str]:
    # A device is not read at all (it could be endless: /dev/zero).
    return ["import", "/dev/zero", "--store", "{store}"], "a device, not a regular file"


@built("import-long-line")
def _long_line(tmp: Path) -> tuple[list[str], str]:
    path = tmp / "long.jsonl"
    path.write_text(GOOD_ROW[:-1] + ', "note": "' + "x" * 1_100_000 + '"}\n')
    return ["import", str(path), "--store", "{store}"], "longer than"


@built("import-long-line-without-newline")
def _long_tail(tmp: Path) -> tuple[list[str], str]:
    path = tmp / "tail.jsonl"
    path.write_text(GOOD_ROW + "\n" + "y" * 1_200_000)
    return ["import", str(path), "--store", "{store}"], ":2: "


@built("import-fifo-is-not-a-file")
def _folder(tmp: Path) -> tuple[list[str], str]:
    return ["import", str(tmp), "--store", "{store}"], "cannot read"


def _derive_chain(tmp: Path, last_parent: str) -> Path:
    odb = tmp / "odb"
    for i in range(1200):
        folder = odb / f"o{i}"
        folder.mkdir(parents=True)
        parent = f"o{i + 1}" if i < 1199 else last_parent
        (folder / "manifest.xml").write_text(f"<object><name>o{i}</name><derive>{parent}</derive></object>")
    return odb


@built("odb-derive-chain-1200-cycle")
def _deep_cycle(tmp: Path) -> tuple[list[str], str]:
    return ["import", "{good}", "--store", "{store}", "--odb", str(_derive_chain(tmp, "o0"))], "cyclic derive"


@built("odb-derive-chain-1200-unknown-root")
def _deep_unknown(tmp: Path) -> tuple[list[str], str]:
    return ["import", "{good}", "--store", "{store}", "--odb", str(_derive_chain(tmp, "nowhere"))], "unknown object 'nowhere'"


@built("odb-derive-chain-1200-no-mug")
def _deep_valid(tmp: Path) -> tuple[list[str], str]:
    # A valid odb 1,200 classes deep that lacks the objects the chains name.
    odb = tmp / "odb"
    for i in range(1200):
        folder = odb / f"o{i}"
        folder.mkdir(parents=True)
        parent = f"<derive>o{i + 1}</derive>" if i < 1199 else ""
        (folder / "manifest.xml").write_text(f"<object><name>o{i}</name>{parent}</object>")
    return ["import", "{good}", "--store", "{store}", "--odb", str(odb)], "unknown"


@built("odb-deep-xml")
def _deep_xml(tmp: Path) -> tuple[list[str], str]:
    folder = tmp / "odb" / "a"
    folder.mkdir(parents=True)
    (folder / "manifest.xml").write_text("<object><name>a</name>" + "<x>" * 100_000 + "</x>" * 100_000 + "</object>")
    return ["import", "{good}", "--store", "{store}", "--odb", str(tmp / "odb")], "unknown object"


@built("odb-manifest-symlink-loop")
def _loop(tmp: Path) -> tuple[list[str], str]:
    folder = tmp / "odb" / "a"
    folder.mkdir(parents=True)
    os.symlink(folder / "manifest.xml", folder / "manifest.xml")
    return ["import", "{good}", "--store", "{store}", "--odb", str(tmp / "odb")], "manifest"


def corrupt(store: Path, seed: int) -> None:
    """Overwrite a few pages in the middle of a SQLite file (not the header)."""
    size = store.stat().st_size
    page = 4096
    pages = max(2, size // page)
    with store.open("r+b") as handle:
        for k in range(3):
            handle.seek(((seed * 7 + k * 13) % (pages - 1) + 1) * page)
            handle.write(bytes((seed * 31 + i) % 251 for i in range(page)))


#: Commands that write: each must find the damage before writing (readers are in test_corpus).
for _seed in range(5):
    for _command in (["import", "{good}"], ["load", "{dump}"]):
        def _builder(tmp: Path, seed: int = _seed, command: list[str] = _command) -> tuple[list[str], str]:
            return [*command, "--store", "{store}", f"corrupt:{seed}"], "corrupt"
        BUILT[f"corrupted-store-{_seed}-{_command[0]}"] = _builder
