:- module(kb_tf,
    [ is_at/2,                  % ?Object, -Pose
      tf_get_pose/3,            % +Object, -Pose, -Stamp
      tf_get_pose/4,            % +Object, ?PoseQuery, +QScope, -FScope
      tf_set_pose/3,            % +Object, +Pose, +FScope
      tf_mng_trajectory/4,      % +Object, +Begin, +End, -Trajectory
      pose_compose/3,           % +Outer, +Inner, -Pose
      tf_logger_enable/0,
      tf_logger_disable/0,
      tf_mem_clear/0,
      object_frame_name/2       % +Object, -Frame
    ]).
/** <module> Where objects were: poses from the NEEM's tf collection (KnowRob 2.x src/ros/tf)

The logger writes a transform in KnowRob's tf layout when a perception comes with a pose
(`header.stamp`, `child_frame_id`, `transform.translation/rotation`); the frame of an
object is its IRI's local name (KnowRob's object_frame_name/2 without a frame-name
annotation). is_at/2 answers with the transform valid at the question scope's time: the
latest stamped at or before it, as KnowRob's tf fluent does.

    ?- is_at(odb:'Object_green_mug', [Ref, Pos, Rot]).              % now: the last pose
    ?- is_at(odb:'Object_green_mug', Pose) until 1714550520.        % at a time
    ?- kb_call(( has_participant(A, O), event_interval(A, B, _),
                 is_at(O, P) until B )).                            % at an action's begin

A pose asked for in another frame than the one it was recorded in (`is_at(O, [map, P, R])`
with `O` recorded relative to a table, the table relative to `map`) walks the chain of parent
frames, as KnowRob's tf module does: the transform of each parent frame valid at the same time
is composed until the asked frame is reached (any ancestor; no answer when it is none).
*/

:- use_module(library(error)).
:- use_module('../store/tf', [store_pose/4, store_assert_pose/3, store_poses/4]).
:- use_module('../lang/scope', [scope_term/2, time_scope_data/2]).
:- use_module('../lang/query', [kb_call/1]).
:- use_module('../lang/triple', [kb_iri/2]).

:- multifile kb_query:kb_scoped_goal/3.
kb_query:kb_scoped_goal(is_at(O, P), Scope, kb_tf:pose_in_scope(O, P, Scope)).

%!  is_at(+Object, -Pose) is semidet.
%   Pose `[RefFrame, [X,Y,Z], [QX,QY,QZ,QW]]` of Object at the question scope's time (now
%   when called from Prolog; `is_at(O, P) until T` for time T).
is_at(O, P) :- once(kb_call(is_at(O, P))).

%!  tf_get_pose(+Object, -Pose, -Stamp) is semidet.
%   The latest recorded pose of Object and when it was recorded.
tf_get_pose(O, P, Stamp) :-
    object_frame_name(O, F),
    store_pose(F, any, P, Stamp).

%!  tf_get_pose(+Object, ?PoseQuery, +QScope, -FScope) is semidet.
%   KnowRob's tf_get_pose/4: PoseQuery `[Ref, Pos, Rot]` of Object valid at the end of the
%   question scope QScope (a scope dictionary, e.g. `time_scope(=(T), =(T), QS)`, or
%   `scope(S, U)`); a bound Ref other than the recorded frame walks the frame chain. FScope is
%   the scope the answer holds from: since the latest stamp used, open end.
tf_get_pose(O, [Ref, Pos, Rot], QScope, FScope) :-
    must_be(nonvar, O),
    scope_term(QScope, Scope),
    scope_time(Scope, At),
    object_frame_name(O, F),
    frame_pose(F, At, Ref, [Ref, Pos, Rot], Stamp, [F]),
    Inf is inf,
    FScope = dict{time: dict{since: Stamp, until: Inf}}.

%!  tf_set_pose(+Object, +Pose, +FScope) is det.
%   KnowRob's tf_set_pose/3: record Pose `[Ref, [X,Y,Z], [QX,QY,QZ,QW]]` of Object from the
%   time FScope begins (`time_scope(=(T), =<('Infinity'), S)` as neem-interface's mem_tf_set
%   builds it) in the NEEM's tf collection.
tf_set_pose(O, Pose, FScope) :-
    object_frame_name(O, F),
    time_scope_data(FScope, [Since, _]),
    must_be(number, Since),
    store_assert_pose(F, Since, Pose).

