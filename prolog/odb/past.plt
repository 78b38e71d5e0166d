:- begin_tests(odb_past).

:- use_module(past).
:- use_module('../neem_store').
:- use_module('../store/tf').
:- use_module('../fixtures/test_episode').
:- use_module('../fixtures/triples', [fixture_assert/4]).

%   The test episode: pour(thermos, green_mug) during [101, 110], idle [110, 200],
%   pick(apple) during [201, 205]; decisions at 100 (pour ranked 1st, pick 2nd) and at 200.

test(latest_time_is_the_last_begin, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    latest_time(T), T =:= 201.

test(done_between_skips_idle_and_mental_actions, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    done_between(none, none, All),
    All == [done(101, 110, pour(thermos, green_mug)), done(201, 205, pick(apple))],
    done_between(102, none, Later), Later == [done(201, 205, pick(apple))],
    done_between(none, 200, Earlier), Earlier == [done(101, 110, pour(thermos, green_mug))].

test(last_before_skips_idle_and_mental_actions, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    last_before(300, D1), D1 == done(201, 205, pick(apple)),
    last_before(201, D2), D2 == done(101, 110, pour(thermos, green_mug)),
    \+ last_before(101, _),
    latest_before(300, 5, L), L == [done(101, 110, pour(thermos, green_mug)), done(201, 205, pick(apple))],
    latest_before(300, 1, [done(201, 205, pick(apple))]).

test(last_done_before_a_time, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    last_done(pick(apple), none, B), B =:= 201,
    \+ last_done(pick(apple), 200, _),
    last_done(pour(thermos, green_mug), 200, B2), B2 =:= 101.

test(done_times_in_a_window, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    done_times(pick(apple), 0, 300, Bs), Bs == [201],
    done_times(pick(apple), 0, 200, []).

test(usual_after_counts_the_next_non_idle_call, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    usual_after(pour(thermos, green_mug), N, Counts),
    N == 1, Counts == [pick(apple)-1],
    usual_after(pick(apple), 1, []).

test(suggestion_is_the_latest_preference_ranking_the_call,
     [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    suggestion(pick(apple), none, S1), S1 = suggested(T1, 1, _, ranked(pick(apple), 1, _)), T1 =:= 200,
    suggestion(pick(apple), 150, S2), S2 = suggested(T2, 2, Score, ranked(pour(thermos, green_mug), 1, _)),
    T2 =:= 100, Score =:= 0.7,
    \+ suggestion(pour(thermos, green_mug), 50, _).

test(object_place_without_pose_names_the_last_use, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    object_place(green_mug, none, place(none, used(B, Call))), B =:= 101, Call == pour(thermos, green_mug),
    object_place(green_mug, 100, place(none, none)).

test(object_place_with_pose, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    store_assert_pose(mug1, 150, ['map', [0.4, 1.2, 0.9], [0, 0, 0, 1]]),
    object_place(green_mug, none, place(pose(S, map, [X, _, _]), _)), S =:= 150, X =:= 0.4,
    object_place(green_mug, 120, place(none, _)).

test(performers_from_is_performed_by, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    % the test episode's actions are performed by `edan`, typed nothing: unknown
    performers(pick(apple), [B-unknown]), B =:= 201,
    fixture_assert('http://example.org/neem#', edan, rdf:type, dul:'PhysicalAgent'),
    performers(pour(thermos, green_mug), [_-robot]).

test(performers_together_when_a_person_and_another_agent, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    fixture_assert('http://example.org/neem#', edan, rdf:type, dul:'PhysicalAgent'),
    fixture_assert('http://example.org/neem#', ada, rdf:type, dul:'NaturalPerson'),
    fixture_assert('http://example.org/neem#', ada, rdf:type, dul:'PhysicalAgent'),
    fixture_assert('http://example.org/neem#', a3, soma:isPerformedBy, ada),
    performers(pick(apple), [_-together]),
    performers(pour(thermos, green_mug), [_-robot]).

test(bad_call_is_an_error, [nondet, setup(load_test_episode), cleanup(store_reset),
                            error(type_error(callable, 3))]) :-
    last_done(3, none, _).

:- end_tests(odb_past).
