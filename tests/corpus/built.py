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


# -- issue 54: files a user is handed (oracle.handed, oracle.xmlguard) and the sweep's findings --
def _good_dump(tmp: Path) -> Path:
    """A valid one-NEEM dump (generate.py's) in ``tmp/dump``; the folder of its NEEM."""
    from tests.corpus.generate import _write_dump_case

    folder = tmp / "dump"
    _write_dump_case(folder, {"docs": None, "raw": None, "meta": "default", "meta_raw": None, "extra": {}, "metadata": None})
    return folder / "corpus-neem"


def _planted(place: str, how: str, expected: str) -> Builder:
    def build(tmp: Path) -> tuple[list[str], str]:
        neem = _good_dump(tmp)
        target = neem / place
        target.unlink()
        if how == "fifo":
            os.mkfifo(target)
        elif how == "dev-zero":
            target.symlink_to("/dev/zero")
        else:  # a link out of the dump to a file of the user's
            secret = tmp / "private.json"
            secret.write_text('{"name": "diary"}')
            target.symlink_to(secret)
        return ["load", str(neem), "--store", "{store}"], expected

    return build


for _place in ("triples/roslog/triples.metadata.json", "triples/roslog/triples.bson", "meta.json"):
    for _how, _expected in (("fifo", "a FIFO, not a regular file"), ("dev-zero", "link"), ("link-out", "link")):
        BUILT[f"load-{_place.rsplit('/', 1)[-1]}-{_how}"] = _planted(_place, _how, _expected)


@built("load-meta-json-bad-oid")
def _bad_oid(tmp: Path) -> tuple[list[str], str]:
    # json_util.loads raised bson's InvalidId (a traceback) for {"$oid": "zz"}
    neem = _good_dump(tmp)
    (neem / "meta.json").write_text('{"id": "corpus-neem", "created_by": {"$oid": "zz"}}')
    return ["load", str(neem), "--store", "{store}"], "meta.json: not a JSON object"


@built("load-metadata-json-bad-decimal")
def _bad_decimal(tmp: Path) -> tuple[list[str], str]:
    neem = _good_dump(tmp)
    (neem / "triples" / "roslog" / "triples.metadata.json").write_text('{"count": {"$numberDecimal": "x"}}')
    return ["load", str(neem), "--store", "{store}"], "not a mongodump metadata JSON object"


@built("import-fifo")
def _import_fifo(tmp: Path) -> tuple[list[str], str]:
    os.mkfifo(tmp / "chains.jsonl")
    return ["import", str(tmp / "chains.jsonl"), "--store", "{store}"], "a FIFO, not a regular file"


@built("settings-fifo")
def _settings_fifo(tmp: Path) -> tuple[list[str], str]:
    os.mkfifo(tmp / "s.yaml")
    return ["rank", "--store", "{store}", "--neem", "p000-tea-red-yogurt", "--settings", str(tmp / "s.yaml")], "a FIFO"


@built("settings-over-the-limit")
def _settings_big(tmp: Path) -> tuple[list[str], str]:
    (tmp / "s.yaml").write_bytes(b"# " + b"x" * (1 << 20) + b"\n")
    return ["rank", "--store", "{store}", "--neem", "p000-tea-red-yogurt", "--settings", str(tmp / "s.yaml")], \
        "larger than the limit of 1048576 bytes"


@built("mapping-link-to-dev-zero")
def _mapping_zero(tmp: Path) -> tuple[list[str], str]:
    (tmp / "m.yaml").symlink_to("/dev/zero")
    return ["import", "{good}", "--store", "{store}", "--mapping", str(tmp / "m.yaml")], "a device, not a regular file"


