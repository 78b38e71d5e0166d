"""Write the bad-input corpus (tests/corpus/<entry>/) from the compact tables below.

Run ``python tests/corpus/generate.py`` after editing a table; the files it writes are committed,
so a reader sees every input as the file a user would pass. Each entry folder has ``cases.tsv``:
one line per input, ``file<TAB>extra arguments<TAB>expected fragment of the one-line error``.
Inputs too large or too structured for a file (a 1,200-deep odb, /dev/zero) are built at test
time by ``built.py``.
"""

from __future__ import annotations

import json
import shlex
import shutil
import struct
from pathlib import Path
from typing import Any

HERE = Path(__file__).resolve().parent
GOOD = {"user": "alice", "time": "2025-03-03T08:00:00", "action": "open(fridge)"}


def row(**changes: Any) -> str:
    """The good row with fields changed (a value of ... removes the field)."""
    obj = {k: v for k, v in {**GOOD, **changes}.items() if v is not ...}
    return json.dumps(obj, ensure_ascii=False, allow_nan=True)


def raw_row(fragment: str) -> str:
    """A row whose ``duration`` (or other field) is spelled literally, e.g. an integer JSON can hold."""
    return '{"user": "alice", "time": "2025-03-03T08:00:00", "action": "open(fridge)", ' + fragment + "}"


# -- import: chains JSONL rows ------------------------------------------------------------------
# (name, file content (str or bytes), extra args, expected fragment)
IMPORT: list[tuple[str, str | bytes, str, str]] = []


def imp(name: str, content: str | bytes, expected: str, args: str = "") -> None:
    if isinstance(content, str) and not content.endswith("\n"):
        content += "\n"
    IMPORT.append((name, content, args, expected))


for name, text in [
    ("open-brace", "{"), ("close-brace", "}"), ("array", "[1, 2]"), ("string", '"alice"'), ("number", "42"),
    ("null", "null"), ("true", "true"), ("missing-value", '{"user": }'), ("single-quotes", "{'user': 'alice'}"),
    ("trailing-comma", '{"user": "alice",}'), ("bare-nan", "NaN"), ("unquoted-key", "{user: 1}"),
    ("two-objects", row() + " " + row()), ("truncated-row", row()[:30]), ("comment-after", row() + " // note"),
    ("python-dict", "{'user': 'alice', 'time': None}"), ("yaml-row", "user: alice"), ("xml-row", "<row/>"),
    ("bare-word", "alice"), ("backslash", '{"user": "a\\q"}'), ("control-char", '{"user": "a\tb"}'.replace("\\t", "\t")),
    ("empty-object", "{}"), ("nested-array", "[[[]]]"), ("deep-brackets", "[" * 100000),
    ("deep-braces", '{"a":' * 50000), ("deep-available", row()[:-1] + ', "available": ' + "[" * 60000 + "]" * 60000 + "}"),
]:
    imp(f"json-{name}", text, ":1: " if name != "empty-object" else "'user' must be a non-empty string")

for name, data, where in [
    ("latin1-user", b'{"user": "caf\xe9", "time": "2025-03-03T08:00:00", "action": "open(fridge)"}\n', ":1: "),
    ("ff-start", b"\xff" + row().encode() + b"\n", ":1: "),
    ("lone-continuation", row().encode()[:-1] + b', "x": "\x80"}\n', ":1: "),
    ("truncated-sequence", row().encode()[:-1] + b', "x": "\xc3"}\n', ":1: "),
    ("overlong-slash", row().encode()[:-1] + b', "x": "\xc0\xaf"}\n', ":1: "),
    ("surrogate-bytes", row().encode()[:-1] + b', "x": "\xed\xa0\x80"}\n', ":1: "),
    ("utf16-file", (row() + "\n").encode("utf-16"), ":1: "),
    ("bad-third-line", (row() + "\n" + row(time="2025-03-03T08:01:00") + "\n").encode() + b'{"user": "\xfe"}\n', ":3: "),
    ("bad-after-200", "".join(row(time=f"2025-03-03T{8 + i // 60:02d}:{i % 60:02d}:00") + "\n" for i in range(200)).encode() + b"\xff\n", ":201: "),
    ("nul-byte", row().encode()[:-1] + b', "x": "\x00"}\n', ":1: "),
    ("nul-line", b"\x00\x00\x00\x00\n", ":1: "),
    ("binary-garbage", bytes(range(256)) * 4, ":1: "),
    ("utf8-bom", b"\xef\xbb\xbf" + row().encode() + b"\n", ":1: "),
    ("cr-only-lines", (row() + "\r" + row(time="2025-03-03T08:01:00") + "\r").encode(), ":1: "),
]:
    imp(f"bytes-{name}", data, where)

imp("empty-file", "", "no rows")
IMPORT[-1] = ("empty-file", "", "", "no rows")
imp("only-comments", "# a comment\n# another\n", "no rows")
imp("only-blank-lines", "\n\n   \n\t\n", "no rows")

for name, value, expected in [
    ("missing", ..., "'user' must be a non-empty string"), ("null", None, "'user' must be a non-empty string"),
    ("empty", "", "'user' must be a non-empty string"), ("number", 5, "'user' must be a non-empty string"),
    ("list", ["alice"], "'user' must be a non-empty string"), ("object", {"$ne": ""}, "'user' must be a non-empty string"),
    ("true", True, "'user' must be a non-empty string"), ("blank", "   ", "'user'"), ("tab", "\t", "'user'"),
    ("newline", "ali\nce", "'user'"), ("nul", "ali\u0000ce", "'user'"), ("bell", "\u0007", "'user'"),
    ("escape-seq", "\u001b[31mred", "'user'"), ("delete", "ali\u007fce", "'user'"), ("too-long", "a" * 300, "'user'"),
    ("bidi-override", "\u202ealice", "'user'"), ("zero-width-only", "\u200b", "'user'"),
]:
    imp(f"user-{name}", row(user=value), expected)
for name, escape in [("lone-high-surrogate", "\\ud800"), ("lone-low-surrogate", "\\udfff"),
                     ("reversed-pair", "\\udc00\\ud800"), ("surrogate-in-name", "al\\ud83dice")]:
    imp(f"user-{name}", '{"user": "' + escape + '", "time": "2025-03-03T08:00:00", "action": "open(fridge)"}', "'user'")

