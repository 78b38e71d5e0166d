"""Development set (never reported): convert van Kasteren houses B and C (Pervasive 2010) into chains, an odb and a mapping.

Houses B and C are two other homes of the study that recorded house A (the reported set): house B
one resident, 21 Jul - 17 Aug 2009, 23 sensors (reed and mercury switches, a float, PIRs and pressure
mats); house C one resident, 19 Nov - 8 Dec 2008, 21 sensors of the same kinds. Neither shares a day
or a sensor with house A.

Follows oracle.evaluation.convert_kasteren's conventions: every sensor firing (the sensor going
on) becomes one action at its start time, named after what the sensor observes, by the kind of
sensor (``cupboard plates`` -> ``open_cupboard(plates_cupboard)``, ``toilet flush`` ->
``flush(toilet_flush)``); the end of a firing is not an action but is kept as the row's ``end``.
The annotated activity around a firing (the last annotated interval containing it) is kept as the
extra field ``activity``; every firing is kept, annotated or not. Kinds house A has no sensor of get
tasks of their own: a PIR ``move_at(<place>)``, a pressure mat on a bed ``lie_on``, on a seat
``sit_on``, a drawer ``open_drawer`` and a window ``open_window`` (as experiments/devset-mit-subject1.py),
a float or flow sensor on a sink ``turn_on`` (a tap). ``--object-sensors`` keeps only the sensors on
objects, the kinds house A has (switches on doors, cupboards, drawers, appliances, flushes and
taps), dropping the PIRs and pressure mats.

Sensor names are those of the dataset's label files (Dutch, as translated by pyadlml's
``_dev_map_House_B``/``_dev_map_House_C``, tcsvn/pyadlml @ e0351571b74776454290635eb1011f9d65749076,
pyadlml/dataset/_datasets/kasteren_2010.py). House B's sensor 23 has no label in either and fires
twice: it is skipped (as pyadlml does); any other unknown id is an error. Some house C reed switches
report the closed state (firings of hours): kept as they are, like every other firing.

RAW_FOLDER holds, byte for byte, source/source-code/data_conversion/house{B,C}-{ss,as}.txt of
agnesvanbelle/TL @ 22d0103a65b7478ddb285d3beffe91f9eb1a5975 (tab-separated ``start<TAB>end<TAB>id``,
``dd-Mon-yyyy HH:MM:SS``: the sensor and activity structures of van Kasteren's tlDatasets.zip,
https://sites.google.com/site/tim0306/, as that repository's data README says; the activity ids are
those of source/source-code/our_project_project/data/house{B,C}.activity_names there). Licence not
stated; cite T.L.M. van Kasteren, G. Englebienne and B.J.A. Kroese, "Transferring Knowledge of
Activity Recognition across Sensor Networks", Pervasive 2010. Never copied into the project.

usage: python experiments/devset-kasteren-bc.py {B,C} RAW_FOLDER OUT_FOLDER [--object-sensors]
"""

from __future__ import annotations

import sys
from datetime import datetime
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "python"))

from oracle.chains import ChainRow, TaskCall  # noqa: E402
from oracle.errors import NeemOracleError  # noqa: E402
from oracle.evaluation.convert_kasteren import ConvertReport, write_sensor_home  # noqa: E402
from oracle.evaluation.convert_kasteren import ACTIONS as KASTEREN_ACTIONS  # noqa: E402
from oracle.evaluation.convert_kasteren import SOMA_ODB_MAP as KASTEREN_SOMA  # noqa: E402

#: Sensor kinds on objects (kept by --object-sensors); the others are PIRs and pressure mats.
OBJECT_TASKS = {"open_door", "open_cupboard", "open_fridge", "open_appliance", "open_drawer", "open_window", "flush",
                "turn_on"}

