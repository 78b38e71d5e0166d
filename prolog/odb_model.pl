:- module(odb_model,
    [ odb_iri/2,                  % ?Local, ?IRI
      odb_set_namespace/1,        % +Namespace
      odb_set_task_roles/3,       % +TaskClass, +TargetRole, +RefRole
      task_class/2,               % ?TaskIndividual, ?Class
      task_call/2,                % +TaskIndividual, -Call
      call_classes/3,             % +Call, -TaskClass, -ObjectClasses
      action_call/4,              % ?Action, ?Call, ?Begin, ?End
      event_time_of_day/2,        % ?Event, ?Part
      is_idle_action/1,           % ?Action
      idle_action/3,              % ?Action, ?Begin, ?End
      decision/3,                 % ?Kind, ?MentalAction, ?Begin
      decision_at/3,              % +Kind, +Time, -MentalAction
      latest_decision/4,          % +Kind, +Test, -MentalAction, -Begin
      call_tasks/2,               % +Call, -TaskIndividuals
      action_time/5,              % +Tasks, ?BeginTest, ?EndTest, +Dir, -Begin
      imagined_available/2,       % +Imagining, -Calls
      available_tasks_at/2,       % +Time, -Calls
      imagined_preference/2,      % +Reasoning, -Ranked
      preference_at/3,            % +Time, -Reasoning, -Ranked
      latest_preference/3,        % -Reasoning, -Begin, -Ranked
      times_available/2,          % +Call, -Begins
      times_done/2,               % +Call, -Actions
      chain_before/3,             % +Action, +N, -Calls
      perceived_at/2,             % +ObjectName, +Time
      task_calls/2,               % +Tasks, -Pairs
      situation_history/1,        % -Situations
      situation_history_json/1,   % -JSONString
      latest_situation/2,         % -Begin, -Calls
      latest_situation_json/1     % -JSONString
    ]).
/** <module> The odb model: what the EDAN NEEM logger adds to SOMA (thesis 3.4)

Project predicates over the NEEM, built on knowrob_model's kb_call/2 so every lookup is
one compiled store query:

  - the time of day of an event (its time interval typed odb:Morning/Midday/Evening/Night);
  - idle actions (executing an odb:IdleTask);
  - decisions: the soma:Imagining mental actions that odb:imagines_situation the available
    tasks (soma:ActionExecutionPlan soma:isPlanFor task), and the soma:Reasoning mental
    actions that odb:imagines_preference a soma:PreferenceOrder whose soma:orders elements
    carry odb:hasPreferenceRank and odb:hasPreferenceScore and soma:encapsulates the plan;
  - task calls: a task individual (typed with its odb task class, roles classifying
    objects typed with odb object classes) as the chain term `pick(banana)`;
  - the chain of actions before an action.

Times are unix seconds. A call is a term whose functor is the odb task's local name and
whose arguments are the odb object local names, reference role first (chains.py).
*/

:- use_module(library(error)).
:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module(library(pairs)).
:- use_module(library(semweb/rdf_prefixes)).
:- use_module(neem_store, [store_match/2, store_match/3]).
:- use_module(knowrob_model).
:- use_module(library(http/json)).

:- dynamic task_roles_/3.         % TaskClass, TargetRole|none, RefRole|none

