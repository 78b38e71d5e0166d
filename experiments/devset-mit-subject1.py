"""Development set (never reported): convert MIT PlaceLab subject 1 (Munguia Tapia 2004) into chains, an odb and a mapping.

Follows oracle.evaluation.convert_kasteren's conventions: every sensor firing (a reed switch
activating) becomes one action at its start time, named after what the sensor observes, by the
sensor's object type (``Kitchen,Cabinet`` id 132 -> ``open_cupboard(kitchen_cabinet_132)``,
``Bathroom,Toilet Flush`` -> ``flush(bathroom_toilet_flush)``); the end of a firing is not an
action but is kept as the row's ``end``. The annotated activity is kept as the extra field
``activity``. An object is ``<location>_<object>`` in snake_case, with ``_<sensor id>`` appended
when several sensors share a location and object.

The source lists firings per annotated activity (``activities_data.csv``: a header row
``label,m/d/yyyy,start,end`` and then rows of sensor ids, objects, activation and deactivation
times), so firings outside any annotated activity are not in the data, and a firing inside two
overlapping activities is listed twice: it is kept once, with the activity that started last
(convert_kasteren keeps the last annotated interval around a firing). Times of day before the
activity's start in an activity that crosses midnight belong to the next day; a deactivation
before its activation is on the next day.

RAW_FOLDER holds, byte for byte, datasets/mitlab/subject1/{sensors,Activities,activities_data}.csv
of tcsvn/pyadlml @ a2a400b0e2b39f16c5b8575259e0cda796bba94e (licence not stated; cite Munguia Tapia,
Intille and Larson, Pervasive 2004). Never copied into the project.

usage: python experiments/devset-mit-subject1.py RAW_FOLDER OUT_FOLDER
"""

from __future__ import annotations

import csv
import sys
from datetime import date, datetime, time, timedelta
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "python"))

from oracle.chains import ChainRow, TaskCall  # noqa: E402
from oracle.errors import NeemOracleError  # noqa: E402
from oracle.evaluation.convert_egtea import snake  # noqa: E402
from oracle.evaluation.convert_kasteren import ConvertReport, write_sensor_home  # noqa: E402
from oracle.evaluation.convert_kasteren import ACTIONS as KASTEREN_ACTIONS  # noqa: E402
from oracle.evaluation.convert_kasteren import SOMA_ODB_MAP as KASTEREN_SOMA  # noqa: E402

USER = "mit-subject1"  # also the NEEM id, which allows no underscores

#: Sensor object type (as in sensors.csv) -> (task, odb parent); by type only, the same for every sensor of it.
TYPES: dict[str, tuple[str, str]] = {
    "Door": ("open_door", "_door"),
    "Window": ("open_window", "_fixture"),
    "Cabinet": ("open_cupboard", "_cupboard"),
    "Medicine cabinet": ("open_cupboard", "_cupboard"),
    "Closet": ("open_cupboard", "_cupboard"),
    "Drawer": ("open_drawer", "_drawer"),
    "Containers": ("open_container", "_container"),
    "Cereal": ("open_container", "_container"),
    "Jewelry box": ("open_container", "_container"),
    "Refrigerator": ("open_fridge", "_appliance"),
    "Freezer": ("open_fridge", "_appliance"),
    "Microwave": ("open_appliance", "_appliance"),
    "Oven": ("open_appliance", "_appliance"),
    "Dishwasher": ("open_appliance", "_appliance"),
    "Washing Machine": ("open_appliance", "_appliance"),
    "Laundry Dryer": ("open_appliance", "_appliance"),
    "Toaster": ("open_appliance", "_appliance"),
    "Light switch": ("turn_on", "_fixture"),
    "Lamp": ("turn_on", "_appliance"),
    "Burner": ("turn_on", "_appliance"),
    "Coffee machine": ("turn_on", "_appliance"),
    "Exhaust Fan": ("turn_on", "_appliance"),
    "Garbage disposal": ("turn_on", "_appliance"),
    "DVD": ("turn_on", "_appliance"),
    "Sink faucet - hot": ("turn_on", "_fixture"),
    "Sink faucet - cold": ("turn_on", "_fixture"),
    "Shower faucet": ("turn_on", "_fixture"),
    "Toilet Flush": ("flush", "_fixture"),
}

#: Object-type SOMA classes where the type names one the kasteren/egtea converters already use.
TYPE_CLASSES = {
    "Refrigerator": "soma:Refrigerator",
    "Freezer": "soma:Refrigerator",
    "Dishwasher": "soma:Dishwasher",
    "Sink faucet - hot": "soma:Tap",
    "Sink faucet - cold": "soma:Tap",
    "Shower faucet": "soma:Tap",
}

SOMA_ODB_MAP = {
    **{k: v for k, v in KASTEREN_SOMA.items() if k.startswith("_")},
    "_drawer": "soma:Drawer",
    "_container": "soma:DesignedContainer",
}

