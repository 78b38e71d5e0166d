"""Importing chains: an action's end decides whether the pause after it is an odb:IdleTask."""

import json

from oracle.neem.importing import import_chains
from oracle.neem.query import executed_actions
from oracle.ontology import build_ontology
from oracle.store import open_store


def test_idle_follows_ends_not_starts(tmp_path):
    rows = [
        {"user": "u", "time": "2026-01-01T08:00:00", "duration": 40, "action": "pick(red_mug)"},
        {"user": "u", "time": "2026-01-01T08:00:45", "duration": 5, "action": "place(red_mug, counter_top)"},
        {"user": "u", "time": "2026-01-01T08:05:00", "action": "pick(apple)"},
    ]
    chains = tmp_path / "c.jsonl"
    chains.write_text("".join(json.dumps(r) + "\n" for r in rows))
    store = open_store(tmp_path / "s.sqlite")
    onto = build_ontology()
    report = import_chains(store, onto, chains)
    (neem,) = report
    idle = [a for a in executed_actions(store, neem) if a.task_class == onto.vocab.idle_task]
    # 45 s between the starts of the first two, but only 5 s of pause: one idle period, before pick(apple)
    assert len(idle) == 1
    assert idle[0].end - idle[0].begin == 250.0  # from the end of place (08:00:50) to 08:05:00


def test_the_second_pass_logs_the_rows_the_first_kept_and_reads_a_long_file_again(tmp_path, monkeypatch):
    import pytest

    from oracle.errors import ChainSyntaxError
    from oracle.neem import importing

    rows = [{"user": "u", "time": f"2026-01-01T08:0{i}:00", "action": "pick(red_mug)"} for i in range(3)]
    onto = build_ontology()

    def checked_then_gone(name):
        chains = tmp_path / f"{name}.jsonl"
        chains.write_text("".join(json.dumps(r) + "\n" for r in rows))
        checked = importing.check_chains(onto, chains)
        chains.unlink()   # the second pass must not need the file ...
        return chains, checked

    chains, checked = checked_then_gone("kept")
    assert checked.rows is not None and [r.line for r in checked.rows] == [1, 2, 3]
    with open_store(tmp_path / "kept.sqlite") as store:
        (neem,) = import_chains(store, onto, chains, checked=checked)
        assert sum(a.task_class != onto.vocab.idle_task for a in executed_actions(store, neem)) == 3
    monkeypatch.setattr(importing, "KEPT_ROWS", 2)   # ... unless it was longer than the rows kept
    chains, checked = checked_then_gone("long")
    assert checked.rows is None and checked.plans["u"].rows == 3
    with open_store(tmp_path / "long.sqlite") as store, pytest.raises(ChainSyntaxError, match="cannot read"):
        import_chains(store, onto, chains, checked=checked)


def test_an_available_set_is_checked_where_it_first_appears_and_a_changed_one_again(tmp_path):
    import pytest

    from oracle.errors import LoggingError
    from oracle.neem.importing import check_chains

    good = ["pick(red_mug)", "pick(apple)"]
    rows = [{"user": "u", "time": f"2026-01-01T08:0{i}:00", "action": "pick(red_mug)", "available": good}
            for i in range(3)]
    onto = build_ontology()
    chains = tmp_path / "c.jsonl"
    chains.write_text("".join(json.dumps(r) + "\n" for r in rows))
    checked = check_chains(onto, chains)   # rows 1-3 share one set: checked once, all good
    assert checked.plans["u"].rows == 3
    # the same set again on line 4, then a set with an unknown object on line 5: the error names line 5
    rows += [dict(rows[0], time="2026-01-01T08:04:00"),
             dict(rows[0], time="2026-01-01T08:05:00", available=[*good, "pick(no_such_thing)"])]
    chains.write_text("".join(json.dumps(r) + "\n" for r in rows))
    with pytest.raises(LoggingError, match=r"c\.jsonl:5: .*no_such_thing"):
        check_chains(onto, chains)
    with open_store(tmp_path / "s.sqlite") as store:
        with pytest.raises(LoggingError, match=r":5: "):
            import_chains(store, onto, chains)
        assert store.neems() == []   # nothing written before the bad row was found
