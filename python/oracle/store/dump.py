"""NEEM interchange: the mongodump layout ``memorize/1`` writes and ``remember/1`` reads.

A NEEM folder holds ``triples/``, ``annotations/``, ``tf/`` and ``inferred/``, each with
``<db>/<collection>.bson`` and ``.metadata.json`` (knowrob-2x-facts §9), plus ``meta.json`` with
the registry entry. Documents are copied unchanged, so dump -> load -> dump is the identity.

Why this module is large: writing and reading the layout are one format, kept in one place, and
a dump is a file a user is handed, so its reading checks every file (oracle.handed), document
and count before the store changes; splitting write from read would split the format.
"""

from __future__ import annotations

import contextlib
import itertools
import os
import re
import struct
import tempfile
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from pathlib import Path
from typing import Any, BinaryIO

import bson
from bson import json_util
from bson.codec_options import DEFAULT_CODEC_OPTIONS, DatetimeConversion

from oracle.errors import StoreError
from oracle.progress import Tick
from oracle.handed import JSON_LIMIT, Handed, handed_files, open_handed, read_handed_text
from oracle.store.base import COLLECTION_KINDS, SUMMARY_KEY, Store, check_neem_id
from oracle.store.staging import STAGING
from oracle.store.ids import ALIAS_KEY, alias_of, check_alias, find_neem, is_object_id, new_neem_id
from oracle.store.meta import hub_document, hub_text_index, loaded_meta
from oracle.store.staging import READY, STAGED_BY
from oracle.store.validate import check_meta
from oracle.store.mongo import DEFAULT_DB, INDEXES

META_FILE = "meta.json"
#: meta.json field with the number of documents per collection, written by ``export``: a
#: ``.bson`` cut exactly at a document boundary is otherwise indistinguishable from a whole one.
COUNTS_KEY = "documents"
#: Dates far outside Python's range must still survive a round trip.
_CODEC = DEFAULT_CODEC_OPTIONS.with_options(datetime_conversion=DatetimeConversion.DATETIME_AUTO)
_CANONICAL = json_util.JSONOptions(json_mode=json_util.JSONMode.CANONICAL)


def _mkdir(path: Path, top: Path) -> None:
    """``path`` with every missing folder above it, each created 0700 whatever the umask; the
    dump's own folders (``top`` and below) are made 0700 if they existed, and are never a symlink."""
    for folder in [path, *path.parents][::-1]:
        inside = folder == top or top in folder.parents
        if inside and folder.is_symlink():
            raise StoreError(f"{folder}: is a symbolic link; refusing to write a dump through it")
        if not folder.exists():
            folder.mkdir(mode=0o700)
            os.chmod(folder, 0o700)
        elif inside:
            os.chmod(folder, 0o700)


def _open_private(path: Path) -> tuple[BinaryIO, Path]:
    """A new 0600 file beside ``path`` that ``_commit`` later moves onto it, and its name.

    Dumps hold personal data (thesis 3.5): files are 0600, also where an existing 0644 file is
    replaced, and a symlink planted at the path is refused, never followed."""
    if path.is_symlink():
        raise StoreError(f"{path}: is a symbolic link; refusing to write through it")
    temporary = path.with_name(f".{path.name}.{os.urandom(4).hex()}.part")
    fd = os.open(temporary, os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW, 0o600)
    os.fchmod(fd, 0o600)
    return os.fdopen(fd, "wb"), temporary


def metadata(collection: str, kind: str) -> dict[str, Any]:
    """mongodump's ``.metadata.json``: mongorestore recreates these indexes."""
    indexes: list[dict[str, Any]] = [{"v": 2, "key": {"_id": 1}, "name": "_id_"}]
    for keys in INDEXES[kind]:
        indexes.append({"v": 2, "key": {k: 1 for k in keys}, "name": "_".join(f"{k}_1" for k in keys)})
    return {"indexes": indexes, "collectionName": collection, "type": "collection"}