for name, value, expected in [
    ("missing", ..., "'time' is required"), ("null", None, "'time' is required"), ("number", 1741000000, "ISO-8601"),
    ("empty", "", "ISO-8601"), ("word", "abc", "ISO-8601"), ("now", "now", "ISO-8601"), ("month-13", "2025-13-01T00:00:00", "ISO-8601"),
    ("feb-30", "2025-02-30T08:00:00", "ISO-8601"), ("hour-25", "2025-03-03T25:00:00", "ISO-8601"),
    ("minute-61", "2025-03-03T08:61:00", "ISO-8601"), ("offset-25h", "2025-03-03T08:00:00+25:00", "ISO-8601"),
    ("zone-name", "2025-03-03T08:00:00 Europe/Berlin", "ISO-8601"), ("list", ["2025-03-03"], "ISO-8601"),
    ("object", {"$date": "2025-03-03"}, "ISO-8601"), ("true", True, "ISO-8601"), ("max-minus-12", "9999-12-31T23:59:59-12:00", "between"),
    ("min-plus-5", "0001-01-01T00:00:00+05:00", "between"), ("year-1", "0001-01-01T00:00:00", "between"),
    ("year-9999", "9999-12-31T23:59:59", "between"), ("before-1970", "1969-12-31T23:59:59Z", "between"),
    ("year-1900", "1900-01-01T00:00:00", "between"), ("year-10000", "10000-01-01T00:00:00", "ISO-8601"),
    ("negative-year", "-0001-01-01T00:00:00", "ISO-8601"), ("fullwidth-digits", "２０２５-03-03T08:00:00", "ISO-8601"),
    ("time-only", "08:00:00", "ISO-8601"), ("unix-string", "1741000000", "ISO-8601"),
]:
    imp(f"time-{name}", row(time=value), expected)

for name, value, expected in [
    ("word", "abc", "ISO-8601"), ("number", 5, "ISO-8601"), ("before-time", "2025-03-03T07:59:59", "'end' must not be before"),
    ("far-future", "9999-12-31T23:59:59-12:00", "between"), ("year-1", "0001-01-01T00:00:00+05:00", "between"),
    ("empty", "", "ISO-8601"), ("list", [], "ISO-8601"),
]:
    imp(f"end-{name}", row(end=value), expected)
imp("end-without-time", row(time=..., end="2025-03-03T08:00:00"), "'end' must not be before 'time'")
imp("end-and-duration", row(end="2025-03-03T08:00:05", duration=5), "not both")

for name, value, expected in [
    ("negative", -1, "'duration'"), ("negative-zero-ish", -1e-9, "'duration'"), ("string", "5", "'duration'"),
    ("true", True, "'duration'"), ("list", [5], "'duration'"), ("object", {"s": 5}, "'duration'"),
    ("1e308", 1e308, "'duration'"), ("year-of-seconds-x1e6", 3.2e13, "'duration'"),
]:
    imp(f"duration-{name}", row(duration=value), expected)
for name, literal in [("nan", "NaN"), ("infinity", "Infinity"), ("minus-infinity", "-Infinity"),
                      ("10-pow-400", "1" + "0" * 400), ("1e400", "1e400"), ("minus-1e400", "-1e400")]:
    imp(f"duration-{name}", raw_row(f'"duration": {literal}'), "'duration'")
imp("duration-without-time", row(time=..., duration=5), "'duration' needs a 'time'")

for name, value, expected in [
    ("missing", ..., "missing 'action'"), ("null", None, "action must be a string"), ("number", 5, "action must be a string"),
    ("list", ["pick(red_mug)"], "action must be a string"), ("object", {"task": "pick"}, "action must be a string"),
    ("empty", "", "malformed action"), ("open-paren", "pour(", "malformed action"), ("empty-args", "pour()", "empty argument list"),
    ("double-comma", "pour(thermos,,green_mug)", "bad object name"), ("three-args", "pour(thermos, green_mug, plate)", "at most two objects"),
    ("no-task", "(red_mug)", "malformed action"), ("space-in-object", "pick(red mug)", "bad object name"),
    ("quote", "pick(red'mug)", "bad object name"), ("unclosed", "pick(red_mug", "malformed action"),
    ("extra-close", "pick(red_mug))", "bad object name"), ("prolog-injection", "pick(red_mug)), halt, (true", "malformed action"),
    ("unknown-task", "juggle(red_mug)", "unknown task 'juggle'"), ("unknown-object", "pick(unicorn)", "unknown object 'unicorn'"),
    ("unknown-second-object", "pour(thermos, unicorn)", "unknown object 'unicorn'"), ("accented-task", "pïck(red_mug)", "malformed action"),
    ("digit-task", "1pick(red_mug)", "malformed action"), ("variable-object", "pick(X)", "unknown object 'X'"),
    ("long-task", "p" * 5000 + "(red_mug)", "unknown task"), ("nul-in-action", "pick(red_mug)\u0000", "malformed action"),
    ("newline-in-action", "pick(red_mug)\nopen(fridge)", "malformed action"),
    ("dollar-where", "$where", "malformed action"), ("sql-quote", "pick(red_mug'); DROP TABLE neems; --", "malformed action"),
    ("iri-task", "http://x/y(red_mug)", "malformed action"), ("colon-object", "pick(odb:red_mug)", "bad object name"),
]:
    imp(f"action-{name}", row(action=value), expected)
for name, value, expected in [
    ("string", "pick(red_mug)", "'available' must be a list"), ("number", 5, "'available' must be a list"),
    ("object", {"pick": "red_mug"}, "'available' must be a list"), ("number-item", [5], "action must be a string"),
    ("null-item", [None], "action must be a string"), ("bad-item", ["pour("], "malformed action"),
    ("unknown-task-item", ["juggle(red_mug)"], "unknown task 'juggle'"), ("unknown-object-item", ["pick(unicorn)"], "unknown object 'unicorn'"),
    ("nested-list", [["pick(red_mug)"]], "action must be a string"), ("empty-string-item", [""], "malformed action"),
    ("good-then-bad", ["pick(red_mug)", "open(fridge)", "close("], "malformed action"),
]:
    imp(f"available-{name}", row(available=value), expected)
for name, changes, expected in [
    ("id-object", {"id": {"$where": "1"}}, "'id'"), ("id-list", {"id": [1]}, "'id'"), ("id-empty", {"id": ""}, "'id'"),
    ("id-null-byte", {"id": "a\u0000"}, "'id'"), ("id-bool", {"id": True}, "'id'"), ("id-float-nan", {"id": float("nan")}, "'id'"),
    ("id-too-long", {"id": "x" * 300}, "'id'"),
    ("performed-by-alien", {"performed_by": "alien"}, "performed_by must be one of robot, user, together"),
    ("performed-by-number", {"performed_by": 5}, "performed_by must be one of robot, user, together"),
    ("performed-by-null", {"performed_by": None}, "performed_by must be one of robot, user, together"),
    ("performed-by-list", {"performed_by": ["robot"]}, "performed_by must be one of robot, user, together"),
    ("performed-by-upper", {"performed_by": "ROBOT"}, "performed_by must be one of robot, user, together"),
]:
    imp(f"field-{name}", row(**changes), expected)

