:- module(odb_past,
    [ latest_time/1,              % -Time
      done_between/3,             % +From, +To, -Done
      last_before/2,              % +Time, -Done
      latest_before/3,            % +Time, +N, -Done
      last_done/3,                % +Call, +Before, -Begin
      done_times/4,               % +Call, +From, +To, -Begins
      usual_after/3,              % +Call, -Occurrences, -Counts
      suggestion/3,               % +Call, +Before, -Suggestion
      object_place/3,             % +ObjectName, +At, -Place
      performers/2,               % +Call, -Modes
      past_answer_json/1          % -JSONString
    ]).
/** <module> Questions about the past: the evidence of the NEEM (RACCOON's state summaries)

The facts behind "when did I last X", "how often did I X", "what do I usually do after X",
"what did you do this morning", "where is the Y" and "why did you suggest X", read with
KnowRob's predicates (executes_task, event_interval, has_role, task_role, the tf fluent)
and the odb modules. Times are unix seconds; the windows (today, this week, this morning)
are chosen by the caller (Python's timeline, the one home of the clock). Calls are chain
terms such as `pick(banana)`; an odb:IdleTask action is never an answer.

The sentences are made in Python (oracle.past); this module hands over the evidence only.
*/

:- use_module(library(error), [must_be/2]).
:- use_module(library(lists), [append/2, append/3, clumped/2, max_member/2, member/2, reverse/2]).
:- use_module(library(apply), [include/3]).
:- use_module(library(pairs), [pairs_values/2]).
:- use_module(library(assoc), [get_assoc/3, list_to_assoc/2]).
:- use_module(library(ordsets), [ord_memberchk/2]).
:- use_module('../json_text', [json_text/2]).
:- use_module('../neem_store', [store_match/3, store_python_request/1]).
:- use_module('../store/tf', [store_pose/4]).
:- use_module('../lang/query', [kb_call/2, kb_findall/4, kb_findall/5]).
:- use_module('../lang/triple', [kb_iri/2]).
:- use_module('../model/rdfs', []).
:- use_module('../model/event', []).
:- use_module('../model/object', []).
:- use_module('../model/situation', []).
:- use_module('../model/tf', [object_frame_name/2]).
:- use_module(names, [odb_iri/2, call_classes/3]).
:- use_module(history, [typed_modes/2]).
:- use_module(calls, [task_calls/2, call_tasks/2, call_task_times/3, call_time/5]).
:- use_module(decisions, [latest_first/4, imagined_preference/2, preference_at/3]).
:- use_module('../answers', [call_text/2]).

%!  latest_time(-Time) is semidet.
%   The latest begin of any event of the NEEM (an action, an imagining): the NEEM's "now".
latest_time(T) :-
    kb_iri(soma:hasIntervalBegin, BeginP),
    once(store_match([t(_, BeginP, T)], any, [order([desc(T)]), limit(1)])).

%!  done_between(+From, +To, -Done) is det.
%   The non-idle actions that began in [From, To] (`none`: no bound), by begin, as
%   `done(Begin, End, Call)`: one store query from the begins the store finds by value,
%   then each distinct odb task's call once (task_calls/2).
done_between(From, To, Done) :-
    bound_or_none(From), bound_or_none(To),
    (   From == none
    ->  BSpec = B
    ;   BSpec = (>=(From) -> B)
    ),
    kb_findall(B-E-T-C, ( triple(I, soma:hasIntervalBegin, BSpec), has_time_interval(A, I),
                          has_interval_end(I, E), executes_task(A, T), triple(T, rdf:type, C) ), any, Rows0),
    odb_iri('IdleTask', Idle),
    % the odb-typed, non-idle actions only: the mental actions' tasks need no call
    findall(B-E-T, ( member(B-E-T-C, Rows0), C \== Idle, odb_iri(_, C), begins_by(To, B) ), Rows1),
    sort(Rows1, Rows),
    findall(T, member(_-_-T, Rows), Ts),
    task_calls(Ts, Pairs),
    list_to_assoc(Pairs, CallOf),
    findall(done(B1, E1, C1), ( member(B1-E1-T1, Rows), get_assoc(T1, CallOf, C1) ), Done0),
    sort(Done0, Done).