def write_dump(
    out: Path | str,
    documents: Mapping[str, Iterable[Mapping[str, Any]]],
    meta: Mapping[str, Any] | None = None,
    db_name: str = DEFAULT_DB,
    prefix: str | None = None,
    registry: Mapping[str, Any] | None = None,
) -> dict[str, int]:
    """Write collections in the mongodump layout; return documents written per kind.

    Without ``prefix`` collections are named ``triples`` etc., which is what a default KnowRob
    (``collection_prefix: ''``) restores with remember/1; with it, ``<prefix>_triples``.
    Every file is written aside and moved into place only when all are complete: a full disk
    or an error mid-way leaves an earlier dump in ``out`` as it was.
    """
    out = Path(out)
    counts: dict[str, int] = {}
    written: list[tuple[Path, Path]] = []  # (finished temporary file, its place)
    moved = 0

    def private(path: Path) -> BinaryIO:
        handle, temporary = _open_private(path)
        written.append((temporary, path))
        return handle

    try:
        for kind in COLLECTION_KINDS:
            collection = f"{prefix}_{kind}" if prefix else kind
            folder = out / kind / db_name
            _mkdir(folder, out)
            count = 0
            with private(folder / f"{collection}.bson") as handle:
                for doc in documents.get(kind, ()):
                    handle.write(bson.encode(doc, codec_options=_CODEC))
                    count += 1
                os.fsync(handle.fileno())
            with private(folder / f"{collection}.metadata.json") as handle:
                handle.write(json_util.dumps(metadata(collection, kind), json_options=_CANONICAL).encode())
            counts[kind] = count
        if registry is not None:  # the hub's registry: collection ``meta`` (never prefixed), text-indexed
            folder = out / "meta" / db_name
            _mkdir(folder, out)
            with private(folder / "meta.bson") as handle:
                handle.write(bson.encode(dict(registry), codec_options=_CODEC))
                os.fsync(handle.fileno())
            with private(folder / "meta.metadata.json") as handle:
                indexes = [{"v": 2, "key": {"_id": 1}, "name": "_id_"}, hub_text_index()]
                handle.write(json_util.dumps({"indexes": indexes, "collectionName": "meta", "type": "collection"},
                                             json_options=_CANONICAL).encode())  # fmt: skip
        if meta is not None:
            _mkdir(out, out)
            with private(out / META_FILE) as handle:
                # the counts written: load then tells a .bson cut at a document boundary from a whole one
                record = {**meta, COUNTS_KEY: dict(counts)}
                handle.write(json_util.dumps(record, indent=2, sort_keys=True).encode() + b"\n")
                os.fsync(handle.fileno())
        for temporary, path in written:
            os.replace(temporary, path)  # replaces a file (or a link planted since), never writes through it
            moved += 1
    except OSError as error:
        kept = "; nothing was replaced" if moved == 0 else ""
        raise StoreError(f"{out}: cannot write the dump ({error.strerror or error}){kept}") from None
    finally:
        for temporary, _ in written:
            with contextlib.suppress(FileNotFoundError):
                os.unlink(temporary)
    return counts


def export_neem(store: Store, neem_id: str, out: Path | str, *, db_name: str = DEFAULT_DB, hub_prefix: bool = False,
                visibility: bool = False, ontology_files: Sequence[Path] = (), url: str | None = None) -> dict[str, int]:  # fmt: skip
    """Write one NEEM as a KnowRob dump folder, with its registry entry as ``meta.json`` (which
    ``load`` reads) and as the NEEM hub's ``meta`` collection (ObjectId ``_id``, ``visibility``
    as given, the text index openEASE searches). ``hub_prefix``: collections named
    ``<id>_triples`` etc., as the hub keeps them (a NEEM whose id is no ObjectId takes the new
    ObjectId of its registry document). ``ontology_files``: whole OWL files (the official SOMA,
    DUL, SOMA-HOME) written into the NEEM's triples in place of its extract of those graphs, so a
    read-only KnowRob (openEASE), which loads no ontology, sees all of them. ``url``: the NEEM's
    repository in the hub's entry (``meta.hub_document``; default: the one the hub would give it)."""
    info = store.neem(neem_id)
    # The kept summary belongs to this store's write marks, not to the dump.
    meta = {k: v for k, v in info.meta.items() if k not in ("temporary", STAGING, STAGED_BY, READY, COUNTS_KEY, SUMMARY_KEY)}
    registry = hub_document(meta, neem_id, visibility=visibility, url=url)
    meta["id"] = neem_id
    docs = {kind: store.read_documents(neem_id, kind) for kind in COLLECTION_KINDS}
    with contextlib.ExitStack() as stack:
        if ontology_files:
            graphs, extra = _ontology_documents(ontology_files, stack)
            # the NEEM's own copy of those graphs (an extract) gives way to the whole files
            kept = (doc for doc in docs["triples"] if doc.get("graph") not in graphs)
            docs["triples"] = itertools.chain(kept, extra["triples"])
            docs["annotations"] = itertools.chain(docs["annotations"], extra["annotations"])
        try:
            counts = write_dump(out, docs, meta, db_name, str(registry["_id"]) if hub_prefix else None, registry)
        finally:
            for reader in store_readers(docs):
                reader.close()  # a dump that failed mid-way leaves no read open on the store
    return counts


