"""Files a user is handed (issue 54): FIFOs, devices, links out of a folder, oversized files and
XML entity bombs are refused in one line, without reading them (oracle.handed, oracle.xmlguard).

Each command runs in this process through ``oracle.cli.main`` under an alarm: a FIFO that is
opened for reading would block for ever, so a hang fails the test instead of stalling it.
"""

from __future__ import annotations

import os
import shutil
import signal
from collections.abc import Iterator
from pathlib import Path

import pytest

from oracle.cli import main
from oracle.errors import OntologyError
from oracle.handed import Handed, read_handed
from oracle.xmlguard import check_entities
from tests.corpus.harness import sample_chains

ROOT = Path(__file__).resolve().parents[2]
SOMA = Path("/work/shared/soma")

#: The issue's 683-byte kind of file: each entity ten of the one before (rdflib: minutes of CPU).
NESTED = (
    '<?xml version="1.0"?>\n<!DOCTYPE rdf:RDF [<!ENTITY a0 "dododododo">'
    + "".join(f'<!ENTITY a{i} "{f"&a{i - 1};" * 10}">' for i in range(1, 8))
    + ']>\n<rdf:RDF xmlns:rdf="http://www.w3.org/1999/02/22-rdf-syntax-ns#" xmlns:owl="http://www.w3.org/2002/07/owl#"'
    ' xmlns:rdfs="http://www.w3.org/2000/01/rdf-schema#"><owl:Ontology rdf:about="http://x/o">'
    "<rdfs:comment>&a7;</rdfs:comment></owl:Ontology></rdf:RDF>\n"
)


@pytest.fixture(autouse=True)
def _no_hang() -> Iterator[None]:
    def hang(signum: int, frame: object) -> None:
        raise TimeoutError("the command blocked (a FIFO opened for reading?)")

    previous = signal.signal(signal.SIGALRM, hang)
    signal.alarm(60)
    yield
    signal.alarm(0)
    signal.signal(signal.SIGALRM, previous)


def refused(argv: list[str], capsys: pytest.CaptureFixture[str], expected: str) -> str:
    capsys.readouterr()
    code = main(argv)
    err = capsys.readouterr().err.strip().splitlines()
    assert code not in (0, None), f"accepted: {argv}"
    assert len(err) == 1 and err[0].startswith("error: ") and expected in err[0], err
    return err[0]


@pytest.fixture(scope="module")
def dump(tmp_path_factory: pytest.TempPathFactory) -> Path:
    root = tmp_path_factory.mktemp("dump")
    chains = sample_chains(root / "good.jsonl", 5, users=1)
    assert main(["import", str(chains), "--store", str(root / "s.sqlite")]) == 0
    assert main(["export", "--store", str(root / "s.sqlite"), "--out", str(root / "all")]) == 0
    (neem,) = (root / "all").iterdir()
    return neem


def _copy(dump: Path, tmp_path: Path) -> Path:
    copy = tmp_path / "dump"
    shutil.copytree(dump, copy, symlinks=True)
    return copy


@pytest.mark.parametrize("plant", ["link-to-dev-zero", "fifo", "link-out"])
@pytest.mark.parametrize("place", ["triples/roslog/triples.metadata.json", "triples/roslog/triples.bson", "meta.json"])
def test_load_refuses_what_is_not_a_regular_file_of_the_dump(dump, tmp_path, capsys, plant, place):
    folder = _copy(dump, tmp_path)
    target = folder / place
    target.unlink()
    if plant == "fifo":
        os.mkfifo(target)
    else:
        secret = tmp_path / "secret.json"
        secret.write_text('{"name": "private"}')
        target.symlink_to("/dev/zero" if plant == "link-to-dev-zero" else secret)
    store = tmp_path / "s.sqlite"
    line = refused(["load", str(folder), "--store", str(store), "--neem", "copy"], capsys,
                   "FIFO" if plant == "fifo" else "link")
    assert str(target) in line