begins_by(none, _) :- !.
begins_by(To, B) :- B =< To.

bound_or_none(none) :- !.
bound_or_none(X) :- must_be(number, X).

%!  last_before(+Time, -Done) is semidet.
%   The latest non-idle action that began before Time, as `done(Begin, End, Call)`.
last_before(Time, Done) :-
    latest_before(Time, 1, [Done]).

%!  latest_before(+Time, +N, -Done) is det.
%   The (at most N) latest non-idle actions that began before Time, oldest first, as
%   `done(Begin, End, Call)`: the store sends the latest odb-typed actions a few at a time
%   (ordered, limited), never the whole NEEM's.
latest_before(Time, N, Done) :-
    must_be(number, Time), must_be(positive_integer, N),
    odb_iri('IdleTask', Idle),
    Ask is 2*N + 4,
    latest_before(Time, Idle, N, Ask, Done).

latest_before(Time, Idle, N, Ask, Done) :-
    kb_findall(B-E-T-C, ( triple(I, soma:hasIntervalBegin, (<(Time) -> B)), has_time_interval(A, I),
                          has_interval_end(I, E), executes_task(A, T), triple(T, rdf:type, C) ),
               any, [order([desc(B)]), limit(Ask)], Rows),
    findall(B-E-T, ( member(B-E-T-C, Rows), C \== Idle, odb_iri(_, C) ), Actions0),
    sort(0, @>=, Actions0, Actions),
    findall(T, member(_-_-T, Actions), Ts),
    task_calls(Ts, Pairs),
    findall(done(B, E, Call), ( member(B-E-T, Actions), memberchk(T-Call, Pairs) ), Found),
    length(Rows, Got),
    (   ( length(Found, K), K >= N ; Got < Ask )
    ->  length(Found, K1), Keep is min(N, K1),
        length(Latest, Keep), append(Latest, _, Found),
        reverse(Latest, Done)
    ;   Ask1 is Ask * 4,
        latest_before(Time, Idle, N, Ask1, Done)
    ).

%!  last_done(+Call, +Before, -Begin) is semidet.
%   The latest begin at or before Before (`none`: ever) of an action that executed Call.
last_done(Call, Before, B) :-
    check_call(Call),
    bound_or_none(Before),
    (   Before == none
    ->  call_time(Call, _, _, desc, B)
    ;   call_time(Call, =<(Before), _, desc, B)
    ).

%!  done_times(+Call, +From, +To, -Begins) is det.
%   The begins, ascending, of the actions that executed Call and began in [From, To].
done_times(Call, From, To, Begins) :-
    check_call(Call),
    must_be(number, From), must_be(number, To),
    call_tasks(Call, Tasks),
    call_task_times(Call, Tasks, Times),
    findall(B, ( member(B-_, Times), B >= From, B =< To ), Bs),
    msort(Bs, Begins).

