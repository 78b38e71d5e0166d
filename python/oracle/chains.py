"""Action chains in text: ``task(obj1[, obj2])`` (thesis 5.2) and their JSONL files.

A JSONL row is ``{"user", "time", "end" | "duration", "action", "available"}``; only ``user`` and
``action`` are required. Optional: ``id``, ``performed_by`` (one of MODES: who did it, the robot by
default), ``state`` (one of EXECUTION_STATES,
what the robot reports) and ``session`` (the recording session, one soma:Episode each; default
the UTC day). ``end`` matters for idle detection: a gap of 20 s or more between one
action's end (its start when no end is given) and the next start is an odb:IdleTask.

A call names an odb task and zero, one or two odb objects. With two arguments the first plays
the task's reference role (the object the arm holds or uses) and the second its target role;
with one argument the object plays the target role, or the reference role when the task has no
target role (docs/ontology.md, "Roles of chain arguments").
"""

from __future__ import annotations

import json
import re
from collections.abc import Iterable, Iterator
from dataclasses import dataclass, field
from functools import lru_cache
from datetime import datetime, timedelta
from pathlib import Path
from typing import Any

from oracle.errors import ChainSyntaxError
from oracle.timeline import TimeValueError, check_seconds, parse_iso, seconds_of

#: Longest line a chains file may have (bytes, newline included): a row with a thousand
#: available actions is ~30 kB; the cap keeps memory bounded whatever the file holds.
MAX_LINE = 1 << 20
#: Longest user name or action id (characters).
MAX_NAME = 200
#: What a robot may report of an action it did (optional ``state`` of a row): KnowRob's
#: execution states (``soma:ExecutionState_Succeeded`` ..., action_succeeded/1 and kin).
EXECUTION_STATES = ("succeeded", "failed", "cancelled", "active", "paused", "pending")
#: Who performs an action (``performed_by`` of a row; thesis 6.3, the autonomy mode): the robot
#: alone, the user by hand, or the two together (the robot doing the part the user cannot).
MODES = ("robot", "user", "together")


def modes_error(value: object) -> str:
    """The one line a value that names no mode gets (the chains reader, the logger, the service)."""
    return f"performed_by must be one of {', '.join(MODES)}, got {_short(value)}"

_NAME = r"[A-Za-z_][A-Za-z0-9_\-]*"
_CALL = re.compile(rf"^\s*({_NAME})\s*(?:\(\s*(.*?)\s*\))?\s*$")
_ARG = re.compile(rf"^{_NAME}$")


@dataclass(frozen=True)
class TaskCall:
    """One task with its objects as written in a chain, e.g. ``pour(thermos, green_mug)``."""

    task: str
    args: tuple[str, ...] = ()

    def __str__(self) -> str:
        return f"{self.task}({', '.join(self.args)})" if self.args else self.task


def parse_call(text: str) -> TaskCall:
    """Parse ``task(a[, b])``; raise ChainSyntaxError naming the text on any defect."""
    if not isinstance(text, str):
        raise ChainSyntaxError(f"action must be a string like 'pick(red_mug)', got {text!r}")
    return _parse_call(text)


@lru_cache(maxsize=1 << 16)
def _parse_call(text: str) -> TaskCall:
    # Chains repeat the same few hundred calls many times; parsing is pure, so it is memoised.
    match = _CALL.match(text)
    if match is None:
        raise ChainSyntaxError(f"malformed action {text!r}: expected task(object[, object])")
    task, inner = match.group(1), match.group(2)
    args: tuple[str, ...] = ()
    if inner is not None and inner != "":
        args = tuple(part.strip() for part in inner.split(","))
        for arg in args:
            if not _ARG.match(arg):
                raise ChainSyntaxError(f"malformed action {text!r}: bad object name {arg!r}")
    elif inner == "":
        raise ChainSyntaxError(f"malformed action {text!r}: empty argument list")
    if len(args) > 2:
        raise ChainSyntaxError(f"malformed action {text!r}: at most two objects (target, reference)")
    return TaskCall(task, args)