ACTIONS: dict[str, dict[str, Any]] = {
    **KASTEREN_ACTIONS,
    "open_window": {"parent": "open"},
    "open_drawer": {"parent": "open_cupboard"},
    "open_container": {"parent": "open", "disposition": "soma:Storage"},
    "turn_on": {"task": "soma:Actuating", "ref_role": False, "target_role": "soma:Patient", "disposition": "soma:Disposition"},
}


def _read_csv(path: Path) -> list[list[str]]:
    try:
        with path.open(newline="", encoding="latin-1") as handle:
            return [row for row in csv.reader(handle)]
    except OSError as error:
        raise NeemOracleError(f"{path}: cannot read ({error.strerror}); is this the MIT subject1 folder?") from None


def read_sensors(path: Path) -> dict[str, tuple[str, str, str, str]]:
    """sensors.csv (id,location,object) -> id -> (odb object, task, odb parent, object type)."""
    rows = [[cell.strip() for cell in row] for row in _read_csv(path) if row]
    pairs: dict[tuple[str, str], int] = {}
    for number, row in enumerate(rows, start=1):
        if len(row) != 3 or not row[0].isdigit():
            raise NeemOracleError(f"{path}:{number}: expected 'id,location,object', got {row!r}")
        if row[2] not in TYPES:
            raise NeemOracleError(f"{path}:{number}: sensor object type {row[2]!r} has no task")
        pairs[(row[1], row[2])] = pairs.get((row[1], row[2]), 0) + 1
    sensors = {}
    for ident, location, kind in rows:
        name = snake(f"{location} {kind}") + (f"_{ident}" if pairs[(location, kind)] > 1 else "")
        task, parent = TYPES[kind]
        sensors[ident] = (name, task, parent, kind)
    return sensors


def _clock(text: str) -> time:
    hour, minute, second = (int(part) for part in text.strip().split(":"))
    return time(hour, minute, second)


def read_mit(folder: Path | str) -> list[ChainRow]:
    """The chain of subject 1: one action per sensor firing, in time order."""
    folder = Path(folder)
    sensors = read_sensors(folder / "sensors.csv")
    path = folder / "activities_data.csv"
    rows = [[cell.strip() for cell in row] for row in _read_csv(path)]
    firings: dict[tuple[str, datetime], tuple[datetime, datetime, str]] = {}
    number = 0
    while number < len(rows):
        if not any(rows[number]):
            number += 1
            continue
        block = rows[number:number + 5]
        try:
            label, day_text, start_text, end_text = block[0]
            month, day_number, year = (int(part) for part in day_text.split("/"))
            day = date(year, month, day_number)
            start, end = _clock(start_text), _clock(end_text)
            ids, _objects, ons, offs = block[1], block[2], block[3], block[4]
            if not (len(ids) == len(ons) == len(offs)):
                raise ValueError
            begin = datetime.combine(day, start)
            for ident, on_text, off_text in zip(ids, ons, offs):
                on = _clock(on_text)
                on_day = day + timedelta(days=1) if end < start and on < start else day
                fired = datetime.combine(on_day, on)
                stopped = datetime.combine(on_day, _clock(off_text))
                if stopped < fired:
                    stopped += timedelta(days=1)
                if ident not in sensors:
                    raise NeemOracleError(f"{path}:{number + 2}: unknown sensor id {ident}")
                key = (ident, fired)
                if key not in firings or firings[key][0] <= begin:
                    firings[key] = (begin, stopped, label)
        except (ValueError, IndexError):
            raise NeemOracleError(f"{path}:{number + 1}: expected a 5-row activity block "
                                  "(label,m/d/yyyy,start,end; ids; objects; on times; off times)") from None
        number += 5
    if not firings:
        raise NeemOracleError(f"{path}: no sensor firings found")
    chain = []
    for (ident, fired), (_begin, stopped, label) in sorted(firings.items(), key=lambda item: (item[0][1], item[0][0])):
        obj, task, _parent, _kind = sensors[ident]
        chain.append(ChainRow(USER, TaskCall(task, (obj,)), fired, None, extra={"activity": label}, end=max(fired, stopped)))
    return chain


def convert(folder: Path | str, out: Path | str) -> ConvertReport:
    """Write ``chains.jsonl``, ``odb/`` and ``mapping.yaml`` for subject 1 into ``out``."""
    folder = Path(folder)
    rows = read_mit(folder)
    sensors = read_sensors(folder / "sensors.csv")
    soma_map = dict(SOMA_ODB_MAP)
    soma_map.update({obj: TYPE_CLASSES[kind] for obj, _task, _parent, kind in sensors.values() if kind in TYPE_CLASSES})
    return write_sensor_home(
        "mit-subject1", rows, ((obj, task, parent) for obj, task, parent, _kind in sensors.values()), out,
        "urn:neem-oracle:odb:mit-subject1#", soma_map, ACTIONS,
        "MIT PlaceLab subject 1 (a development set): sensors as odb objects, what they observe as tasks"
        " (experiments/devset-mit-subject1.py).",
    )


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__.strip().splitlines()[-1])
    try:
        print(convert(sys.argv[1], sys.argv[2]))
    except NeemOracleError as error:
        sys.exit(f"error: {error}")