#: Sensor id -> (odb object, task, odb parent); the label of the dataset's label file in the comment.
SENSORS: dict[str, dict[int, tuple[str, str, str]]] = {
    "B": {
        1: ("toilet_door", "open_door", "_door"),                   # toilet door
        3: ("fridge", "open_fridge", "_appliance"),                 # fridge
        5: ("groceries_cupboard", "open_cupboard", "_cupboard"),    # cupboard groceries
        6: ("toilet_flush", "flush", "_fixture"),                   # toilet flush
        7: ("front_door", "open_door", "_door"),                    # frontdoor
        9: ("plates_cupboard", "open_cupboard", "_cupboard"),       # cupboard plates
        10: ("bedroom_door", "open_door", "_door"),                 # Bedroom door
        12: ("bed_right", "lie_on", "_furniture"),                  # press bed rechts
        13: ("bed_left", "lie_on", "_furniture"),                   # press bed links
        14: ("cutlery_drawer", "open_drawer", "_drawer"),           # kwik cutlary drawer
        15: ("stove_lid", "open_appliance", "_appliance"),          # kwik stove lid
        16: ("bedroom", "move_at", "_place"),                       # PIR slaapkamer
        18: ("dresser", "open_drawer", "_drawer"),                  # kwik dresser
        19: ("bathroom", "move_at", "_place"),                      # PIR badkamer
        20: ("office_chair", "sit_on", "_furniture"),               # drukmat bureaustoel (piano)
        21: ("kitchen_sink", "turn_on", "_fixture"),                # gootsteen float
        22: ("server_corner_chair", "sit_on", "_furniture"),        # drukmat stoel serverhoekje
        24: ("balcony_door", "open_door", "_door"),                 # balkon deur
        25: ("window", "open_window", "_fixture"),                  # raam
        26: ("toaster", "open_appliance", "_appliance"),            # toaster
        27: ("microwave", "open_appliance", "_appliance"),          # magnetron
        28: ("kitchen", "move_at", "_place"),                       # PIR keuken
    },
    "C": {
        5: ("bed_right", "lie_on", "_furniture"),                   # mat bed rechts, drukmat
        6: ("couch", "sit_on", "_furniture"),                       # mat bank, huiskamer
        7: ("freezer", "open_fridge", "_appliance"),                # vriezer, reed
        8: ("upstairs_toilet_flush", "flush", "_fixture"),          # toilet flush boven
        10: ("downstairs_toilet_flush", "flush", "_fixture"),       # toilet flush beneden
        15: ("keys_drawer", "open_drawer", "_drawer"),              # la sleutels
        16: ("bathroom_door", "open_door", "_door"),                # badkamer klapdeur links
        18: ("cutlery_drawer", "open_drawer", "_drawer"),           # bestek la, kwik
        20: ("pans_cupboard", "open_cupboard", "_cupboard"),        # kastje pannen, reed
        21: ("microwave", "open_appliance", "_appliance"),          # magnetron, reed
        22: ("leftovers_cupboard", "open_cupboard", "_cupboard"),   # kastje restjesbakjes, reed
        23: ("plates_spices_cupboard", "open_cupboard", "_cupboard"),  # kastje borden/kruiden, reed
        25: ("downstairs_toilet_door", "open_door", "_door"),       # deur toilet beneden
        27: ("cups_cupboard", "open_cupboard", "_cupboard"),        # kastje cups/bowl/tuna, reed
        28: ("front_door", "open_door", "_door"),                   # voordeur, reed
        29: ("bedroom_door", "open_door", "_door"),                 # deur slaapkamer
        30: ("fridge", "open_fridge", "_appliance"),                 # koelkast, reed
        35: ("bathtub", "move_at", "_place"),                       # badkuip, pir
        36: ("dresser", "move_at", "_place"),                       # dressoir, pir
        38: ("upstairs_washbasin", "turn_on", "_fixture"),          # wasbak boven, flush
        39: ("bed_left", "lie_on", "_furniture"),                   # mat bed links, drukmat
    },
}
#: Sensor ids without a label, skipped.
UNLABELLED = {"B": {23}, "C": set()}

#: Activity ids of both houses (house{B,C}.activity_names).
ACTIVITIES = {1: "leave-house", 4: "use-toilet", 5: "take-shower", 6: "brush-teeth", 10: "go-to-bed",
              13: "prep-breakfast", 15: "prep-dinner", 17: "get-drink"}

SOMA_ODB_MAP = {
    **{k: v for k, v in KASTEREN_SOMA.items() if k.startswith("_")},
    "_drawer": "soma:Drawer",
    "_furniture": "soma:DesignedFurniture",
    "_place": "soma:Room",
}
#: Objects whose own SOMA class the kasteren/MIT converters already use.
OBJECT_CLASSES = {"fridge": "soma:Refrigerator", "freezer": "soma:Refrigerator", "stove_lid": "soma:Stove",
                  "kitchen_sink": "soma:Tap", "upstairs_washbasin": "soma:Tap", "kitchen": "soma:Kitchen"}

