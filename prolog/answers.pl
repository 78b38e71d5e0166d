:- module(answers,
    [ why_not/2,                  % +Call, -Reason
      why_not/3,                  % +Call, +Time, -Reason
      what_next/1,                % -Chain
      something_else/2,           % ?Current, -Alternative
      something_else/3,           % ?Current, -Alternative, -RankScore
      chosen_after/3,             % +Time, -Call, -Begin
      call_text/2,                % +Call, -Text
      reason_dict/2,              % +Reason, -Dict
      answer_json/1               % -JSONString
    ]).
/** <module> The robot's answers (thesis 4.6)

"Why didn't you do X?", "What do you want to do next?" and "Do something else!",
answered from the history of imagined situations, imagined preferences and executed
actions in the NEEM (the odb modules). Calls are chain terms such as `pick(banana)`.

Reason terms of why_not/2,3 (each a separate solution, most telling first):

  - done(Call, Begin): it was done then (the question's premise is wrong);
  - not_available(Call, When, Why): it was not among the tasks imagined available at
    the decision of time When; Why is `object_not_perceived(Object)` when no object of
    that class had been perceived by then (the logger scopes an object's type from its
    first perception), else `precondition_failed` (the NEEM does not say which);
  - ranked_lower(Call, When, rank(Rank, Score), Higher): it was available but the
    imagined preference ranked the tasks Higher (`ranked(Call, Rank, Score)`) above it;
  - ranked_first(Call, When, Score): it was available and ranked first (the question's
    premise is wrong: it was the suggestion);
  - user_chose(Other, Begin): the user had the robot do Other instead;
  - done_later(Call, Begin) / done_earlier(Call, Begin): when it was done nearest after
    (before) the time asked about.
*/

:- use_module(library(error)).
:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module(json_text, [json_text/2]).
:- use_module(neem_store).
:- use_module(lang/query, [kb_call/2]).
:- use_module(lang/triple, [kb_iri/2]).
:- use_module(model/rdfs, []).
:- use_module(model/event, []).
:- use_module(odb/names, [odb_iri/2]).
:- use_module(odb/calls, [task_call/2, call_time/4, call_time/5]).
:- use_module(odb/events, [perceived_at/2]).
:- use_module(odb/decisions, [decision_at/3, imagined_available/2, latest_decision/4, preference_at/3,
                              latest_preference/3]).

%!  why_not(+Call, -Reason) is nondet.
%   Why Call was not done lately: at the latest decision the robot made.
why_not(Call, Reason) :-
    check_call(Call),
    (   latest_decision(situation, any, _, At)
    ->  true
    ;   get_time(At)
    ),
    why_not(Call, At, Reason).

%!  why_not(+Call, +Time, -Reason) is nondet.
%   Why Call was not done at Time (unix seconds). Every step asks the store for the few
%   rows it needs (comparisons, order and limit evaluated by the database), so the answer
%   costs a few queries however long the NEEM and however often Call was done.
why_not(Call, At, Reason) :-
    check_call(Call),
    must_be(number, At),
    (   call_time(Call, =<(At), >=(At), B)
    ->  Reason = done(Call, B)
    ;   decision_at(situation, At, M)
    ->  once(kb_call(event_interval(M, When, _), any)),
        reasons_at(Call, At, M, When, Reason)
    ;   later_earlier(Call, At, Reason)
    ).

reasons_at(Call, At, M, When, Reason) :-
    imagined_available(M, Available),
    (   \+ memberchk(Call, Available)
    ->  missing_reason(Call, When, Why),
        R1 = [not_available(Call, When, Why)]
    ;   preference_at(At, _, Ranked),
        nth1(_, Ranked, ranked(Call, Rank, Score))
    ->  (   Rank > 1
        ->  findall(ranked(C, R, S), ( member(ranked(C, R, S), Ranked), R < Rank ), Higher),
            R1 = [ranked_lower(Call, When, rank(Rank, Score), Higher)]
        ;   R1 = [ranked_first(Call, When, Score)]   % the premise is wrong: it was suggested
        )
    ;   R1 = []
    ),
    (   chosen_after(When, Other, OB), Other \== Call
    ->  R2 = [user_chose(Other, OB)]
    ;   R2 = []
    ),
    findall(R, later_earlier(Call, At, R), R3),
    append([R1, R2, R3], Reasons),
    member(Reason, Reasons).

