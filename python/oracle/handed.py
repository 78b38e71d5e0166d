"""Files a user is handed (chains, dumps, odb folders, mappings, settings, ontologies): the one
rule for opening them.

A file is read only when it is a regular file: a FIFO would block the reader for ever, a device
(``/dev/zero``) never ends, a folder is not data. It is opened with ``O_NONBLOCK`` (so opening a
FIFO returns at once) and checked with ``fstat`` on the open descriptor (what is read is what
was checked, not what the name pointed to a moment before). A file found inside a handed folder
(a dump's ``.bson`` files, an odb's manifests) is never reached through a symbolic link: the
link at its name is refused (``O_NOFOLLOW``) and so is a path that resolves outside the folder,
so a folder sent by someone else cannot make the tool read ``~/.ssh`` or ``/dev/zero``. A file
named on the command line may be a link (the user's own pointer) to a regular file.

Files read whole have a size limit, checked on ``fstat`` before anything is read, and no more
than the limit plus one byte is ever read (a file that grows meanwhile is refused too). Every
refusal is one ``error`` line naming the file.
"""

from __future__ import annotations

import errno
import os
import stat
from dataclasses import dataclass
from pathlib import Path
from typing import Any, BinaryIO

MiB = 1 << 20

#: Size limits of the files read whole, in bytes. Each is tens of times the largest real file of
#: its kind (the official SOMA-HOME.owl is 0.8 MB, a settings file under 2 KB).
SETTINGS_LIMIT = 1 * MiB
MAPPING_LIMIT = 8 * MiB
MANIFEST_LIMIT = 1 * MiB
JSON_LIMIT = 16 * MiB
OWL_LIMIT = 64 * MiB


@dataclass(frozen=True)
class Handed:
    """How to read one kind of handed file: what the messages call it, the error type raised,
    and the folder it was found in (None: named by the user, a link to a regular file is fine)."""

    what: str
    error: type[Exception]
    inside: Path | None = None


def _kind(mode: int) -> str:
    if stat.S_ISDIR(mode):
        return "a folder"
    if stat.S_ISFIFO(mode):
        return "a FIFO"
    if stat.S_ISCHR(mode) or stat.S_ISBLK(mode):
        return "a device"
    if stat.S_ISSOCK(mode):
        return "a socket"
    return "not a regular file"


def _outside(path: Path, folder: Path) -> bool:
    real, root = os.path.realpath(path), os.path.realpath(folder)
    return os.path.commonpath([real, root]) != root


def open_handed(path: Path | str, kind: Handed) -> BinaryIO:
    """``path`` opened for reading in binary, once it is known to be a regular file (see the
    module's docstring); ``kind.error`` naming the file otherwise."""
    path = Path(path)
    flags = os.O_RDONLY | os.O_NONBLOCK | getattr(os, "O_CLOEXEC", 0)
    if kind.inside is not None:
        flags |= os.O_NOFOLLOW
        if _outside(path, kind.inside):
            raise kind.error(f"{path}: {kind.what} reached through a link out of {kind.inside}; refusing to read it")
    try:
        fd = os.open(path, flags)
    except OSError as failure:
        if failure.errno == errno.ELOOP and kind.inside is not None:
            raise kind.error(f"{path}: {kind.what} is a symbolic link inside {kind.inside}; refusing to follow it") from None
        if failure.errno == errno.EISDIR:
            raise kind.error(f"{path}: cannot read {kind.what} (it is a folder)") from None
        raise kind.error(f"{path}: cannot read {kind.what} ({failure.strerror or type(failure).__name__})") from None
    try:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode):
            raise kind.error(f"{path}: cannot read {kind.what} ({_kind(info.st_mode)}, not a regular file)")
        os.set_blocking(fd, True)  # a regular file never blocks; reads behave as usual
        return os.fdopen(fd, "rb")
    except BaseException:
        os.close(fd)
        raise


def read_handed(path: Path | str, kind: Handed, limit: int) -> bytes:
    """The bytes of ``path`` (``open_handed``), at most ``limit`` of them: a larger file is refused
    from its ``fstat`` size before it is read, and reading stops one byte past the limit."""
    with open_handed(path, kind) as handle:
        size = os.fstat(handle.fileno()).st_size
        if size > limit:
            raise kind.error(f"{path}: {kind.what} is {size} bytes, larger than the limit of {limit} bytes")
        try:
            data = handle.read(limit + 1)
        except OSError as failure:
            raise kind.error(f"{path}: cannot read {kind.what} ({failure.strerror or type(failure).__name__})") from None
    if len(data) > limit:
        raise kind.error(f"{path}: {kind.what} grew past the limit of {limit} bytes while it was read")
    return data


def read_handed_text(path: Path | str, kind: Handed, limit: int) -> str:
    """``read_handed`` decoded as UTF-8; a byte that is not UTF-8 is refused naming its line."""
    data = read_handed(path, kind, limit)
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as failure:
        line = data.count(b"\n", 0, failure.start) + 1
        raise kind.error(
            f"{path}:{line}: {kind.what} is not UTF-8 (byte 0x{data[failure.start]:02x} at offset {failure.start})"
        ) from None


def handed_files(folder: Path, pattern: str, kind: Handed) -> list[Path]:
    """The files under ``folder`` matching the glob ``pattern``, sorted, none of them reached
    through a link (a link matching the pattern, or a linked folder on the way, is refused)."""
    found = sorted(folder.glob(pattern))
    for path in found:
        if path.is_symlink():
            raise kind.error(f"{path}: {kind.what} is a symbolic link inside {folder}; refusing to follow it")
        if _outside(path, folder):
            raise kind.error(f"{path}: {kind.what} reached through a link out of {folder}; refusing to read it")
    return found




def parse_rdf_file(graph: Any, path: Path | str, fmt: str, kind: Handed) -> None:
    """Parse the handed RDF file ``path`` (``fmt``: rdflib's format name) into the rdflib ``graph``:
    read by the rule above (at most ``OWL_LIMIT`` bytes), its XML entities bounded first
    (oracle.xmlguard), then parsed from those bytes with the file's URI as its base, as rdflib
    would have parsed the file itself."""
    import io

    from oracle.xmlguard import check_entities

    data = read_handed(path, kind, OWL_LIMIT)
    if fmt == "xml":
        check_entities(data, str(path), kind.error)
    try:
        graph.parse(source=io.BytesIO(data), publicID=Path(path).absolute().as_uri(), format=fmt)
    except Exception as failure:  # noqa: BLE001 - rdflib raises many parser-specific types
        raise kind.error(f"{path}: cannot parse as {fmt} ({str(failure)[:160]})") from None


__all__ = [
    "JSON_LIMIT", "MANIFEST_LIMIT", "MAPPING_LIMIT", "OWL_LIMIT", "SETTINGS_LIMIT",
    "Handed", "handed_files", "open_handed", "parse_rdf_file", "read_handed", "read_handed_text",
]