ACTIONS: dict[str, dict[str, Any]] = {
    **KASTEREN_ACTIONS,
    "open_window": {"parent": "open"},
    "open_drawer": {"parent": "open_cupboard"},
    "turn_on": {"task": "soma:Actuating", "ref_role": False, "target_role": "soma:Patient", "disposition": "soma:Disposition"},
    "rest_on": {"task": "soma:PhysicalTask", "ref_role": False, "target_role": "soma:Location", "disposition": "soma:Disposition"},
    "lie_on": {"parent": "rest_on"},
    "sit_on": {"parent": "rest_on"},
    "move_at": {"task": "soma:PhysicalTask", "ref_role": False, "target_role": "soma:Location", "disposition": "soma:Disposition"},
}

_STAMP = "%d-%b-%Y %H:%M:%S"


def _user(house: str) -> str:
    return f"kasteren-house-{house.lower()}"  # also the NEEM id, which allows no underscores


def _rows(path: Path) -> list[tuple[int, datetime, datetime, int]]:
    try:
        lines = path.read_text(encoding="latin-1").splitlines()
    except OSError as error:
        raise NeemOracleError(f"{path}: cannot read ({error.strerror}); is this the data_conversion folder?") from None
    rows = []
    for number, line in enumerate(lines, start=1):
        parts = line.strip().split("\t")
        if not line.strip():
            continue
        try:
            rows.append((number, datetime.strptime(parts[0].strip(), _STAMP), datetime.strptime(parts[1].strip(), _STAMP),
                         int(parts[2])))
        except (ValueError, IndexError):
            raise NeemOracleError(f"{path}:{number}: expected 'start<TAB>end<TAB>id', got {line.strip()!r}") from None
    return rows


def sensors_of(house: str, object_sensors: bool) -> dict[int, tuple[str, str, str]]:
    return {ident: spec for ident, spec in SENSORS[house].items() if not object_sensors or spec[1] in OBJECT_TASKS}


def read_house(house: str, folder: Path | str, object_sensors: bool = False) -> list[ChainRow]:
    """The chain of one house: one action per sensor firing, in time order."""
    folder = Path(folder)
    sense, acts = folder / f"house{house}-ss.txt", folder / f"house{house}-as.txt"
    intervals = [(start, end, ACTIVITIES.get(ident, str(ident))) for _, start, end, ident in _rows(acts)]
    kept = sensors_of(house, object_sensors)
    firings = []
    for number, start, end, ident in _rows(sense):
        if ident in UNLABELLED[house] or (ident in SENSORS[house] and ident not in kept):
            continue
        if ident not in SENSORS[house]:
            raise NeemOracleError(f"{sense}:{number}: unknown sensor id {ident}")
        firings.append((start, number, kept[ident], max(start, end)))
    if not firings:
        raise NeemOracleError(f"{sense}: no sensor firings found")
    rows = []
    user = _user(house)
    for start, _number, (obj, task, _parent), end in sorted(firings):
        inside = [name for begin, stop, name in intervals if begin <= start <= stop]
        extra = {"activity": inside[-1]} if inside else {}
        rows.append(ChainRow(user, TaskCall(task, (obj,)), start, None, extra=extra, end=end))
    return rows


def convert(house: str, folder: Path | str, out: Path | str, object_sensors: bool = False) -> ConvertReport:
    """Write ``chains.jsonl``, ``odb/`` and ``mapping.yaml`` for one house into ``out``."""
    rows = read_house(house, folder, object_sensors)
    sensors = sensors_of(house, object_sensors)
    soma_map = dict(SOMA_ODB_MAP)
    soma_map.update({obj: OBJECT_CLASSES[obj] for obj, _task, _parent in sensors.values() if obj in OBJECT_CLASSES})
    used = {parent for _obj, _task, parent in sensors.values()}
    soma_map = {k: v for k, v in soma_map.items() if not k.startswith("_") or k in used}
    which = "object sensors only" if object_sensors else "all sensors"
    name = _user(house) + ("-objects" if object_sensors else "")
    return write_sensor_home(
        name, rows, sensors.values(), out, f"urn:neem-oracle:odb:{_user(house)}#", soma_map, ACTIONS,
        f"van Kasteren house {house} (a development set, {which}): sensors as odb objects, what they observe as tasks"
        " (experiments/devset-kasteren-bc.py).",
    )


if __name__ == "__main__":
    args = [arg for arg in sys.argv[1:] if arg != "--object-sensors"]
    if len(args) != 3 or args[0] not in SENSORS or len(sys.argv) - len(args) > 2:
        sys.exit(__doc__.strip().splitlines()[-1])
    try:
        print(convert(args[0], args[1], args[2], object_sensors="--object-sensors" in sys.argv[1:]))
    except NeemOracleError as error:
        sys.exit(f"error: {error}")
