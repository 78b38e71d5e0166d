:- module(odb_history,
    [ situation_history/1,        % -Situations
      situation_history_after/2,  % +After, -Situations
      situation_history_json/1,   % -JSONString
      situation_history_json/2,   % +After, -JSONString
      situation_history_json/3,   % +After, +Until, -JSONString
      history_slice_bounds/2,     % +Size, -Bounds
      history_slice_bounds_json/2, % +Size, -JSONString
      latest_situation/2,         % -Begin, -Calls
      latest_situation/3,         % -Begin, -Calls, -Part
      latest_situation_json/1,    % -JSONString
      history_view_json/2,        % +After, -JSONString
      action_modes/2,             % +After, -ModeOf
      typed_modes/2               % +Rows, -ModeOf
    ]).
/** <module> odb history: the oracle's view of a NEEM (thesis 4.2)

Every executed action with its call, its time of day and the tasks imagined available
before it, read in a fixed number of compiled store queries; and the latest imagined
situation, the one the next ranking is for.
*/

:- use_module(library(error), [must_be/2]).
:- use_module(library(lists), [append/3, last/2, member/2, nth0/3]).
:- use_module(library(apply), [foldl/5, include/3, maplist/3]).
:- use_module(library(pairs), [group_pairs_by_key/2, transpose_pairs/2]).
:- use_module(library(assoc), [assoc_to_list/2, assoc_to_values/2, empty_assoc/1, get_assoc/3,
                               list_to_assoc/2, put_assoc/4]).
:- use_module(library(ordsets), [ord_memberchk/2]).
:- use_module('../json_text', [json_text/2]).
:- use_module('../lang/query', [kb_call/2, kb_findall/4, kb_findall/5, kb_group/5]).
:- use_module('../lang/triple', [kb_iri/2]).
:- use_module('../model/rdfs', []).
:- use_module('../model/event', []).
:- use_module('../model/object', []).
:- use_module('../model/situation', []).
:- use_module(names, [odb_iri/2]).
:- use_module(calls, [task_calls/2, task_calls/3]).
:- use_module(decisions, [latest_decision/4, imagined_available/2]).

%!  situation_history(-Situations) is det.
%   Every executed action of the NEEM in begin order, as
%   `situation(Begin, End, Call, Part, Available)`: Call is the task call (`idle` for an
%   odb:IdleTask action), Part the time of day (`none` if not logged), Available the calls of
%   the latest imagining that began after the previous action and not after this one (`none`
%   if there was none). This is the oracle's history: a fixed number of compiled store
%   queries, however long the NEEM, one task_call per distinct task individual, and one
%   pass over the actions in begin order that merges the imaginings (also in begin order)
%   and looks parts of day and calls up in AVL trees: O(n log n) in the rows read.
situation_history(Situations) :-
    situation_history(range(none, none), Situations, _).

%!  situation_history_after(+After, -Situations) is det.
%   The situations of situation_history/1 whose action began after the number After, as
%   that read gives them when its last situation before them began at After: the imaginings
%   that began after After are merged, the earlier ones are not. Every store query reads from
%   the intervals that began after After, so a kept history grows by its new actions alone
%   (oracle.historycache); After `none` is the whole history.
situation_history_after(After, Situations) :-
    after_bound(After),
    situation_history(range(After, none), Situations, _).

%   situation_history(+Range, -Situations, -Calls): the situations of the actions that began
%   in Range, `range(After, Until)`: after After and not after Until (`none`: no bound); also
%   the AVL tree of task individual -> call the rows were made from (every call in Situations
%   but `idle` is one of its values).
situation_history(Range, Situations, Calls) :-
    situation_history(Range, Situations, Calls, _).

