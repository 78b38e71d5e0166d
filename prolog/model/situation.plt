:- begin_tests(dul_situation).

:- use_module(situation).
:- use_module('../neem_store').
:- use_module('../fixtures/test_episode').

n(L, I) :- atom_concat('http://example.org/neem#', L, I).

test(task_role_and_plan, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    n(pour1, T), findall(R, task_role(T, R), Rs), length(Rs, 2),
    n(pour1_plan, P), plan_defines_task(P, T),
    is_task(T).

:- end_tests(dul_situation).