later = lambda minutes: f"2025-03-03T08:{minutes:02d}:00"  # noqa: E731
for name, lines, expected in [
    ("duplicate-id", [row(id="x1"), row(id="x1", time=later(1))], "duplicate action id 'x1'"),
    ("duplicate-id-far", [row(id="x1")] + [row(time=later(i)) for i in range(1, 10)] + [row(id="x1", time=later(20))], "duplicate action id"),
    ("duplicate-numeric-id", [row(id=7), row(id=7, time=later(1))], "duplicate action id"),
    ("time-backwards", [row(time=later(5)), row(time=later(1))], "time goes backwards"),
    ("time-backwards-overlapping", [row(time=later(5), end=later(9)), row(time=later(3))], "time goes backwards"),
    ("bad-row-after-good", [row(time=later(i)) for i in range(5)] + [row(action="juggle(x)", time=later(9))], ":6: "),
    ("bad-second-user", [row(), row(user="bob"), row(user="bob", time=later(1), action="pick(unicorn)")], ":3: "),
    ("bad-last-of-many", [row(time=later(i)) for i in range(40)] + ["{"], ":41: "),
    ("bad-json-in-middle", [row(), "{", row(time=later(1))], ":2: "),
    ("unknown-object-first", [row(action="pick(unicorn)"), row(time=later(1))], ":1: "),
    ("backwards-other-user-ok", [row(), row(user="bob", time=later(9)), row(user="bob", time=later(2))], ":3: "),
]:
    imp(f"rows-{name}", "\n".join(lines), expected)

for name, args, expected in [
    ("commit-every-0", "--commit-every 0", "--commit-every"), ("commit-every-negative", "--commit-every=-5", "--commit-every"),
    ("commit-every-word", "--commit-every many", "--commit-every"), ("commit-every-float", "--commit-every 1.5", "--commit-every"),
    ("commit-every-huge", "--commit-every " + "9" * 40, "--commit-every"),
]:
    IMPORT.append((f"args-{name}", row() + "\n", args, expected))
for name, args in [("replace-bad-first-row", "--replace"), ("session-bad-first-row", "--session"),
                   ("commit-every-1-bad-row", "--commit-every 1")]:
    IMPORT.append((f"args-{name}", row(user="p000-tea-red-yogurt", action="pick(unicorn)") + "\n", args, "unknown object 'unicorn'"))
IMPORT.append(("args-replace-bad-late-row", "\n".join(
    [row(user="p000-tea-red-yogurt", time=later(i)) for i in range(3)] + [row(user="p000-tea-red-yogurt", action="juggle(x)", time=later(5))]) + "\n",
    "--replace", ":4: "))
IMPORT.append(("args-replace-duplicate-ids", "\n".join(
    [row(user="p000-tea-red-yogurt", id="a"), row(user="p000-tea-red-yogurt", id="a", time=later(1))]) + "\n",
    "--replace --commit-every 1", "duplicate action id"))


# -- settings YAML (rank --settings) --------------------------------------------------------------
SETTINGS: list[tuple[str, str, str, str]] = []
PARAMS = ("object_factor", "task_factor", "knockout", "penalty", "event_horizon_backwards",
          "decreasing_importance_factor", "compare_situations", "time_of_day_penalty",
          "event_horizon_forward", "multiple_occurrences_factor")
for param in PARAMS:
    for name, literal, expected in [
        ("nan", ".nan", "finite"), ("inf", ".inf", "finite"), ("minus-inf", "-.inf", param), ("negative", "-1", param),
        ("string", "'high'", "must be a number"), ("bool", "true", "must be a number"), ("null", "null", "must be a number"),
        ("list", "[1, 2]", "must be a number"), ("400-digits", "1" + "0" * 400, param), ("1e300", "1.0e+300", param),
    ]:
        SETTINGS.append((f"{param.replace('_', '-')}-{name}", f"{param}: {literal}\n", "", expected))
for name, text, expected in [
    ("horizon-10-million", "event_horizon_backwards: 10000000\n", "event_horizon_backwards"),
    ("horizon-fraction", "event_horizon_backwards: 2.5\n", "whole number"), ("forward-fraction", "event_horizon_forward: 0.5\n", "whole number"),
    ("forward-10-million", "event_horizon_forward: 10000000\n", "event_horizon_forward"),
    ("decreasing-zero", "decreasing_importance_factor: 0\n", "(0, 1]"), ("decreasing-above-one", "decreasing_importance_factor: 1.5\n", "(0, 1]"),
    ("knockout-huge", "knockout: 1.0e+12\n", "knockout"), ("penalty-huge", "penalty: 1.0e+12\n", "penalty"),
    ("unknown-key", "knockut: 1.2\n", "unknown hyperparameter"), ("unknown-preset", "preset: Z\n", "unknown preset"),
    ("preset-list", "preset: [A]\n", "unknown preset"), ("top-list", "- knockout: 1\n", "expected a mapping"),
    ("top-string", "recommended\n", "expected a mapping"), ("top-number", "42\n", "expected a mapping"),
    ("bad-yaml", "knockout: [1,\n", "malformed YAML"), ("tab-indent", "knockout:\n\t1\n", "malformed YAML"),
    ("duplicate-anchor-bomb", "a: &a [1,1,1,1,1,1,1,1,1]\nb: &b [*a,*a,*a,*a,*a,*a,*a,*a,*a]\nc: &c [*b,*b,*b,*b,*b,*b,*b,*b,*b]\nd: [*c,*c,*c,*c,*c,*c,*c,*c,*c]\n", "unknown hyperparameter"),
    ("python-tag", "knockout: !!python/object/apply:os.system ['true']\n", "malformed YAML"),
    ("binary-file", "\x00\x01\x02", "settings"), ("key-is-number", "5: 1.0\n", "unknown hyperparameter"),
    ("key-is-list", "? [a, b]\n: 1\n", "malformed YAML"), ("nested-value", "knockout: {value: 1}\n", "must be a number"),
    ("date-value", "knockout: 2025-03-03\n", "must be a number"), ("deep-nesting", "knockout: " + "[" * 5000 + "]" * 5000 + "\n", "settings"),
]:
    SETTINGS.append((name, text, "", expected))

