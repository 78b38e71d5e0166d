"""NEEM ids are openEASE's 24-hex ObjectIds with a human alias beside them; a name a user types
(id or alias) is resolved in one place, and stores with human ids keep working."""

from __future__ import annotations

import pytest

from oracle.cli import main
from oracle.errors import StoreError
from oracle.store.dump import export_neem, load_dump
from oracle.store.ids import ALIAS_KEY, check_alias, find_neem, is_object_id, new_neem_id, resolve_neem, unique_alias


def test_new_ids_are_object_ids_in_creation_order():
    ids = [new_neem_id() for _ in range(3)]
    assert all(is_object_id(i) for i in ids) and len(set(ids)) == 3
    assert not is_object_id("alice") and not is_object_id("0" * 23) and not is_object_id("A" * 24)


def test_an_id_or_an_alias_names_the_neem(store):
    hex_id = new_neem_id()
    store.create_neem(hex_id, meta={ALIAS_KEY: "alice"})
    store.create_neem("bob")  # a store from before the ids: a human id stays as it is
    assert resolve_neem(store, hex_id) == hex_id
    assert resolve_neem(store, "alice") == hex_id
    assert resolve_neem(store, "bob") == "bob"
    with pytest.raises(StoreError, match=r"no NEEM 'carol' \(neither an id nor a name"):
        resolve_neem(store, "carol")


def test_an_alias_two_neems_share_is_an_error_naming_both(store, tmp_path):
    first, second = new_neem_id(), new_neem_id()
    store.create_neem(first, meta={ALIAS_KEY: "alice"})
    store.create_neem(second, meta={ALIAS_KEY: "alice"})  # e.g. loaded from two stores
    with pytest.raises(StoreError, match=rf"'alice' is ambiguous \({first}, {second}\); give the id") as caught:
        resolve_neem(store, "alice")
    assert "\n" not in str(caught.value)
    assert resolve_neem(store, second) == second  # the id still names it


def test_an_id_wins_over_an_alias(store):
    store.create_neem("alice")
    other = new_neem_id()
    store.create_neem(other, meta={ALIAS_KEY: "alice"})
    assert find_neem(store, "alice").id == "alice"


def test_unique_alias_skips_ids_and_aliases_in_use(store):
    store.create_neem("ann")
    store.create_neem(new_neem_id(), meta={ALIAS_KEY: "ann-2"})
    assert unique_alias(store, "ann") == "ann-3"


@pytest.mark.parametrize("bad", ["", "a b", "-x", "0123456789abcdef01234567", "x" * 65, "a_b"])
def test_bad_aliases_are_refused(bad):
    with pytest.raises(StoreError, match="invalid NEEM name"):
        check_alias(bad)


def test_a_dump_keeps_its_id_and_alias(store, tmp_path):
    hex_id = new_neem_id()
    store.create_neem(hex_id, meta={ALIAS_KEY: "alice", "name": "alice"})
    export_neem(store, hex_id, tmp_path / "dump")
    store.drop_neem(hex_id)
    assert load_dump(store, tmp_path / "dump") == [hex_id]
    assert store.neem(hex_id).meta[ALIAS_KEY] == "alice"
    # --neem of an existing NEEM's alias replaces that NEEM, which keeps its id and alias
    assert load_dump(store, tmp_path / "dump", neem_id="alice", replace=True) == [hex_id]
    with pytest.raises(StoreError, match="already exists"):
        load_dump(store, tmp_path / "dump", neem_id="alice")
    (copy,) = load_dump(store, tmp_path / "dump", neem_id="alice-copy")
    assert is_object_id(copy) and copy != hex_id and resolve_neem(store, "alice-copy") == copy


def test_cli_reading_commands_take_the_alias_or_the_id(tmp_path, capsys):
    from oracle.store.sqlite import SQLiteStore

    db = tmp_path / "s.sqlite"
    with SQLiteStore(db) as store:
        first, second = new_neem_id(), new_neem_id()
        store.create_neem(first, meta={ALIAS_KEY: "alice"})
        store.create_neem(second, meta={ALIAS_KEY: "alice"})
    for name, expected in (("alice", "is ambiguous"), ("nobody", "no NEEM 'nobody'")):
        assert main(["export", "--store", str(db), "--neem", name, "--out", str(tmp_path / "d")]) == 1
        err = capsys.readouterr().err
        assert expected in err and len(err.strip().splitlines()) == 1
    assert main(["export", "--store", str(db), "--neem", second, "--out", str(tmp_path / "d")]) == 0
    assert capsys.readouterr().out.startswith(f"{second}: ")


def test_two_builders_that_picked_one_name_do_not_both_land(store):
    first = store.create_staging(new_neem_id(), meta={ALIAS_KEY: "alice"})
    second_target = new_neem_id()
    second = store.create_staging(second_target, meta={ALIAS_KEY: "alice"})
    store.swap_in(first, store.neem(first).meta["staging_for"])
    with pytest.raises(StoreError, match="the name 'alice' is taken by NEEM"):
        store.swap_in(second, second_target, replace=False)
    assert [alias for alias in (i.meta.get(ALIAS_KEY) for i in store.neems())] == ["alice"]


def test_a_dump_with_a_bad_name_is_refused_and_changes_nothing(store, tmp_path):
    import json

    hex_id = new_neem_id()
    store.create_neem(hex_id, meta={ALIAS_KEY: "alice"})
    export_neem(store, hex_id, tmp_path / "dump")
    meta = json.loads((tmp_path / "dump" / "meta.json").read_text())
    (tmp_path / "dump" / "meta.json").write_text(json.dumps({**meta, ALIAS_KEY: "a b"}))
    store.drop_neem(hex_id)
    with pytest.raises(StoreError, match=r"meta\.json: invalid NEEM name 'a b'"):
        load_dump(store, tmp_path / "dump")
    assert store.neems() == [] and store.staging_neems() == []