missing_reason(Call, When, object_not_perceived(Obj)) :-
    Call =.. [_|Objects],
    member(Obj, Objects),
    \+ perceived_at(Obj, When), !.
missing_reason(_, _, precondition_failed).

%   done_later: the first begin after At; else done_earlier: the latest begin of an action
%   that ended before At (and so began before it: the store scans back from At).
later_earlier(Call, At, done_later(Call, B)) :-
    call_time(Call, >(At), _, asc, B), !.
later_earlier(Call, At, done_earlier(Call, B)) :-
    call_time(Call, <(At), <(At), desc, B), !.

%!  chosen_after(+Time, -Call, -Begin) is semidet.
%   The first non-idle task executed at or after Time: executions in begin order, fetched
%   from the store in growing ordered chunks until one is not idle.
chosen_after(Time, Call, Begin) :-
    must_be(number, Time),
    odb_iri('IdleTask', Idle),
    first_done(asc, Time, 16, Idle, Call, Begin).

%   first_done(+Dir, +Bound, +N, +Idle, -Call, -Begin): the first non-idle execution in
%   begin order (Dir `asc`: at or after Bound; `desc`: at or before it; Bound `none`: any),
%   ties in the same direction by task (as sort/4 orders Begin-Task pairs),
%   read from the store in ordered chunks of N, 4N, ... rows until one is found.
first_done(Dir, Bound, N, Idle, Call, Begin) :-
    maplist(kb_iri, [dul:executesTask, dul:hasTimeInterval, soma:hasIntervalBegin], [Ex, HI, BeginP]),
    (   Bound == none -> BO = B ; Dir == asc -> BO = cmp(>=, Bound, B) ; BO = cmp(=<, Bound, B) ),
    Key =.. [Dir, B],
    findall(B-T, store_match([t(A, Ex, T), t(A, HI, I), t(I, BeginP, BO)], any, [order([Key]), limit(N)]),
            Rows),
    (   Dir == asc -> Order = @=< ; Order = @>= ),
    length(Rows, Got),
    (   Got < N
    ->  sort(0, Order, Rows, Pairs),
        first_choice(Pairs, Idle, Call, Begin)
    ;   last(Rows, Last-_),
        exclude(begins_at(Last), Rows, Complete),   % the last begin may have more rows
        sort(0, Order, Complete, Pairs),
        (   first_choice(Pairs, Idle, Call, Begin)
        ->  true
        ;   % from a hair short of the last begin: a begin read back may differ from the stored
            % number in its last bit (a Decimal128); the rows looked at again hold no choice
            Hair is max(1.0e-9, abs(Last) * 1.0e-15),
            (   Dir == asc -> Next is Last - Hair ; Next is Last + Hair ),
            N1 is N*4,
            first_done(Dir, Next, N1, Idle, Call, Begin)
        )
    ).

begins_at(Last, B-_) :- B =:= Last.

first_choice(Pairs, Idle, Call, Begin) :-
    member(Begin-T, Pairs),
    \+ kb_call(instance_of(T, Idle), any),
    task_call(T, Call), !.

%!  what_next(-Chain) is semidet.
%   The predicted next tasks, best first, from the latest imagined preference:
%   a list of `ranked(Call, Rank, Score)`.
what_next(Chain) :-
    latest_preference(_, _, Chain).

%!  something_else(?Current, -Alternative) is nondet.
%!  something_else(?Current, -Alternative, -RankScore) is nondet.
%   Alternatives to Current, best first, from the preference imagined before Current
%   started (or the latest one when Current was not started). Current defaults to the
%   task of the latest action. RankScore is `rank(Rank, Score)`.
something_else(Current, Alternative) :-
    something_else(Current, Alternative, _).