# -- mapping YAML (import --mapping) --------------------------------------------------------------
MAPPING: list[tuple[str, str, str, str]] = []
for name, text, expected in [
    ("top-list", "- a\n", "expected a mapping at the top level"), ("top-string", "hello\n", "expected a mapping at the top level"),
    ("empty", "", "expected a mapping at the top level"), ("unknown-key", "namespaces: x\n", "unknown key(s)"),
    ("bad-yaml", "actions: [\n", "malformed YAML"), ("python-tag", "actions: !!python/name:os.system\n", "malformed YAML"),
    ("namespace-space", "namespace: http://a b/c\n", "'namespace'"), ("namespace-relative", "namespace: odb\n", "'namespace'"),
    ("namespace-number", "namespace: 5\n", "'namespace'"), ("namespace-quote", "namespace: 'http://x/\"y'\n", "'namespace'"),
    ("namespace-angle", "namespace: http://x/<y>\n", "'namespace'"), ("namespace-newline", "namespace: \"http://x/\\ny\"\n", "'namespace'"),
    ("namespace-empty-host", "namespace: 'http://'\n", "'namespace'"), ("namespace-javascript", "namespace: 'javascript:alert(1)'\n", "'namespace'"),
    ("imports-list", "imports: [soma]\n", "'imports' must map"), ("imports-not-iri", "imports:\n  x: notaniri\n", "is not an IRI"),
    ("imports-number", "imports:\n  x: 5\n", "is not an IRI"), ("imports-space", "imports:\n  x: http://a b/\n", "imports.x"),
    ("imports-bad-prefix", "imports:\n  'a b': http://x/\n", "prefix"), ("imports-numeric-prefix", "imports:\n  5: http://x/\n", "prefix"),
    ("map-list", "soma_odb_map: [a]\n", "'soma_odb_map' must map"), ("map-number-class", "soma_odb_map:\n  _mug: 5\n", "expected a class"),
    ("map-unknown-prefix", "soma_odb_map:\n  _mug: foo:Cup\n", "unknown prefix 'foo'"), ("map-no-prefix", "soma_odb_map:\n  _mug: Cup\n", "not a prefixed name"),
    ("map-empty-local", "soma_odb_map:\n  _mug: 'soma:'\n", "empty local name"), ("map-iri-space", "soma_odb_map:\n  _mug: 'http://x/a b c'\n", "soma_odb_map._mug"),
    ("map-not-in-tbox", "soma_odb_map:\n  _mug: soma:NoSuchClass\n", "NoSuchClass"), ("map-null", "soma_odb_map:\n  _mug: null\n", "expected a class"),
    ("map-key-number", "soma_odb_map:\n  5: soma:Cup\n", "soma_odb_map"),
    ("root-number", "root_object: 5\n", "'root_object'"), ("root-list", "root_object: [dul:Object]\n", "'root_object'"),
    ("root-unknown-prefix", "root_object: foo:Object\n", "unknown prefix"), ("root-not-in-tbox", "root_object: dul:Nothing\n", "dul:Nothing" if False else "Nothing"),
    ("defaults-list", "action_defaults: [a]\n", "action_defaults"), ("defaults-parent", "action_defaults:\n  parent: pick\n", "unknown key(s)"),
    ("defaults-task-number", "action_defaults:\n  task: 5\n", "action_defaults.task"), ("defaults-role-number", "action_defaults:\n  ref_role: 5\n", "expected a class"),
    ("defaults-role-true", "action_defaults:\n  ref_role: true\n", "expected a class"), ("defaults-unknown", "action_defaults:\n  tsk: soma:Task\n", "unknown key(s)"),
    ("actions-list", "actions: [pick]\n", "'actions' must map"), ("actions-int-key", "actions: {5: {task: soma:Pouring}}\n", "actions.5"),
    ("actions-bool-key", "actions: {true: {task: soma:Pouring}}\n", "actions"), ("actions-null-key", "actions: {null: {task: soma:Pouring}}\n", "actions"),
    ("actions-list-key", "actions:\n  ? [a, b]\n  : {task: soma:Pouring}\n", "actions"), ("actions-space-key", "actions: {'pick up': {task: soma:Pouring}}\n", "actions"),
    ("actions-spec-list", "actions: {pick: [soma:Picking]}\n", "expected a mapping"), ("actions-spec-string", "actions: {pick: soma:Picking}\n", "expected a mapping"),
    ("actions-unknown-field", "actions: {pick: {taks: soma:Picking}}\n", "unknown key(s)"), ("actions-task-number", "actions: {pick: {task: 5}}\n", "actions.pick.task"),
    ("actions-task-list", "actions: {pick: {task: [soma:Picking]}}\n", "actions.pick.task"), ("actions-role-number", "actions: {pick: {ref_role: 5}}\n", "expected a class"),
    ("actions-unknown-parent", "actions: {pick: {parent: grab}}\n", "unknown parent 'grab'"), ("actions-self-parent", "actions: {pick: {parent: pick}}\n", "cyclic parent"),
    ("actions-cycle", "actions: {pick: {parent: place}, place: {parent: pick}}\n", "cyclic parent"),
    ("actions-parent-number", "actions: {pick: {parent: 5}}\n", "unknown parent"), ("actions-parent-list", "actions: {pick: {parent: [place]}}\n", "parent"),
    ("actions-task-not-in-tbox", "actions: {pick: {task: soma:NoSuchTask}}\n", "NoSuchTask"),
    ("actions-task-bad-prefix", "actions: {pick: {task: 'x:y'}}\n", "unknown prefix"), ("actions-task-iri-space", "actions: {pick: {task: 'http://x/a b'}}\n", "actions.pick.task"),
    ("deep-parent-cycle", "actions:\n" + "".join(f"  a{i}: {{parent: a{i + 1}}}\n" for i in range(2000)) + "  a2000: {parent: a0}\n", "cyclic parent"),
    ("deep-parent-unknown", "actions:\n" + "".join(f"  a{i}: {{parent: a{i + 1}}}\n" for i in range(2000)) + "  a2000: {parent: nowhere}\n", "unknown parent 'nowhere'"),
    ("deep-nesting", "actions: " + "[" * 5000 + "]" * 5000 + "\n", "mapping"), ("binary", "\x00\x01\x02\x03", "mapping"),
    ("anchor-bomb", "x: &a [1,1,1,1,1,1,1,1,1]\ny: &b [*a,*a,*a,*a,*a,*a,*a,*a,*a]\nz: [*b,*b,*b,*b,*b,*b,*b,*b,*b]\n", "unknown key(s)"),
]:
    MAPPING.append((name, text, "", expected))

# -- odb folders (import --odb): one manifest.xml per object ------------------------------------------
def manifest(name: str, *parents: str, body: str = "") -> str:
    derive = "".join(f"<derive>{p}</derive>" for p in parents)
    return f'<?xml version="1.0"?>\n<object><name>{name}</name>{derive}{body}</object>\n'