for _name, _argv, _data, _expected in (
    # the sweep's three non-UTF-8 YAML files: a UnicodeDecodeError traceback each
    ("settings-latin1", ["rank", "--store", "{store}", "--neem", "p000-tea-red-yogurt", "--settings"], b"# caf\xe9\nknockout: 1.2\n",
     "s.yaml:1: settings is not UTF-8"),
    ("settings-utf16", ["rank", "--store", "{store}", "--neem", "p000-tea-red-yogurt", "--settings"],
     "knockout: 1.2\n".encode("utf-16"), "settings is not UTF-8"),
    ("mapping-latin1", ["import", "{good}", "--store", "{store}", "--mapping"], b"namespace: http://x/\n# m\xfcg\n",
     "s.yaml:2: mapping is not UTF-8"),
):
    def _yaml(tmp: Path, argv: list[str] = _argv, data: bytes = _data, expected: str = _expected) -> tuple[list[str], str]:
        (tmp / "s.yaml").write_bytes(data)
        return [*argv, str(tmp / "s.yaml")], expected
    BUILT[_name] = _yaml


@built("odb-manifest-link-to-dev-zero")
def _odb_zero(tmp: Path) -> tuple[list[str], str]:
    folder = tmp / "odb" / "a"
    folder.mkdir(parents=True)
    (folder / "manifest.xml").symlink_to("/dev/zero")
    return ["import", "{good}", "--store", "{store}", "--odb", str(tmp / "odb")], "symbolic link"


@built("odb-folder-linked-out")
def _odb_out(tmp: Path) -> tuple[list[str], str]:
    (tmp / "elsewhere").mkdir()
    (tmp / "elsewhere" / "manifest.xml").write_text("<object><name>a</name></object>")
    (tmp / "odb").mkdir()
    (tmp / "odb" / "a").symlink_to(tmp / "elsewhere")
    return ["import", "{good}", "--store", "{store}", "--odb", str(tmp / "odb")], "link out of"


#: The issue's kind of OWL file: 683 bytes of nested entities cost rdflib 160 s of CPU.
_NESTED_OWL = (
    '<?xml version="1.0"?>\n<!DOCTYPE rdf:RDF [<!ENTITY a0 "dododododo">'
    + "".join(f'<!ENTITY a{i} "{f"&a{i - 1};" * 10}">' for i in range(1, 8))
    + ']>\n<rdf:RDF xmlns:rdf="http://www.w3.org/1999/02/22-rdf-syntax-ns#" xmlns:owl="http://www.w3.org/2002/07/owl#">'
    '<owl:Ontology rdf:about="http://x/o"><owl:versionInfo>&a7;</owl:versionInfo></owl:Ontology></rdf:RDF>\n'
)


@built("soma-nested-entities")
def _soma_nested(tmp: Path) -> tuple[list[str], str]:
    (tmp / "soma").mkdir()
    (tmp / "soma" / "SOMA.owl").write_text(_NESTED_OWL)
    return ["import", "{good}", "--store", "{store}", "--soma", str(tmp / "soma")], "expands to"


@built("soma-external-entity")
def _soma_external(tmp: Path) -> tuple[list[str], str]:
    (tmp / "soma").mkdir()
    (tmp / "soma" / "SOMA.owl").write_text(_NESTED_OWL.replace('<!ENTITY a0 "dododododo">', '<!ENTITY a0 SYSTEM "/etc/passwd">'))
    return ["import", "{good}", "--store", "{store}", "--soma", str(tmp / "soma")], "external entity"


@built("import-users-who-have-neems")
def _again(tmp: Path) -> tuple[list[str], str]:
    # every user of the file has a NEEM: one error line (was one bare line per user, no 'error:')
    return ["import", "{good}", "--store", "{store}"], "users not imported: user 'p000-tea-red-yogurt' already has NEEM"


@built("load-triple-p-bson-code")
def _code_p(tmp: Path) -> tuple[list[str], str]:
    # bson's Code is a str subclass: it passed the check and then was a TypeError in the store
    from bson import Code

    from tests.corpus.generate import _write_dump_case, bson_docs

    docs = bson_docs()
    docs[1] = {**docs[1], "p": Code("f()")}
    _write_dump_case(tmp / "dump", {"docs": docs, "raw": None, "meta": "default", "meta_raw": None, "extra": {}, "metadata": None})
    return ["load", str(tmp / "dump" / "corpus-neem"), "--store", "{store}"], "'p' must be a non-empty string"