%   situation_history(+Range, -Situations, -Calls, -Actions): also the rows' actions, in the
%   order of Situations.
situation_history(Range, Situations, Calls, Acts) :-
    odb_iri('IdleTask', Idle),
    % Each action with its task's types, grouped by the store (a logged task has two).
    typed_actions(Range, Typed),
    % The few distinct types are checked once, not once per action.
    findall(C, ( member(_-Cs, Typed), member(C, Cs) ), AllTypes),
    sort(AllTypes, Types),
    include(odb_or_idle(Idle), Types, Kept),
    findall(B-A-T-E-C, ( member(B-A-T-E-Cs, Typed), member(C, Cs), ord_memberchk(C, Kept) ), Actions0),
    sort(Actions0, Actions),
    % The store's replies and the grouped rows are garbage once sorted: collected now, before
    % the next reads make the stacks grow past them (at 50,000 actions the read's peak RSS went
    % from 649 to 466 MiB with the three collections, its time unchanged; docs/prolog.md).
    garbage_collect,
    interval_types(Range, IntervalTypes),
    findall(PC-P, ( member(P, ['Morning', 'Midday', 'Evening', 'Night']), odb_iri(P, PC) ), PartClasses),
    findall(A-P, ( member(A-PC, IntervalTypes), memberchk(PC-P, PartClasses) ), Parts),
    imagined_plans(Range, ImaginedPlans),
    garbage_collect,
    % The few plans' tasks once, not once per (imagining, plan) row: the same join, in Prolog.
    kb_findall(Plan-T, plan_defines_task(Plan, T), any, PlanTasks0),
    sort(PlanTasks0, PlanTasks),
    group_pairs_by_key(PlanTasks, TasksByPlan),
    list_to_assoc(TasksByPlan, TasksOf),
    findall(Plan, ( member(_-Plans, ImaginedPlans), member(Plan, Plans) ), Used0),
    sort(Used0, Used),
    plans_tasks(TasksOf, Used, Ts1),
    findall(T, ( member(_-_-T-_-C, Actions), C \== Idle ), Ts0),
    append(Ts0, Ts1, Ts),
    history_calls(Range, Ts, CallPairs),
    list_to_assoc(CallPairs, Calls),
    empty_assoc(Memo),
    imagined_calls(ImaginedPlans, TasksOf, Calls, Memo, ByBegin),
    first_values(Parts, PartOf),
    Range = range(After, _),
    (   After == none -> Prev = inf ; Prev = After ),
    history_rows(Actions, Prev, Idle, PartOf, ByBegin, none, Calls, Situations),
    findall(A, member(_-A-_-_-_, Actions), Acts).

%   history_calls(+After, +Ts, -CallPairs): the Task-Call pairs of at least the tasks Ts (those
%   of the actions read and of the plans their imaginings used). After a begin, the tasks of
%   the events begun since and those of every plan (the plans are few) reach them all
%   (task_calls/3): reading a few hundred new actions then costs what they cost, not what the
%   NEEM does (at 50,000 actions, the last 100: 1.96 s before, 0.12 s; docs/prolog.md).
history_calls(range(none, none), Ts, CallPairs) :- !,
    task_calls(Ts, CallPairs).
history_calls(Range, Ts, CallPairs) :-
    begun_in(Range, I, _, Begun),
    task_calls(Ts, [ ( Begun, has_time_interval(A, I), executes_task(A, T) )-T,
                     plan_defines_task(_, P)-P ], CallPairs).