ODB: list[tuple[str, dict[str, str | bytes], str]] = []
for name, files, expected in [
    ("empty-folder", {".keep": ""}, "no */manifest.xml found"),
    ("malformed-xml", {"a/manifest.xml": "<object><name>a</name>"}, "malformed XML"),
    ("not-xml", {"a/manifest.xml": "name: a\n"}, "malformed XML"),
    ("empty-manifest", {"a/manifest.xml": ""}, "malformed XML"),
    ("wrong-root", {"a/manifest.xml": "<thing><name>a</name></thing>"}, "root element must be <object>"),
    ("no-name", {"a/manifest.xml": "<object></object>"}, "missing <name>"),
    ("empty-name", {"a/manifest.xml": "<object><name> </name></object>"}, "missing <name>"),
    ("name-space", {"a/manifest.xml": manifest("red mug")}, "not a valid odb name"),
    ("name-digit", {"a/manifest.xml": manifest("1mug")}, "not a valid odb name"),
    ("name-quote", {"a/manifest.xml": manifest("mug'")}, "not a valid odb name"),
    ("name-unicode", {"a/manifest.xml": manifest("müg")}, "not a valid odb name"),
    ("name-too-long", {"a/manifest.xml": manifest("m" * 300)}, "not a valid odb name"),
    ("duplicate-name", {"a/manifest.xml": manifest("mug"), "b/manifest.xml": manifest("mug")}, "also defined in"),
    ("unknown-parent", {"a/manifest.xml": manifest("mug", "_cup")}, "derives from unknown object '_cup'"),
    ("empty-derive", {"a/manifest.xml": "<object><name>mug</name><derive/></object>"}, "empty <derive>"),
    ("bad-derive", {"a/manifest.xml": "<object><name>mug</name><derive>a b</derive></object>"}, "is not a valid odb name"),
    ("self-derive", {"a/manifest.xml": manifest("mug", "mug")}, "cyclic derive"),
    ("cycle-2", {"a/manifest.xml": manifest("a", "b"), "b/manifest.xml": manifest("b", "a")}, "cyclic derive"),
    ("cycle-3", {"a/manifest.xml": manifest("a", "b"), "b/manifest.xml": manifest("b", "c"), "c/manifest.xml": manifest("c", "a")}, "cyclic derive"),
    ("empty-snippet", {"a/manifest.xml": manifest("mug", body="<logic><code_snippet/></logic>")}, "empty <code_snippet>"),
    ("bad-snippet", {"a/manifest.xml": manifest("mug", body="<logic><code_snippet>pick up.yml</code_snippet></logic>")}, "names no valid task"),
    ("snippet-path-only", {"a/manifest.xml": manifest("mug", body="<logic><code_snippet>/</code_snippet></logic>")}, "names no valid task"),
    ("mass-word", {"a/manifest.xml": manifest("mug", body="<mass>heavy</mass>")}, "<mass>"),
    ("mass-nan", {"a/manifest.xml": manifest("mug", body="<mass>nan</mass>")}, "<mass>"),
    ("mass-inf", {"a/manifest.xml": manifest("mug", body="<mass>inf</mass>")}, "<mass>"),
    ("mass-negative", {"a/manifest.xml": manifest("mug", body="<mass>-1</mass>")}, "<mass>"),
    ("mass-1e400", {"a/manifest.xml": manifest("mug", body="<mass>1e400</mass>")}, "<mass>"),
    ("dimension-word", {"a/manifest.xml": manifest("mug", body="<dimension>1 x 2</dimension>")}, "<dimension>"),
    ("dimension-nan", {"a/manifest.xml": manifest("mug", body="<dimension>nan 1 1</dimension>")}, "<dimension>"),
    ("dimension-inf", {"a/manifest.xml": manifest("mug", body="<dimension>1 inf 1</dimension>")}, "<dimension>"),
    ("dimension-negative", {"a/manifest.xml": manifest("mug", body="<dimension>1 -2 1</dimension>")}, "<dimension>"),
    ("entity-bomb", {"a/manifest.xml": '<?xml version="1.0"?><!DOCTYPE o [<!ENTITY a "aaaaaaaaaa"><!ENTITY b "&a;&a;&a;&a;&a;&a;&a;&a;&a;&a;"><!ENTITY c "&b;&b;&b;&b;&b;&b;&b;&b;&b;&b;"><!ENTITY d "&c;&c;&c;&c;&c;&c;&c;&c;&c;&c;">]><object><name>&d;</name></object>'}, "manifest"),
    ("external-entity", {"a/manifest.xml": '<?xml version="1.0"?><!DOCTYPE o [<!ENTITY x SYSTEM "file:///etc/passwd">]><object><name>&x;</name></object>'}, "manifest"),
    ("latin1-undeclared", {"a/manifest.xml": b"<object><name>m\xfcg</name></object>"}, "malformed XML"),
    ("utf16-no-bom", {"a/manifest.xml": "<object><name>mug</name></object>".encode("utf-16-le")}, "unknown object"),
    ("binary", {"a/manifest.xml": bytes(range(256))}, "malformed XML"),
    ("manifest-is-folder", {"a/manifest.xml/x": ""}, "manifest"),
]:
    ODB.append((name, files, expected))

# -- prolog: task strings handed to why-not / something-else -------------------------------------------
QUERIES: list[tuple[str, str, str]] = []
for name, text, expected in [
    ("halt", "halt", "unknown task 'halt'"), ("injection-halt", "pick(banana)), halt, (true", "malformed action"),
    ("clause", "pick(banana) :- true", "malformed action"), ("full-stop", "pick(banana).", "malformed action"),
    ("variable", "pick(X)", "unknown object 'X'"), ("quoted-atom", "'pick'(banana)", "malformed action"),
    ("list", "[pick, banana]", "malformed action"), ("curly", "{pick(banana)}", "malformed action"),
    ("operator", "pick(banana);halt", "malformed action"), ("shell", "pick(banana)`rm -rf /`", "malformed action"),
    ("assert", "assertz(foo)", "unknown task 'assertz'"), ("nested-call", "pick(call(halt))", "bad object name"),
    ("string-arg", 'pick("banana")', "bad object name"), ("empty", "", "malformed action"),
    ("only-spaces", "   ", "malformed action"), ("unknown-task", "juggle(banana)", "unknown task 'juggle'"),
    ("unknown-object", "pick(unicorn)", "unknown object 'unicorn'"), ("three-args", "pour(a, b, c)", "at most two objects"),
    ("backslash", "pick(ban\\ana)", "bad object name"), ("percent-comment", "pick(banana) % c", "malformed action"),
    ("block-comment", "pick(/*x*/banana)", "bad object name"), ("long-atom", "pick(" + "b" * 5000 + ")", "unknown object"),
]:
    QUERIES.append((name, text, expected))

