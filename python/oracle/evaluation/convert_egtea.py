"""Convert EGTEA Gaze+ action annotations (RULSTM split files) into chains, an odb and a mapping.

One user per subject (``P07``, ``OP04``); the subject's sessions (videos) follow each other in
recipe order (the data has no recording order and no clock time, so rows carry no time) and the
actions of a session in frame order. ``Take_eating:utensil`` becomes ``take(eating_utensil)``;
the session is kept as the extra field ``session``. Split 1's training and validation files
together hold every annotated instance once.
"""

from __future__ import annotations

import csv
import re
from collections import defaultdict
from collections.abc import Callable, Iterable
from pathlib import Path

from oracle.chains import ChainRow, TaskCall, write_chains
from oracle.errors import NeemOracleError
from oracle.evaluation.convert_kasteren import ConvertReport, prepare_out, write_mapping, write_odb

SPLIT_FILES = ("training1.csv", "validation1.csv")

#: Verb (snake_case) -> mapping entry; verbs not listed fall back to action_defaults.
ACTIONS: dict[str, dict[str, object]] = {
    "take": {"task": "soma:PickingUp", "ref_role": False, "target_role": "soma:MovedObject", "disposition": "soma:Graspability"},
    "put": {"task": "soma:PuttingDown", "ref_role": False, "target_role": "soma:MovedObject", "disposition": "soma:Graspability"},
    "move_around": {"task": "soma:Positioning", "ref_role": False, "target_role": "soma:MovedObject", "disposition": "soma:Graspability"},
    "open": {"task": "soma:Opening", "ref_role": False, "target_role": "soma:ShapedObject", "disposition": "soma:Enclosing"},
    "close": {"task": "soma:Closing", "ref_role": False, "target_role": "soma:ShapedObject", "disposition": "soma:Enclosing"},
    "operate": {"task": "soma:Actuating", "ref_role": False, "target_role": "soma:Patient", "disposition": "soma:Disposition"},
    "turn_on": {"parent": "operate"},
    "turn_off": {"parent": "operate"},
    "cut": {"task": "soma:Cutting", "ref_role": False, "target_role": "soma:CutObject", "disposition": "soma:Disposition"},
    "divide_pull_apart": {"task": "soma:ModifyingPhysicalObject", "ref_role": False, "target_role": "soma:AlteredObject"},
    "crack": {"parent": "divide_pull_apart"},
    "wash": {"task": "soma:Cleaning", "ref_role": False, "target_role": "soma:Patient", "disposition": "soma:Disposition"},
    "clean_wipe": {"parent": "wash"},
    "mix": {"task": "soma:Mixing", "ref_role": False, "target_role": "soma:Patient"},
    "pour": {"task": "soma:Pouring", "ref_role": False, "target_role": "soma:PouredObject", "disposition": "soma:Disposition"},
    "spread": {"parent": "pour"},
    "squeeze": {"task": "soma:Squeezing", "ref_role": False, "target_role": "soma:Patient"},
    "compress": {"task": "soma:PushingDown", "ref_role": False, "target_role": "soma:Patient"},
    "inspect_read": {"task": "soma:LookingAt", "ref_role": False, "target_role": "soma:Patient"},
}

#: Abstract odb parents and the SOMA/DUL classes they stand for.
PARENTS = {
    "_crockery": "soma:Crockery",
    "_tool": "soma:DesignedTool",
    "_container": "soma:DesignedContainer",
    "_storage": "soma:DesignedContainer",
    "_appliance": "soma:Appliance",
    "_fixture": "soma:DesignedComponent",
    "_produce": "dul:BiologicalObject",
    "_food": "dul:DesignedSubstance",
    "_thing": "dul:DesignedArtifact",
}

#: Noun (snake_case) -> (odb parent, own SOMA class or None to inherit the parent's).
NOUNS: dict[str, tuple[str, str | None]] = {
    "eating_utensil": ("_tool", "soma:Cutlery"),
    "cooking_utensil": ("_tool", None),
    "cutting_board": ("_tool", None),
    "sponge": ("_tool", None),
    "strainer": ("_tool", None),
    "paper_towel": ("_tool", None),
    "plate": ("_crockery", "soma:Plate"),
    "bowl": ("_crockery", "soma:Bowl"),
    "cup": ("_crockery", "soma:Cup"),
    "pan": ("_crockery", "soma:Pan"),
    "pot": ("_crockery", "soma:Pot"),
    "fridge": ("_storage", "soma:Refrigerator"),
    "fridge_drawer": ("_storage", "soma:Drawer"),
    "drawer": ("_storage", "soma:Drawer"),
    "cabinet": ("_storage", "soma:Cupboard"),
    "dishwasher": ("_appliance", "soma:Dishwasher"),
    "microwave": ("_appliance", None),
    "stove": ("_appliance", "soma:Stove"),
    "faucet": ("_fixture", "soma:Tap"),
    "counter": ("_fixture", "soma:Countertop"),
    "hand": ("_thing", "soma:Hand"),
    "recipe": ("_thing", None),
    "trash": ("_thing", None),
    "bread": ("_food", "soma:Bread"),
    "bacon": ("_food", None),
    "patty": ("_food", None),
    "cheese": ("_food", None),
    "pasta": ("_food", None),
    "mixture": ("_food", None),
    "condiment": ("_food", None),
    "seasoning": ("_food", None),
    "oil": ("_food", None),
    "sandwich": ("_food", "soma:Dish"),
    "water": ("_food", "soma:Fluid"),
    "washing_liquid": ("_food", None),
    "tomato": ("_produce", None),
    "cucumber": ("_produce", None),
    "carrot": ("_produce", None),
    "onion": ("_produce", None),
    "bell_pepper": ("_produce", None),
    "lettuce": ("_produce", None),
    "olive": ("_produce", None),
    "egg": ("_produce", None),
}

