:- begin_tests(odb_model).

:- use_module(odb_model).
:- use_module(neem_store).
:- use_module(test_episode).

n(L, I) :- atom_concat('http://example.org/neem#', L, I).

test(task_call_orders_reference_first, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    n(pour1, T), task_call(T, C), C == pour(thermos, green_mug).

test(action_call, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    findall(C-B, action_call(_, C, B, _), L), msort(L, S),
    S == ['IdleTask'-110, pick(apple)-201, pour(thermos, green_mug)-101].

test(situation_history, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    situation_history(S),
    S = [situation(B1, E1, C1, P1, A1), situation(_, _, C2, _, A2), situation(_, _, C3, P3, A3)],
    B1 =:= 101, E1 =:= 110, C1 == pour(thermos, green_mug), P1 == 'Morning',
    A1 == [pick(apple), pour(thermos, green_mug)],
    C2 == idle, A2 == none,
    C3 == pick(apple), P3 == 'Midday', A3 == [pick(apple)].

test(situation_history_json, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    situation_history_json(J), sub_string(J, _, _, _, "\"call\":\"pour(thermos,green_mug)\"").

test(latest_situation, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    latest_situation(B, C), B =:= 200, C == [pick(apple)],
    latest_situation_json(J), sub_string(J, _, _, _, "\"begin\":200").

test(time_of_day, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    n(a1, A1), n(a3, A3),
    event_time_of_day(A1, 'Morning'), event_time_of_day(A3, P), P == 'Midday'.

test(idle, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    n(a2, A2), findall(A, is_idle_action(A), [A2]),
    idle_action(A2, B, E), B =:= 110, E =:= 200.

test(available_at, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    available_tasks_at(150, L1), L1 == [pick(apple), pour(thermos, green_mug)],
    available_tasks_at(250, L2), L2 == [pick(apple)],
    \+ available_tasks_at(50, _).

test(preference_at, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    preference_at(150, _, R), R == [ranked(pour(thermos, green_mug), 1, 0.2), ranked(pick(apple), 2, 0.7)].

test(latest_preference, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    latest_preference(_, B, R), B =:= 200, R == [ranked(pick(apple), 1, 0.1)].

test(chain_before_skips_idle, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    n(a3, A3), chain_before(A3, 5, C), C == [pour(thermos, green_mug)],
    chain_before(A3, 0, []).

test(times, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    times_available(pick(apple), Bs), Bs == [100, 200],
    times_done(pick(apple), [action(201, 205, _)]).

:- end_tests(odb_model).
