"""Convert van Kasteren house A (UbiComp 2008) into chains, an odb and a mapping YAML.

Every sensor firing becomes one action at its start time, named after what the sensor observes
(a reed switch on a cupboard door: ``open_cupboard(cups_cupboard)``), the convention of Almeida &
Azkune (2018) for next-action prediction; the end of a firing (the door closing) is not an
action. The annotated activity around a firing is kept as the extra field ``activity``.
This module also holds the odb and mapping writers that both converters share.
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from datetime import datetime
from pathlib import Path
from typing import Any
from xml.sax.saxutils import escape

import yaml

from oracle.chains import ChainRow, TaskCall, write_chains
from oracle.errors import NeemOracleError

#: Namespace imports of every converted mapping (thesis appendix A).
IMPORTS = {
    "soma": "http://www.ease-crc.org/ont/SOMA.owl#",
    "dul": "http://www.ontologydesignpatterns.org/ont/dul/DUL.owl#",
    "knowrob": "http://knowrob.org/kb/knowrob.owl#",
}
ACTION_DEFAULTS = {"task": "soma:PhysicalTask", "ref_role": False, "target_role": "soma:Patient",
                   "disposition": "soma:Disposition"}

#: Sensor label -> (odb object, task, odb parent).
SENSORS: dict[str, tuple[str, str, str]] = {
    "Microwave": ("microwave", "open_appliance", "_appliance"),
    "Hall-Toilet door": ("hall_toilet_door", "open_door", "_door"),
    "Hall-Bathroom door": ("hall_bathroom_door", "open_door", "_door"),
    "Cups cupboard": ("cups_cupboard", "open_cupboard", "_cupboard"),
    "Fridge": ("fridge", "open_fridge", "_appliance"),
    "Plates cupboard": ("plates_cupboard", "open_cupboard", "_cupboard"),
    "Frontdoor": ("front_door", "open_door", "_door"),
    "Dishwasher": ("dishwasher", "open_appliance", "_appliance"),
    "ToiletFlush": ("toilet_flush", "flush", "_fixture"),
    "Freezer": ("freezer", "open_fridge", "_appliance"),
    "Pans Cupboard": ("pans_cupboard", "open_cupboard", "_cupboard"),
    "Washingmachine": ("washing_machine", "open_appliance", "_appliance"),
    "Groceries Cupboard": ("groceries_cupboard", "open_cupboard", "_cupboard"),
    "Hall-Bedroom door": ("hall_bedroom_door", "open_door", "_door"),
}

SOMA_ODB_MAP = {
    "_door": "soma:Door",
    "_cupboard": "soma:Cupboard",
    "_appliance": "soma:Appliance",
    "_fixture": "soma:DesignedComponent",
    "fridge": "soma:Refrigerator",
    "freezer": "soma:Refrigerator",
    "dishwasher": "soma:Dishwasher",
}

ACTIONS: dict[str, dict[str, Any]] = {
    "open": {"task": "soma:Opening", "ref_role": False, "target_role": "soma:ShapedObject", "disposition": "soma:Enclosing"},
    "open_door": {"parent": "open"},
    "open_cupboard": {"parent": "open", "disposition": "soma:Storage"},
    "open_fridge": {"parent": "open_cupboard"},
    "open_appliance": {"parent": "open"},
    "flush": {"task": "soma:PushingDown", "ref_role": False, "target_role": "soma:Patient", "disposition": "soma:Disposition"},
}

USER = "kasteren-house-a"  # also the NEEM id, which allows no underscores
_STAMP = "%d-%b-%Y %H:%M:%S"
_LABEL = re.compile(r"^\s*\[\s*(\d+)\]\s*'([^']+)'")
_ACTIVITY = re.compile(r"^\s*(\d+)\s*:\s*'([^']+)'")


@dataclass(frozen=True)
class ConvertReport:
    """What a converter wrote."""

    dataset: str
    actions: int
    users: int
    objects: int
    tasks: int
    out: Path

    def __str__(self) -> str:
        return (f"{self.dataset}: {self.actions} actions, {self.users} user(s), {self.objects} odb objects, "
                f"{self.tasks} tasks -> {self.out / 'chains.jsonl'}, {self.out / 'odb'}, {self.out / 'mapping.yaml'}")


# --- shared writers -------------------------------------------------------------------------------
def write_odb(directory: Path, objects: Mapping[str, tuple[str | None, Iterable[str]]]) -> None:
    """One folder per object with a ``manifest.xml``: name, derive parent, tasks as code snippets."""
    for name, (parent, tasks) in objects.items():
        folder = directory / name
        folder.mkdir(parents=True, exist_ok=True)
        lines = ['<?xml version="1.0" encoding="UTF-8"?>', "<object>", f"  <name>{escape(name)}</name>"]
        if parent is not None:
            lines.append(f"  <derive>{escape(parent)}</derive>")
        snippets = sorted(set(tasks))
        if snippets:
            lines.append("  <logic>")
            lines += [f"    <code_snippet>{escape(task)}_sct.yml</code_snippet>" for task in snippets]
            lines.append("  </logic>")
        lines.append("</object>")
        (folder / "manifest.xml").write_text("\n".join(lines) + "\n", encoding="utf-8")


def write_mapping(path: Path, namespace: str, soma_odb_map: Mapping[str, str], actions: Mapping[str, dict[str, Any]],
                  comment: str) -> None:
    """The mapping YAML of thesis appendix A."""
    data = {
        "namespace": namespace,
        "imports": IMPORTS,
        "soma_odb_map": dict(soma_odb_map),
        "root_object": "dul:PhysicalObject",
        "action_defaults": ACTION_DEFAULTS,
        "actions": {name: dict(spec) for name, spec in actions.items()},
    }
    text = "".join(f"# {line}\n" for line in comment.strip().splitlines())
    path.write_text(text + yaml.safe_dump(data, sort_keys=False, width=100), encoding="utf-8")


def prepare_out(out: Path | str) -> Path:
    from oracle.files import private_folder

    out = Path(out)
    try:
        private_folder(out)  # it will hold a person's days: 0700
    except OSError as error:
        raise NeemOracleError(f"{out}: cannot create output folder ({error.strerror})") from None
    return out


# --- van Kasteren ----------------------------------------------------------------------------------
def _read_lines(path: Path) -> list[str]:
    try:
        return path.read_text(encoding="latin-1").splitlines()
    except OSError as error:
        raise NeemOracleError(f"{path}: cannot read ({error.strerror}); is this the kasteren_house_a folder?") from None


def _rows(path: Path, lines: list[str]) -> Iterable[tuple[int, datetime, datetime, int]]:
    for number, line in enumerate(lines, start=1):
        parts = line.strip().split("\t")
        if len(parts) < 3 or not parts[0][:2].isdigit():
            continue
        try:
            start = datetime.strptime(parts[0].strip(), _STAMP)
            end = datetime.strptime(parts[1].strip(), _STAMP)
            ident = int(parts[2])
        except ValueError:
            raise NeemOracleError(f"{path}:{number}: expected 'start<TAB>end<TAB>id', got {line.strip()!r}") from None
        yield number, start, end, ident


def read_kasteren(folder: Path | str) -> list[ChainRow]:
    """The chain of house A: one action per sensor firing, in time order."""
    folder = Path(folder)
    sense = folder / "original" / "kasterenSenseData.txt"
    acts = folder / "original" / "kasterenActData.txt"
    sense_lines, act_lines = _read_lines(sense), _read_lines(acts)
    labels = {int(m.group(1)): m.group(2).strip() for m in map(_LABEL.match, sense_lines) if m}
    activities = {int(m.group(1)): m.group(2).strip() for m in map(_ACTIVITY.match, act_lines) if m}
    intervals = [(start, end, activities.get(ident, str(ident))) for _, start, end, ident in _rows(acts, act_lines)]
    firings = []
    for number, start, end, ident in _rows(sense, sense_lines):
        label = labels.get(ident)
        if label not in SENSORS:
            raise NeemOracleError(f"{sense}:{number}: unknown sensor id {ident} ({label!r})")
        firings.append((start, number, SENSORS[label], max(start, end)))
    if not firings:
        raise NeemOracleError(f"{sense}: no sensor firings found")
    rows = []
    for start, _number, (obj, task, _parent), end in sorted(firings):
        inside = [name for begin, stop, name in intervals if begin <= start <= stop]
        extra = {"activity": inside[-1]} if inside else {}
        # The firing lasts while the sensor is active; the gap after it decides idle periods.
        rows.append(ChainRow(USER, TaskCall(task, (obj,)), start, None, extra=extra, end=end))
    return rows


def convert(folder: Path | str, out: Path | str) -> ConvertReport:
    """Write ``chains.jsonl``, ``odb/`` and ``mapping.yaml`` for house A into ``out``."""
    return write_sensor_home("kasteren", read_kasteren(folder), SENSORS.values(), out, "urn:neem-oracle:odb:kasteren#",
                             SOMA_ODB_MAP, ACTIONS, "van Kasteren house A: sensors as odb objects, what they observe as tasks"
                             " (oracle convert kasteren).")


def write_sensor_home(name: str, rows: list[ChainRow], sensors: Iterable[tuple[str, str, str]], out: Path | str,
                      namespace: str, soma_map: Mapping[str, str], actions: Mapping[str, dict[str, Any]],
                      comment: str) -> ConvertReport:
    """``chains.jsonl``, ``odb/`` and ``mapping.yaml`` of one home's sensor firings into ``out``:
    each sensor (object, the task it observes, its odb parent) an odb object with that task."""
    sensors = list(sensors)
    out = prepare_out(out)
    write_chains(rows, out / "chains.jsonl")
    objects: dict[str, tuple[str | None, list[str]]] = {parent: (None, []) for parent in sorted({s[2] for s in sensors})}
    for obj, task, parent in sensors:
        objects[obj] = (parent, [task])
    write_odb(out / "odb", objects)
    write_mapping(out / "mapping.yaml", namespace, soma_map, actions, comment)
    tasks = {row.action.task for row in rows}
    users = {row.user for row in rows}
    return ConvertReport(name, len(rows), len(users), len(objects), len(tasks), out)