%!  usual_after(+Call, -Occurrences, -Counts) is det.
%   What followed Call: Occurrences is how often Call was done, Counts the list of
%   `Next-N` (the next non-idle action's call, how often), most often first (ties by the
%   calls' text). The rule of oracle.past.routines.follows, which the service runs on the
%   kept history (tests/past/test_follows.py holds the two equal). The last action of the NEEM has no next one. Reads Call's
%   actions, every odb action's begin and task (one query each), then the calls of the few tasks
%   that follow an occurrence: not the call of every task of the NEEM.
usual_after(Call, Occurrences, Counts) :-
    check_call(Call),
    call_tasks(Call, Tasks),
    call_task_times(Call, Tasks, Times0),
    msort(Times0, Times),
    length(Times, Occurrences),
    kb_findall(B-T-C, ( executes_task(A, T), triple(T, rdf:type, C), has_time_interval(A, I),
                        has_interval_begin(I, B) ), any, Typed),
    findall(B-T, ( member(B-T-C, Typed), odb_iri(_, C) ), Rows0),
    sort(Rows0, Rows),
    findall(Follow, ( member(B0-_, Times), following(Rows, B0, Follow) ), Follows),
    append(Follows, Ts),
    task_calls(Ts, Pairs),
    list_to_assoc(Pairs, CallOf),
    findall(Next, ( member(F, Follows), first_call(F, CallOf, Next) ), Nexts),
    counted(Nexts, Counts).

%!  following(+Rows, +Begin, -Tasks) is det.
%   The tasks of the (at most 2) odb actions that began after Begin, in begin order: the
%   next non-idle action is among them (an idle gap may come first).
following(Rows, B0, Tasks) :-
    findall(T, ( member(B-T, Rows), B > B0 ), After),
    length(After, N),
    K is min(N, 2),
    length(Tasks, K),
    append(Tasks, _, After).

first_call(Tasks, CallOf, Call) :-
    member(T, Tasks),
    get_assoc(T, CallOf, Call),
    Call \== 'IdleTask', !.

%   Items as Item-N pairs, most often first, ties by the calls' text.
counted(Items, Counts) :-
    msort(Items, Sorted),
    clumped(Sorted, Pairs),
    findall((Neg-Text)-(I-N), ( member(I-N, Pairs), Neg is -N, call_text(I, Text) ), Keyed),
    keysort(Keyed, ByCount),
    pairs_values(ByCount, Counts).

%!  suggestion(+Call, +Before, -Suggestion) is semidet.
%   The latest imagined preference that began at or before Before (`none`: any) and ranked
%   Call, as `suggested(Time, Rank, Score, Top)`, Top its first `ranked(Call, Rank, Score)`.
suggestion(Call, Before, suggested(T, Rank, Score, Top)) :-
    check_call(Call),
    bound_or_none(Before),
    latest_first(preference, Before, T, M),
    imagined_preference(M, Ranked),
    memberchk(ranked(Call, Rank, Score), Ranked), !,
    Ranked = [Top|_].

%!  object_place(+ObjectName, +At, -Place) is det.
%   Where an object of the odb class ObjectName was at At (`none`: latest), as
%   `place(Pose, Used)`: Pose the latest tf pose recorded by then, `pose(Stamp, Frame,
%   [X,Y,Z])` or `none`; Used the latest action by then in which an object of that class had
%   a role, `used(Begin, Call)` or `none`.
object_place(Name, At, place(Pose, Used)) :-
    must_be(atom, Name),
    bound_or_none(At),
    odb_iri(Name, C),
    kb_findall(O, triple(O, rdf:type, C), any, Os0),
    sort(Os0, Os),
    (   At == none -> When = any ; When = At ),
    findall(S-pose(S, Ref, Pos),
            ( member(O, Os), object_frame_name(O, F), store_pose(F, When, [Ref, Pos, _], S) ),
            Poses),
    (   Poses == [] -> Pose = none ; max_member(_-Pose, Poses) ),
    kb_findall(B-T, ( triple(O1, rdf:type, C), has_role(O1, R), task_role(T, R),
                      executes_task(A, T), event_interval(A, B, _) ), any, Uses0),
    include(began_by(At), Uses0, Uses),
    (   Uses == []
    ->  Used = none
    ;   max_member(UB-UT, Uses),
        task_calls([UT], [UT-UC]),
        Used = used(UB, UC)
    ).

%!  performers(+Call, -Modes) is det.
%   Who performed each action of Call, by begin: `Begin-Mode`, Mode `user` when a performer
%   (soma:isPerformedBy) is a dul:NaturalPerson and no other is, `robot` when the performers
%   are other dul:PhysicalAgents, `together` when there are both (the user and the robot),
%   `unknown` without a performer of either type (odb_history:typed_modes/2). Two store
%   queries over the actions of Call's task class (their begins; their performers with their
%   types), kept for Call's tasks.
performers(Call, Modes) :-
    check_call(Call),
    call_classes(Call, TC, _),
    call_tasks(Call, Tasks0),
    sort(Tasks0, Tasks),
    kb_findall(A-B-T, ( triple(T, rdf:type, TC), executes_task(A, T), has_time_interval(A, I),
                        has_interval_begin(I, B) ), any, Actions0),
    findall(A-B, ( member(A-B-T, Actions0), ord_memberchk(T, Tasks) ), Actions),
    kb_findall(A-Ag-C, ( triple(T, rdf:type, TC), executes_task(A, T), is_performed_by(A, Ag),
                         triple(Ag, rdf:type, C) ), any, Typed),
    typed_modes(Typed, ModeOf),
    findall(B-Mode, ( member(A-B, Actions), ( get_assoc(A, ModeOf, Mode) -> true ; Mode = unknown ) ), Modes0),
    msort(Modes0, Modes).