def _parse_calls(items: list[Any]) -> tuple[TaskCall, ...]:
    """The calls of an available list; raise ChainSyntaxError on the first bad one."""
    try:
        return _parse_texts(tuple(items))  # a non-string raises in parse_call, uncached
    except TypeError:  # an unhashable item (a list, an object): parse_call names it
        return tuple(map(parse_call, items))


@lru_cache(maxsize=1 << 12)
def _parse_texts(texts: tuple[str, ...]) -> tuple[TaskCall, ...]:
    # A persona meets the same few hundred available sets again and again: one look-up for
    # the whole set, and every row with that set shares one tuple of calls.
    return tuple(map(parse_call, texts))


@dataclass(frozen=True)
class ChainRow:
    """One line of a chains JSONL file."""

    user: str
    action: TaskCall
    time: datetime | None = None
    available: tuple[TaskCall, ...] | None = None
    line: int = 0
    extra: dict[str, object] = field(default_factory=dict, compare=False)
    end: datetime | None = None

    def to_json(self) -> dict[str, object]:
        row: dict[str, object] = {"user": self.user}
        if self.time is not None:
            row["time"] = self.time.isoformat()
        if self.end is not None:
            row["end"] = self.end.isoformat()
        row["action"] = str(self.action)
        if self.available is not None:
            row["available"] = [str(call) for call in self.available]
        row.update(self.extra)
        return row


def parse_row(obj: object, where: str = "<row>") -> ChainRow:
    """Turn one decoded JSON object into a ChainRow; ``where`` names file and line in errors."""
    if not isinstance(obj, dict):
        raise ChainSyntaxError(f"{where}: expected a JSON object, got {type(obj).__name__}")
    unknown = set(obj) - {"user", "time", "end", "duration", "action", "available"}
    user = obj.get("user")
    if not isinstance(user, str) or not user:
        raise ChainSyntaxError(f"{where}: 'user' must be a non-empty string")
    if not _printable_name(user):
        raise ChainSyntaxError(f"{where}: 'user' {user[:60]!r} must be 1-{MAX_NAME} printable characters, not only spaces")
    if "id" in obj:
        action_id = obj["id"]
        if isinstance(action_id, bool) or not isinstance(action_id, (str, int)) or (
            isinstance(action_id, str) and not _printable_name(action_id)
        ) or len(str(action_id)) > MAX_NAME:
            raise ChainSyntaxError(f"{where}: 'id' must be a string of 1-{MAX_NAME} printable characters or an integer")
    if "state" in obj and obj["state"] not in EXECUTION_STATES:
        raise ChainSyntaxError(f"{where}: 'state' must be one of {', '.join(EXECUTION_STATES)}, got {_short(obj['state'])}")
    if "performed_by" in obj and obj["performed_by"] not in MODES:
        raise ChainSyntaxError(f"{where}: {modes_error(obj['performed_by'])}")
    if "session" in obj and not (isinstance(obj["session"], str) and _printable_name(obj["session"])):
        raise ChainSyntaxError(f"{where}: 'session' must be a string of 1-{MAX_NAME} printable characters")
    if "action" not in obj:
        raise ChainSyntaxError(f"{where}: missing 'action'")
    try:
        action = parse_call(obj["action"])
        available = None
        if obj.get("available") is not None:
            if not isinstance(obj["available"], list):
                raise ChainSyntaxError("'available' must be a list of actions")
            available = _parse_calls(obj["available"])
    except ChainSyntaxError as error:
        raise ChainSyntaxError(f"{where}: {error}") from None
    time = _moment(obj, "time", where)
    end = _moment(obj, "end", where)
    if obj.get("duration") is not None:
        duration = obj["duration"]
        if isinstance(duration, bool) or not isinstance(duration, (int, float)) or not duration >= 0:
            raise ChainSyntaxError(f"{where}: 'duration' must be a number of seconds >= 0, got {_short(duration)}")
        if time is None:
            raise ChainSyntaxError(f"{where}: 'duration' needs a 'time'")
        if end is not None:
            raise ChainSyntaxError(f"{where}: give 'end' or 'duration', not both")
        try:
            check_seconds(seconds_of(time) + float(duration), "'time' + 'duration'")
        except (TimeValueError, OverflowError):
            raise ChainSyntaxError(
                f"{where}: 'duration' {_short(duration)} ends after 9000-01-01; 'time' + 'duration' must lie between"
                " 1970-01-01 and 9000-01-01 (UTC)"
            ) from None
        end = time + timedelta(seconds=float(duration))
    if end is not None and (time is None or end < time):
        raise ChainSyntaxError(f"{where}: 'end' must not be before 'time'")
    line = int(where.rsplit(":", 1)[-1]) if where.rsplit(":", 1)[-1].isdigit() else 0
    extra = {key: obj[key] for key in sorted(unknown)}
    return ChainRow(user, action, time, available, line, extra, end)


