:- module(dul_situation,
    [ is_task/1,                % ?Task
      is_physical_task/1,       % ?Task
      is_episode/1,             % ?Episode
      task_role/2,              % ?Task, ?Role
      plan_defines_task/2       % ?Plan, ?Task
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
