"""Time, in one home: how a time is read, its part of the day and the idle gap (thesis 3.4).

The one rule (docs/time.md): a time without a zone ("naive") is the robot's wall clock and is
read as UTC, and seconds become a clock time in UTC too, so the machine's ``TZ`` never changes
an answer. A time with a zone keeps its instant (its seconds) and its part of the day comes from
its own wall clock as written. The thesis names the four parts of the day but not their hours;
the boundaries below are this project's choice (docs/ontology.md).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from datetime import datetime, timezone, tzinfo

#: (first hour, local name) in day order; a part lasts until the next one starts.
PARTS_OF_DAY: tuple[tuple[int, str], ...] = (
    (0, "Night"),
    (5, "Morning"),
    (11, "Midday"),
    (17, "Evening"),
    (22, "Night"),
)

#: The class names, each once, in the order they are introduced in the ontology.
TIME_OF_DAY_NAMES: tuple[str, ...] = ("Morning", "Midday", "Evening", "Night")

#: Registry mark (``meta["clock"]``) of a NEEM logged from a time-less action log: its intervals
#: are positions in the log, not clock times (docs/time.md, "Logs without a clock").
CLOCK_KEY = "clock"
SEQUENCE_CLOCK = "sequence"

#: Shared grasping (no task) for this long or longer is an odb:IdleTask; shorter gaps are
#: transitions between tasks (thesis 3.4).
IDLE_THRESHOLD_S = 20.0


class TimeValueError(ValueError):
    """A value that is not a time; callers turn it into their domain's error."""


#: The instants a store accepts (unix seconds): from the epoch up to the start of the year 9000.
#: Every reader can turn these into a clock time in any zone, and Decimal128, doubles and
#: Prolog floats hold them exactly enough; a time outside would be stored and then break the
#: commands that read it (Python's datetime ends in 9999, a zone offset can push past it).
EARLIEST_S = 0.0
LATEST_S = 221845392000.0  # 9000-01-01T00:00:00Z


def _in_range(seconds: float) -> bool:
    return math.isfinite(seconds) and EARLIEST_S <= seconds < LATEST_S


def check_seconds(seconds: float, what: str = "a time") -> float:
    """``seconds`` if it lies in [EARLIEST_S, LATEST_S); else TimeValueError naming ``what``."""
    if not _in_range(seconds):
        raise TimeValueError(f"{what} must lie between 1970-01-01 and 9000-01-01 (UTC), got {seconds!r} seconds")
    return seconds


def time_of_day(moment: datetime | float | int) -> str:
    """Return the local name of the odb:TimeOfDay subclass for a clock time.

    A number is taken as the hour of the day (0 <= h < 24, fractions allowed); a datetime
    uses its own hour and minute as written (its wall clock).
    """
    if isinstance(moment, datetime):
        hour = moment.hour + moment.minute / 60.0
    else:
        hour = float(moment)
    if not 0.0 <= hour < 24.0:
        raise ValueError(f"hour of day must be in [0, 24), got {hour}")
    name = PARTS_OF_DAY[0][1]
    for start, part in PARTS_OF_DAY:
        if hour >= start:
            name = part
    return name


def first_hour(part: str) -> int:
    """The hour a part of the day starts (Night: its evening start, 22)."""
    return max(start for start, name in PARTS_OF_DAY if name == part)


def clock(seconds: float) -> datetime:
    """The wall-clock time of unix seconds under the one rule (UTC, never the machine's zone)."""
    return datetime.fromtimestamp(seconds, timezone.utc)


def seconds_of(moment: datetime) -> float:
    """Unix seconds of a datetime; a naive one is the wall clock, read as UTC.

    Raises TimeValueError when the instant lies outside [EARLIEST_S, LATEST_S)."""
    aware = moment if moment.tzinfo is not None else moment.replace(tzinfo=timezone.utc)
    try:
        seconds = aware.timestamp()
    except (OverflowError, ValueError):  # year 1 at +05:00 is before year 1 in UTC
        seconds = -math.inf
    # The text naming the time is made only for the error (an import checks 4 times per row).
    return seconds if _in_range(seconds) else check_seconds(seconds, moment.isoformat())