# -- command lines ---------------------------------------------------------------------------------------
# ``{store}`` is the corpus store, ``{tmp}`` a scratch folder, ``{good}`` a valid chains file.
CLI: list[tuple[str, str, str]] = []
for value, expected in [
    ("nan", "--at"), ("inf", "--at"), ("infinity", "--at"), ("1e400", "--at"), ("1e20", "--at"), ("1e308", "--at"),
    ("-1e20", "--at"), ("NaN", "--at"), ("+inf", "--at"), ("", "--at"), ("abc", "--at"), ("2025-13-01T00:00", "--at"),
    ("9999-12-31T23:59:59-12:00", "--at"), ("0001-01-01T00:00:00+05:00", "--at"), ("0x10", "--at"),
    ("-5", "--at"), ("yesterday", "--at"),
]:
    slug = {"": "empty", "+inf": "plus-inf", "-1e20": "minus-1e20", "-5": "minus-5"}.get(value, value.lower().replace(":", "").replace("+", "p"))
    CLI.append((f"why-not-at-{slug}", f"why-not 'pick(banana)' --store {{store}} --neem p000-tea-red-yogurt --at={shlex.quote(value)}", expected))
    CLI.append((f"rank-at-{slug}", f"rank --store {{store}} --neem p000-tea-red-yogurt --available 'pick(banana)' --at={shlex.quote(value)}", expected))
for name, uri, expected in [
    ("bad-port", "mongodb://alice:s3cret@localhost:99999/db", "Port"), ("space-host", "mongodb://alice:s3cret@ho st/db", "mongodb://"),
    ("at-in-password", "mongodb://alice:p@ss@localhost/db", "mongodb://"), ("slash-in-password", "mongodb://alice:pa/ss@localhost/db", "mongodb://"),
    ("colon-in-password", "mongodb://alice:pa:ss@localhost/db", "mongodb://"), ("empty-host", "mongodb://alice:s3cret@/db", "mongodb://"),
    ("bad-option", "mongodb://alice:s3cret@localhost/db?foo=bar&ssl=maybe", "mongodb://"),
    ("bad-db-name", "mongodb://alice:s3cret@localhost/d$b", "mongodb://"), ("bad-percent", "mongodb://alice:s3cr%zzet@localhost/db", "mongodb://"),
    ("srv-with-port", "mongodb+srv://alice:s3cret@host.example:27017/db", "mongodb+srv://"),
    ("srv-no-dots", "mongodb+srv://alice:s3cret@host/db", "mongodb+srv://"), ("no-host", "mongodb://", "mongodb://"),
    ("unknown-scheme", "postgres://alice:s3cret@localhost/db", "unknown store"), ("http", "http://alice:s3cret@localhost/", "unknown store"),
    ("sqlite-empty", "sqlite://", "sqlite:// needs a path"), ("ftp", "ftp://alice:s3cret@x/y", "unknown store"),
]:
    CLI.append((f"store-uri-{name}", f"neems --store {shlex.quote(uri)}", expected))
    CLI.append((f"store-uri-{name}-import", f"import {{good}} --store {shlex.quote(uri)}", expected))
for name, uri in [("env-bad-port", "mongodb://alice:s3cret@localhost:99999/db"), ("env-space", "mongodb://alice:s3cret@ho st/db"),
                  ("env-at", "mongodb://alice:p@ss@localhost/db")]:
    CLI.append((name, f"env:NEEM_MONGO_URI={shlex.quote(uri)} neems --store mongodb", "mongodb://"))
CLI.append(("env-unset", "env:NEEM_MONGO_URI= neems --store mongodb", "NEEM_MONGO_URI"))
for name, path, expected in [
    ("store-is-folder", "{tmp}", "no NEEM store"), ("store-not-sqlite", "{good}", "not a NEEM store"),
    ("store-dev-null", "/dev/null", "store"), ("store-in-missing-proc", "/proc/nonexistent/x.sqlite", "no NEEM store"),
]:
    CLI.append((name, f"neems --store {path}", expected))
for name, neem in [("underscore", "a_b"), ("empty", ""), ("dotdot", "../x"), ("too-long", "x" * 65), ("dollar", "$where"),
                   ("space", "a b"), ("quote", "a'b"), ("unknown", "nobody-here")]:
    expected = "no NEEM" if name == "unknown" else "NEEM"
    CLI.append((f"export-neem-{name}", f"export --store {{store}} --neem {shlex.quote(neem)} --out {{tmp}}/out", expected))
    CLI.append((f"why-not-neem-{name}", f"why-not 'pick(banana)' --store {{store}} --neem {shlex.quote(neem)}", expected))
    CLI.append((f"rank-neem-{name}", f"rank --store {{store}} --neem {shlex.quote(neem)}", expected))
    CLI.append((f"persist-neem-{name}", f"persist --store {{store}} --neem {shlex.quote(neem)} --as kept", expected))
for name, new in [("underscore", "a_b"), ("empty", ""), ("dotdot", "../x"), ("too-long", "y" * 65), ("existing", "p001-coffee-green-fruit")]:
    CLI.append((f"persist-as-{name}", f"persist --store {{store}} --neem p000-tea-red-yogurt --as {shlex.quote(new)}", "NEEM"))
