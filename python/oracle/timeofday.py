"""Time of day: the one place where clock times become odb:Morning/Midday/Evening/Night.

The thesis (3.4) names the four parts of the day but not their hours; the boundaries below are
this project's choice and are documented in docs/ontology.md.
"""

from __future__ import annotations

from datetime import datetime

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


def time_of_day(moment: datetime | float | int) -> str:
    """Return the local name of the odb:TimeOfDay subclass for a clock time.

    A number is taken as the hour of the day (0 <= h < 24, fractions allowed); a datetime
    uses its own (local, as logged) hour and minute.
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
