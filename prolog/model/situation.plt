:- begin_tests(dul_situation).

:- use_module(situation).
:- use_module('../lang/query').
:- use_module('../neem_store').
:- use_module('../fixtures/test_episode').

n(L, I) :- atom_concat('http://example.org/neem#', L, I).

test(task_role_and_plan, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    n(pour1, T), findall(R, task_role(T, R), Rs), length(Rs, 2),
    n(pour1_plan, P), plan_defines_task(P, T),
    is_task(T).

test(setting_and_satisfies, [nondet, setup(store_reset), cleanup(store_reset)]) :-
    \+ is_setting_for(ep, act),
    kb_project((is_setting_for(ep, act), satisfies(ep, masterful))),
    is_setting_for(ep, act), satisfies(ep, masterful).

:- end_tests(dul_situation).
