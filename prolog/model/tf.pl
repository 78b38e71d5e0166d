:- module(kb_tf,
    [ is_at/2,                  % ?Object, -Pose
      tf_get_pose/3,            % +Object, -Pose, -Stamp
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

Poses are as recorded, in their reference frame: there is no transform tree to re-express
them in another frame (KnowRob's tf_get_pose/4 with a reference frame).
*/

:- use_module(library(error)).
:- use_module('../neem_store', [store_pose/4]).
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
    store_pose(F, At, P0, _),
    P = P0.
