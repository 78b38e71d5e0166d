"""The answers of the HTTP API as typed models: what /openapi.json documents is what is sent
(every route declares its answer; every refusal is an ``ErrorAnswer``), each with an example
(oracle.service.examples)."""

from __future__ import annotations

from typing import Any

from pydantic import BaseModel, ConfigDict, Field

from oracle.service.examples import example


class Answer(BaseModel):
    model_config = ConfigDict(extra="allow")


class ErrorAnswer(BaseModel):
    model_config = ConfigDict(json_schema_extra=example("ErrorAnswer"))
    error: str = Field(description="one line saying what was wrong")


class Health(Answer):
    model_config = ConfigDict(extra="allow", json_schema_extra=example("Health"))
    ok: bool
    sessions: int
    subscribers: int


class NeemListed(Answer):
    model_config = ConfigDict(extra="allow", json_schema_extra=example("NeemListed"))
    id: str
    name: str | None = None
    user: str | None = None
    created_at: str | None = None
    temporary: bool = False


class NeemMade(Answer):
    model_config = ConfigDict(extra="allow", json_schema_extra=example("NeemMade"))
    id: str
    name: str | None = None
    user: str


class PerceptionAnswer(Answer):
    model_config = ConfigDict(extra="allow", json_schema_extra=example("PerceptionAnswer"))
    neem: str
    objects: list[str]
    logged: list[str]


class ModeSupport(BaseModel):
    """What a usual mode rests on: the most specific context with counts (``call and part``,
    ``call``, ``task and part``, ``task``, ``none``) and the modes counted there."""
    model_config = ConfigDict(json_schema_extra=example("ModeSupport"))
    context: str | None = None
    counts: dict[str, int] = {}


class RankedEntry(Answer):
    model_config = ConfigDict(extra="allow", json_schema_extra=example("RankedEntry"))
    rank: int
    task: str = Field(description="the task call, e.g. pick(red_mug)")
    score: float | None = None
    support: int | None = None
    probability: float | None = None
    context_order: int | None = None
    context: list[str] = []
    situations: list[float] = []
    reason: str = ""
    mode: str | None = Field(None, description="who usually does it, from the user's own past: robot, user or together "
                                               "(null: no action of the task known; oracle.past.autonomy)")
    mode_support: ModeSupport | None = Field(None, description="what the mode rests on")


class RoutineNow(BaseModel):
    """The routine the user is in (oracle.past.routines.recognise): its key and name, how many of
    its steps are done, the calls that remain and how many."""
    model_config = ConfigDict(json_schema_extra=example("RoutineNow"))
    key: str
    name: str
    done: int
    remaining: list[str]
    remaining_modes: list[str | None] = Field([], description="who usually does each step that remains (as `mode`)")
    steps_left: int
    score: float


class SituationAnswer(Answer):
    model_config = ConfigDict(extra="allow", json_schema_extra=example("SituationAnswer"))
    neem: str
    ranking: list[RankedEntry]
    chain: list[str]
    chain_modes: list[str | None] = Field([], description="who usually does each step of the chain (as `mode`)")
    routine: RoutineNow | None = Field(None, description="the routine in progress and what remains (null: none)")
    at: float | None = None
    time_of_day: str | None = None
    history: int | None = None
    ms: float | None = None


class ActionAnswer(Answer):
    model_config = ConfigDict(extra="allow", json_schema_extra=example("ActionAnswer"))
    neem: str
    id: str
    call: str
    open: bool
    begin: float | None = None
    end: float | None = None
    time_of_day: str | None = None
    idle: str | None = None
    history: int | None = None


class ChoiceAnswer(Answer):
    model_config = ConfigDict(extra="allow", json_schema_extra=example("ChoiceAnswer"))
    neem: str
    task: str | None = Field(description="the task the user chose (the workflow's first step)")
    workflow: list[str] | None = None
    modes: list[str] | None = Field(None, description="who does each step (the task: one): robot, user or together")
    at: float | None = Field(None, description="when the user confirmed it (unix seconds)")
    decision: str | None = Field(None, description="the decision's IRI in the NEEM")


