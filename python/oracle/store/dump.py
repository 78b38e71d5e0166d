"""NEEM interchange: the mongodump layout ``memorize/1`` writes and ``remember/1`` reads.

A NEEM folder holds ``triples/``, ``annotations/``, ``tf/`` and ``inferred/``, each with
``<db>/<collection>.bson`` and ``.metadata.json`` (knowrob-2x-facts §9), plus ``meta.json`` with
the registry entry. Documents are copied unchanged, so dump -> load -> dump is the identity.
"""

from __future__ import annotations

import os
import re
import struct
from collections.abc import Iterable, Iterator, Mapping
from pathlib import Path
from typing import Any, BinaryIO

import bson
from bson import json_util
from bson.codec_options import DEFAULT_CODEC_OPTIONS, DatetimeConversion

from oracle.errors import StoreError
from oracle.store.base import COLLECTION_KINDS, SUMMARY_KEY, Store, check_neem_id
from oracle.store.mongo import DEFAULT_DB, INDEXES

META_FILE = "meta.json"
#: Dates far outside Python's range must still survive a round trip.
_CODEC = DEFAULT_CODEC_OPTIONS.with_options(datetime_conversion=DatetimeConversion.DATETIME_AUTO)
_CANONICAL = json_util.JSONOptions(json_mode=json_util.JSONMode.CANONICAL)


def _mkdir(path: Path) -> None:
    path.mkdir(parents=True, exist_ok=True, mode=0o700)


def _open_private(path: Path) -> BinaryIO:
    """Dumps hold personal data (thesis 3.5): files are created 0600."""
    fd = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o600)
    return os.fdopen(fd, "wb")


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
) -> dict[str, int]:
    """Write collections in the mongodump layout; return documents written per kind.

    Without ``prefix`` collections are named ``triples`` etc., which is what a default KnowRob
    (``collection_prefix: ''``) restores with remember/1; with it, ``<prefix>_triples``.
    """
    out = Path(out)
    counts: dict[str, int] = {}
    try:
        for kind in COLLECTION_KINDS:
            collection = f"{prefix}_{kind}" if prefix else kind
            folder = out / kind / db_name
            _mkdir(folder)
            count = 0
            with _open_private(folder / f"{collection}.bson") as handle:
                for doc in documents.get(kind, ()):
                    handle.write(bson.encode(doc, codec_options=_CODEC))
                    count += 1
            with _open_private(folder / f"{collection}.metadata.json") as handle:
                handle.write(json_util.dumps(metadata(collection, kind), json_options=_CANONICAL).encode())
            counts[kind] = count
        if meta is not None:
            with _open_private(out / META_FILE) as handle:
                handle.write(json_util.dumps(dict(meta), indent=2, sort_keys=True).encode() + b"\n")
    except OSError as error:
        raise StoreError(f"{out}: cannot write the dump ({error.strerror or error})") from None
    return counts


def export_neem(store: Store, neem_id: str, out: Path | str, *, db_name: str = DEFAULT_DB) -> dict[str, int]:
    """Write one NEEM as a KnowRob dump folder."""
    info = store.neem(neem_id)
    # The kept summary belongs to this store's write marks, not to the dump.
    meta = {k: v for k, v in info.meta.items() if k not in ("temporary", SUMMARY_KEY)}
    meta["id"] = neem_id
    docs = {kind: store.read_documents(neem_id, kind) for kind in COLLECTION_KINDS}
    return write_dump(out, docs, meta, db_name)


def export_all(store: Store, out: Path | str, *, db_name: str = DEFAULT_DB) -> dict[str, dict[str, int]]:
    """Every NEEM of the store, each in ``OUT/<neem id>/``."""
    return {info.id: export_neem(store, info.id, Path(out) / info.id, db_name=db_name) for info in store.neems()}


class LoadedDocument(dict):  # type: ignore[type-arg]
    """A decoded document that remembers its BSON bytes, so storing it needs no re-encoding."""

    __slots__ = ("raw",)

    def __init__(self, raw: bytes) -> None:
        super().__init__(bson.decode(raw, codec_options=_CODEC))
        self.raw = raw


def iter_bson(path: Path) -> Iterator[dict[str, Any]]:
    """Documents of a ``.bson`` file; a truncated or corrupt file is an error naming it."""
    try:
        handle = path.open("rb")
    except OSError as error:
        raise StoreError(f"{path}: cannot read ({error.strerror})") from None
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
    for path in sorted(root.rglob("*.bson")):
        stem = path.name[: -len(".bson")]
        kind = next((k for k in COLLECTION_KINDS if stem == k or stem.endswith(f"_{k}")), None)
        if kind is None:
            continue
        prefix = stem[: -len(kind) - 1] if stem != kind else None
        parts = path.relative_to(root).parts
        folder = root / Path(*parts[: parts.index(kind)]) if kind in parts[:-1] else path.parent
        groups.setdefault((folder, prefix), {})[kind] = path
    return groups


def load_dump(store: Store, path: Path | str, *, neem_id: str | None = None, replace: bool = False) -> list[str]:
    """Load every NEEM found under ``path`` (a NEEM folder, a folder of them, or a hub dump).

    The id is ``neem_id`` (only when one NEEM is found), else the collection prefix, else the
    ``id`` in meta.json, else the folder name. Return the ids loaded.
    """
    root = Path(path)
    if not root.is_dir():
        raise StoreError(f"{root}: not a folder with a NEEM dump")
    groups = _neem_groups(root)
    if not groups:
        raise StoreError(f"{root}: no triples/annotations/tf/inferred .bson files found")
    if neem_id is not None and len(groups) > 1:
        raise StoreError(f"{root}: holds {len(groups)} NEEMs; --neem names only one")
    loaded: list[str] = []
    for (folder, prefix), files in sorted(groups.items(), key=lambda item: (str(item[0][0]), item[0][1] or "")):
        meta = _read_meta(folder)
        target = neem_id or prefix or meta.pop("id", None) or _SAFE.sub("-", folder.resolve().name).strip("-")
        meta.pop("id", None)
        meta.pop(SUMMARY_KEY, None)
        check_neem_id(target)
        if store.has_neem(target):
            if not replace:
                raise StoreError(f"{store.location}: NEEM {target!r} already exists (load with --replace)")
            store.drop_neem(target)
        meta["temporary"] = False
        store.create_neem(target, user=meta.get("created_by"), meta=meta)
        try:
            for kind in COLLECTION_KINDS:
                if kind in files:
                    store.write_documents(target, kind, iter_bson(files[kind]))
        except BaseException:
            store.drop_neem(target)  # a half-loaded NEEM would look complete in listings
            raise
        loaded.append(target)
    return loaded


def _read_meta(folder: Path) -> dict[str, Any]:
    path = folder / META_FILE
    if not path.is_file():
        return {}
    try:
        meta = json_util.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError) as error:
        raise StoreError(f"{path}: not a JSON object ({error})") from None
    if not isinstance(meta, dict):
        raise StoreError(f"{path}: not a JSON object")
    return meta


__all__ = ["export_all", "export_neem", "iter_bson", "load_dump", "metadata", "write_dump"]
