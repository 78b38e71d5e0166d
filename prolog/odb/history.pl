:- module(odb_history,
    [ situation_history/1,        % -Situations
      situation_history_json/1,   % -JSONString
      latest_situation/2,         % -Begin, -Calls
      latest_situation_json/1     % -JSONString
    ]).
/** <module> odb history: the oracle's view of a NEEM (thesis 4.2)

Every executed action with its call, its time of day and the tasks imagined available
before it, read in a fixed number of compiled store queries; and the latest imagined
situation, the one the next ranking is for.
*/

:- use_module(library(error)).
:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module(library(pairs)).
:- use_module(library(http/json)).
:- use_module('../lang/query', [kb_call/2]).
:- use_module('../lang/triple', [kb_iri/2]).
:- use_module('../model/rdfs', []).
:- use_module('../model/event', []).
:- use_module('../model/object', []).
:- use_module('../model/situation', []).
:- use_module(names, [odb_iri/2]).
:- use_module(calls, [task_calls/2]).
:- use_module(decisions, [latest_decision/4, imagined_available/2]).

%!  situation_history(-Situations) is det.
%   Every executed action of the NEEM in begin order, as
%   `situation(Begin, End, Call, Part, Available)`: Call is the task call (`idle` for an
%   odb:IdleTask action), Part the time of day (`none` if not logged), Available the calls of
%   the latest imagining that began after the previous action and not after this one (`none`
%   if there was none). This is the oracle's history: a fixed number of compiled store
%   queries, however long the NEEM, and one task_call per distinct task individual.
situation_history(Situations) :-
    odb_iri('IdleTask', Idle),
    findall(B-A-T-E-C,
            ( kb_call(( executes_task(A, T), triple(T, rdf:type, C), event_interval(A, B, E) ), any),
              ( C == Idle -> true ; odb_iri(_, C) ) ),
            Actions0),
    sort(Actions0, Actions),
    findall(A-P, ( kb_call(( has_time_interval(A, I), triple(I, rdf:type, PC) ), any),
                   member(P, ['Morning', 'Midday', 'Evening', 'Night']), odb_iri(P, PC) ), Parts),
    findall(B-T, kb_call(( executes_task(M, MT), instance_of(MT, soma:'Imagining'),
                           event_interval(M, B, _), holds(M, odb:imagines_situation, Plan),
                           plan_defines_task(Plan, T) ), any), Imagined0),
    sort(Imagined0, Imagined),
    findall(T, ( member(_-_-T-_-C, Actions), C \== Idle ), Ts0),
    findall(T, member(_-T, Imagined), Ts1),
    append(Ts0, Ts1, Ts),
    task_calls(Ts, Calls),
    group_pairs_by_key(Imagined, ByBegin),
    history_rows(Actions, inf, Idle, Parts, ByBegin, Calls, Situations).

history_rows([], _, _, _, _, _, []).
history_rows([B-A-T-E-C|Actions], Prev, Idle, Parts, ByBegin, Calls, [situation(B, E, Call, Part, Avail)|Rows]) :-
    (   C == Idle -> Call = idle ; memberchk(T-Call, Calls) ),
    (   memberchk(A-Part, Parts) -> true ; Part = none ),
    (   C \== Idle,
        findall(Bi-Ts, ( member(Bi-Ts, ByBegin), Bi =< B, ( Prev == inf ; Bi > Prev ) ), Candidates),
        last(Candidates, _-AvTs)
    ->  findall(AC, ( member(AT, AvTs), memberchk(AT-AC, Calls) ), Avail0),
        sort(Avail0, Avail)
    ;   Avail = none
    ),
    history_rows(Actions, B, Idle, Parts, ByBegin, Calls, Rows).

%!  situation_history_json(-JSON) is det.
%   situation_history/1 as a JSON array of `{"begin", "end", "call", "part", "available"}`
%   objects, calls written in the chain syntax `pour(thermos,green_mug)`; one crossing for
%   the Python side.
situation_history_json(JSON) :-
    situation_history(Situations),
    maplist(situation_dict, Situations, Dicts),
    with_output_to(string(JSON), json_write_dict(current_output, Dicts, [width(0)])).

situation_dict(situation(B, E, Call, Part, Avail), _{begin:B, end:E, call:CallText, part:Part, available:AvailJ}) :-
    format(atom(CallText), '~w', [Call]),
    (   Avail == none
    ->  AvailJ = null
    ;   findall(X, ( member(C, Avail), format(atom(X), '~w', [C]) ), AvailJ)
    ).

%!  latest_situation(-Begin, -Calls) is semidet.
%   The latest imagined situation of the NEEM: when it began and the calls it found
%   available (sorted). Fails when nothing was ever imagined.
latest_situation(B, Calls) :-
    latest_decision(situation, any, M, B),
    imagined_available(M, Calls).

%!  latest_situation_json(-JSON) is det.
%   latest_situation/2 as `{"begin": B, "available": [...]}`, or `null` when there is none.
latest_situation_json(JSON) :-
    (   latest_situation(B, Calls)
    ->  findall(X, ( member(C, Calls), format(atom(X), '~w', [C]) ), Xs),
        Dict = _{begin:B, available:Xs}
    ;   Dict = null
    ),
    with_output_to(string(JSON), json_write_dict(current_output, Dict, [width(0)])).
