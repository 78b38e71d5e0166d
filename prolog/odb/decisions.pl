:- module(odb_decisions,
    [ decision/3,                 % ?Kind, ?MentalAction, ?Begin
      decision_at/3,              % +Kind, +Time, -MentalAction
      latest_decision/4,          % +Kind, +Test, -MentalAction, -Begin
      latest_first/4,             % +Kind, +Before, -Begin, -MentalAction
      imagined_available/2,       % +Imagining, -Calls
      available_tasks_at/2,       % +Time, -Calls
      imagined_preference/2,      % +Reasoning, -Ranked
      preference_at/3,            % +Time, -Reasoning, -Ranked
      latest_preference/3,        % -Reasoning, -Begin, -Ranked
      times_available/2,          % +Call, -Begins
      action_time/5               % +Tasks, ?BeginTest, ?EndTest, +Dir, -Begin
    ]).
/** <module> odb decisions: what the robot imagined available and preferred (thesis 3.4)

Decisions are the soma:Imagining mental actions that odb:imagines_situation the available
tasks (soma:ActionExecutionPlan soma:isPlanFor task), and the soma:Reasoning mental
actions that odb:imagines_preference a soma:PreferenceOrder whose soma:orders elements
carry odb:hasPreferenceRank and odb:hasPreferenceScore and soma:encapsulates the plan.
Times are unix seconds; the lookups by time ask the store for the one row they need.
*/

:- use_module(library(error)).
:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module(library(pairs)).
:- use_module(library(ordsets)).
:- use_module('../neem_store', [store_match/2, store_match/3]).
:- use_module('../lang/query', [kb_call/2]).
:- use_module('../lang/triple', [kb_iri/2]).
:- use_module('../model/rdfs', []).
:- use_module('../model/event', []).
:- use_module('../model/object', []).
:- use_module('../model/situation', []).
:- use_module(names, [odb_iri/2, call_classes/3]).
:- use_module(calls, [task_call/2, task_calls/2, task_calls_reached/3, task_class/2]).

%!  decision(?Kind, ?MentalAction, ?Begin) is nondet.
%   Kind `situation`: an imagining of the available tasks; `preference`: a reasoning
%   that imagined a preference order.
decision(situation, M, B) :-
    kb_call(( executes_task(M, T), instance_of(T, soma:'Imagining'),
              event_interval(M, B, _) ), any).
decision(preference, M, B) :-
    kb_call(( executes_task(M, T), instance_of(T, soma:'Reasoning'),
              event_interval(M, B, _) ), any).

%!  decision_at(+Kind, +Time, -MentalAction) is semidet.
%   The latest decision of Kind that began at or before Time.
decision_at(Kind, Time, M) :-
    must_be(number, Time),
    latest_decision(Kind, =<(Time), M, _).

%!  latest_decision(+Kind, +Test, -MentalAction, -Begin) is semidet.
%   The latest decision of Kind whose begin passes Test (`=<(Time)`, or `any`); the greatest
%   in the standard order of terms when several began then, as max_member/2. A NEEM with few
%   decisions of Kind (a NEEM ranked once or twice) has them all read from the class's
%   tasks and chosen here. Otherwise two store queries ordered by begin: the latest begin
%   (the scan stops at the first decision), then the decisions from just below that begin
%   on, a few at a time, until a later begin shows that none at it is left out. Either way
%   the cost is not the whole NEEM's intervals, which an ordered scan walks when no decision
%   passes the test.
latest_decision(Kind, Test, M, B) :-
    (   few_decisions(Kind, Few)
    ->  include(begin_passes(Test), Few, Passing),
        max_member(B-_, Passing),
        findall(Mx, ( member(Bx-Mx, Passing), Bx =:= B ), Latest),
        max_member(M, Latest)
    ;   (   Test = =<(Time) -> BO = cmp(=<, Time, B1) ; BO = B1 ),
        decision_patterns(Kind, _, BO, Ordered),
        once(store_match(Ordered, any, [order([desc(B1)]), limit(1)])),
        % From a hair below the latest begin: a begin read back from a store may differ from
        % its stored number in the last bit (a Decimal128), and begins are compared here.
        From is B1 - max(1.0e-9, abs(B1) * 1.0e-15),
        decisions_from(Kind, From, B1, 4, M),
        B = B1
    ).

%!  latest_first(+Kind, +Before, -Begin, -MentalAction) is nondet.
%   The decisions of Kind that began at or before Before (`none`: any), latest first and
%   those that began together greatest first: the order of sort(0, @>=) on their
%   Begin-MentalAction pairs. A NEEM with few decisions of Kind has them all read
%   (few_decisions/2); otherwise the store sends the latest a page at a time, ordered by
%   begin, so a caller that stops at one of the first does not have them all read.
latest_first(Kind, Before, B, M) :-
    (   Before == none -> Test = any ; must_be(number, Before), Test = =<(Before) ),
    (   few_decisions(Kind, Few)
    ->  include(begin_passes(Test), Few, Passing),
        sort(0, @>=, Passing, Sorted),
        member(B-M, Sorted)
    ;   latest_pages(Kind, Test, 16, [], B, M)
    ).

