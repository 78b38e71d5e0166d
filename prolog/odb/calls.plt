:- begin_tests(odb_calls).

:- use_module(calls).
:- use_module('../neem_store').
:- use_module('../fixtures/test_episode').

n(L, I) :- atom_concat('http://example.org/neem#', L, I).

test(task_call_orders_reference_first, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    n(pour1, T), task_call(T, C), C == pour(thermos, green_mug).

test(action_call, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    findall(C-B, action_call(_, C, B, _), L), msort(L, S),
    S == ['IdleTask'-110, pick(apple)-201, pour(thermos, green_mug)-101].

test(chain_before_skips_idle, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    n(a3, A3), chain_before(A3, 5, C), C == [pour(thermos, green_mug)],
    chain_before(A3, 0, []).

test(times_done, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    times_done(pick(apple), [action(201, 205, _)]).

:- end_tests(odb_calls).