def part_of_day_at(seconds: float) -> str:
    """The part of the day of unix seconds (their UTC wall clock)."""
    return time_of_day(clock(seconds))


def parse_iso(text: str) -> datetime:
    """ISO-8601 text as a datetime (``Z`` is UTC; without a zone it stays naive, the wall clock
    that ``seconds_of`` reads as UTC). Raises TimeValueError naming the text when it is not one."""
    try:
        return datetime.fromisoformat(text.replace("Z", "+00:00"))
    except ValueError:
        raise TimeValueError(f"{text!r}: expected ISO-8601 (2024-05-01T08:30) or unix seconds") from None


def parse_instant(text: str) -> Instant:
    """``--at`` text as an Instant: unix seconds, or ISO-8601 (without a zone: UTC).

    Raises TimeValueError naming the text when it is neither."""
    try:
        seconds = float(text)
    except ValueError:
        pass
    else:
        return Instant.of(check_seconds(seconds, repr(text)))
    return Instant.of(parse_iso(text))


def now() -> Instant:
    """This moment: its seconds, and the part of day of the machine's wall clock (a time with a
    zone keeps its own wall clock; "now" is the one time whose zone is the machine's)."""
    return Instant.of(datetime.now().astimezone())


def format_clock(seconds: float, timespec: str = "seconds") -> str:
    """ISO text of unix seconds in the one rule's clock (UTC, written with its +00:00)."""
    return clock(seconds).isoformat(timespec=timespec)


def is_idle_gap(previous_end: float | None, start: float, threshold: float = IDLE_THRESHOLD_S) -> bool:
    """True when the pause from the last action's end to ``start`` is an odb:IdleTask."""
    return previous_end is not None and start - previous_end >= threshold


@dataclass(frozen=True)
class Instant:
    """A logged time: unix seconds for the interval, wall-clock part of day for odb:TimeOfDay
    (None on a sequence clock, where the seconds are a position and there is no part of day)."""

    seconds: float
    part_of_day: str | None

    @staticmethod
    def of(moment: Moment) -> Instant:
        """A datetime keeps its part of day as written; seconds get their UTC part of day."""
        if isinstance(moment, Instant):
            return moment
        if isinstance(moment, datetime):
            return Instant(seconds_of(moment), time_of_day(moment))
        if isinstance(moment, bool) or not isinstance(moment, (int, float)):
            raise TimeValueError(f"a time must be a datetime or unix seconds, got {moment!r}")
        seconds = check_seconds(float(moment), repr(moment))
        return Instant(seconds, part_of_day_at(seconds))


def sequence_instant(position: float) -> Instant:
    """Position ``position`` of a time-less log on the sequence clock: that many seconds after
    the epoch, with no part of the day (action n of a user spans [n, n + 1])."""
    return Instant(check_seconds(float(position), f"position {position!r}"), None)


def has_clock(meta: Mapping[str, object]) -> bool:
    """False for a NEEM logged on the sequence clock (its registry ``meta`` says so)."""
    return meta.get(CLOCK_KEY) != SEQUENCE_CLOCK


#: What callers may pass as a time: a datetime, unix seconds, or an Instant already read.
Moment = datetime | float | int | Instant


def display_zone(name: str | None) -> tzinfo:
    """The zone a person is shown times in (``serve --tz``): the IANA zone ``name``, or the
    machine's own. Showing is all it does: what is stored, ranked and answered keeps the rule
    above. TimeValueError for a zone the machine does not know."""
    if name is None:
        local = datetime.now().astimezone().tzinfo
        return local if local is not None else timezone.utc
    from zoneinfo import ZoneInfo, ZoneInfoNotFoundError

    try:
        return ZoneInfo(name)
    except (ZoneInfoNotFoundError, ValueError):
        raise TimeValueError(f"--tz {name!r}: no such time zone (expected e.g. Europe/Berlin or UTC)") from None


def shown_clock(seconds: float, zone: tzinfo) -> datetime:
    """Unix seconds as the wall clock of ``zone``, for showing a person (``display_zone``)."""
    return datetime.fromtimestamp(seconds, zone)
