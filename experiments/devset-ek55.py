"""Development set (never reported): convert EPIC-Kitchens-55 action annotations (RULSTM split files) into chains, an odb and a mapping.

Follows oracle.evaluation.convert_egtea's conventions: one user per participant (``P01``); the
participant's sessions (videos) follow each other in video-id order (the data has no clock time,
so rows carry no time) and the actions of a session in frame order. An action is
``verb(noun)`` with the EPIC verb and noun class keys in snake_case (``turn-on`` ->
``turn_on``, ``pan:dust`` -> ``pan_dust``); the session is kept as the extra field ``session``.
RULSTM's training and validation files together hold every annotated EK55 training instance
once (28,472). Verbs and nouns reuse convert_egtea's ACTIONS / NOUNS / PARENTS where the name
matches exactly; every other verb falls back to action_defaults and every other noun to
``_thing`` (``_container`` for ``*_container``), as convert_egtea does. Objects and tasks share one
namespace in the odb ontology, so a noun class that is also a verb class (``brush``, ``water``,
``fork``, ...) becomes ``<noun>_object``.

RAW_FOLDER holds, byte for byte: RULSTM/data/ek55/{training,validation}.csv and actions.csv of
fpv-iplab/rulstm @ e648c7ee40a1a71381bfaa7563f2e8a6935275ab, and EPIC_verb_classes.csv and
EPIC_noun_classes.csv of epic-kitchens/epic-kitchens-55-annotations @
63fa7d78eba41a8d2280374061a6b1bab3e7e41d (annotations CC BY-NC 4.0). Never copied into the project.

usage: python experiments/devset-ek55.py RAW_FOLDER OUT_FOLDER
"""

from __future__ import annotations

import csv
import sys
from collections import defaultdict
from pathlib import Path
from typing import TextIO

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "python"))

from oracle.chains import ChainRow, TaskCall  # noqa: E402
from oracle.errors import NeemOracleError  # noqa: E402
from oracle.evaluation.convert_egtea import snake, write_cooking_set  # noqa: E402
from oracle.evaluation.convert_kasteren import ConvertReport  # noqa: E402

SPLIT_FILES = ("training.csv", "validation.csv")


def _open(path: Path) -> TextIO:
    try:
        return path.open(newline="", encoding="utf-8")
    except OSError as error:
        raise NeemOracleError(f"{path}: cannot read ({error.strerror}); is this the ek55 folder?") from None


def read_classes(path: Path) -> dict[int, str]:
    """``EPIC_{verb,noun}_classes.csv``: class id -> snake_case class key."""
    with _open(path) as handle:
        reader = csv.reader(handle)
        next(reader, None)  # header: id,class_key,members
        classes = {}
        for number, row in enumerate(reader, start=2):
            try:
                classes[int(row[0])] = snake(row[1])
            except (ValueError, IndexError):
                raise NeemOracleError(f"{path}:{number}: expected 'id,class_key,...', got {row!r}") from None
    return classes


def read_actions(folder: Path) -> dict[int, tuple[int, int, TaskCall]]:
    """``actions.csv`` (id,action,verb,noun): action id -> (verb id, noun id, verb(noun))."""
    verbs = read_classes(folder / "EPIC_verb_classes.csv")
    nouns = read_classes(folder / "EPIC_noun_classes.csv")
    taken = set(verbs.values())
    nouns = {ident: f"{noun}_object" if noun in taken else noun for ident, noun in nouns.items()}
    path = folder / "actions.csv"
    calls: dict[int, tuple[int, int, TaskCall]] = {}
    with _open(path) as handle:
        reader = csv.reader(handle, skipinitialspace=True)
        next(reader, None)
        for number, row in enumerate(reader, start=2):
            if not row:
                continue
            try:
                ident, verb, noun = int(row[0]), int(row[2]), int(row[3])
            except (ValueError, IndexError):
                raise NeemOracleError(f"{path}:{number}: expected 'id,verb_noun,verb id,noun id', got {row!r}") from None
            if verb not in verbs or noun not in nouns:
                raise NeemOracleError(f"{path}:{number}: unknown verb {verb} or noun {noun} class")
            calls[ident] = (verb, noun, TaskCall(verbs[verb], (nouns[noun],)))
    return calls


def _video_key(video: str) -> tuple[str, int, str]:
    participant, _, number = video.partition("_")
    return (participant, int(number) if number.isdigit() else -1, video)


def read_ek55(folder: Path | str) -> list[ChainRow]:
    """One chain per participant: sessions in video-id order, actions in frame order."""
    folder = Path(folder)
    calls = read_actions(folder)
    instances: dict[int, tuple[str, int, int]] = {}
    for name in SPLIT_FILES:
        path = folder / name
        with _open(path) as handle:
            for number, row in enumerate(csv.reader(handle, skipinitialspace=True), start=1):
                if not row:
                    continue
                try:
                    ident, video, start = int(row[0]), row[1].strip(), int(row[2])
                    verb, noun, action = int(row[4]), int(row[5]), int(row[6])
                except (ValueError, IndexError):
                    raise NeemOracleError(f"{path}:{number}: expected 7 columns id,video,start,end,verb,noun,action") from None
                if action not in calls:
                    raise NeemOracleError(f"{path}:{number}: unknown action id {action}")
                if calls[action][:2] != (verb, noun):
                    raise NeemOracleError(f"{path}:{number}: action {action} is not verb {verb} + noun {noun}")
                if ident in instances:
                    raise NeemOracleError(f"{path}:{number}: instance id {ident} appears twice")
                instances[ident] = (video, start, action)
    sessions: dict[str, list[tuple[int, int, int]]] = defaultdict(list)
    for ident, (video, start, action) in instances.items():
        sessions[video].append((start, ident, action))
    rows = []
    for video in sorted(sessions, key=_video_key):
        participant = video.split("_")[0]
        for _start, _ident, action in sorted(sessions[video]):
            rows.append(ChainRow(participant, calls[action][2], None, None, extra={"session": video}))
    if not rows:
        raise NeemOracleError(f"{folder}: no action instances in {', '.join(SPLIT_FILES)}")
    return rows


def convert(folder: Path | str, out: Path | str) -> ConvertReport:
    """Write ``chains.jsonl``, ``odb/`` and ``mapping.yaml`` for EK55 into ``out``."""
    folder = Path(folder)
    rows = read_ek55(folder)
    renamed = {f"{noun}_object": noun for noun in read_classes(folder / "EPIC_noun_classes.csv").values()}
    return write_cooking_set(
        "ek55", rows, (call for _verb, _noun, call in read_actions(folder).values()), out, "urn:neem-oracle:odb:ek55#",
        "EPIC-Kitchens-55 (a development set): nouns as odb objects, verbs as tasks (experiments/devset-ek55.py).",
        lambda noun: renamed.get(noun, noun),  # NOUNS and the container rule see the EPIC class key
    )


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__.strip().splitlines()[-1])
    try:
        print(convert(sys.argv[1], sys.argv[2]))
    except NeemOracleError as error:
        sys.exit(f"error: {error}")
