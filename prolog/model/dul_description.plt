:- begin_tests(dul_description).

:- use_module(dul_description).
:- use_module(dul_object_types).
:- use_module(situation).
:- use_module(owl_description).
:- use_module('../neem_store').
:- use_module('../lang/query').
:- use_module('../fixtures/owl_world').

test(plans_goals_roles, [nondet, setup(load_owl_world), cleanup(store_reset)]) :-
    ow(plan1, P), ow(goal1, G), ow(task1, T), ow(role1, R), ow('CupPatient', RT), ow('Cup', Cup),
    is_plan(P), is_description(P), is_goal(G), plan_has_goal(P, G), \+ is_situation(P),
    has_task_role(T, R), task_role_type(T, R, RT),
    task_role_range(T, R, Range), Range == Cup.

test(parameters, [nondet, setup(load_owl_world), cleanup(store_reset)]) :-
    ow(task1, T), ow(param1, Pa), ow(region1, Re),
    kb_project(( triple(T, dul:hasParameter, Pa), triple(Pa, dul:classifies, Re) )),
    has_parameter(T, Pa), has_assignment(Pa, Re), \+ has_parameter(Pa, _).

:- end_tests(dul_description).