%!  odb_set_namespace(+Namespace) is det.
%   Use Namespace for the `odb` prefix (the ontology's, when not the default).
odb_set_namespace(NS) :-
    must_be(atom, NS),
    rdf_register_prefix(odb, NS, [force(true)]).

%!  odb_iri(?Local, ?IRI) is semidet.
%   IRI is Local in the odb namespace.
odb_iri(Local, IRI) :-
    rdf_current_prefix(odb, NS),
    (   nonvar(IRI)
    ->  atom(IRI), atom_concat(NS, Local, IRI), Local \== ''
    ;   must_be(atom, Local), atom_concat(NS, Local, IRI)
    ).

%!  odb_set_task_roles(+TaskClass, +TargetRole, +RefRole) is det.
%   Which role class is the target and which the reference of an odb task (`none` when
%   the task has none); orders the arguments of task calls. Set by the bridge from the
%   ontology.
odb_set_task_roles(Task, Target, Ref) :-
    must_be(atom, Task), must_be(atom, Target), must_be(atom, Ref),
    retractall(task_roles_(Task, _, _)),
    assertz(task_roles_(Task, Target, Ref)).

%!  task_class(?Task, ?Class) is nondet.
%   Class is an odb class the task individual is asserted to be an instance of.
task_class(T, C) :-
    kb_call(triple(T, rdf:type, C), any),
    odb_iri(_, C).

%!  task_call(+Task, -Call) is semidet.
%   The chain term of a task individual, e.g. `pour(thermos, green_mug)`.
task_call(T, Call) :-
    must_be(atom, T),
    findall(C-R-RC-OC,
            kb_call(( triple(T, rdf:type, C), task_role(T, R), has_role(O, R),
                      triple(R, rdf:type, RC), triple(O, rdf:type, OC) ), any),
            Rows0),
    (   Rows0 == []
    ->  once(task_class(T, C)), Args = []
    ;   include(odb_row, Rows0, Rows),
        Rows = [C-_-_-_|_],
        findall(R-RC-OC, member(C-R-RC-OC, Rows), RoleRows),
        role_args(C, RoleRows, Args)
    ),
    odb_iri(Name, C),
    Call =.. [Name|Args].

odb_row(C-_-_-OC) :- odb_iri(_, C), odb_iri(_, OC).

%   One object name per role; the reference role's object first.
role_args(C, RoleRows, Args) :-
    findall(R-RC, member(R-RC-_, RoleRows), RPairs0),
    sort(RPairs0, RPairs1),
    pairs_keys(RPairs1, Roles0), sort(Roles0, Roles),
    findall(Rank-Name,
            ( member(R, Roles),
              once(member(R-_-OC, RoleRows)),
              odb_iri(Name, OC),
              findall(RC, member(R-RC, RPairs1), RCs),
              role_rank(C, RCs, Rank) ),
            Ranked),
    keysort(Ranked, Sorted),
    pairs_values(Sorted, Args).

role_rank(C, RCs, 0) :- task_roles_(C, _, Ref), memberchk(Ref, RCs), !.
role_rank(C, RCs, 2) :- task_roles_(C, Target, _), memberchk(Target, RCs), !.
role_rank(_, _, 1).

%!  call_classes(+Call, -TaskClass, -ObjectClasses) is det.
%   The odb class IRIs a chain term names.
call_classes(Call, TaskClass, ObjClasses) :-
    must_be(callable, Call),
    Call =.. [Name|Args],
    odb_iri(Name, TaskClass),
    maplist(odb_iri, Args, ObjClasses).

%!  action_call(?Action, ?Call, ?Begin, ?End) is nondet.
%   Action executed the task Call during [Begin, End] (physical actions, idle included).
action_call(A, Call, B, E) :-
    (   nonvar(Call)
    ->  call_classes(Call, TC, _)
    ;   true
    ),
    findall(A0-T-B0-E0,
            ( kb_call(( executes_task(A0, T), triple(T, rdf:type, TC),
                        event_interval(A0, B0, E0) ), any),
              odb_iri(_, TC) ),
            Rows),
    findall(T, member(_-T-_-_, Rows), Ts),
    task_calls(Ts, Calls),
    member(A-T1-B-E, Rows),
    memberchk(T1-Call, Calls).

%!  task_calls(+Tasks, -Pairs) is det.
%   `Task-Call` for each distinct task individual (the logger reuses one individual per
%   call, so this costs one store query per distinct task, not per action).
task_calls(Ts, Pairs) :-
    sort(Ts, Distinct),
    findall(T-C, ( member(T, Distinct), task_call(T, C) ), Pairs).

%!  event_time_of_day(?Event, ?Part) is nondet.
%   Part (`'Morning'`, `'Midday'`, `'Evening'` or `'Night'`) is the odb:TimeOfDay class of
%   the event's time interval.
event_time_of_day(E, Part) :-
    member(Part, ['Morning', 'Midday', 'Evening', 'Night']),
    odb_iri(Part, C),
    kb_call(( has_time_interval(E, I), triple(I, rdf:type, C) ), any).

%!  is_idle_action(?Action) is nondet.
%   Action executes an odb:IdleTask (the robot in shared grasping for 20 s or more).
is_idle_action(A) :-
    idle_action(A, _, _).

%!  idle_action(?Action, ?Begin, ?End) is nondet.
idle_action(A, B, E) :-
    odb_iri('IdleTask', Idle),
    kb_call(( executes_task(A, T), instance_of(T, Idle), event_interval(A, B, E) ), any).

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
%   The latest decision of Kind whose begin passes Test (`=<(Time)`, or `any`): one store
%   query ordered by begin, limited to a few rows, which holds every decision that began
%   at the latest begin unless they fill it (then it is asked again with a larger limit);
%   the greatest in the standard order of terms when several began then, as max_member/2.
latest_decision(Kind, Test, M, B) :-
    latest_decision_(Kind, Test, 4, M, B).

latest_decision_(Kind, Test, N, M, B) :-
    (   Test = =<(Time) -> BO = cmp(=<, Time, B0) ; BO = B0 ),
    decision_patterns(Kind, M0, BO, Ps),
    findall(B0-M0, store_match(Ps, any, [order([desc(B0)]), limit(N)]), Rows),
    Rows = [B1-_|_],
    findall(Bx-Mx, ( member(Bx-Mx, Rows), Bx =:= B1 ), Latest),
    length(Latest, NLatest),
    (   NLatest < N
    ->  max_member(_-M, Latest),
        B = B1
    ;   N1 is N*4,
        latest_decision_(Kind, Test, N1, M, B)
    ).

%   decision/3 as store patterns (what kb_call compiles it to).
decision_patterns(Kind, M, BO, [t(M, Ex, T), t(T, Type, C), t(M, HI, I), t(I, Begin, BO), t(I, End, _)]) :-
    decision_class(Kind, C0),
    maplist(kb_iri, [dul:executesTask, rdf:type, C0, dul:hasTimeInterval, soma:hasIntervalBegin, soma:hasIntervalEnd],
            [Ex, Type, C, HI, Begin, End]).

decision_class(situation, soma:'Imagining').
decision_class(preference, soma:'Reasoning').

%!  call_tasks(+Call, -Tasks) is det.
%   The task individuals whose call is Call (the logger makes one per call).
call_tasks(Call, Tasks) :-
    call_classes(Call, TC, _),
    findall(T, kb_call(triple(T, rdf:type, TC), any), Ts0),
    sort(Ts0, Ts),
    findall(T, ( member(T, Ts), task_call(T, C), C = Call ), Tasks).

%!  action_time(+Tasks, ?BeginTest, ?EndTest, +Dir, -Begin) is semidet.
%   The least (Dir `asc` or `min`) or greatest (`desc`) begin of an action executing one of
%   Tasks whose begin and end pass the tests (`>(T)`, `=<(T)`, ...; unbound: any): one store
%   query per task, compared by the database. `asc`/`desc` also order and limit there (the
%   scan starts at the test's bound); `min` lets the database plan from the task, for tests
%   that bound the begin from above only and so would scan every earlier action.
action_time(Tasks, BTest, ETest, Dir, B) :-
    maplist(kb_iri, [dul:executesTask, dul:hasTimeInterval, soma:hasIntervalBegin, soma:hasIntervalEnd],
            [Ex, HI, Begin, End]),
    findall(B0, ( member(T, Tasks),
                  test_object(BTest, B0, BO), test_object(ETest, _, EO),
                  Ps = [t(A, Ex, T), t(A, HI, I), t(I, Begin, BO), t(I, End, EO)],
                  (   Dir == min
                  ->  store_match(Ps, any)
                  ;   Key =.. [Dir, B0],
                      once(store_match(Ps, any, [order([Key]), limit(1)]))
                  ) ),
            Bs),
    Bs \== [],
    (   Dir == desc -> max_list(Bs, B) ; min_list(Bs, B) ).

test_object(Test, V, cmp(Op, Arg, V)) :-
    nonvar(Test), Test =.. [Op, Arg], !.
test_object(_, V, V).

%!  imagined_available(+Imagining, -Calls) is det.
%   The task calls an imagining found available, sorted.
imagined_available(M, Calls) :-
    must_be(atom, M),
    findall(T, kb_call(( holds(M, odb:imagines_situation, P),
                         plan_defines_task(P, T) ), any), Ts),
    findall(C, ( member(T, Ts), task_call(T, C) ), Calls0),
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

%!  times_done(+Call, -Actions) is det.
%   `action(Begin, End, Action)` for every action that executed Call, by begin.
times_done(Call, Actions) :-
    findall(action(B, E, A), action_call(A, Call, B, E), As),
    sort(As, Actions).

%!  chain_before(+Action, +N, -Calls) is det.
%   The calls of the (at most N) non-idle actions that ended before Action began, oldest
%   first.
chain_before(A, N, Calls) :-
    must_be(atom, A), must_be(nonneg, N),
    once(kb_call(event_interval(A, B0, _), any)),
    odb_iri('IdleTask', Idle),
    findall(B-T, kb_call(( executes_task(A1, T), has_time_interval(A1, I),
                           has_interval_begin(I, B) ), any),
            Pairs0),
    findall(B-T, ( member(B-T, Pairs0), B < B0 ), Pairs1),
    sort(0, @>, Pairs1, Desc),
    take_calls(Desc, Idle, N, Rev),
    reverse(Rev, Calls).

take_calls(_, _, 0, []) :- !.
take_calls([], _, _, []).
take_calls([_-T|Ps], Idle, N, Calls) :-
    (   \+ kb_call(instance_of(T, Idle), any),
        task_call(T, Call)
    ->  Calls = [Call|Rest], N1 is N-1
    ;   Calls = Rest, N1 = N
    ),
    take_calls(Ps, Idle, N1, Rest).

%!  perceived_at(+ObjectName, +Time) is semidet.
%   Some object of the odb class ObjectName was known at Time: the logger scopes an
%   object's type triple from its first perception.
perceived_at(Name, Time) :-
    must_be(atom, Name), must_be(number, Time),
    odb_iri(Name, C),
    once(kb_call(instance_of(_, C), scope(Time, Time))).


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