%   begun_in(+Range, ?I, ?B, -Goal): Goal finds the intervals I that began in Range at B, by
%   value (the store's index on property and value). Both bounds compare the same begin B:
%   the store asks for them in one pattern (store_read's fused ranges), one index range, so a
%   slice of the history reads the rows of its own actions alone (oracle.slicedread).
begun_in(range(After, none), I, B, triple(I, soma:hasIntervalBegin, >(After)->B)) :- !.
begun_in(range(none, Until), I, B, triple(I, soma:hasIntervalBegin, =<(Until)->B)) :- !.
begun_in(range(After, Until), I, B,
         ( triple(I, soma:hasIntervalBegin, >(After)->B), triple(I, soma:hasIntervalBegin, =<(Until)->B) )).

%   Every action (After `none`), or every action that began after After, with its begin,
%   task, end and the task's types. The restricted reads start from the interval begins the
%   store finds by value (its index on property and value), before fanning out.
typed_actions(range(none, none), Typed) :- !,
    kb_group(B-A-T-E, C, ( executes_task(A, T), triple(T, rdf:type, C), event_interval(A, B, E) ),
             any, Typed).
typed_actions(Range, Typed) :-
    begun_in(Range, I, B, Begun),
    kb_group(B-A-T-E, C, ( Begun, has_time_interval(A, I),
                           has_interval_end(I, E), executes_task(A, T), triple(T, rdf:type, C) ),
             any, Typed).

%   Each event (of an interval that began after After) with the types of its interval.
interval_types(range(none, none), IntervalTypes) :- !,
    kb_findall(A-PC, ( has_time_interval(A, I), triple(I, rdf:type, PC) ), any, IntervalTypes).
interval_types(Range, IntervalTypes) :-
    begun_in(Range, I, _, Begun),
    kb_findall(A-PC, ( Begun, has_time_interval(A, I),
                       triple(I, rdf:type, PC) ), any, IntervalTypes).

%   Each imagining's begin with its plans, grouped by the store (one row per begin, not one
%   per imagined plan). The mental action's own patterns come first: SQLite then joins its
%   interval before fanning out to the ~20 plans (4x faster at 10,000 actions).
imagined_plans(range(none, none), ImaginedPlans) :- !,
    kb_group(B, Plan, ( executes_task(M, MT), instance_of(MT, soma:'Imagining'),
                        event_interval(M, B, _), holds(M, odb:imagines_situation, Plan) ),
             any, ImaginedPlans).
imagined_plans(Range, ImaginedPlans) :-
    begun_in(Range, I, B, Begun),
    kb_group(B, Plan, ( Begun, has_time_interval(M, I),
                        has_interval_end(I, _), executes_task(M, MT), instance_of(MT, soma:'Imagining'),
                        holds(M, odb:imagines_situation, Plan) ),
             any, ImaginedPlans).

after_bound(After) :-
    (   After == none -> true ; must_be(number, After) ).

odb_or_idle(Idle, C) :-
    (   C == Idle -> true ; odb_iri(_, C) ).

%   The sorted tasks the plans define.
plans_tasks(TasksOf, Plans, Ts) :-
    findall(T, ( member(Plan, Plans), get_assoc(Plan, TasksOf, PlanTs), member(T, PlanTs) ), Ts0),
    sort(Ts0, Ts).

%   imagined_calls(+Imaginings, +TasksOf, +Calls, +Memo, -ByBegin): each imagining's begin
%   with the sorted calls of its plans' tasks, each distinct set of plans worked out once
%   (Memo). An imagining whose plans define no task is no situation (as if not imagined).
imagined_calls([], _, _, _, []).
imagined_calls([B-Plans|Groups], TasksOf, Calls, Memo0, ByBegin) :-
    (   get_assoc(Plans, Memo0, Avail)
    ->  Memo = Memo0
    ;   plans_tasks(TasksOf, Plans, Ts),
        (   Ts == []
        ->  Avail = none
        ;   findall(AC, ( member(T, Ts), get_assoc(T, Calls, AC) ), Avail0),
            sort(Avail0, Avail)
        ),
        put_assoc(Plans, Memo0, Avail, Memo)
    ),
    (   Avail == none -> ByBegin = Rest ; ByBegin = [B-Avail|Rest] ),
    imagined_calls(Groups, TasksOf, Calls, Memo, Rest).

%   Key-Value pairs as an AVL tree keeping the first value of a key (memberchk/2's answer):
%   sort/4 on the key drops the later duplicates of a key, keeping the first.
first_values(Pairs, Assoc) :-
    sort(1, @<, Pairs, Firsts),
    list_to_assoc(Firsts, Assoc).

%   history_rows(+Actions, +PrevBegin, +Idle, +PartOf, +Imaginings, +Latest, +Calls, -Rows):
%   Imaginings are the begin-calls pairs not yet passed (ascending begin), Latest the last
%   one that began at or before the previous action (`none` before the first one).
history_rows([], _, _, _, _, _, _, []).
history_rows([B-A-T-E-C|Actions], Prev, Idle, PartOf, Groups0, Latest0, Calls,
             [situation(B, E, Call, Part, Avail)|Rows]) :-
    (   C == Idle -> Call = idle ; get_assoc(T, Calls, Call) ),
    (   get_assoc(A, PartOf, Part0) -> Part = Part0 ; Part = none ),
    advance(Groups0, B, Latest0, Groups, Latest),
    (   C \== Idle,
        Latest = Bi-Avail0,
        ( Prev == inf ; Bi > Prev )
    ->  Avail = Avail0
    ;   Avail = none
    ),
    history_rows(Actions, B, Idle, PartOf, Groups, Latest, Calls, Rows).

%   Pass the imaginings that began at or before B; the last one passed is the latest.
advance([Bi-Ts|Groups0], B, _, Groups, Latest) :-
    Bi =< B, !,
    advance(Groups0, B, Bi-Ts, Groups, Latest).
advance(Groups, _, Latest, Groups, Latest).

%!  situation_history_json(-JSON) is det.
%   situation_history/1 as JSON, one crossing for the Python side: `{"calls": [Text, ...],
%   "sets": [[CallIndex, ...], ...], "rows": [Begin, End, CallIndex, Part, SetIndex, Mode,
%   ...]}`, each distinct call written once in the chain syntax `pour(thermos,green_mug)`,
%   each distinct available set once (10,000 situations of a persona hold ~760 of them) as
%   the indexes of its calls, and the situations as one flat list of six values each
%   (SetIndex -1: none available; Mode who performed the action, action_modes/2). Flat rows
%   write 10x faster than one JSON object per situation.
situation_history_json(JSON) :-
    situation_history_json(none, JSON).

%!  situation_history_json(+After, -JSON) is det.
%   situation_history_after/2 as JSON, in the shape of situation_history_json/1.
situation_history_json(After, JSON) :-
    situation_history_json(After, none, JSON).

%!  situation_history_json(+After, +Until, -JSON) is det.
%   The situations of situation_history_json/2 whose action began after After and not after
%   Until (`none`: no bound), as one slice of the whole read: the rows that read gives them
%   when After and Until are begins of its rows (a slice ends at an action's begin, so the
%   imaginings that began before an action are read with it). Read one after another from
%   the bounds of history_slice_bounds/2 and joined, the slices are the whole history, each
%   read holding the rows of its own actions alone and costing what they cost (oracle.slicedread).
situation_history_json(After, Until, JSON) :-
    after_bound(After),
    after_bound(Until),
    Range = range(After, Until),
    situation_history(Range, Situations, Calls, Actions),
    garbage_collect,    % the read's intermediate lists, before the JSON text is made
    range_modes(Range, ModeOf),
    maplist(action_mode(ModeOf), Actions, Modes),
    assoc_to_values(Calls, CallList),
    sort([idle|CallList], Distinct),
    findall(C-I, nth0(I, Distinct, C), Numbered),
    list_to_assoc(Numbered, Index),
    findall(X, ( member(C, Distinct), format(string(X), '~w', [C]) ), Texts),
    empty_assoc(Sets0),
    foldl(situation_row(Index), Situations, Modes, Rows, Sets0-0, Sets-_),
    assoc_to_list(Sets, Indexed),
    transpose_pairs(Indexed, ByIndex),      % index-set pairs, by index
    findall(Set, ( member(_-Avail, ByIndex), maplist(call_index(Index), Avail, Is), format(string(Set), '~w', [Is]) ),
            SetLists),
    json_text(Texts, CallsJSON),
    with_output_to(string(JSON),
                   ( format('{"calls":'),
                     write(CallsJSON),
                     format(',"sets":['),
                     write_separated(SetLists),
                     format('],"rows":['),
                     write_separated(Rows),
                     format(']}')
                   )).

%   One situation with who performed its action as the text
%   `Begin,End,CallIndex,"Part",SetIndex,"Mode"`, each distinct set numbered on first use.
situation_row(Index, situation(B, E, Call, Part, Avail), Mode, Row, Sets0-N0, Sets-N) :-
    get_assoc(Call, Index, CI),
    (   Avail == none
    ->  AI = -1, Sets-N = Sets0-N0
    ;   get_assoc(Avail, Sets0, AI0)
    ->  AI = AI0, Sets-N = Sets0-N0
    ;   AI = N0, N is N0+1,
        put_assoc(Avail, Sets0, N0, Sets)
    ),
    format(string(Row), '~w,~w,~d,"~w",~d,"~w"', [B, E, CI, Part, AI, Mode]).

call_index(Index, Call, I) :-
    get_assoc(Call, Index, I).

%   Texts separated by commas.
write_separated([]).
write_separated([X|Xs]) :-
    write(X),
    forall(member(Y, Xs), ( write(','), write(Y) )).

%!  latest_situation(-Begin, -Calls) is semidet.
%   The latest imagined situation of the NEEM: when it began and the calls it found
%   available (sorted). Fails when nothing was ever imagined.
latest_situation(B, Calls) :-
    latest_situation(B, Calls, _).

%!  latest_situation(-Begin, -Calls, -Part) is semidet.
%   latest_situation/2 and the part of the day its interval was logged with (`none` if not).
latest_situation(B, Calls, Part) :-
    latest_decision(situation, any, M, B),
    imagined_available(M, Calls),
    kb_findall(PC, ( has_time_interval(M, I), triple(I, rdf:type, PC) ), any, PCs),
    (   member(PC, PCs), member(Part, ['Morning', 'Midday', 'Evening', 'Night']), odb_iri(Part, PC)
    ->  true
    ;   Part = none
    ).

%!  latest_situation_json(-JSON) is det.
%   latest_situation/3 as `{"begin": B, "available": [...], "part": P}`, or `null` when there
%   is none.
latest_situation_json(JSON) :-
    latest_dict(Dict),
    json_text(Dict, JSON).

latest_dict(Dict) :-
    (   latest_situation(B, Calls, Part)
    ->  findall(X, ( member(C, Calls), format(atom(X), '~w', [C]) ), Xs),
        Dict = _{begin:B, available:Xs, part:Part}
    ;   Dict = null
    ).

%!  history_view_json(+After, -JSON) is det.
%   What the oracle reads of a NEEM, in one reply: situation_history_json/2 (After `none`:
%   the whole history) with the latest imagined situation as `"latest"` (latest_situation_json/1).
history_view_json(After, JSON) :-
    situation_history_json(After, History),
    latest_dict(Dict),
    json_text(Dict, Latest),
    sub_string(History, 0, _, 1, Open),    % without its closing brace
    string_concat(Open, ",\"latest\":", Head),
    atomics_to_string([Head, Latest, "}"], JSON).

%!  action_modes(+After, -ModeOf) is det.
%   Who performed each action whose interval began after After (`none`: every action), as an
%   AVL tree Action -> Mode: `user` when its performers (soma:isPerformedBy) are a
%   dul:NaturalPerson alone, `robot` when they are other dul:PhysicalAgents, `together` when
%   there are both. An action with neither kind of performer is not in the tree (its mode is
%   `unknown`, action_mode/3). At most three store queries however long the NEEM
%   (performers_typed/4).
action_modes(After, ModeOf) :-
    after_bound(After),
    range_modes(range(After, none), ModeOf).

range_modes(Range, ModeOf) :-
    performers_typed(Range, Pairs, Persons, Agents),
    pairs_modes(Pairs, Persons, Agents, ModeOf).

%!  history_slice_bounds(+Size, -Bounds) is det.
%   The begins at which to end the slices of the history (situation_history_json/3) so that
%   each holds about Size actions: the ascending begins of every Size-th distinct begin of
%   the rows of situation_history/1, but the last (its slice reads to the end, `none`). Equal
%   begins count once and stay in one slice, so a slice may hold more. One store query of
%   the actions' begins and task types, grouped by begin (one row a begin reaches Prolog,
%   not one an action: 1.9 -> 1.2 s at 50,000 actions), however long the NEEM.
history_slice_bounds(Size, Bounds) :-
    must_be(positive_integer, Size),
    odb_iri('IdleTask', Idle),
    kb_group(B, C, ( executes_task(A, T), triple(T, rdf:type, C), event_interval(A, B, _) ), any, Typed),
    findall(C, ( member(_-Cs, Typed), member(C, Cs) ), AllTypes),
    sort(AllTypes, Types),
    include(odb_or_idle(Idle), Types, Kept),
    % a begin some row has: one of the actions begun then has a kept type
    findall(B, ( member(B-Cs, Typed), once(( member(C, Cs), ord_memberchk(C, Kept) )) ), Begins0),
    msort(Begins0, Begins),
    every_nth(Begins, Size, Size, Bounds0),
    last_dropped(Bounds0, Begins, Bounds).

%!  history_slice_bounds_json(+Size, -JSON) is det.
%   history_slice_bounds/2 as a JSON list of numbers (each reads back as the same number).
history_slice_bounds_json(Size, JSON) :-
    history_slice_bounds(Size, Bounds),
    json_text(Bounds, JSON).

%   every_nth(+Begins, +K, +Size, -Bounds): the begin of every Size-th row (K rows to the next),
%   each distinct and not the begin of the rows after it.
every_nth([], _, _, []).
every_nth([B|Bs], K, Size, Bounds) :-
    (   K =:= 1, \+ Bs = [B|_]
    ->  Bounds = [B|Rest], every_nth(Bs, Size, Size, Rest)
    ;   K1 is max(1, K-1), every_nth(Bs, K1, Size, Bounds)
    ).

%   The last row's begin is no bound: the last slice reads to the end.
last_dropped(Bounds0, Begins, Bounds) :-
    (   append(Bounds, [Last], Bounds0), last(Begins, Last) -> true ; Bounds = Bounds0 ).

%!  typed_modes(+Rows, -ModeOf) is det.
%   ModeOf as action_modes/2 gives it, from rows `Action-Agent-Type`: an action, one of its
%   performers (soma:isPerformedBy) and one of that performer's rdf:types, as one query over a
%   few actions reads them (odb_past:performers/2).
typed_modes(Rows, ModeOf) :-
    must_be(list, Rows),
    typed_pairs(Rows, Pairs, Persons, Agents),
    pairs_modes(Pairs, Persons, Agents, ModeOf).

pairs_modes(Pairs, Persons, Agents, ModeOf) :-
    group_pairs_by_key(Pairs, Groups),
    findall(A-Mode, ( member(A-Ags, Groups), agents_mode(Ags, Persons, Agents, Mode) ), ModePairs),
    list_to_assoc(ModePairs, ModeOf).

%   performers_typed(+Range, -Pairs, -Persons, -Agents): the sorted Action-Agent pairs of the
%   actions begun in Range, and the sorted agents typed dul:NaturalPerson and
%   dul:PhysicalAgent among them. The whole NEEM: the pairs, then the few agents of each type
%   (three queries; the pairs joined with the agents' types would be several rows an action).
%   A range: one query of its actions' pairs, joined as written from the interval begins
%   found by value (SQLite's own plan drives from every performer triple instead: 250 ms
%   against 3 ms at 50,000 actions), then the asserted types of each distinct performer.
performers_typed(range(none, none), Pairs, Persons, Agents) :- !,
    kb_findall(A-Ag, is_performed_by(A, Ag), any, Pairs0),
    sort(Pairs0, Pairs),
    kb_findall(P, triple(P, rdf:type, dul:'NaturalPerson'), any, Persons0),
    sort(Persons0, Persons),
    kb_findall(R, triple(R, rdf:type, dul:'PhysicalAgent'), any, Agents0),
    sort(Agents0, Agents).
performers_typed(Range, Pairs, Persons, Agents) :-
    begun_in(Range, I, _, Begun),
    kb_findall(A-Ag, ( Begun, has_time_interval(A, I), is_performed_by(A, Ag) ), any, [plan(written)], Pairs0),
    % the few performers' asserted types, one query each (with the pairs, one row per action
    % and type: a slice of 2,000 actions read 7,860 rows)
    findall(Ag, member(_-Ag, Pairs0), Ags0),
    sort(Ags0, Ags),
    findall(A-Ag-C, ( member(Ag, Ags), kb_call(triple(Ag, rdf:type, C), any), member(A-Ag, Pairs0) ), Rows),
    typed_pairs(Rows, Pairs, Persons, Agents).

typed_pairs(Rows, Pairs, Persons, Agents) :-
    kb_iri(dul:'NaturalPerson', Person), kb_iri(dul:'PhysicalAgent', Agent),
    findall(A-Ag, member(A-Ag-_, Rows), Pairs0),
    sort(Pairs0, Pairs),
    findall(Ag, member(_-Ag-Person, Rows), Persons0),
    sort(Persons0, Persons),
    findall(Ag, member(_-Ag-Agent, Rows), Agents0),
    sort(Agents0, Agents).

%   The mode of an action performed by Ags: a person counts as the user (a dul:NaturalPerson
%   is also a dul:PhysicalAgent), any other physical agent as the robot.
agents_mode(Ags, Persons, Agents, Mode) :-
    findall(Who, ( member(Ag, Ags), agent_kind(Ag, Persons, Agents, Who) ), Whos0),
    sort(Whos0, Whos),
    (   Whos == [user] -> Mode = user
    ;   Whos == [robot] -> Mode = robot
    ;   Whos == [robot, user] -> Mode = together
    ).

agent_kind(Ag, Persons, _, user) :-
    ord_memberchk(Ag, Persons), !.
agent_kind(Ag, _, Agents, robot) :-
    ord_memberchk(Ag, Agents).

%   action_mode(+ModeOf, +Action, -Mode): Action's mode in ModeOf (action_modes/2),
%   `unknown` when it has none.
action_mode(ModeOf, A, Mode) :-
    (   get_assoc(A, ModeOf, Mode0) -> Mode = Mode0 ; Mode = unknown ).
