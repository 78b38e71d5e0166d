:- begin_tests(kb_tf).

:- use_module(tf).
:- use_module('../lang/query').
:- use_module('../lang/temporal').
:- use_module('../neem_store').
:- use_module(event).

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

:- end_tests(kb_tf).
