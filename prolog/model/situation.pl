:- module(dul_situation,
    [ is_task/1,                % ?Task
      is_physical_task/1,       % ?Task
      is_episode/1,             % ?Episode
      task_role/2,              % ?Task, ?Role
      plan_defines_task/2,      % ?Plan, ?Task
      is_setting_for/2,         % ?Situation, ?Entity
      satisfies/2,              % ?Situation, ?Description
      is_diagnosis/1            % ?Description
    ]).
/** <module> Tasks, plans and episodes (KnowRob 2.x src/model/DUL/Situation.pl, SOMA)

Each predicate is a kb_rule/2 over DUL/SOMA properties and, called from Prolog, kb_call/1
of itself.
*/

:- use_module('../lang/query', [kb_call/1]).

:- multifile kb_query:kb_rule/2.
kb_query:kb_rule(is_task(A), has_type(A, dul:'Task')).
kb_query:kb_rule(is_physical_task(A), has_type(A, soma:'PhysicalTask')).
kb_query:kb_rule(is_episode(A), has_type(A, soma:'Episode')).
kb_query:kb_rule(task_role(T, R), holds(T, dul:isTaskOf, R)).
kb_query:kb_rule(plan_defines_task(P, T), holds(P, soma:isPlanFor, T)).
kb_query:kb_rule(is_setting_for(S, E), holds(S, dul:isSettingFor, E)).
kb_query:kb_rule(satisfies(S, D), holds(S, dul:satisfies, D)).
kb_query:kb_rule(is_diagnosis(D), has_type(D, dul:'Diagnosis')).

%!  is_task(?Task) is nondet.
is_task(A) :- kb_call(is_task(A)).
%!  is_physical_task(?Task) is nondet.
is_physical_task(A) :- kb_call(is_physical_task(A)).
%!  is_episode(?Episode) is nondet.
is_episode(A) :- kb_call(is_episode(A)).
%!  task_role(?Task, ?Role) is nondet.
task_role(T, R) :- kb_call(task_role(T, R)).
%!  plan_defines_task(?Plan, ?Task) is nondet.
plan_defines_task(P, T) :- kb_call(plan_defines_task(P, T)).
%!  is_setting_for(?Situation, ?Entity) is nondet.
%   The situation (e.g. an episode) is the setting for the entity (e.g. an action).
is_setting_for(S, E) :- kb_call(is_setting_for(S, E)).
%!  satisfies(?Situation, ?Description) is nondet.
satisfies(S, D) :- kb_call(satisfies(S, D)).
%!  is_diagnosis(?Description) is nondet.
is_diagnosis(D) :- kb_call(is_diagnosis(D)).