began_by(none, _) :- !.
began_by(At, B-_) :- B =< At.

check_call(Call) :-
    must_be(callable, Call),
    call_classes(Call, _, _).

                 /*******************************
                 *        FOR THE BRIDGE        *
                 *******************************/

%!  past_answer_json(-JSON) is det.
%   Answer the request the Python bridge handed over (store_python_request/1) as a JSON
%   string (oracle.past.evidence reads it); values arrive as terms, never as query text.
past_answer_json(JSON) :-
    store_python_request(Request),
    past_answer(Request, Dict),
    json_text(Dict, JSON).

past_answer([now], _{time: T}) :-
    (   latest_time(T0) -> T = T0 ; T = null ).
past_answer([last, Name, Args, Before], _{task: Text, begin: B}) :-
    call_of(Name, Args, Call, Text),
    (   last_done(Call, Before, B0) -> B = B0 ; B = null ).
past_answer([count, Name, Args, From, To], _{task: Text, begins: Bs}) :-
    call_of(Name, Args, Call, Text),
    done_times(Call, From, To, Bs).
past_answer([after, Name, Args], _{task: Text, occurrences: N, next: Ds}) :-
    call_of(Name, Args, Call, Text),
    usual_after(Call, N, Counts),
    findall(_{task: T, count: K}, ( member(C-K, Counts), call_text(C, T) ), Ds).
past_answer([before, Time, N], _{actions: Ds}) :-
    latest_before(Time, N, Done),
    findall(_{task: T, begin: B, end: E}, ( member(done(B, E, C), Done), call_text(C, T) ), Ds).
past_answer([who, Name, Args], _{task: Text, modes: Ds}) :-
    call_of(Name, Args, Call, Text),
    performers(Call, Modes),
    findall(_{time: B, mode: M}, member(B-M, Modes), Ds).
past_answer([predicted, Time], _{predicted: Ds}) :-
    (   preference_at(Time, _, Ranked) -> true ; Ranked = [] ),
    findall(_{task: T, rank: R, score: S}, ( member(ranked(C, R, S), Ranked), call_text(C, T) ), Ds).
past_answer([done, From, To], _{actions: Ds}) :-
    done_between(From, To, Done),
    findall(_{task: T, begin: B, end: E}, ( member(done(B, E, C), Done), call_text(C, T) ), Ds).
past_answer([where, Name, At], _{object: Name, pose: PD, used: UD}) :-
    object_place(Name, At, place(Pose, Used)),
    (   Pose = pose(S, F, Pos) -> PD = _{time: S, frame: F, position: Pos} ; PD = null ),
    (   Used = used(B, C) -> call_text(C, T), UD = _{time: B, task: T} ; UD = null ).
past_answer([suggested, Name, Args, Before], D) :-
    call_of(Name, Args, Call, Text),
    (   suggestion(Call, Before, suggested(T, R, S, ranked(TC, _, _)))
    ->  call_text(TC, Top),
        D = _{task: Text, time: T, rank: R, score: S, top: Top}
    ;   D = _{task: Text, time: null}
    ).

call_of(Name, Args, Call, Text) :-
    must_be(atom, Name), must_be(list, Args),
    Call =.. [Name|Args],
    call_text(Call, Text).