def _printable_name(text: str) -> bool:
    # isprintable() is False for control, format (bidi overrides, zero-width) and surrogate
    # characters, none of which belong in a name shown in listings and answers.
    return bool(text.strip()) and text.isprintable() and len(text) <= MAX_NAME


def _short(value: object) -> str:
    text = repr(value)
    return text if len(text) <= 40 else text[:37] + "..."


def _moment(obj: dict[str, Any], key: str, where: str) -> datetime | None:
    raw = obj.get(key)
    if raw is None:
        return None
    if not isinstance(raw, str):
        raise ChainSyntaxError(f"{where}: {key!r} must be an ISO-8601 string")
    try:
        moment = parse_iso(raw)
    except TimeValueError:
        raise ChainSyntaxError(f"{where}: {key!r} {raw[:60]!r} is not ISO-8601") from None
    try:
        seconds_of(moment)
    except TimeValueError:
        raise ChainSyntaxError(f"{where}: {key!r} {raw!r} must lie between 1970-01-01 and 9000-01-01 (UTC)") from None
    return moment


def read_chains(path: Path | str) -> Iterator[ChainRow]:
    """Yield the rows of a JSONL chains file (blank lines and ``#`` comments are skipped)."""
    from oracle.handed import Handed, open_handed

    path = Path(path)
    handle = open_handed(path, Handed("chains", ChainSyntaxError))  # a regular file: no FIFO, no device
    with handle:
        # Line by line in binary with a cap: memory stays bounded (even for /dev/zero), and a
        # byte that is not UTF-8 is reported with its line instead of failing a whole chunk.
        number = 0
        while True:
            try:
                raw = handle.readline(MAX_LINE + 1)
            except OSError as error:
                raise ChainSyntaxError(f"{path}:{number + 1}: cannot read ({error.strerror})") from None
            if not raw:
                return
            number += 1
            if len(raw) > MAX_LINE:
                raise ChainSyntaxError(f"{path}:{number}: line longer than {MAX_LINE} bytes")
            try:
                text = raw.decode("utf-8")
            except UnicodeDecodeError as error:
                raise ChainSyntaxError(
                    f"{path}:{number}: not UTF-8 (byte 0x{raw[error.start]:02x} at column {error.start + 1})"
                ) from None
            stripped = text.strip()
            if not stripped or stripped.startswith("#"):
                continue
            try:
                obj = json.loads(stripped)
            except json.JSONDecodeError as error:
                raise ChainSyntaxError(f"{path}:{number}: invalid JSON ({error.msg} at column {error.colno})") from None
            except RecursionError:
                raise ChainSyntaxError(f"{path}:{number}: invalid JSON (nested too deeply)") from None
            except ValueError as error:  # e.g. an integer of more than 4,300 digits
                raise ChainSyntaxError(f"{path}:{number}: invalid JSON ({error})") from None
            yield parse_row(obj, f"{path}:{number}")


def write_chains(rows: Iterable[ChainRow], path: Path | str) -> int:
    """Write rows as JSONL (a person's day: 0600, complete or not at all); return how many were written."""
    from oracle.files import private_file

    count = 0
    with private_file(path) as handle:
        for row in rows:
            handle.write(json.dumps(row.to_json(), ensure_ascii=False) + "\n")
            count += 1
    return count
