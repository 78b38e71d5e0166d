:- module(store_tf,
    [ store_pose/4,             % +Frame, +At, -Pose, -Stamp
      store_assert_pose/3,      % +Frame, +Stamp, +Pose
      store_poses/4             % +Frame, +Begin, +End, -Trajectory
    ]).
/** <module> Poses: the NEEM's tf collection

A pose is `[RefFrame, [X,Y,Z], [QX,QY,QZ,QW]]`, the transform of a tf frame stamped at a
time, as KnowRob's tf_set_pose/3 and the tf logger write them. Poses have no scopes and no
graphs: a read asks for the latest at a time or for every one in an interval.
*/

:- use_module(library(error)).
:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module(neem, [store_backend/1]).
:- use_module(python, [store_python_call/3]).

:- dynamic mem_tf/3.            % ChildFrame, Stamp, [RefFrame, [X,Y,Z], [QX,QY,QZ,QW]]

:- multifile store_neem:memory_facts/1.
store_neem:memory_facts(store_tf:mem_tf(_, _, _)).

%!  store_pose(+Frame, +At, -Pose, -Stamp) is semidet.
%   The latest transform of tf frame Frame stamped at or before At (`any`: the latest of
%   all): Pose is `[RefFrame, [X,Y,Z], [QX,QY,QZ,QW]]`, from the NEEM's tf collection.
store_pose(Frame, At, Pose, Stamp) :-
    must_be(atom, Frame),
    (   At == any -> true ; must_be(number, At) ),
    (   store_backend(python(Neem))
    ->  ( At == any -> A = -1 ; A = At ),
        store_python_call(tf, [Neem, Frame, A], [[Stamp, Ref, X, Y, Z, QX, QY, QZ, QW]]),
        Pose = [Ref, [X, Y, Z], [QX, QY, QZ, QW]]
    ;   findall(St-P, ( mem_tf(Frame, St, P), ( At == any -> true ; St =< At ) ), Ps),
        Ps \== [],
        keysort(Ps, Sorted),
        last(Sorted, Stamp-Pose)
    ).

%!  store_assert_pose(+Frame, +Stamp, +Pose) is det.
%   Add a transform of Frame stamped Stamp to the NEEM's tf collection (KnowRob's
%   tf_set_pose/3 and the tf logger write them).
store_assert_pose(Frame, Stamp, Pose) :-
    must_be(atom, Frame), must_be(number, Stamp),
    (   Pose = [Ref, [X, Y, Z], [QX, QY, QZ, QW]], atom(Ref),
        maplist(number, [X, Y, Z, QX, QY, QZ, QW])
    ->  (   store_backend(python(Neem))
        ->  store_python_call(tf, [Neem, Frame, Stamp, Ref, X, Y, Z, QX, QY, QZ, QW, write], _)
        ;   assertz(mem_tf(Frame, Stamp, Pose))
        )
    ;   type_error(pose, Pose)
    ).

%!  store_poses(+Frame, +Begin, +End, -Trajectory) is det.
%   Every transform of Frame stamped in [Begin, End], as `Stamp-Pose` pairs in time order.
store_poses(Frame, Begin, End, Trajectory) :-
    must_be(atom, Frame), must_be(number, Begin), must_be(number, End),
    (   store_backend(python(Neem))
    ->  store_python_call(tf, [Neem, Frame, Begin, End], Rows),
        findall(St-[Ref, [X, Y, Z], [QX, QY, QZ, QW]], member([St, Ref, X, Y, Z, QX, QY, QZ, QW], Rows), Trajectory)
    ;   findall(St-P, ( mem_tf(Frame, St, P), St >= Begin, St =< End ), Ps),
        keysort(Ps, Trajectory)
    ).