for name, args, expected in [
    ("load-missing", "load {tmp}/nothing --store {store}", "not a folder"), ("load-file", "load {good} --store {store}", "not a folder"),
    ("load-empty-folder", "load {tmp} --store {store}", "no triples"), ("load-neem-bad-id", "load {dump} --neem a_b --store {store}", "invalid NEEM name"),
    ("load-existing", "load {dump} --neem p000-tea-red-yogurt --store {store}", "already exists"),
    ("export-out-is-file", "export --store {store} --neem p000-tea-red-yogurt --out {good}", "cannot write"),
    ("export-out-dev-null", "export --store {store} --neem p000-tea-red-yogurt --out /dev/null", "cannot write"),
    ("settings-unknown-preset", "rank --store {store} --neem p000-tea-red-yogurt --settings Z", "--settings"), ("settings-empty", "rank --store {store} --neem p000-tea-red-yogurt --settings ''", "settings"),
    ("settings-missing-yaml", "rank --store {store} --neem p000-tea-red-yogurt --settings {tmp}/none.yaml", "cannot read"),
    ("available-bad-call", "rank --store {store} --neem p000-tea-red-yogurt --available 'pick('", "malformed action"),
    ("available-unknown-task", "rank --store {store} --neem p000-tea-red-yogurt --available 'juggle(banana)'", "unknown task"),
    ("available-unknown-object", "rank --store {store} --neem p000-tea-red-yogurt --available 'pick(unicorn)'", "unknown object"),
    ("available-injection", "rank --store {store} --neem p000-tea-red-yogurt --available 'pick(banana)), halt, (true'", "malformed action"),
    ("import-missing-file", "import {tmp}/none.jsonl --store {store}", "cannot read"), ("import-folder", "import {tmp} --store {store}", "cannot read"),
    ("import-mapping-and-ontology", "import {good} --store {store} --ontology {tmp}/o.owl --mapping {tmp}/m.yaml", "either --ontology"),
    ("import-ontology-missing", "import {good} --store {store} --ontology {tmp}/none.owl", "none.owl"),
    ("import-ontology-not-owl", "import {good} --store {store} --ontology {good}", "cannot parse"),
    ("import-odb-missing", "import {good} --store {store} --odb {tmp}/none", "odb folder not found"),
    ("import-mapping-missing", "import {good} --store {store} --mapping {tmp}/none.yaml", "cannot read"),
    ("import-soma-missing", "import {good} --store {store} --soma {tmp}/none", "none"),
    ("no-command", "", "command"), ("unknown-command", "explode", "no such command"), ("unknown-option", "neems --store {store} --colour", "unrecognized"),
    ("demo-bad-days", "demo --store {store} --days=-1", "--days"), ("demo-zero-days", "demo --store {store} --days 0", "--days"),
    ("demo-huge-days", "demo --store {store} --days 100000000", "--days"),
]:
    CLI.append((name, args, expected))


# -- load: dump folders ----------------------------------------------------------------------------------
def bson_docs() -> list[dict[str, Any]]:
    """A tiny valid NEEM: one class with a label-less subclass edge and one typed individual."""
    odb = "https://ontology.dlr.de/soma/odb#"
    rdf_type = "http://www.w3.org/1999/02/22-rdf-syntax-ns#type"
    sub = "http://www.w3.org/2000/01/rdf-schema#subClassOf"
    dul = "http://www.ontologydesignpatterns.org/ont/dul/DUL.owl#"
    docs = [
        {"s": odb + "Mug", "p": sub, "o": dul + "PhysicalObject", "p*": [sub], "o*": [odb + "Mug", dul + "PhysicalObject"],
         "graph": "odb", "scope": {"time": {"since": 0.0, "until": float("inf")}}},
        {"s": odb + "Object_red_mug", "p": rdf_type, "o": odb + "Mug", "p*": [rdf_type], "o*": [odb + "Mug", dul + "PhysicalObject"],
         "graph": "user", "scope": {"time": {"since": 0.0, "until": float("inf")}}},
    ]
    return docs


LOAD: list[tuple[str, dict[str, Any], str]] = []


def dump_case(name: str, expected: str, *, docs: list[Any] | None = None, raw: bytes | None = None,
              meta: Any = "default", meta_raw: str | bytes | None = None, extra: dict[str, bytes] | None = None,
              metadata: str | None = None) -> None:
    LOAD.append((name, {"docs": docs, "raw": raw, "meta": meta, "meta_raw": meta_raw, "extra": extra or {},
                        "metadata": metadata}, expected))


def with_doc(**changes: Any) -> list[dict[str, Any]]:
    docs = bson_docs()
    docs[1] = {k: v for k, v in {**docs[1], **changes}.items() if v is not ...}
    return docs


for name, changes, expected in [
    ("scope-string", {"scope": "always"}, "scope"), ("scope-number", {"scope": 5}, "scope"), ("scope-list", {"scope": [0, 1]}, "scope"),
    ("scope-time-list", {"scope": {"time": [0, 1]}}, "scope"), ("scope-time-string", {"scope": {"time": "now"}}, "scope"),
    ("since-string", {"scope": {"time": {"since": "abc", "until": float("inf")}}}, "since"),
    ("until-string", {"scope": {"time": {"since": 0.0, "until": "later"}}}, "until"),
    ("since-nan", {"scope": {"time": {"since": float("nan"), "until": float("inf")}}}, "since"),
    ("since-after-until", {"scope": {"time": {"since": 10.0, "until": 5.0}}}, "since"),
    ("since-list", {"scope": {"time": {"since": [0], "until": 1.0}}}, "since"),
    ("ostar-number", {"o*": 5}, "o*"), ("ostar-string", {"o*": "abc"}, "o*"), ("ostar-object", {"o*": {"a": 1}}, "o*"),
    ("pstar-number", {"p*": 5}, "p*"), ("pstar-null", {"p*": None}, "p*"),
    ("s-missing", {"s": ...}, "'s'"), ("s-number", {"s": 5}, "'s'"), ("s-object", {"s": {"$gt": ""}}, "$gt"), ("s-empty", {"s": ""}, "'s'"),
    ("p-missing", {"p": ...}, "'p'"), ("p-number", {"p": 5}, "'p'"), ("p-list", {"p": ["a"]}, "'p'"),
    ("o-missing", {"o": ...}, "'o'"), ("o-object", {"o": {"$where": "1"}}, "$where"), ("o-list", {"o": [1, 2]}, "'o'"),
    ("graph-number", {"graph": 5}, "graph"), ("graph-object", {"graph": {"a": 1}}, "graph"),
    ("dollar-key", {"$where": "sleep(1000)"}, "$where"), ("dotted-key", {"a.b": 1}, "a.b"),
]:
    dump_case(f"doc-{name}", expected, docs=with_doc(**changes))

for name, expected in [
    ("truncated-half", "truncated"), ("truncated-4-bytes", "truncated"), ("truncated-header", "truncated"),
    ("length-huge", "corrupt"), ("length-negative", "corrupt"), ("length-zero", "corrupt"), ("garbage", "document 1"),
    ("bad-type-byte", "not valid BSON"), ("bad-utf8-key", "not valid BSON"), ("cut-at-boundary", "counts 2"),
    ("empty-file-with-count", "counts 2"), ("missing-terminator", "not valid BSON"), ("extra-bytes", "truncated"),
    ("json-instead", "corrupt"),
]:
    dump_case(f"bson-{name}", expected, raw=name.encode())

