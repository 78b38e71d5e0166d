"""One-shot loader of the compose stack: import the sample chains into an empty NEEM store.

Run as ``python /app/load-samples.py [CHAINS.jsonl]`` with ``NEEM_MONGO_URI`` (and
``NEEM_MONGO_PASSWORD_FILE``) set, which ``import`` then writes to: it is the default store. ``docker compose up``
starts this container again on every run, so it imports only while the database holds no NEEM yet
(a NEEM is a collection prefix: ``<neem>_triples``, KnowRob 2.x layout); otherwise it does nothing.
"""

from __future__ import annotations

import os
import subprocess
import sys
from collections.abc import Iterable, Sequence
from pathlib import Path

DEFAULT_DB = "roslog"


def neem_collections(names: Iterable[str]) -> list[str]:
    """The ``<neem>_triples`` collections among ``names``: one per NEEM."""
    return sorted(name for name in names if name.endswith("_triples") and name != "_triples")


def main(argv: Sequence[str] | None = None, client_factory=None) -> int:
    args = list(sys.argv[1:] if argv is None else argv)
    if len(args) > 1:
        print("usage: load-samples.py [CHAINS.jsonl]  (default: the sample chains shipped in the package)",
              file=sys.stderr)
        return 2
    if args:
        chains = Path(args[0])
    else:
        from oracle.paths import data_dir

        chains = data_dir() / "sample-chains.jsonl"
    if not os.environ.get("NEEM_MONGO_URI"):
        print("load-samples: NEEM_MONGO_URI is not set", file=sys.stderr)
        return 2
    from oracle.errors import StoreError
    from oracle.store import mongo_uri_from_env

    try:
        uri = mongo_uri_from_env()  # with the password of NEEM_MONGO_PASSWORD_FILE
    except StoreError as error:
        print(f"load-samples: {error}", file=sys.stderr)
        return 2
    assert uri is not None
    if not chains.is_file():
        print(f"load-samples: {chains}: no such file", file=sys.stderr)
        return 1
    if client_factory is None:
        from pymongo import MongoClient as client_factory
    from pymongo.errors import PyMongoError

    try:
        client = client_factory(uri, serverSelectionTimeoutMS=15000)
        db = client.get_default_database(default=DEFAULT_DB)
        existing = neem_collections(db.list_collection_names())
    except PyMongoError as error:
        from oracle.store.uri import scrub

        print(f"load-samples: cannot read the store ({type(error).__name__}: {scrub(str(error), uri)})", file=sys.stderr)
        return 1
    if existing:
        print(f"load-samples: {db.name} already holds {len(existing)} NEEM(s); nothing imported")
        return 0
    print(f"load-samples: importing {chains} into {db.name}", flush=True)
    return subprocess.call([sys.executable, "-m", "oracle", "import", str(chains)])


if __name__ == "__main__":
    raise SystemExit(main())