def test_import_settings_and_mapping_refuse_fifos_and_devices(tmp_path, capsys):
    fifo = tmp_path / "fifo"
    os.mkfifo(fifo)
    store = tmp_path / "s.sqlite"
    good = sample_chains(tmp_path / "good.jsonl", 3, users=1)
    refused(["import", str(fifo), "--store", str(store)], capsys, "a FIFO, not a regular file")
    refused(["import", "/dev/zero", "--store", str(store)], capsys, "a device, not a regular file")
    refused(["import", str(good), "--store", str(store), "--mapping", str(fifo)], capsys, "a FIFO")
    (tmp_path / "zero.yaml").symlink_to("/dev/zero")
    refused(["import", str(good), "--store", str(store), "--mapping", str(tmp_path / "zero.yaml")], capsys, "a device")
    refused(["rank", "--store", str(store), "--settings", str(fifo)], capsys, "a FIFO")
    assert not store.exists()


def test_yaml_that_is_not_utf8_or_too_large_is_one_line(tmp_path, capsys):
    store = tmp_path / "s.sqlite"
    good = sample_chains(tmp_path / "good.jsonl", 3, users=1)
    latin = tmp_path / "latin.yaml"
    latin.write_bytes(b"# caf\xe9\nnamespace: http://x/\n")
    refused(["import", str(good), "--store", str(store), "--mapping", str(latin)], capsys, "latin.yaml:1: mapping is not UTF-8")
    big = tmp_path / "big.yaml"
    big.write_bytes(b"# " + b"x" * (1 << 20) + b"\n")
    refused(["rank", "--store", str(store), "--settings", str(big)], capsys, "larger than the limit of 1048576 bytes")


def test_odb_manifests_are_not_read_through_links(tmp_path, capsys):
    odb = tmp_path / "odb"
    shutil.copytree(ROOT / "ontology" / "kitchen-odb", odb)
    first = sorted(odb.glob("*/manifest.xml"))[0]
    first.unlink()
    first.symlink_to("/dev/zero")
    refused(["ontology", "build", "--odb", str(odb), "--out", str(tmp_path / "o.owl")], capsys, "symbolic link")
    first.unlink()
    outside = tmp_path / "elsewhere"
    outside.mkdir()
    (outside / "manifest.xml").write_text("<object><name>stolen</name></object>")
    shutil.rmtree(first.parent)
    first.parent.symlink_to(outside)
    refused(["ontology", "build", "--odb", str(odb), "--out", str(tmp_path / "o.owl")], capsys, "link out of")


def test_nested_and_external_entities_are_refused_before_parsing(tmp_path, capsys):
    soma = tmp_path / "soma"
    soma.mkdir()
    (soma / "SOMA.owl").write_text(NESTED)
    refused(["ontology", "build", "--soma", str(soma), "--out", str(tmp_path / "o.owl")], capsys, "expands to")
    (soma / "SOMA.owl").write_text(NESTED.replace('<!ENTITY a0 "dododododo">', '<!ENTITY a0 SYSTEM "file:///etc/passwd">'))
    refused(["ontology", "build", "--soma", str(soma), "--out", str(tmp_path / "o.owl")], capsys, "external entity")


def test_entities_within_bounds_parse_as_before():
    # Protégé declares IRI prefixes as entities; they are used all over a file.
    doc = ('<?xml version="1.0"?><!DOCTYPE r [<!ENTITY owl "http://www.w3.org/2002/07/owl#">]><r a="&owl;Thing">'
           + '<x b="&owl;T">&owl;</x>' * 5000 + "</r>").encode()
    check_entities(doc, "doc", OntologyError)
    # the same prefixes used beyond the budget (entities that more than double the file)
    long = ('<?xml version="1.0"?><!DOCTYPE r [<!ENTITY e "' + "x" * 4000 + '">]><r>' + "&e;" * 400 + "</r>").encode()
    with pytest.raises(OntologyError, match="expand"):
        check_entities(long, "long", OntologyError)


@pytest.mark.skipif(not (SOMA / "SOMA.owl").exists(), reason="the official SOMA files are not on this machine")
def test_the_official_files_pass_the_entity_check():
    for name in ("DUL.owl", "SOMA.owl", "SOMA-HOME.owl"):
        check_entities((SOMA / name).read_bytes(), name, OntologyError)


def test_nothing_is_read_past_the_limit(tmp_path):
    big = tmp_path / "big"
    big.write_bytes(b"x" * 5000)
    with pytest.raises(OntologyError, match="larger than the limit of 4096"):
        read_handed(big, Handed("file", OntologyError), 4096)
    assert read_handed(big, Handed("file", OntologyError), 5000) == b"x" * 5000
