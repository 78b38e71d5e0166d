"""Reader for EDAN's object database (odb): one folder per object with a ``manifest.xml``.

A manifest names the object, its ``derive`` parents, physical data and ``logic/code_snippet``
entries naming shared-control templates (``pick_from_side_sct.yml`` -> task ``pick_from_side``).
Objects whose name starts with an underscore are abstract; both kinds become OWL classes.
"""

from __future__ import annotations

import math
import re
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from pathlib import Path

from oracle.errors import OntologyError
from oracle.handed import MANIFEST_LIMIT, Handed, handed_files, read_handed
from oracle.xmlguard import check_entities

_NAME = re.compile(r"^[A-Za-z_][A-Za-z0-9_\-]{0,127}$")  # at most 128 characters
_SNIPPET_SUFFIX = re.compile(r"(_sct)?\.(ya?ml)$", re.IGNORECASE)


@dataclass(frozen=True)
class OdbObject:
    """One odb entry as written in its manifest (tasks are its own, not inherited)."""

    name: str
    parents: tuple[str, ...]
    tasks: tuple[str, ...]
    mass: float | None
    dimension: tuple[float, ...] | None
    source: Path

    @property
    def abstract(self) -> bool:
        return self.name.startswith("_")


def task_of_snippet(snippet: str) -> str:
    """``pick_from_side_sct.yml`` -> ``pick_from_side``."""
    base = Path(snippet.strip()).name
    return _SNIPPET_SUFFIX.sub("", base)


def _text(element: ET.Element | None) -> str | None:
    if element is None or element.text is None:
        return None
    text = element.text.strip()
    return text or None


def read_manifest(path: Path, folder: Path | None = None) -> OdbObject:
    """Parse one ``manifest.xml`` (found in the odb ``folder``: no link followed out of it, see
    oracle.handed; its entities bounded, see oracle.xmlguard); errors name the file and the
    offending entry."""
    data = read_handed(path, Handed("manifest", OntologyError, folder), MANIFEST_LIMIT)
    check_entities(data, str(path), OntologyError)
    try:
        root = ET.fromstring(data)
    except ET.ParseError as error:
        line, column = error.position
        raise OntologyError(f"{path}:{line}:{column}: malformed XML ({error.msg})") from None
    if root.tag != "object":
        raise OntologyError(f"{path}: root element must be <object>, found <{root.tag}>")
    name = _text(root.find("name"))
    if name is None:
        raise OntologyError(f"{path}: missing <name>")
    if not _NAME.match(name):
        raise OntologyError(f"{path}: <name> {name!r} is not a valid odb name")
    parents = []
    for element in root.findall("derive"):
        parent = _text(element)
        if parent is None:
            raise OntologyError(f"{path}: empty <derive> in object {name!r}")
        if not _NAME.match(parent):
            raise OntologyError(f"{path}: <derive> {parent!r} of {name!r} is not a valid odb name")
        if parent not in parents:
            parents.append(parent)
    tasks = []
    for element in root.findall("logic/code_snippet"):
        snippet = _text(element)
        if snippet is None:
            raise OntologyError(f"{path}: empty <code_snippet> in object {name!r}")
        task = task_of_snippet(snippet)
        if not _NAME.match(task):
            raise OntologyError(f"{path}: code_snippet {snippet!r} of {name!r} names no valid task")
        if task not in tasks:
            tasks.append(task)
    mass = None
    mass_text = _text(root.find("mass"))
    if mass_text is not None:
        try:
            mass = float(mass_text)
        except ValueError:
            raise OntologyError(f"{path}: <mass> {mass_text!r} of {name!r} is not a number") from None
        if not (math.isfinite(mass) and mass >= 0):
            raise OntologyError(f"{path}: <mass> {mass_text!r} of {name!r} must be a finite number >= 0")
    dimension = None
    dim_text = _text(root.find("dimension"))
    if dim_text is not None:
        try:
            dimension = tuple(float(part) for part in dim_text.split())
        except ValueError:
            raise OntologyError(f"{path}: <dimension> {dim_text!r} of {name!r} is not numbers") from None
        if not all(math.isfinite(part) and part >= 0 for part in dimension):
            raise OntologyError(f"{path}: <dimension> {dim_text!r} of {name!r} must be finite numbers >= 0")
    return OdbObject(name, tuple(parents), tuple(tasks), mass, dimension, path)


def read_odb(directory: Path | str) -> dict[str, OdbObject]:
    """Read every ``*/manifest.xml`` under an odb folder and check parents exist and are acyclic."""
    directory = Path(directory)
    if not directory.is_dir():
        raise OntologyError(f"{directory}: odb folder not found")
    objects: dict[str, OdbObject] = {}
    for manifest in handed_files(directory, "*/manifest.xml", Handed("manifest", OntologyError)):
        obj = read_manifest(manifest, directory)
        if obj.name in objects:
            raise OntologyError(f"{manifest}: object {obj.name!r} is also defined in {objects[obj.name].source}")
        objects[obj.name] = obj
    if not objects:
        raise OntologyError(f"{directory}: no */manifest.xml found; is this an odb folder?")
    for obj in objects.values():
        for parent in obj.parents:
            if parent not in objects:
                raise OntologyError(f"{obj.source}: object {obj.name!r} derives from unknown object {parent!r}")
    _check_acyclic(objects)
    return objects


def _check_acyclic(objects: dict[str, OdbObject]) -> None:
    """Depth-first search with an explicit stack: a derive chain may be thousands deep."""
    state: dict[str, int] = {}  # 1 = on the path, 2 = done
    for root in objects:
        if state.get(root) == 2:
            continue
        path: list[str] = [root]
        pending: list[list[str]] = [list(objects[root].parents)]
        state[root] = 1
        while path:
            if not pending[-1]:
                state[path.pop()] = 2
                pending.pop()
                continue
            parent = pending[-1].pop()
            if state.get(parent) == 2:
                continue
            if state.get(parent) == 1:
                cycle = path[path.index(parent):] + [parent]
                shown = cycle if len(cycle) <= 8 else cycle[:4] + [f"... ({len(cycle) - 6} more)"] + cycle[-2:]
                raise OntologyError(f"{objects[parent].source}: cyclic derive: {' -> '.join(shown)}")
            state[parent] = 1
            path.append(parent)
            pending.append(list(objects[parent].parents))


def inherited_tasks(objects: dict[str, OdbObject], name: str) -> tuple[str, ...]:
    """Own tasks followed by those inherited from every ancestor, each once, in a stable order."""
    seen: list[str] = []
    queue = [name]
    visited: set[str] = set()
    while queue:
        current = queue.pop(0)
        if current in visited:
            continue
        visited.add(current)
        for task in objects[current].tasks:
            if task not in seen:
                seen.append(task)
        queue.extend(objects[current].parents)
    return tuple(seen)