class SpokenAnswer(Answer):
    model_config = ConfigDict(extra="allow", json_schema_extra=example("SpokenAnswer"))
    sentence: str = Field(description="English, for the robot's log and speech")
    said: str = Field(description="the same for the person, in plain words and the asked language")
    answer: dict[str, Any]


class PrologAnswer(Answer):
    model_config = ConfigDict(extra="allow", json_schema_extra=example("PrologAnswer"))
    solutions: list[dict[str, Any]]
    more: bool
    offset: int


class TabletTask(BaseModel):
    model_config = ConfigDict(json_schema_extra=example("TabletTask"))
    task: str = Field(description="the call, as the robot names it")
    rank: int
    said: str = Field(description="the task as a person says it")
    reason: str = Field(description="why it stands here, one short sentence")
    mode: str | None = Field(None, description="who usually does it (robot, user, together; null: not known)")
    mode_said: str = Field("", description="the same in the person's words, with how often")


class TabletStep(BaseModel):
    model_config = ConfigDict(json_schema_extra=example("TabletStep"))
    task: str
    said: str
    mode: str = Field("robot", description="who does the step unless the person changes it: the usual mode, else the robot")
    who: str = Field("", description="the same as the sheet's toggle says it")


class TabletRoutine(BaseModel):
    model_config = ConfigDict(json_schema_extra=example("TabletRoutine"))
    key: str
    name: str
    steps_left: int
    label: str = Field(description="the page's control, e.g. Finish \u201cCoffee in the red mug\u201d (3 steps left)")
    steps: list[TabletStep] = Field(description="the steps that remain, in order")


class TabletView(BaseModel):
    model_config = ConfigDict(json_schema_extra=example("TabletView"))
    neem: str
    user: str | None
    person: str = Field("", description="the person's name for the header (empty: none known; never an id)")
    lang: str
    at: float | None
    clock: str = Field(description="part of the day and time on the person's clock")
    tasks: list[TabletTask]
    workflow: list[TabletStep]
    routine: TabletRoutine | None = Field(None, description="the routine in progress (null: none)")


class Said(BaseModel):
    model_config = ConfigDict(json_schema_extra=example("Said"))
    call: str
    said: str


#: Every refusal's body, for the routes' documented answers.
class PastAnswer(Answer):
    """A question about the past (oracle.past.ask): its form, language, the answer in both
    languages and the evidence it rests on."""
    model_config = ConfigDict(extra="allow", json_schema_extra=example("PastAnswer"))
    question: str
    form: str
    language: str
    text: str
    english: str
    german: str
    evidence: dict[str, Any]


class StateSummary(Answer):
    """The NEEM's state summary (oracle.past.summary): what a language model may take as ground truth."""
    model_config = ConfigDict(extra="allow", json_schema_extra=example("StateSummary"))
    format: int | str
    neem: str
    now: float | None = None
    recent: list[dict[str, Any]] = []
    latest: dict[str, Any] | None = None
    usual_next: list[dict[str, Any]] = []
    predicted: list[dict[str, Any]] = []


class RoutinesAnswer(Answer):
    """The user's routines mined from the NEEM (oracle.past.mine) and the one in progress."""
    model_config = ConfigDict(extra="allow", json_schema_extra=example("RoutinesAnswer"))
    now: float | None = None
    routines: list[dict[str, Any]] = []
    in_progress: dict[str, Any] | None = None


class PrepareAnswer(Answer):
    """What is worth preparing now for the coming part of the day (oracle.past.mine)."""
    model_config = ConfigDict(extra="allow", json_schema_extra=example("PrepareAnswer"))


ERRORS: dict[int | str, dict[str, Any]] = {code: {"model": ErrorAnswer} for code in (400, 401, 403, 404, 405, 409, 422, 500)}
