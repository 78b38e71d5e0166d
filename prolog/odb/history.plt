:- begin_tests(odb_history).

:- use_module(history).
:- use_module(library(http/json)).
:- use_module(library(assoc), [assoc_to_list/2]).
:- use_module('../fixtures/triples', [fixture_assert/4]).
:- use_module('../neem_store').
:- use_module('../lang/triple', [kb_iri/2]).
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
    situation_history_json(J),
    atom_json_dict(J, D, []),
    D.rows = [101, 110, C1, "Morning", 0, "unknown", _, _, C2, _, -1, _, _, _, C3, "Midday", 1, "unknown"],
    nth0(C1, D.calls, "pour(thermos,green_mug)"), nth0(C2, D.calls, "idle"), nth0(C3, D.calls, "pick(apple)"),
    D.sets = [Set0, [C3]], maplist([I, T]>>nth0(I, D.calls, T), Set0, ["pick(apple)", "pour(thermos,green_mug)"]).

test(action_modes_name_who_performed_each_action, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    action_modes(none, Untyped), assoc_to_list(Untyped, []),    % edan performs a1-a3, of no agent type
    fixture_assert('http://example.org/neem#', ada, rdf:type, dul:'NaturalPerson'),
    fixture_assert('http://example.org/neem#', a1, soma:isPerformedBy, ada),
    fixture_assert('http://example.org/neem#', edan, rdf:type, dul:'PhysicalAgent'),
    n(a1, A1), n(a2, A2), n(a3, A3),
    action_modes(none, All), assoc_to_list(All, [A1-together, A2-robot, A3-robot]),
    action_modes(150, Later), assoc_to_list(Later, [A3-robot]),
    situation_history_json(J), atom_json_dict(J, D, []),
    D.rows = [_, _, _, _, _, "together", _, _, _, _, _, "robot", _, _, _, _, _, "robot"].

test(typed_modes_read_the_rows_of_a_few_actions) :-
    kb_iri(dul:'NaturalPerson', P), kb_iri(dul:'PhysicalAgent', G),
    typed_modes([a1-ada-P, a1-ada-G, a1-edan-G, a2-edan-G, a3-ada-P, a4-nobody-other], ModeOf),
    assoc_to_list(ModeOf, [a1-together, a2-robot, a3-user]).

test(typed_modes_need_a_list, [error(type_error(list, rows))]) :-
    typed_modes(rows, _).

test(action_modes_needs_a_number_or_none, [error(type_error(number, soon))]) :-
    action_modes(soon, _).

test(latest_situation, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    latest_situation(B, C), B =:= 200, C == [pick(apple)],
    latest_situation_json(J), sub_string(J, _, _, _, "\"begin\":200").

test(latest_situation_has_its_part_of_day, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    latest_situation(B, C, P), B =:= 200, C == [pick(apple)], P == 'Morning',   % as the fixture logs it
    latest_situation_json(J), atom_json_dict(J, D, []), D.part == "Morning".

test(history_view_is_the_history_and_the_latest_situation, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    history_view_json(none, J), atom_json_dict(J, D, []),
    situation_history_json(H), atom_json_dict(H, DH, []),
    D.rows == DH.rows, D.calls == DH.calls, D.sets == DH.sets,
    D.latest.begin =:= 200, D.latest.available == ["pick(apple)"].

test(one_pass_equals_reference, [cleanup(store_reset)]) :-
    forall(member(Seed, [1, 2, 3, 4]),
           ( load_generated_episode(300, Seed),
             situation_history(New),
             situation_history_reference(Old),
             length(New, N), N >= 300,
             assertion(New == Old) )).

test(one_pass_equals_reference_small_episode, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    situation_history(New), situation_history_reference(Old), New == Old.

test(after_is_the_suffix_after_a_begin, [cleanup(store_reset)]) :-
    forall(member(Seed, [1, 2]),
           ( load_generated_episode(300, Seed),
             situation_history(All),
             length(All, N),
             % every 7th cut and the last few: the reads are the same code at every cut
             forall(( between(1, N, K), ( K mod 7 =:= 1 ; K >= N - 3 ) ),
                    ( Cut is N - K,
                      length(Before, Cut), append(Before, Suffix, All),
                      (   Before == [] -> After = -1.0e12
                      ;   last(Before, situation(After, _, _, _, _))
                      ),
                      % a cut between two actions that began together is no cut by begin
                      (   Suffix = [situation(First, _, _, _, _)|_], First =< After
                      ->  true
                      ;   situation_history_after(After, Got),
                          assertion(Got == Suffix)
                      ) )) )).

test(after_the_last_action_is_empty, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    situation_history(All), last(All, situation(B, _, _, _, _)),
    situation_history_after(B, []),
    situation_history_json(B, J), atom_json_dict(J, D, []), D.rows == [].

test(after_none_is_everything, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    situation_history(All), situation_history_after(none, Got), Got == All.

test(after_must_be_a_number, [error(type_error(number, soon)), setup(load_test_episode), cleanup(store_reset)]) :-
    situation_history_after(soon, _).

%   A situation_history_json reply as rows of texts (its call and set indexes are its own).
decoded(J, Rows) :-
    atom_json_dict(J, D, []),
    findall([B, E, C, P, S, M],
            ( append(_, [B, E, CI, P, SI, M|Rest], D.rows), length(Rest, L), L mod 6 =:= 0,
              nth0(CI, D.calls, C),
              ( SI < 0 -> S = none ; nth0(SI, D.sets, Is), maplist([I, T]>>nth0(I, D.calls, T), Is, S) ) ),
            Rows).

%   The history read slice by slice from the bounds for Size, joined.
sliced(Size, Rows) :-
    history_slice_bounds(Size, Bounds),
    append([none|Bounds], [none], Ends),
    slices(Ends, Parts),
    append(Parts, Rows).

slices([_], []).
slices([After, Until|Ends], [Rows|Parts]) :-
    situation_history_json(After, Until, J), decoded(J, Rows),
    slices([Until|Ends], Parts).

test(slices_joined_are_the_whole_read, [cleanup(store_reset)]) :-
    forall(member(Seed, [1]),
           ( load_generated_episode(300, Seed),
             situation_history_json(J), decoded(J, Whole),
             length(Whole, N), N >= 300,
             % slices of one action are joined on the small episode below: the memory
             % backend scans every begin for each slice, so 300 of them cost minutes here
             forall(member(Size, [29, 120, 1000]),
                    ( sliced(Size, Got), assertion(Got == Whole) )) )).

test(slices_of_the_small_episode, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    history_slice_bounds(1, Bounds), Bounds = [B1, B2], B1 =:= 101, B2 > B1,
    history_slice_bounds_json(1, BJ), term_string(JBounds, BJ), JBounds == Bounds,
    situation_history_json(J), decoded(J, Whole),
    sliced(1, Got), Got == Whole,
    situation_history_json(none, B1, J1), decoded(J1, [First]), Whole = [First|_].

test(slice_bounds_keep_equal_begins_together) :-
    every_nth_bounds([1, 2, 2, 2, 3, 4, 4], 2, Bounds), Bounds == [2],    % 4 ends the last slice
    every_nth_bounds([1, 2, 3, 4, 5], 2, Five), Five == [2, 4],
    every_nth_bounds([], 2, None), None == [].

every_nth_bounds(Begins, Size, Bounds) :-
    odb_history:every_nth(Begins, Size, Size, Bounds0),
    odb_history:last_dropped(Bounds0, Begins, Bounds).

test(slice_bounds_need_a_positive_size, [error(type_error(positive_integer, 0))]) :-
    history_slice_bounds(0, _).

test(until_must_be_a_number, [error(type_error(number, later))]) :-
    situation_history_json(none, later, _).

:- end_tests(odb_history).
