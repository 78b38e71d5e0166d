"""The built-ontology cache: a changed input makes a new build, a damaged entry is rebuilt,
entries are private to the user."""

from __future__ import annotations

import shutil
import stat

from oracle.ontology import build_with_report
from oracle.ontology.inputs import DEFAULT_MAPPING, DEFAULT_ODB


def _entries(cache):
    return sorted(cache.glob("ontology-*.json"))


def _copy_inputs(tmp_path):
    odb = tmp_path / "odb"
    shutil.copytree(DEFAULT_ODB, odb)
    mapping = tmp_path / "mapping.yaml"
    shutil.copy(DEFAULT_MAPPING, mapping)
    return odb, mapping


def test_a_second_build_is_the_cached_one_and_equal(tmp_path):
    cache = tmp_path / "cache"
    odb, mapping = _copy_inputs(tmp_path)
    first, report = build_with_report(odb, mapping, cache_dir=cache)
    (entry,) = _entries(cache)
    again, again_report = build_with_report(odb, mapping, cache_dir=cache)
    assert _entries(cache) == [entry]
    assert again is not first and again_report == report
    assert set(again.graph) == set(first.graph) and again.tasks == first.tasks and again.objects == first.objects
    assert again.source == first.source and again.cache_dir == cache
    assert again.prefixes == first.prefixes and again.labels == first.labels
    assert again.taxonomy.parent_table() == first.taxonomy.parent_table()
    assert all(again.taxonomy.ancestors(c) == first.taxonomy.ancestors(c) for c in first.taxonomy.classes)


def test_an_entry_is_json_and_a_tagged_one_of_the_wrong_shape_is_rebuilt(tmp_path):
    """The entry is plain JSON behind its tag; an entry that verifies under the user's key but whose
    parts are not what the cache writes (a class where a text belongs) is built again, not used."""
    import json

    from oracle.files import TAG_BYTES, signed, user_key

    cache = tmp_path / "cache"
    odb, mapping = _copy_inputs(tmp_path)
    good, _ = build_with_report(odb, mapping, cache_dir=cache)
    (entry,) = _entries(cache)
    data = json.loads(entry.read_bytes()[TAG_BYTES:])
    assert set(data) == {"key", "value"} and data["value"]["namespace"] == good.namespace
    for part, wrong in (("objects", [[{"py/object": "os.system"}, "x", [], [], False]]), ("taxonomy", ["not a mapping"]),
                        ("graph", {"prefixes": [], "triples": [[["x", "y"], "p", "o"]]})):
        spoiled = {**data, "value": {**data["value"], part: wrong}}
        entry.write_bytes(signed(user_key(cache), json.dumps(spoiled).encode()))
        rebuilt, _ = build_with_report(odb, mapping, cache_dir=cache)
        assert rebuilt.objects == good.objects and len(rebuilt.graph) == len(good.graph), part


def test_a_changed_input_is_built_again_never_read_stale(tmp_path):
    cache = tmp_path / "cache"
    odb, mapping = _copy_inputs(tmp_path)
    before, _ = build_with_report(odb, mapping, cache_dir=cache)
    gone = next(name for name, obj in sorted(before.objects.items()) if not obj.abstract and not
                any(name in o.parents for o in before.objects.values()))  # fmt: skip  (a leaf)
    shutil.rmtree(odb / gone)
    after, _ = build_with_report(odb, mapping, cache_dir=cache)
    assert gone in before.objects and gone not in after.objects
    assert len(_entries(cache)) == 2
    mapping.write_text(mapping.read_text() + "\n# an edit\n")
    build_with_report(odb, mapping, cache_dir=cache)
    assert len(_entries(cache)) == 3


def test_a_damaged_entry_is_rebuilt_not_fatal(tmp_path):
    cache = tmp_path / "cache"
    odb, mapping = _copy_inputs(tmp_path)
    good, _ = build_with_report(odb, mapping, cache_dir=cache)
    (entry,) = _entries(cache)
    for damage in (b"not an entry", entry.read_bytes()[:1000], b""):
        entry.write_bytes(damage)
        rebuilt, _ = build_with_report(odb, mapping, cache_dir=cache)
        assert len(rebuilt.graph) == len(good.graph) and rebuilt.tasks == good.tasks  # fresh blank nodes
        assert entry.stat().st_size > 1000  # written again, whole


def test_entries_are_private_and_a_foreign_writable_one_is_not_loaded(tmp_path):
    cache = tmp_path / "cache"
    odb, mapping = _copy_inputs(tmp_path)
    build_with_report(odb, mapping, cache_dir=cache)
    (entry,) = _entries(cache)
    assert stat.S_IMODE(entry.stat().st_mode) == 0o600
    assert stat.S_IMODE(cache.stat().st_mode) == 0o700
    entry.chmod(0o666)  # anyone could have replaced it: it is rebuilt, not read
    entry.write_bytes(b"\x80\x05anything")
    rebuilt, _ = build_with_report(odb, mapping, cache_dir=cache)
    assert rebuilt.tasks and stat.S_IMODE(entry.stat().st_mode) == 0o600


def test_a_cached_build_loads_without_rdflib_until_its_graph_is_used(tmp_path):
    import subprocess
    import sys

    cache = tmp_path / "cache"
    odb, mapping = _copy_inputs(tmp_path)
    build_with_report(odb, mapping, cache_dir=cache)
    probe = (
        "import sys\n"
        "from oracle.ontology import build_ontology\n"
        f"onto = build_ontology({str(odb)!r}, {str(mapping)!r}, cache_dir=__import__('pathlib').Path({str(cache)!r}))\n"
        "before = 'rdflib' in sys.modules\n"
        "names = onto.name(onto.task_iri('pick')), onto.name('http://www.ease-crc.org/ont/SOMA.owl#PhysicalTask')\n"
        "distances = onto.distances().classes[:1]\n"
        "still = 'rdflib' in sys.modules\n"
        "triples = len(onto.graph)\n"
        "print(before, still, 'rdflib' in sys.modules, names, triples > 0)\n"
    )
    out = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, check=True).stdout.split()
    assert out[:3] == ["False", "False", "True"] and out[-1] == "True"
    assert "soma:PhysicalTask" in " ".join(out)