%!  tf_mng_trajectory(+Object, +Begin, +End, -Trajectory) is det.
%   KnowRob's tf_mng_trajectory/4: every recorded pose of Object stamped in [Begin, End], as
%   `Stamp-[Ref, Pos, Rot]` pairs in time order, each in the frame it was recorded in.
tf_mng_trajectory(O, Begin, End, Trajectory) :-
    object_frame_name(O, F),
    store_poses(F, Begin, End, Trajectory).

%!  tf_logger_enable is det.
%!  tf_logger_disable is det.
%!  tf_mem_clear is det.
%   KnowRob's tf logger switches and its in-memory tf buffer. There is no ROS /tf topic to
%   record here: transforms enter the NEEM through tf_set_pose/3 (and the logger's
%   perceptions), so the switches and the buffer have nothing to act on and succeed.
tf_logger_enable.
tf_logger_disable.
tf_mem_clear.

%!  pose_compose(+Outer, +Inner, -Pose) is det.
%   Outer `[A, P1, Q1]` is frame B's pose in A; Inner `[B, P2, Q2]` a pose in B; Pose is the
%   latter in A: `[A, P1 + rotate(Q1, P2), Q1 * Q2]`.
pose_compose([A, P1, Q1], [_, P2, Q2], [A, P, Q]) :-
    quaternion_rotate(Q1, P2, R),
    maplist([X, Y, Z]>>(Z is X + Y), P1, R, P),
    quaternion_multiply(Q1, Q2, Q).

quaternion_multiply([X1, Y1, Z1, W1], [X2, Y2, Z2, W2], [X, Y, Z, W]) :-
    X is W1*X2 + X1*W2 + Y1*Z2 - Z1*Y2,
    Y is W1*Y2 - X1*Z2 + Y1*W2 + Z1*X2,
    Z is W1*Z2 + X1*Y2 - Y1*X2 + Z1*W2,
    W is W1*W2 - X1*X2 - Y1*Y2 - Z1*Z2.

quaternion_rotate(Q, [VX, VY, VZ], [X, Y, Z]) :-
    Q = [QX, QY, QZ, QW],
    quaternion_multiply(Q, [VX, VY, VZ, 0.0], T),
    quaternion_multiply(T, [-QX, -QY, -QZ, QW], [X, Y, Z, _]).

%   frame_pose(+Frame, +At, ?Ref, -Pose, -Stamp, +Seen): the pose of Frame at At in Ref (its
%   recorded frame when Ref is free), composing parent frames' poses valid at At; Stamp the
%   latest stamp used. Seen guards against a cycle in a broken tree.
frame_pose(F, At, Ref, Pose, Stamp, Seen) :-
    store_pose(F, At, Pose0, Stamp0),
    Pose0 = [Parent|_],
    (   ( var(Ref) ; Ref == Parent )
    ->  Pose = Pose0, Stamp = Stamp0
    ;   \+ memberchk(Parent, Seen),
        frame_pose(Parent, At, Ref, Outer, Stamp1, [Parent|Seen]),
        pose_compose(Outer, Pose0, Pose),
        Stamp is max(Stamp0, Stamp1)
    ).

scope_time(scope(_, U), At) :- !,
    (   U =:= inf -> At = any ; At = U ).
scope_time(_, any).

%!  object_frame_name(+Object, -Frame) is det.
%   The tf frame of an object: the local name of its IRI.
object_frame_name(O0, F) :-
    kb_iri(O0, O),
    must_be(atom, O),
    (   sub_atom(O, B, 1, _, '#'), \+ ( sub_atom(O, B1, 1, _, '#'), B1 > B )
    ->  B2 is B + 1, sub_atom(O, B2, _, 0, F)
    ;   sub_atom(O, B, 1, _, '/'), \+ ( sub_atom(O, B1, 1, _, '/'), B1 > B )
    ->  B2 is B + 1, sub_atom(O, B2, _, 0, F)
    ;   F = O
    ).

%   The question scope's time: the end of scope(S, U) (the time asked about; `G until T`
%   is scope(T, T), now is scope(Now, Now)); any time for `any`.
pose_in_scope(O, P, Scope) :-
    must_be(nonvar, O),
    object_frame_name(O, F),
    (   Scope = scope(_, U) -> At = U ; At = any ),
    (   nonvar(P), P = [Ref|_], atom(Ref) -> true ; true ),
    frame_pose(F, At, Ref, P0, _, [F]),
    P = P0.