def store_readers(docs: Mapping[str, Any]) -> list[Any]:
    return [reader for reader in docs.values() if getattr(reader, "close", None) is not None]


def _ontology_documents(files: Sequence[Path], stack: contextlib.ExitStack) -> tuple[set[str], dict[str, Iterator[dict[str, Any]]]]:
    """The documents KnowRob's ``load_owl`` makes of whole OWL files (each its own graph), made
    in a scratch store in a private temporary folder: the graphs and their triples/annotations."""
    from oracle.store.owlfile import graph_of_file, tbox_from_files
    from oracle.store.sqlite import SQLiteStore
    from oracle.store.tbox import load_tbox

    for path in files:
        if not Path(path).is_file():
            raise StoreError(f"{path}: no such OWL file")
    scratch = stack.enter_context(tempfile.TemporaryDirectory(prefix="neem-oracle-owl-"))
    owl = stack.enter_context(SQLiteStore(Path(scratch) / "owl.sqlite"))
    owl.create_neem("owl")
    load_tbox(owl, "owl", tbox_from_files(list(files)))
    return {graph_of_file(p) for p in files}, {k: owl.read_documents("owl", k) for k in ("triples", "annotations")}


def export_all(store: Store, out: Path | str, **options: Any) -> dict[str, dict[str, int]]:
    """Every NEEM of the store, each in ``OUT/<neem id>/`` (options: those of export_neem)."""
    return {info.id: export_neem(store, info.id, Path(out) / info.id, **options) for info in store.neems()}


class LoadedDocument(dict):  # type: ignore[type-arg]
    """A decoded document that remembers its BSON bytes, so storing it needs no re-encoding."""

    __slots__ = ("raw",)

    def __init__(self, raw: bytes) -> None:
        super().__init__(bson.decode(raw, codec_options=_CODEC))
        self.raw = raw


#: What json_util.loads raises on a value it cannot make (``{"$oid": "zz"}`` is a BSONError,
#: ``{"$numberDecimal": "x"}`` an ArithmeticError, ``{"$code": 5}`` a TypeError).
_JSON_FAULTS = (OSError, ValueError, TypeError, OverflowError, ArithmeticError, LookupError, AttributeError,
                bson.errors.BSONError)

#: The largest document a dump may hold: MongoDB's own limit (16 MiB) and a little room.
MAX_DOCUMENT = 16 * 1024 * 1024 + 16 * 1024


def iter_bson(path: Path, inside: Path | None = None) -> Iterator[dict[str, Any]]:
    """Documents of a ``.bson`` file (a regular file, found in the dump folder ``inside``: no
    link followed out of it, oracle.handed); a truncated or corrupt file is an error naming it."""
    handle = open_handed(path, Handed("dump file", StoreError, inside))
    with handle:
        number = 0
        while True:
            head = handle.read(4)
            if not head:
                return
            number += 1
            if len(head) < 4:
                raise StoreError(f"{path}: truncated after document {number - 1}")
            (size,) = struct.unpack("<i", head)
            if size > MAX_DOCUMENT:
                raise StoreError(f"{path}: document {number} is corrupt (it claims {size} bytes, more than MongoDB's 16 MiB)")
            body = handle.read(size - 4) if size >= 5 else b""
            if size < 5 or len(body) != size - 4:
                raise StoreError(f"{path}: document {number} is truncated or corrupt")
            try:
                doc = LoadedDocument(head + body)
            except Exception as error:
                raise StoreError(f"{path}: document {number} is not valid BSON ({error})") from None
            yield doc


_SAFE = re.compile(r"[^A-Za-z0-9\-]+")


def _neem_groups(root: Path) -> dict[tuple[Path, str | None], dict[str, Path]]:
    """Find the ``.bson`` files of each NEEM under ``root``: (folder, prefix) -> kind -> file."""
    groups: dict[tuple[Path, str | None], dict[str, Path]] = {}
    for path in handed_files(root, "**/*.bson", Handed("dump file", StoreError)):
        stem = path.name[: -len(".bson")]
        kind = next((k for k in COLLECTION_KINDS if stem == k or stem.endswith(f"_{k}")), None)
        if kind is None:
            continue
        prefix = stem[: -len(kind) - 1] if stem != kind else None
        parts = path.relative_to(root).parts
        folder = root / Path(*parts[: parts.index(kind)]) if kind in parts[:-1] else path.parent
        groups.setdefault((folder, prefix), {})[kind] = path
    for (folder, prefix), files in groups.items():
        if "triples" not in files:  # a NEEM is its triples: a dump without them is cut
            name = f"{prefix}_triples.bson" if prefix else "triples.bson"
            raise StoreError(f"{folder}: no {name} beside {', '.join(sorted(p.name for p in files.values()))}; the dump is incomplete")
    return groups