%   latest_pages(+Kind, +Test, +N, +Seen, -B, -M): the N latest decisions of Kind from Test's
%   bound down, in the store's order of begins. Those that began above the page's last begin
%   are all in it (a hair above: a begin read back from a store may differ from its stored
%   number in the last bit), so they come in order, but for those in Seen (the ordered set
%   of the earlier pages'); then the next page, 4 times larger, unless this one was the last.
latest_pages(Kind, Test, N, Seen, B, M) :-
    (   Test = =<(Time)
    ->  Bound is Time + max(1.0e-9, abs(Time) * 1.0e-15), BO = cmp(=<, Bound, B0)
    ;   BO = B0
    ),
    decision_patterns(Kind, M0, BO, Ps),
    findall(B0-M0, store_match(Ps, any, [order([desc(B0)]), limit(N)]), Rows),
    length(Rows, Got),
    (   Got < N
    ->  Whole = Rows, More = false
    ;   last(Rows, BL-_),
        Above is BL + max(1.0e-9, abs(BL) * 1.0e-15),
        include(began_above(Above), Rows, Whole), More = true
    ),
    include(begin_passes(Test), Whole, Passing),
    exclude(seen_decision(Seen), Passing, New),
    sort(0, @>=, New, Sorted),
    (   member(B-M, Sorted)
    ;   More == true,
        findall(Mx, member(_-Mx, Passing), Ms0),
        list_to_ord_set(Ms0, Seen1),
        N1 is N*4,
        latest_pages(Kind, Test, N1, Seen1, B, M)
    ).

began_above(Above, B-_) :- B > Above.

seen_decision(Seen, _-M) :- ord_memberchk(M, Seen).

%   few_decisions(+Kind, -Decisions): Begin-Decision for every decision of Kind, when there
%   are fewer than 64 (fails otherwise): the class's tasks, their actions, each one's
%   interval, in one-pattern queries the store answers from an index without a sort.
few_decisions(Kind, Few) :-
    decision_patterns(Kind, _, _, [t(_, Ex, _), t(_, Type, C), t(_, HI, _), t(_, Begin, _), t(_, End, _)]),
    % (Written order: the closure ids go into the query, so SQLite reads the type index
    % instead of walking the table in id order.)
    findall(T, store_match([t(T, Type, C)], any, [limit(64), plan(written)]), Ts),
    length(Ts, NTs), NTs < 64,
    findall(M, ( member(T, Ts), store_match([t(M, Ex, T)], any, [limit(64), plan(written)]) ), Ms),
    length(Ms, NMs), NMs < 64,
    findall(B0-M, ( member(M, Ms),
                    store_match([t(M, HI, I), t(I, Begin, B0), t(I, End, _)], any) ), Few).

begin_passes(any, _) :- !.
begin_passes(=<(Time), B-_) :- B =< Time.

%   decisions_from(+Kind, +From, +B1, +N, -M): the greatest decision of Kind that began at
%   B1, reading N at a time in ascending begin from From (below B1).
decisions_from(Kind, From, B1, N, M) :-
    decision_patterns(Kind, M0, cmp(>=, From, B0), Ps),
    findall(B0-M0, store_match(Ps, any, [order([asc(B0)]), limit(N)]), Rows),
    findall(Mx, ( member(Bx-Mx, Rows), Bx =:= B1 ), Latest),
    (   ( length(Rows, NRows), NRows < N ; last(Rows, BL-_), BL > B1 )
    ->  max_member(M, Latest)
    ;   N1 is N*4,
        decisions_from(Kind, From, B1, N1, M)
    ).

%   decision/3 as store patterns (what kb_call compiles it to).
decision_patterns(Kind, M, BO, [t(M, Ex, T), t(T, Type, C), t(M, HI, I), t(I, Begin, BO), t(I, End, _)]) :-
    decision_class(Kind, C0),
    maplist(kb_iri, [dul:executesTask, rdf:type, C0, dul:hasTimeInterval, soma:hasIntervalBegin, soma:hasIntervalEnd],
            [Ex, Type, C, HI, Begin, End]).

decision_class(situation, soma:'Imagining').
decision_class(preference, soma:'Reasoning').

%!  action_time(+Tasks, ?BeginTest, ?EndTest, +Dir, -Begin) is semidet.
%   The least (Dir `asc` or `min`) or greatest (`desc`) begin of an action executing one of
%   Tasks whose begin and end pass the tests (`>(T)`, `=<(T)`, ...; unbound: any): one store
%   query per task, compared by the database. `asc`/`desc` also order and limit there (the
%   scan starts at the test's bound); `min` lets the database plan from the task, for tests
%   that bound the begin from above only and so would scan every earlier action.
action_time(Tasks, BTest, ETest, Dir, B) :-
    maplist(kb_iri, [dul:executesTask, dul:hasTimeInterval, soma:hasIntervalBegin, soma:hasIntervalEnd],
            [Ex, HI, Begin, End]),
    length(Tasks, NTasks),
    (   NTasks > 8, Tasks = [T1|_], once(task_class(T1, TC))
    ->  % One task per action: one query over the actions of the tasks' class, tested here
        % (comparisons in the query let SQLite plan from the interval ranges: ~40x slower).
        kb_iri(rdf:type, Type),
        list_to_ord_set(Tasks, TaskSet),
        findall(B0, ( store_match([t(A, Ex, T), t(T, Type, TC), t(A, HI, I), t(I, Begin, B0), t(I, End, E0)], any),
                      ord_memberchk(T, TaskSet),
                      passes(BTest, B0), passes(ETest, E0) ),
                Bs)
    ;   findall(B0, ( member(T, Tasks),
                      test_object(BTest, B0, BO), test_object(ETest, _, EO),
                      Ps = [t(A, Ex, T), t(A, HI, I), t(I, Begin, BO), t(I, End, EO)],
                      (   Dir == min
                      ->  store_match(Ps, any)
                      ;   Key =.. [Dir, B0],
                          once(store_match(Ps, any, [order([Key]), limit(1)]))
                      ) ),
                Bs)
    ),
    Bs \== [],
    (   Dir == desc -> max_list(Bs, B) ; min_list(Bs, B) ).

passes(Test, _) :- var(Test), !.
passes(Test, V) :- Test =.. [Op, Arg], number(V), compare_number(Op, V, Arg).

compare_number(<, V, A) :- V < A.
compare_number(=<, V, A) :- V =< A.
compare_number(>, V, A) :- V > A.
compare_number(>=, V, A) :- V >= A.

test_object(Test, V, cmp(Op, Arg, V)) :-
    nonvar(Test), Test =.. [Op, Arg], !.
test_object(_, V, V).

%!  imagined_available(+Imagining, -Calls) is det.
%   The task calls an imagining found available, sorted: two store queries, however many
%   tasks (task_calls_reached/3).
imagined_available(M, Calls) :-
    must_be(atom, M),
    task_calls_reached(( holds(M, odb:imagines_situation, P), plan_defines_task(P, T) ), T, Pairs),
    pairs_values(Pairs, Calls0),
    sort(Calls0, Calls).

%!  available_tasks_at(+Time, -Calls) is semidet.
%   The tasks imagined as available at the latest imagining before Time.
available_tasks_at(Time, Calls) :-
    decision_at(situation, Time, M),
    imagined_available(M, Calls).

%!  imagined_preference(+Reasoning, -Ranked) is det.
%   The preference order a reasoning imagined: `ranked(Call, Rank, Score)` by rank.
imagined_preference(M, Ranked) :-
    must_be(atom, M),
    odb_iri(hasPreferenceRank, RankP),
    odb_iri(hasPreferenceScore, ScoreP),
    findall(R-ranked(E, R, S),
            kb_call(( holds(M, odb:imagines_preference, PO), holds(PO, soma:orders, E),
                      triple(E, RankP, R), triple(E, ScoreP, S) ), any),
            Pairs0),
    keysort(Pairs0, Pairs),
    findall(ranked(Call, R, S),
            ( member(_-ranked(E, R, S), Pairs), element_call(E, Call) ),
            Ranked).

%   An ordered element soma:encapsulates the plan for the task (the logger's shape), is the
%   task individual itself, or points at one.
element_call(E, Call) :-
    kb_call(( holds(E, soma:encapsulates, P), plan_defines_task(P, T) ), any),
    task_call(T, Call), !.
element_call(E, Call) :-
    task_call(E, Call), !.
element_call(E, Call) :-
    kb_call(triple(E, P, T), any),
    atom(T), P \== 'http://www.w3.org/1999/02/22-rdf-syntax-ns#type',
    task_call(T, Call), !.

%!  preference_at(+Time, -Reasoning, -Ranked) is semidet.
%   The preference imagined by the latest reasoning before Time.
preference_at(Time, M, Ranked) :-
    decision_at(preference, Time, M),
    imagined_preference(M, Ranked).

%!  latest_preference(-Reasoning, -Begin, -Ranked) is semidet.
latest_preference(M, B, Ranked) :-
    latest_decision(preference, any, M, B),
    imagined_preference(M, Ranked).

%!  times_available(+Call, -Begins) is det.
%   Begin times of the imaginings that found Call available, ascending.
times_available(Call, Begins) :-
    call_classes(Call, TC, _),
    findall(B-T, kb_call(( triple(T, rdf:type, TC), plan_defines_task(P, T),
                           holds(M, odb:imagines_situation, P),
                           event_interval(M, B, _) ), any), Pairs),
    findall(T, member(_-T, Pairs), Ts),
    task_calls(Ts, Calls),
    findall(B, ( member(B-T, Pairs), memberchk(T-Call, Calls) ), Bs),
    sort(Bs, Begins).
