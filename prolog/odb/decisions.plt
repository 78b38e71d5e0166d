:- begin_tests(odb_decisions).

:- use_module(decisions).
:- use_module('../neem_store').
:- use_module('../fixtures/test_episode').

n(L, I) :- atom_concat('http://example.org/neem#', L, I).

test(available_at, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    available_tasks_at(150, L1), L1 == [pick(apple), pour(thermos, green_mug)],
    available_tasks_at(250, L2), L2 == [pick(apple)],
    \+ available_tasks_at(50, _).

test(preference_at, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    preference_at(150, _, R), R == [ranked(pour(thermos, green_mug), 1, 0.2), ranked(pick(apple), 2, 0.7)].

test(latest_preference, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    latest_preference(_, B, R), B =:= 200, R == [ranked(pick(apple), 1, 0.1)].

test(latest_first, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    findall(B-M, latest_first(preference, none, B, M), All),
    findall(B-M, decision(preference, M, B), Pairs), sort(0, @>=, Pairs, All), All = [B1-_, _],
    B1 =:= 200,
    findall(B-M, latest_first(preference, 199.5, B, M), Before), Before = [B2-_], B2 =:= 100,
    \+ latest_first(preference, 99.5, _, _).

test(times_available, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    times_available(pick(apple), Bs), Bs == [100, 200].

:- end_tests(odb_decisions).