for name, meta_raw, expected in [
    ("not-json", "{", "meta.json"), ("list", "[1]", "not a JSON object"), ("string", '"x"', "not a JSON object"),
    ("created-by-number", '{"created_by": 12345}', "created_by"), ("created-by-object", '{"created_by": {"$gt": ""}}', "$gt"),
    ("created-by-list", '{"created_by": ["a"]}', "created_by"), ("created-at-number", '{"created_at": 5}', "created_at"),
    ("created-at-word", '{"created_at": "yesterday"}', "created_at"), ("temporary-string", '{"temporary": "yes"}', "temporary"),
    ("id-invalid", '{"id": "a_b"}', "invalid NEEM id"), ("id-number", '{"id": 5}', "id"), ("id-object", '{"id": {"$ne": null}}', "id"),
    ("where-key", '{"$where": "sleep(1000)"}', "$where"), ("dollar-nested", '{"name": {"$gt": ""}}', "$gt"),
    ("dotted-key", '{"a.b": 1}', "a.b"), ("nan", '{"created_at": NaN}', "created_at"), ("deep", '{"a":' * 5000 + "1" + "}" * 5000, "meta.json"),
    ("bad-utf8", b'{"created_by": "caf\xe9"}', "meta.json"), ("huge-number", '{"x": 1' + "0" * 5000 + "}", "meta.json"),
    ("bson-extended-bad", '{"created_at": {"$date": "never"}}', "meta.json"),
]:
    dump_case(f"meta-{name}", expected, meta=None, meta_raw=meta_raw)
dump_case("layout-id-from-folder-invalid", "invalid NEEM id", meta=None, extra={"name": b"___"})
dump_case("metadata-not-json", "metadata", metadata="{")
dump_case("meta-count-wrong", "counts 5", meta_raw='{"id": "corpus-neem", "documents": {"triples": 5}}')
dump_case("meta-count-not-a-number", "'documents'", meta_raw='{"id": "corpus-neem", "documents": {"triples": "two"}}')
dump_case("meta-count-unknown-kind", "'documents'", meta_raw='{"id": "corpus-neem", "documents": {"people": 2}}')


def write_all() -> int:
    total = 0
    for entry in ("import", "settings", "mapping", "odb", "prolog", "cli", "load"):
        folder = HERE / entry
        if folder.exists():
            shutil.rmtree(folder)
        folder.mkdir()
    def table(entry: str, lines: list[tuple[str, str, str]]) -> None:
        nonlocal total
        with (HERE / entry / "cases.tsv").open("w", encoding="utf-8") as handle:
            handle.write("# file\textra arguments\texpected fragment of the one-line error\n")
            for file, args, expected in lines:
                assert "\t" not in args + expected and "\n" not in args + expected, file
                handle.write(f"{file}\t{args}\t{expected}\n")
        total += len(lines)
    lines = []
    for number, (name, content, args, expected) in enumerate(IMPORT, start=1):
        file = f"{number:03d}-{name}.jsonl"
        (HERE / "import" / file).write_bytes(content if isinstance(content, bytes) else content.encode("utf-8", "surrogatepass"))
        lines.append((file, args, expected))
    table("import", lines)
    for entry, cases, ext in (("settings", SETTINGS, "yaml"), ("mapping", MAPPING, "yaml")):
        lines = []
        for number, (name, text, args, expected) in enumerate(cases, start=1):
            file = f"{number:03d}-{name}.{ext}"
            (HERE / entry / file).write_text(text, encoding="utf-8")
            lines.append((file, args, expected))
        table(entry, lines)
    lines = []
    for number, (name, files, expected) in enumerate(ODB, start=1):
        folder = HERE / "odb" / f"{number:03d}-{name}"
        for rel, content in files.items():
            target = folder / rel
            target.parent.mkdir(parents=True, exist_ok=True)
            target.write_bytes(content if isinstance(content, bytes) else content.encode())
        lines.append((folder.name, "", expected))
    table("odb", lines)
    lines = []
    for number, (name, text, expected) in enumerate(QUERIES, start=1):
        file = f"{number:03d}-{name}.txt"
        (HERE / "prolog" / file).write_text(text + "\n", encoding="utf-8")
        lines.append((file, "", expected))
    table("prolog", lines)
    lines = []
    for number, (name, args, expected) in enumerate(CLI, start=1):
        file = f"{number:03d}-{name}.args"
        (HERE / "cli" / file).write_text(args + "\n", encoding="utf-8")
        lines.append((file, "", expected))
    table("cli", lines)
    lines = []
    for number, (name, spec, expected) in enumerate(LOAD, start=1):
        folder = HERE / "load" / f"{number:03d}-{name}"
        _write_dump_case(folder, spec)
        lines.append((folder.name, "", expected))
    table("load", lines)
    return total


def _write_dump_case(folder: Path, spec: dict[str, Any]) -> None:
    import bson
    from bson import json_util

    base = folder / spec["extra"].get("name", b"corpus-neem").decode()
    triples = base / "triples" / "roslog"
    triples.mkdir(parents=True)
    docs = spec["docs"] if spec["docs"] is not None else bson_docs()
    good = b"".join(bson.encode(d, check_keys=False) for d in bson_docs())
    first = bson.encode(bson_docs()[0])
    raw = {
        None: None,
        b"truncated-half": good[: len(good) // 2 + 3],
        b"truncated-4-bytes": good[:-4],
        b"truncated-header": good + b"\x10\x00",
        b"length-huge": struct.pack("<i", 1 << 30) + good[4:],
        b"length-negative": struct.pack("<i", -7) + good[4:],
        b"length-zero": struct.pack("<i", 0) + good[4:],
        b"garbage": b"\x05\x00\x00\x00\xff" * 3 + b"not bson at all",
        b"bad-type-byte": first[:4] + b"\x7a" + first[5:] + good[len(first):],
        b"bad-utf8-key": first[:5] + b"\xff" + first[6:],
        b"cut-at-boundary": first,
        b"empty-file-with-count": b"",
        b"missing-terminator": first[:-1] + b"\x01" + good[len(first):],
        b"extra-bytes": good + b"\x01\x02\x03",
        b"json-instead": json.dumps({"s": "x"}).encode(),
    }[spec["raw"]]
    if raw is None:
        raw = b"".join(bson.encode(d, check_keys=False) for d in docs)
        count = len(docs)
    else:
        count = len(bson_docs())
    (triples / "triples.bson").write_bytes(raw)
    metadata = spec["metadata"] or json.dumps({"indexes": [{"v": 2, "key": {"_id": 1}, "name": "_id_"}],
                                                 "collectionName": "triples", "type": "collection", "count": count})
    (triples / "triples.metadata.json").write_text(metadata)
    meta_raw = spec["meta_raw"]
    if meta_raw is not None:
        (base / "meta.json").write_bytes(meta_raw if isinstance(meta_raw, bytes) else meta_raw.encode())
    elif spec["meta"] == "default":
        (base / "meta.json").write_text(json_util.dumps({"id": "corpus-neem", "created_by": "corpus",
                                                         "documents": {"triples": count}}))


if __name__ == "__main__":
    print(f"{write_all()} inputs written")
