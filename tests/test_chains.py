import json

import pytest
from hypothesis import given
from hypothesis import strategies as st

from oracle.chains import ChainRow, TaskCall, parse_call, read_chains, write_chains
from oracle.errors import ChainSyntaxError

names = st.from_regex(r"[a-z_][a-z0-9_]{0,10}", fullmatch=True)


def test_parse_two_objects():
    assert parse_call("pour(thermos, green_mug)") == TaskCall("pour", ("thermos", "green_mug"))


def test_parse_bare_task():
    assert parse_call("idle") == TaskCall("idle", ())


@pytest.mark.parametrize(
    "text", ["pour(", "pour()", "pour(a,,b)", "pour(a, b, c)", "(a)", "pick(red mug)", "", "pick(a'b)"]
)
def test_malformed_actions_are_rejected(text):
    with pytest.raises(ChainSyntaxError, match="malformed action"):
        parse_call(text)


@given(names, st.lists(names, max_size=2))
def test_format_parse_round_trip(task, args):
    call = TaskCall(task, tuple(args))
    assert parse_call(str(call)) == call


def test_jsonl_round_trip(tmp_path):
    path = tmp_path / "c.jsonl"
    path.write_text(
        json.dumps({"user": "u", "time": "2026-01-01T08:00:00", "action": "pick(a)", "available": ["pick(a)", "open(d)"]})
        + "\n\n# comment\n"
        + json.dumps({"user": "u", "action": "place(a)"})
        + "\n"
    )
    rows = list(read_chains(path))
    assert [str(r.action) for r in rows] == ["pick(a)", "place(a)"]
    assert rows[0].available == (TaskCall("pick", ("a",)), TaskCall("open", ("d",)))
    assert rows[1].time is None and rows[1].available is None
    out = tmp_path / "o.jsonl"
    assert write_chains(rows, out) == 2
    assert [r.action for r in read_chains(out)] == [r.action for r in rows]


def test_bad_line_names_file_and_line(tmp_path):
    path = tmp_path / "c.jsonl"
    path.write_text('{"user": "u", "action": "pick(a)"}\n{"user": "u", "action": "pick(a"}\n')
    with pytest.raises(ChainSyntaxError, match=r"c\.jsonl:2: malformed action"):
        list(read_chains(path))


def test_row_to_json_keeps_fields():
    row = ChainRow("u", TaskCall("pick", ("a",)))
    assert row.to_json() == {"user": "u", "action": "pick(a)"}


def test_end_and_duration(tmp_path):
    path = tmp_path / "c.jsonl"
    path.write_text(
        '{"user": "u", "time": "2026-01-01T08:00:00", "duration": 12.5, "action": "pick(a)"}\n'
        '{"user": "u", "time": "2026-01-01T08:01:00", "end": "2026-01-01T08:01:30", "action": "place(a)"}\n'
    )
    first, second = read_chains(path)
    assert (first.end - first.time).total_seconds() == 12.5 and (second.end - second.time).total_seconds() == 30
    assert second.to_json()["end"] == "2026-01-01T08:01:30"


@pytest.mark.parametrize(
    "row, message",
    [
        ('{"user": "u", "time": "2026-01-01T08:00:00", "end": "2026-01-01T07:00:00", "action": "a"}', "'end' must not be before"),
        ('{"user": "u", "duration": 3, "action": "a"}', "'duration' needs a 'time'"),
        ('{"user": "u", "time": "2026-01-01T08:00:00", "duration": -1, "action": "a"}', "'duration' must be a number"),
    ],
)
def test_bad_end_or_duration(tmp_path, row, message):
    path = tmp_path / "c.jsonl"
    path.write_text(row + "\n")
    with pytest.raises(ChainSyntaxError, match=message):
        list(read_chains(path))