_SNAKE = re.compile(r"[^a-z0-9]+")


def snake(text: str) -> str:
    """``Divide/Pull Apart`` -> ``divide_pull_apart``, ``eating:utensil`` -> ``eating_utensil``."""
    return _SNAKE.sub("_", text.strip().lower()).strip("_")


def _container_noun(noun: str) -> tuple[str, str | None]:
    if noun.endswith("_container") or noun == "grocery_bag":
        return ("_container", None)
    return ("_thing", None)


def read_actions(path: Path) -> dict[int, TaskCall]:
    """``actions.csv``: action id -> task call, e.g. 2 -> take(eating_utensil)."""
    try:
        handle = path.open(newline="", encoding="utf-8")
    except OSError as error:
        raise NeemOracleError(f"{path}: cannot read ({error.strerror}); is this the egtea_gaze_plus folder?") from None
    calls: dict[int, TaskCall] = {}
    with handle:
        for number, row in enumerate(csv.reader(handle, skipinitialspace=True), start=1):
            if not row:
                continue
            if len(row) != 3 or "_" not in row[2]:
                raise NeemOracleError(f"{path}:{number}: expected 'id, verb_noun ids, Verb_noun', got {row!r}")
            verb, noun = row[2].split("_", 1)
            try:
                calls[int(row[0])] = TaskCall(snake(verb), (snake(noun),))
            except ValueError:
                raise NeemOracleError(f"{path}:{number}: action id {row[0]!r} is not a number") from None
    return calls


def read_egtea(folder: Path | str) -> list[ChainRow]:
    """One chain per subject: sessions in recipe order, actions in frame order."""
    folder = Path(folder)
    calls = read_actions(folder / "actions.csv")
    instances: dict[int, tuple[str, int, int]] = {}
    for name in SPLIT_FILES:
        path = folder / name
        try:
            handle = path.open(newline="", encoding="utf-8")
        except OSError as error:
            raise NeemOracleError(f"{path}: cannot read ({error.strerror})") from None
        with handle:
            for number, row in enumerate(csv.reader(handle), start=1):
                if not row:
                    continue
                try:
                    ident, video, start, action = int(row[0]), row[1], int(row[2]), int(row[6])
                except (ValueError, IndexError):
                    raise NeemOracleError(f"{path}:{number}: expected 7 columns id,video,start,end,verb,noun,action") from None
                if action not in calls:
                    raise NeemOracleError(f"{path}:{number}: unknown action id {action}")
                instances[ident] = (video, start, action)
    sessions: dict[str, list[tuple[int, int, int]]] = defaultdict(list)
    for ident, (video, start, action) in instances.items():
        sessions[video].append((start, ident, action))
    rows = []
    for video in sorted(sessions, key=lambda v: (v.split("-")[0], v.split("-")[1] if "-" in v else "", v)):
        subject = video.split("-")[0]
        for _start, _ident, action in sorted(sessions[video]):
            rows.append(ChainRow(subject, calls[action], None, None, extra={"session": video}))
    if not rows:
        raise NeemOracleError(f"{folder}: no action instances in {', '.join(SPLIT_FILES)}")
    return rows


def convert(folder: Path | str, out: Path | str) -> ConvertReport:
    """Write ``chains.jsonl``, ``odb/`` and ``mapping.yaml`` for EGTEA Gaze+ into ``out``."""
    folder = Path(folder)
    rows = read_egtea(folder)
    return write_cooking_set("egtea", rows, read_actions(folder / "actions.csv").values(), out,
                             "urn:neem-oracle:odb:egtea#",
                             "EGTEA Gaze+: nouns as odb objects, verbs as tasks (oracle convert egtea).")


def write_cooking_set(name: str, rows: list[ChainRow], calls: Iterable[TaskCall], out: Path | str, namespace: str,
                      comment: str, class_key: Callable[[str], str] = lambda noun: noun) -> ConvertReport:
    """``chains.jsonl``, ``odb/`` and ``mapping.yaml`` of verb(noun) actions into ``out``: each noun
    an odb object (its parent and SOMA class from NOUNS / the container rule, looked up by
    ``class_key(noun)``), each verb a task (ACTIONS, else the action defaults)."""
    out = prepare_out(out)
    write_chains(rows, out / "chains.jsonl")
    tasks_of: dict[str, set[str]] = defaultdict(set)
    for call in calls:
        tasks_of[call.args[0]].add(call.task)
    objects: dict[str, tuple[str | None, list[str]]] = {parent: (None, []) for parent in PARENTS}
    soma_map = dict(PARENTS)
    for noun, tasks in sorted(tasks_of.items()):
        key = class_key(noun)
        parent, cls = NOUNS.get(key) or _container_noun(key)
        objects[noun] = (parent, sorted(tasks))
        if cls is not None:
            soma_map[noun] = cls
    write_odb(out / "odb", objects)
    verbs = sorted({task for tasks in tasks_of.values() for task in tasks})
    actions = {verb: spec for verb, spec in ACTIONS.items()}
    for verb in verbs:
        actions.setdefault(verb, {})
    write_mapping(out / "mapping.yaml", namespace, soma_map, actions, comment)
    users = {row.user for row in rows}
    return ConvertReport(name, len(rows), len(users), len(objects), len(verbs), out)
