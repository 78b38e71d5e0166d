:- begin_tests(odb_history).

:- use_module(history).
:- use_module(library(http/json)).
:- use_module('../neem_store').
:- use_module('../fixtures/test_episode').
:- use_module('../fixtures/history_reference').

n(L, I) :- atom_concat('http://example.org/neem#', L, I).

test(situation_history, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    situation_history(S),
    S = [situation(B1, E1, C1, P1, A1), situation(_, _, C2, _, A2), situation(_, _, C3, P3, A3)],
    B1 =:= 101, E1 =:= 110, C1 == pour(thermos, green_mug), P1 == 'Morning',
    A1 == [pick(apple), pour(thermos, green_mug)],
    C2 == idle, A2 == none,
    C3 == pick(apple), P3 == 'Midday', A3 == [pick(apple)].

test(situation_history_json, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    situation_history_json(J), sub_string(J, _, _, _, "\"call\":\"pour(thermos,green_mug)\""),
    atom_json_dict(J, D, []), D.situations = [S1, S2, _], S1.available == 0, S2.available == null,
    D.sets = [["pick(apple)", "pour(thermos,green_mug)"]|_].

test(latest_situation, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    latest_situation(B, C), B =:= 200, C == [pick(apple)],
    latest_situation_json(J), sub_string(J, _, _, _, "\"begin\":200").

test(one_pass_equals_reference, [cleanup(store_reset)]) :-
    forall(member(Seed, [1, 2, 3, 4]),
           ( load_generated_episode(300, Seed),
             situation_history(New),
             situation_history_reference(Old),
             length(New, N), N >= 300,
             assertion(New == Old) )).

test(one_pass_equals_reference_small_episode, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    situation_history(New), situation_history_reference(Old), New == Old.

:- end_tests(odb_history).
