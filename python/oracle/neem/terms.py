"""The SOMA/DUL terms a NEEM is written and read back with, as strings (store values are
strings; built from the namespace IRIs, so reading a NEEM needs no rdflib)."""

from __future__ import annotations

from oracle.chains import EXECUTION_STATES as STATE_NAMES
from oracle.namespaces import DUL_IRI as DUL, OWL_IRI as OWL, SOMA_IRI as SOMA

NAMED_INDIVIDUAL = OWL + "NamedIndividual"
ACTION = DUL + "Action"
MENTAL_ACTION = SOMA + "MentalAction"
EXECUTES = DUL + "executesTask"
PARTICIPANT = DUL + "hasParticipant"
PERFORMED_BY = SOMA + "isPerformedBy"
HAS_INTERVAL = DUL + "hasTimeInterval"
TIME_INTERVAL = DUL + "TimeInterval"
BEGIN = SOMA + "hasIntervalBegin"
END = SOMA + "hasIntervalEnd"
IS_TASK_OF = DUL + "isTaskOf"
CLASSIFIES = DUL + "classifies"
PLAN = SOMA + "ActionExecutionPlan"
PLAN_FOR = SOMA + "isPlanFor"
IMAGINING = SOMA + "Imagining"
REASONING = SOMA + "Reasoning"
PREFERENCE_ORDER = SOMA + "PreferenceOrder"
ORDER = SOMA + "Order"
ORDERS = SOMA + "orders"
ORDERED_ELEMENT = SOMA + "OrderedElement"
ENCAPSULATES = SOMA + "encapsulates"
ROBOT_CLASS = DUL + "PhysicalAgent"
PERSON_CLASS = DUL + "NaturalPerson"

# KnowRob's episode structure (neem-interface's mem_episode_start / add_subaction_with_task)
EPISODE = SOMA + "Episode"
PHYSICAL_ACTION = SOMA + "PhysicalAction"
PHYSICAL_TASK = SOMA + "PhysicalTask"
AGENT_ROLE = SOMA + "AgentRole"
INCLUDES_ACTION = DUL + "includesAction"
IS_SETTING_FOR = DUL + "isSettingFor"
HAS_CONSTITUENT = DUL + "hasConstituent"
EXECUTION_STATE = SOMA + "hasExecutionState"
EXECUTION_STATE_REGION = SOMA + "ExecutionStateRegion"
#: What a robot may report of an action, as KnowRob's action_succeeded/failed/... name the states.
EXECUTION_STATES = {name: f"{SOMA}ExecutionState_{name.capitalize()}" for name in STATE_NAMES}
