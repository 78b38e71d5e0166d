:- begin_tests(store_tf).

:- use_module(tf).
:- use_module(neem, [store_reset/0, store_use_python/1]).

pose(X, [map, [X, 0.0, 0.0], [0.0, 0.0, 0.0, 1.0]]).

poses :-
    store_reset,
    forall(member(T-X, [200.0-2.0, 100.0-1.0, 300.0-3.0]),
           ( pose(X, P), store_assert_pose(mug, T, P) )).

% The python backend, stood in for: py_tf/2 keeps the request it got and answers Reply
% (made at run time, see python.plt).
python_stub(Reply) :-
    Tf =.. [py_tf, Request, Reply],
    assertz((store_python:Tf :- nb_setval(store_sent, Request))),
    Match =.. [py_match, _, "r(d,[])"],
    assertz(store_python:Match),
    store_use_python(n1).

python_unstub :-
    abolish(store_python:py_tf/2),
    abolish(store_python:py_match/2),
    store_reset.

test(latest_pose_at_or_before, [setup(poses), cleanup(store_reset)]) :-
    store_pose(mug, 250.0, P, T), T == 200.0, pose(2.0, P),
    store_pose(mug, 100.0, _, T1), T1 == 100.0,
    \+ store_pose(mug, 50.0, _, _),
    store_pose(mug, any, _, T2), T2 == 300.0,
    \+ store_pose(cup, any, _, _).

test(trajectory_in_time_order, [setup(poses), cleanup(store_reset)]) :-
    store_poses(mug, 100.0, 250.0, Trajectory),
    pairs_keys(Trajectory, [100.0, 200.0]),
    store_poses(mug, 400.0, 500.0, []).

test(pose_checked, [error(type_error(pose, [map, [1, 2], [0, 0, 0, 1]]))]) :-
    store_assert_pose(mug, 1.0, [map, [1, 2], [0, 0, 0, 1]]).

test(at_is_a_number_or_any, [error(type_error(number, now))]) :-
    store_pose(mug, now, _, _).

test(python_read, [cleanup(python_unstub)]) :-
    python_stub("[[200.0, map, 2.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0]]"),
    store_pose(mug, any, P, T),
    T == 200.0, pose(2.0, P),
    nb_getval(store_sent, [n1, mug, -1]),
    store_poses(mug, 0.0, 300.0, [T-P]),
    nb_getval(store_sent, [n1, mug, 0.0, 300.0]).

test(python_write, [cleanup(python_unstub)]) :-
    python_stub("[]"),
    pose(1.0, P),
    store_assert_pose(mug, 5.0, P),
    nb_getval(store_sent, [n1, mug, 5.0, map, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, write]).

:- end_tests(store_tf).