class _Documents:
    """The documents of one ``.bson`` file, counted as they are read, named for error messages."""

    def __init__(self, path: Path, root: Path, progress: Callable[[int], None] | None = None) -> None:
        self.path = path
        self.root = root
        self.where = str(path)
        self.count = 0
        #: Told the documents read so far, every 1,024 (oracle.progress, through load_dump).
        self.progress = progress

    def __iter__(self) -> Iterator[dict[str, Any]]:
        for doc in iter_bson(self.path, self.root):
            self.count += 1
            if self.progress is not None and not self.count % 1024:
                self.progress(self.count)
            yield doc


def load_dump(store: Store, path: Path | str, *, neem_id: str | None = None, replace: bool = False,
              progress: Tick | None = None) -> list[str]:
    """Load every NEEM found under ``path`` (a NEEM folder, a folder of them, or a hub dump).

    The id is the collection prefix, else the ``id`` in meta.json, else the folder name (a dump
    keeps its id). ``neem_id`` (only when one NEEM is found) names the NEEM to load it as: the
    NEEM of that id or alias, else that id (24 hex digits), else a new NEEM with a fresh id and
    that alias. Return the ids loaded.

    Each NEEM is loaded into a hidden staging NEEM and swapped in under its id only when every
    document was read, checked and counted (meta.json's ``documents``, when present, must match):
    on any error, or a kill, an existing NEEM of that id is untouched (``replace``).
    ``progress`` (oracle.progress) is told the documents read, of those meta.json counts.
    """
    root = Path(path)
    if not root.is_dir():
        raise StoreError(f"{root}: not a folder with a NEEM dump")
    groups = _neem_groups(root)
    if not groups:
        raise StoreError(f"{root}: no triples/annotations/tf/inferred .bson files found")
    if neem_id is not None and len(groups) > 1:
        raise StoreError(f"{root}: holds {len(groups)} NEEMs; --neem names only one")
    plans: list[tuple[str, dict[str, Path], dict[str, Any], Path]] = []
    for (folder, prefix), files in sorted(groups.items(), key=lambda item: (str(item[0][0]), item[0][1] or "")):
        meta = _read_meta(folder, root)
        target = prefix or meta.pop("id", None) or _SAFE.sub("-", folder.resolve().name).strip("-")
        if neem_id is not None:
            target = _named_target(store, neem_id, meta)
        for key in ("id", SUMMARY_KEY, STAGING, STAGED_BY, READY):
            meta.pop(key, None)
        meta = loaded_meta(meta, folder.resolve().name)
        if not meta.get("name"):
            meta["name"] = meta.get(ALIAS_KEY) or target  # never the staging NEEM's id
        check_neem_id(target)
        if store.has_neem(target) and not replace:
            raise StoreError(f"{store.location}: NEEM {target!r} already exists (load with --replace)")
        twin = next((other for other in plans if other[0] == target), None)
        if twin is not None:
            raise StoreError(f"{root}: {twin[3]} and {folder} both hold NEEM {target!r}; load them one at a time")
        plans.append((target, files, meta, folder))
    for _, files, _, _ in plans:  # every file a regular one before anything is staged (oracle.handed)
        for file in files.values():
            open_handed(file, Handed("dump file", StoreError, root)).close()
    # Every NEEM is staged before any is swapped in, and the swaps are one transaction (on
    # SQLite): a bad second NEEM leaves the store as it was, not with the first one loaded.
    staged: list[str] = []
    counted = [meta.get(COUNTS_KEY) for _, _, meta, _ in plans]
    total = (sum(sum(int(n) for n in c.values() if isinstance(n, int)) for c in counted if isinstance(c, dict))
             if all(isinstance(c, dict) for c in counted) else None)
    loaded = 0

    def told(read: int) -> None:
        if progress is not None:
            progress(loaded + read, total)

    try:
        for target, files, meta, folder in plans:
            counts = meta.pop(COUNTS_KEY, None)
            meta["temporary"] = False
            staging = store.create_staging(target, user=meta.get("created_by"), meta=meta)
            staged.append(staging)
            for kind in COLLECTION_KINDS:
                if kind in files:
                    docs = _Documents(files[kind], root, told)
                    store.write_documents(staging, kind, docs)
                    loaded += docs.count
                    told(0)
                    expected = counts.get(kind) if isinstance(counts, dict) else None
                    if expected is not None and expected != docs.count:
                        raise StoreError(
                            f"{files[kind]}: holds {docs.count} documents but {folder / META_FILE} counts {expected};"
                            " the dump is cut or altered"
                        )
        with store.transaction():
            for staging, (target, *_) in zip(staged, plans):
                store.swap_in(staging, target, replace=replace)
    except BaseException:
        for staging in staged:
            if store.has_neem(staging):
                store.drop_neem(staging)  # the old NEEM, if any, was never touched
        raise
    return [target for target, *_ in plans]