something_else(Current, Alternative, rank(R, S)) :-
    (   var(Current)
    ->  latest_action(Current, Begin)
    ;   check_call(Current),
        (   call_time(Current, _, _, desc, Begin) -> true ; true )
    ),
    (   number(Begin), preference_at(Begin, _, Ranked)
    ->  true
    ;   latest_preference(_, _, Ranked)
    ),
    member(ranked(Alternative, R, S), Ranked),
    Alternative \== Current.

%   The task call of the latest non-idle execution (by begin, then the greatest task), read
%   newest first in growing chunks (not every action of the NEEM).
latest_action(Call, Begin) :-
    odb_iri('IdleTask', Idle),
    first_done(desc, none, 16, Idle, Call, Begin).

check_call(Call) :-
    must_be(callable, Call),
    Call =.. [_|Args],
    maplist(must_be(atom), Args).

                 /*******************************
                 *        FOR THE BRIDGE        *
                 *******************************/

%!  call_text(+Call, -Text) is det.
%   `pick(banana)` as the string "pick(banana)" (chain syntax, no quoting).
call_text(Call, Text) :-
    Call =.. [Name|Args],
    (   Args == []
    ->  atom_string(Name, Text)
    ;   atomic_list_concat(Args, ', ', Inner),
        format(string(Text), "~w(~w)", [Name, Inner])
    ).

ranked_dict(ranked(C, R, S), _{task: T, rank: R, score: S}) :-
    call_text(C, T).

%!  reason_dict(+Reason, -Dict) is det.
%   A reason term as a JSON-ready dict with a `reason` key naming its kind.
reason_dict(done(C, B), _{reason: done, task: T, time: B}) :- call_text(C, T).
reason_dict(not_available(C, W, Why), D) :-
    call_text(C, T),
    (   Why = object_not_perceived(O)
    ->  D = _{reason: not_available, task: T, time: W, why: object_not_perceived, object: O}
    ;   D = _{reason: not_available, task: T, time: W, why: Why}
    ).
reason_dict(ranked_lower(C, W, rank(R, S), Higher), _{reason: ranked_lower, task: T, time: W,
                                                      rank: R, score: S, higher: Hs}) :-
    call_text(C, T), maplist(ranked_dict, Higher, Hs).
reason_dict(ranked_first(C, W, S), _{reason: ranked_first, task: T, time: W, score: S}) :- call_text(C, T).
reason_dict(user_chose(C, B), _{reason: user_chose, task: T, time: B}) :- call_text(C, T).
reason_dict(done_later(C, B), _{reason: done_later, task: T, time: B}) :- call_text(C, T).
reason_dict(done_earlier(C, B), _{reason: done_earlier, task: T, time: B}) :- call_text(C, T).

%!  answer_json(-JSON) is det.
%   Answer the request the Python bridge handed over (store_python_request/1) as a JSON
%   string; the request's values arrive as arguments, never as query text.
answer_json(JSON) :-
    store_python_request(Request),
    answer(Request, Dict),
    json_text(Dict, JSON).

answer([why_not, Name, Args, At], _{question: why_not, task: T, at: AtOut, reasons: Ds}) :-
    Call =.. [Name|Args],
    call_text(Call, T),
    (   number(At)
    ->  findall(R, why_not(Call, At, R), Rs), AtOut = At
    ;   findall(R, why_not(Call, R), Rs), AtOut = null
    ),
    maplist(reason_dict, Rs, Ds).
answer([what_next], _{question: what_next, chain: Ds}) :-
    (   what_next(Chain) -> true ; Chain = [] ),
    maplist(ranked_dict, Chain, Ds).
answer([something_else, Name, Args], _{question: something_else, current: CT,
                                       alternatives: Ds}) :-
    (   Name == none
    ->  ignore(latest_action(Current, _))
    ;   Current =.. [Name|Args]
    ),
    findall(ranked(A, R, S), something_else(Current, A, rank(R, S)), Alts),
    (   var(Current) -> CT = null ; call_text(Current, CT) ),
    maplist(ranked_dict, Alts, Ds).
answer([chain_before, Action, N], _{question: chain_before, chain: Ts}) :-
    chain_before(Action, N, Calls),
    maplist(call_text, Calls, Ts).
