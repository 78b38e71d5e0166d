:- begin_tests(odb_events).

:- use_module(events).
:- use_module('../neem_store').
:- use_module('../fixtures/test_episode').

n(L, I) :- atom_concat('http://example.org/neem#', L, I).

test(time_of_day, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    n(a1, A1), n(a3, A3),
    event_time_of_day(A1, 'Morning'), event_time_of_day(A3, P), P == 'Midday'.

test(idle, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    n(a2, A2), findall(A, is_idle_action(A), [A2]),
    idle_action(A2, B, E), B =:= 110, E =:= 200.

:- end_tests(odb_events).
