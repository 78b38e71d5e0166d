:- module(dul_description,
    [ is_event_type/1,          % ?Entity
      is_process/1,             % ?Entity
      is_description/1,         % ?Entity
      is_situation/1,           % ?Entity
      is_goal/1,                % ?Entity
      is_design/1,              % ?Entity
      is_plan/1,                % ?Entity
      is_plan_execution/1,      % ?Entity
      is_norm/1,                % ?Entity
      is_transition/1,          % ?Entity
      has_task_role/2,          % ?Task, ?Role
      task_role_type/3,         % ?Task, ?Role, ?RoleType
      task_role_range/3,        % ?Task, ?Role, ?Range
      has_parameter/2,          % ?Entity, ?Parameter
      has_parameter/3,          % ?Entity, ?Parameter, ?Type
      has_parameter_range/3,    % ?Entity, ?Parameter, ?Range
      has_assignment/2,         % ?Parameter, ?Region
      plan_has_goal/2           % ?Plan, ?Goal
    ]).
/** <module> Descriptions, situations, plans and their roles (KnowRob 2.x src/model/DUL.pl)

DUL's descriptions (plans, goals, norms, ...) and situations, with the roles and parameters
a description defines. `task_role_range/3` and `has_parameter_range/3` read the `only`
restriction on dul:classifies of the role's class (model/owl_description). Each predicate is a
kb_rule/2 and, called from Prolog, kb_call/1 of itself.
*/

:- use_module('../lang/query', [kb_call/1]).

:- multifile kb_query:kb_rule/2.
kb_query:kb_rule(is_event_type(E), has_type(E, dul:'EventType')).
kb_query:kb_rule(is_process(E), has_type(E, dul:'Process')).
kb_query:kb_rule(is_description(E), has_type(E, dul:'Description')).
kb_query:kb_rule(is_situation(E), has_type(E, dul:'Situation')).
kb_query:kb_rule(is_goal(E), has_type(E, dul:'Goal')).
kb_query:kb_rule(is_design(E), has_type(E, dul:'Design')).
kb_query:kb_rule(is_plan(E), has_type(E, dul:'Plan')).
kb_query:kb_rule(is_plan_execution(E), has_type(E, dul:'PlanExecution')).
kb_query:kb_rule(is_norm(E), has_type(E, dul:'Norm')).
kb_query:kb_rule(is_transition(E), has_type(E, dul:'Transition')).
kb_query:kb_rule(has_task_role(T, R), task_role(T, R)).
kb_query:kb_rule(task_role_type(T, R, RT), ( holds(T, dul:isTaskOf, R), has_object_type(R, RT) )).
kb_query:kb_rule(task_role_range(T, R, Range), ( holds(T, dul:isTaskOf, R), holds(R, dul:classifies, only(Range)) )).
kb_query:kb_rule(has_parameter(E, P), holds(E, dul:hasParameter, P)).
kb_query:kb_rule(has_parameter(E, P, T), ( holds(E, dul:hasParameter, P), has_object_type(P, T) )).
kb_query:kb_rule(has_parameter_range(E, P, Range), ( holds(E, dul:hasParameter, P), holds(P, dul:classifies, only(Range)) )).
kb_query:kb_rule(has_assignment(P, R), holds(P, dul:classifies, R)).
kb_query:kb_rule(plan_has_goal(P, G), ( holds(P, dul:hasComponent, G), has_type(G, dul:'Goal') )).

%!  is_event_type(?Entity) is nondet.
%   Typed dul:'EventType' (or a subclass).
is_event_type(Entity) :- kb_call(is_event_type(Entity)).
%!  is_process(?Entity) is nondet.
%   Typed dul:'Process' (or a subclass).
is_process(Entity) :- kb_call(is_process(Entity)).
%!  is_description(?Entity) is nondet.
%   Typed dul:'Description' (or a subclass).
is_description(Entity) :- kb_call(is_description(Entity)).
%!  is_situation(?Entity) is nondet.
%   Typed dul:'Situation' (or a subclass).
is_situation(Entity) :- kb_call(is_situation(Entity)).
%!  is_goal(?Entity) is nondet.
%   Typed dul:'Goal' (or a subclass).
is_goal(Entity) :- kb_call(is_goal(Entity)).
%!  is_design(?Entity) is nondet.
%   Typed dul:'Design' (or a subclass).
is_design(Entity) :- kb_call(is_design(Entity)).
%!  is_plan(?Entity) is nondet.
%   Typed dul:'Plan' (or a subclass).
is_plan(Entity) :- kb_call(is_plan(Entity)).
%!  is_plan_execution(?Entity) is nondet.
%   Typed dul:'PlanExecution' (or a subclass).
is_plan_execution(Entity) :- kb_call(is_plan_execution(Entity)).
%!  is_norm(?Entity) is nondet.
%   Typed dul:'Norm' (or a subclass).
is_norm(Entity) :- kb_call(is_norm(Entity)).
%!  is_transition(?Entity) is nondet.
%   Typed dul:'Transition' (or a subclass).
is_transition(Entity) :- kb_call(is_transition(Entity)).
%!  has_task_role(?Task, ?Role) is nondet.
%   The same as task_role/2.
has_task_role(Task, Role) :- kb_call(has_task_role(Task, Role)).
%!  task_role_type(?Task, ?Role, ?RoleType) is nondet.
%   Role of Task and a type of it below dul:Object.
task_role_type(Task, Role, RoleType) :- kb_call(task_role_type(Task, Role, RoleType)).
%!  task_role_range(?Task, ?Role, ?Range) is nondet.
%   Role of Task, whose class restricts what it classifies to Range (an `only` restriction).
task_role_range(Task, Role, Range) :- kb_call(task_role_range(Task, Role, Range)).
%!  has_parameter(?Entity, ?Parameter) is nondet.
has_parameter(Entity, Parameter) :- kb_call(has_parameter(Entity, Parameter)).
%!  has_parameter(?Entity, ?Parameter, ?Type) is nondet.
%   A parameter of Entity and a type of it below dul:Object.
has_parameter(Entity, Parameter, Type) :- kb_call(has_parameter(Entity, Parameter, Type)).
%!  has_parameter_range(?Entity, ?Parameter, ?Range) is nondet.
%   A parameter of Entity whose class restricts what it classifies to Range.
has_parameter_range(Entity, Parameter, Range) :- kb_call(has_parameter_range(Entity, Parameter, Range)).
%!  has_assignment(?Parameter, ?Region) is nondet.
%   The region a parameter classifies.
has_assignment(Parameter, Region) :- kb_call(has_assignment(Parameter, Region)).
%!  plan_has_goal(?Plan, ?Goal) is nondet.
plan_has_goal(Plan, Goal) :- kb_call(plan_has_goal(Plan, Goal)).
