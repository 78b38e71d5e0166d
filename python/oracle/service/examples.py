"""An example of each model the HTTP API takes or answers, for /openapi.json and /docs
(oracle.service.schemas, the request models of oracle.service.routes): what a robot framework
or a fuzzer may start from. Times are the demo NEEM's."""

from __future__ import annotations

from typing import Any

EXAMPLES: dict[str, dict[str, Any]] = {
    "ErrorAnswer": {"error": "unknown task 'pik'. Did you mean 'pick'? Known tasks: close, cut, drink_from, ..."},
    "Health": {"ok": True, "sessions": 1, "subscribers": 2},
    "NeemListed": {
        "id": "6b1703c1bb5a244c6b90efd5",
        "name": "demo",
        "user": "ada",
        "created_at": "2025-03-03T07:52:30+00:00",
        "temporary": False,
    },
    "NeemMade": {"id": "6b1703c1bb5a244c6b90efd5", "name": "ada", "user": "ada"},
    "PerceptionAnswer": {
        "neem": "6b1703c1bb5a244c6b90efd5",
        "objects": ["red_mug"],
        "logged": ["https://ontology.dlr.de/soma/odb#RedMug_6b17"],
    },
    "ModeSupport": {"context": "call and part", "counts": {"robot": 5, "user": 1, "together": 0}},
    "RankedEntry": {
        "rank": 1,
        "task": "open(fridge)",
        "score": 0.207,
        "support": 3,
        "probability": 0.866,
        "context_order": 3,
        "context": ["close(fridge)", "close(small_drawer)", "idle"],
        "situations": [1741330800.0],
        "reason": "after close(small_drawer): 3x",
        "mode": "robot",
        "mode_support": {"context": "call", "counts": {"robot": 14, "user": 0, "together": 0}},
    },
    "RoutineNow": {
        "key": "open(fridge)>pick(beer_bottle)",
        "name": "Beer in the glass",
        "done": 1,
        "remaining": ["pick(beer_bottle)", "pour(beer_bottle, drinking_glass)"],
        "remaining_modes": ["robot", "robot"],
        "steps_left": 2,
        "score": 0.8,
    },
    "SituationAnswer": {
        "neem": "6b1703c1bb5a244c6b90efd5",
        "ranking": [
            {
                "rank": 1,
                "task": "open(fridge)",
                "score": 0.207,
                "probability": 0.866,
                "reason": "after close(small_drawer): 3x",
                "mode": "robot",
            }
        ],
        "chain": ["open(fridge)", "pick(beer_bottle)"],
        "chain_modes": ["robot", "robot"],
        "routine": None,
        "at": 1741421087.9,
        "time_of_day": "Morning",
        "history": 229,
        "ms": 0.8,
    },
    "ActionAnswer": {
        "neem": "6b1703c1bb5a244c6b90efd5",
        "id": "a17",
        "call": "pick(red_mug)",
        "open": False,
        "begin": 1741421090.0,
        "end": 1741421100.0,
        "time_of_day": "Morning",
        "idle": None,
        "history": 230,
    },
    "ChoiceAnswer": {
        "neem": "6b1703c1bb5a244c6b90efd5",
        "task": "open(fridge)",
        "workflow": ["open(fridge)", "pick(beer_bottle)"],
        "modes": ["robot", "user"],
        "at": 1741421095.0,
        "decision": "https://ontology.dlr.de/soma/odb#Decision_6b17",
    },
    "SpokenAnswer": {
        "sentence": "At 2025-03-08 08:04 I ranked open(fridge) first: it is what I suggested.",
        "said": "This is my first suggestion.",
        "answer": {
            "question": "why_not",
            "task": "open(fridge)",
            "reasons": [{"reason": "ranked_first", "task": "open(fridge)", "time": 1741421087.9, "score": 0.207}],
        },
    },
    "PrologAnswer": {"solutions": [{"T": "open(fridge)"}], "more": False, "offset": 0},
    "TabletTask": {
        "task": "place(beer_bottle, fridge)",
        "rank": 1,
        "said": "Put the beer bottle in the fridge",
        "reason": "You did this 3 times after pouring the beer into the glass, last at 16:05.",
        "mode": "robot",
        "mode_said": "The robot usually does this for you (3 of 3 times).",
    },
    "TabletStep": {"task": "pick(beer_bottle)", "said": "Pick up the beer bottle", "mode": "robot", "who": "The robot"},
    "TabletRoutine": {
        "key": "open(fridge)>pick(beer_bottle)",
        "name": "Beer in the glass",
        "steps_left": 1,
        "label": "Finish “Beer in the glass” (1 step left)",
        "steps": [{"task": "pick(beer_bottle)", "said": "Pick up the beer bottle", "mode": "robot", "who": "The robot"}],
    },
    "TabletView": {
        "neem": "6b1703c1bb5a244c6b90efd5",
        "user": "ada",
        "person": "Ada",
        "lang": "de",
        "at": 1741421087.9,
        "clock": "morgens, 08:04",
        "tasks": [
            {
                "task": "open(fridge)",
                "rank": 1,
                "said": "Den Kühlschrank öffnen",
                "reason": "Das haben Sie 3-mal nach einer Pause gemacht, zuletzt um 08:03.",
                "mode": "robot",
                "mode_said": "",
            }
        ],
        "workflow": [],
        "routine": None,
    },
    "Said": {"call": "place(beer_bottle, fridge)", "said": "Put the beer bottle in the fridge"},
    "PastAnswer": {
        "question": "wann habe ich zuletzt den Kühlschrank geöffnet?",
        "form": "last",
        "language": "de",
        "text": "Zuletzt am 07.03.2025 um 16:04 den Kühlschrank geöffnet.",
        "english": "Opening the fridge was last done on 2025-03-07 at 16:04.",
        "german": "Zuletzt am 07.03.2025 um 16:04 den Kühlschrank geöffnet.",
        "evidence": {"now": 1741421087.9, "task": "open(fridge)", "begin": 1741363460.6},
    },
    "StateSummary": {
        "format": 1,
        "neem": "6b1703c1bb5a244c6b90efd5",
        "now": 1741421087.9,
        "recent": [{"begin": 1741363460.6, "end": 1741363488.4, "task": "open(fridge)"}],
        "latest": None,
        "usual_next": [],
        "predicted": [],
    },
    "RoutinesAnswer": {
        "now": 1741421087.9,
        "routines": [
            {"key": "open(fridge)>pick(beer_bottle)", "name": "Beer in the glass", "steps": ["open(fridge)", "pick(beer_bottle)"]}
        ],
        "in_progress": None,
    },
    "PrepareAnswer": {"for": "Evening", "objects": [{"object": "beer_bottle", "reason": "Beer in the glass, most evenings"}]},
    "NewNeem": {"user": "ada"},
    "Perception": {"objects": [{"name": "red_mug", "pose": [0.4, 1.2, 0.9]}], "at": "2025-03-08T08:04:00"},
    "SituationIn": {"available": ["open(fridge)", "pick(red_mug)", "open(small_drawer)"], "at": "2025-03-08T08:04:47"},
    "ActionIn": {
        "call": "open(fridge)",
        "phase": "done",
        "begin": "2025-03-08T08:05:00",
        "end": "2025-03-08T08:05:20",
        "performed_by": "robot",
    },
    "ChoiceIn": {"task": "open(fridge)", "workflow": ["open(fridge)", "pick(beer_bottle)"], "modes": ["robot", "user"]},
    "PrologIn": {"query": "kb_call(executes_task(A, T))", "limit": 5},
}


def example(name: str) -> dict[str, Any]:
    """The ``json_schema_extra`` of model ``name``: its example."""
    return {"examples": [EXAMPLES[name]]}
