:- begin_tests(kb_tf).

:- use_module(tf).
:- use_module('../lang/query').
:- use_module('../lang/temporal').
:- use_module('../neem_store').
:- use_module('../store/tf').
:- use_module(event).
:- use_module('../lang/scope').

mug('https://ontology.dlr.de/soma/odb#Object_green_mug').

poses :-
    store_reset,
    store_assert_pose('Object_green_mug', 100.0, [map, [1.0, 2.0, 0.8], [0.0, 0.0, 0.0, 1.0]]),
    store_assert_pose('Object_green_mug', 200.0, [map, [3.0, 2.0, 0.8], [0.0, 0.0, 0.0, 1.0]]).

test(frame_name) :-
    object_frame_name(odb:'Object_green_mug', F), F == 'Object_green_mug',
    object_frame_name('http://e.org/things/cup', C), C == cup.

test(now_is_the_last_pose, [setup(poses), cleanup(store_reset)]) :-
    mug(M), is_at(M, [Ref, [X, _, _], _]), Ref == map, X =:= 3.0.

test(until_a_time_is_the_pose_then, [nondet, setup(poses), cleanup(store_reset)]) :-
    mug(M),
    kb_call(is_at(M, [_, [X, _, _], _]) until 150), X =:= 1.0,
    kb_call(is_at(M, [_, [Y, _, _], _]) until 200), Y =:= 3.0,
    \+ kb_call(is_at(M, _) until 50).                 % not seen yet

test(in_a_conjunction, [nondet, setup(poses), cleanup(store_reset)]) :-
    mug(M),
    kb_project(( has_participant(act, M), event_interval(act, 120.0, 130.0) )),
    kb_call(( has_participant(A, M), event_interval(A, B, _), is_at(M, [_, [X, _, _], _]) until B )),
    A == act, X =:= 1.0.

test(stamp, [setup(poses), cleanup(store_reset)]) :-
    mug(M), tf_get_pose(M, _, S), S =:= 200.0.

test(bad_pose, [setup(store_reset), cleanup(store_reset), error(type_error(pose, [map, [1, 2], []]))]) :-
    store_assert_pose(f, 1.0, [map, [1, 2], []]).

%   A tree: the table in map (turned 90 degrees about z, moved at 200), the mug on the table,
%   the handle on the mug (turned 90 degrees). Hand computation in the tests below.
tree :-
    store_reset,
    H is sqrt(0.5),
    store_assert_pose(table, 100.0, [map, [1.0, 2.0, 0.0], [0.0, 0.0, H, H]]),
    store_assert_pose(table, 200.0, [map, [5.0, 5.0, 0.0], [0.0, 0.0, 0.0, 1.0]]),
    store_assert_pose(mug, 150.0, [table, [0.5, 0.0, 0.8], [0.0, 0.0, 0.0, 1.0]]),
    store_assert_pose(handle, 150.0, [mug, [0.1, 0.0, 0.0], [0.0, 0.0, H, H]]).

close_to(Xs, Ys) :- maplist([X, Y]>>(abs(X - Y) =< 1e-9), Xs, Ys).

test(chain_to_map, [nondet, setup(tree), cleanup(store_reset)]) :-
    % at 160 the table is at (1,2,0) turned 90 degrees: (0.5,0,0.8) on it is (1,2.5,0.8) in map
    kb_call(is_at('http://e.org/x#mug', [map, P, R]) until 160),
    H is sqrt(0.5), close_to(P, [1.0, 2.5, 0.8]), close_to(R, [0.0, 0.0, H, H]),
    % the handle: (0.1,0,0) turned twice more is (1,2.6,0.8), turned 180 degrees
    kb_call(is_at('http://e.org/x#handle', [map, P2, R2]) until 160),
    close_to(P2, [1.0, 2.6, 0.8]), close_to(R2, [0.0, 0.0, 1.0, 0.0]),
    % an ancestor that is not map: the handle in the table's frame
    kb_call(is_at('http://e.org/x#handle', [table, P3, _]) until 160),
    close_to(P3, [0.6, 0.0, 0.8]),
    % after the table moved (identity rotation at (5,5,0))
    kb_call(is_at('http://e.org/x#mug', [map, P4, _]) until 300),
    close_to(P4, [5.5, 5.0, 0.8]).

test(no_chain_to_a_stranger, [setup(tree), cleanup(store_reset)]) :-
    \+ kb_call(is_at('http://e.org/x#mug', [kitchen, _, _]) until 160),
    \+ kb_call(is_at('http://e.org/x#mug', [map, _, _]) until 120).    % the mug is not seen yet

test(get_set_and_trajectory, [setup(store_reset), cleanup(store_reset)]) :-
    time_scope(=(10.0), =<('Infinity'), S1),
    tf_set_pose(cup, [map, [1.0, 0.0, 0.0], [0.0, 0.0, 0.0, 1.0]], S1),
    time_scope(=(20.0), =<('Infinity'), S2),
    tf_set_pose(cup, [map, [2.0, 0.0, 0.0], [0.0, 0.0, 0.0, 1.0]], S2),
    time_scope(=(15.0), =(15.0), Q),
    tf_get_pose(cup, [map, [X, _, _], _], Q, F),
    X =:= 1.0, get_dict(time, F, T), T.since =:= 10.0,
    tf_mng_trajectory(cup, 0.0, 30.0, Traj),
    Traj = [10.0-[map, [1.0|_], _], 20.0-[map, [2.0|_], _]],
    tf_mng_trajectory(cup, 11.0, 30.0, [20.0-_]).

:- end_tests(kb_tf).