def remember_dump(store: Store, neem_id: str, path: Path | str) -> dict[str, int]:
    """KnowRob's ``remember/1``: the documents of one NEEM dump added to the NEEM ``neem_id``
    (mongorestore into the current collections: what is already there stays, and a document
    already stored is not added again, as mongorestore skips a duplicate ``_id``; a triple
    counts as stored when its s, p, o and graph are). Return documents added per kind."""
    root = Path(path)
    if not root.is_dir():
        raise StoreError(f"{root}: not a folder with a NEEM dump")
    groups = _neem_groups(root)
    if len(groups) != 1:
        raise StoreError(f"{root}: holds {len(groups)} NEEMs; remember/1 reads one" if groups else
                         f"{root}: no triples/annotations/tf/inferred .bson files found")  # fmt: skip
    (files,) = groups.values()
    added: dict[str, int] = {}
    with store.transaction():
        for kind, file in files.items():
            ids = set() if kind == "triples" else {doc.get("_id") for doc in store.read_documents(neem_id, kind)}
            docs = [doc for doc in iter_bson(file, root) if not _stored(store, neem_id, kind, doc, ids)]
            added[kind] = store.write_documents(neem_id, kind, docs)
    return added


def _stored(store: Store, neem_id: str, kind: str, doc: dict[str, Any], ids: set[Any]) -> bool:
    """The dump's document is in the NEEM already: a triple with its s, p, o and graph, another
    document with its ``_id`` (among ``ids``)."""
    if kind != "triples":
        return doc.get("_id") in ids
    found = store.find(neem_id, s=doc.get("s"), p=doc.get("p"), o=doc.get("o"), graph=doc.get("graph"), limit=1, exact=True)
    return next(found, None) is not None


def _named_target(store: Store, name: str, meta: dict[str, Any]) -> str:
    """The id ``load --neem NAME`` loads under; a new alias goes into ``meta``."""
    existing = find_neem(store, name)
    if existing is not None:  # it keeps its id and its alias
        meta[ALIAS_KEY] = alias_of(existing)
        return existing.id
    if is_object_id(name):
        return name
    meta[ALIAS_KEY] = check_alias(name)
    meta["name"] = name
    return new_neem_id()


def _read_meta(folder: Path, root: Path) -> dict[str, Any]:
    path = folder / META_FILE
    if not path.exists() and not path.is_symlink():
        return {}
    text = read_handed_text(path, Handed("meta.json", StoreError, root), JSON_LIMIT)
    try:
        meta = json_util.loads(text)
    except RecursionError:
        raise StoreError(f"{path}: not a JSON object (nested too deeply)") from None
    except _JSON_FAULTS as error:
        raise StoreError(f"{path}: not a JSON object ({str(error)[:120]})") from None
    if not isinstance(meta, dict):
        raise StoreError(f"{path}: not a JSON object")
    check_meta(meta, str(path))
    counts = meta.get(COUNTS_KEY)
    if counts is not None and not (
        isinstance(counts, dict) and all(k in COLLECTION_KINDS and type(v) is int and v >= 0 for k, v in counts.items())
    ):
        raise StoreError(f"{path}: {COUNTS_KEY!r} must map collection kinds to document counts")
    if "id" in meta and not isinstance(meta["id"], str):
        raise StoreError(f"{path}: 'id' must be a string, got {meta['id']!r}")
    metadata_kind = Handed("mongodump metadata file", StoreError, root)
    for metadata_file in handed_files(folder, "**/*.metadata.json", metadata_kind):
        text = read_handed_text(metadata_file, metadata_kind, JSON_LIMIT)
        try:
            if not isinstance(json_util.loads(text), dict):
                raise ValueError("not an object")
        except RecursionError:
            raise StoreError(f"{metadata_file}: not a mongodump metadata JSON object (nested too deeply)") from None
        except _JSON_FAULTS as error:
            raise StoreError(f"{metadata_file}: not a mongodump metadata JSON object ({str(error)[:120]})") from None
    return meta


__all__ = ["export_all", "export_neem", "iter_bson", "load_dump", "metadata", "remember_dump", "write_dump"]
