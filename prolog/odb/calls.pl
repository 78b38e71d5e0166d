:- module(odb_calls,
    [ task_class/2,               % ?TaskIndividual, ?Class
      task_call/2,                % +TaskIndividual, -Call
      task_calls/2,               % +Tasks, -Pairs
      task_calls/3,               % +Tasks, +Reaches, -Pairs
      task_calls_reached/3,       % :Reach, ?Task, -Pairs
      task_calls_reached/4,       % :Reach, ?Task, +Options, -Pairs
      call_tasks/2,               % +Call, -TaskIndividuals
      call_task_times/3,          % +Call, +Tasks, -Times
      call_time/4,                % +Call, ?BeginTest, ?EndTest, -Begin
      call_time/5,                % +Call, ?BeginTest, ?EndTest, +Dir, -Begin
      action_call/4,              % ?Action, ?Call, ?Begin, ?End
      times_done/2,               % +Call, -Actions
      chain_before/3              % +Action, +N, -Calls
    ]).
/** <module> odb task calls: task individuals as chain terms, and the actions that executed them

A task individual is typed with its odb task class; its roles classify objects typed with
odb object classes. Its call is the chain term `pick(banana)` (odb_names).
*/

:- use_module(library(error), [must_be/2]).
:- use_module(library(lists), [append/2, last/2, member/2, reverse/2]).
:- use_module(library(apply), [exclude/3, include/3]).
:- use_module(library(pairs), [group_pairs_by_key/2, pairs_keys/2, pairs_values/2]).
:- use_module(library(assoc), [assoc_to_keys/2, get_assoc/3, list_to_assoc/2]).
:- use_module(library(ordsets), [list_to_ord_set/2, ord_memberchk/2]).
:- use_module('../lang/query', [kb_call/2, kb_findall/4, kb_findall/5]).
:- use_module('../model/rdfs', []).
:- use_module('../model/event', []).
:- use_module('../model/object', []).
:- use_module('../model/situation', []).
:- use_module(names, [odb_iri/2, odb_task_roles/3, call_classes/3]).

%!  task_class(?Task, ?Class) is nondet.
%   Class is an odb class the task individual is asserted to be an instance of.
task_class(T, C) :-
    kb_call(triple(T, rdf:type, C), any),
    odb_iri(_, C).

%!  task_call(+Task, -Call) is semidet.
%   The chain term of a task individual, e.g. `pour(thermos, green_mug)`.
task_call(T, Call) :-
    must_be(atom, T),
    task_role_rows(T, C, R, RC, OC, Goal),
    kb_findall(C-R-RC-OC, Goal, any, Rows0),
    rows_call(T, Rows0, Call).

%   The rows task_call/2 reads: the task's class, each role with its class and the class of
%   the object it classifies.
task_role_rows(T, C, R, RC, OC,
               ( triple(T, rdf:type, C), task_role(T, R), has_role(O, R),
                 triple(R, rdf:type, RC), triple(O, rdf:type, OC) )).

%   Rows of roles classifying no odb object (the agent roles of an action performed together)
%   are no argument: a task with only those has the call of a task without roles.
rows_call(T, Rows0, Call) :-
    include(odb_row, Rows0, Rows),
    (   Rows == []
    ->  once(task_class(T, C)), Args = []
    ;   Rows = [C-_-_-_|_],
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

role_rank(C, RCs, 0) :- odb_task_roles(C, _, Ref), memberchk(Ref, RCs), !.
role_rank(C, RCs, 2) :- odb_task_roles(C, Target, _), memberchk(Target, RCs), !.
role_rank(_, _, 1).

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
%   `Task-Call` for each distinct task individual, the call task_call/2 gives. The rows it
%   reads are the product of a task's types, its role-object pairs, the role's types and
%   the object's types (~11 rows per role in a logged NEEM); they are read as their four
%   factors (four store queries, each in the store's order) and joined here, plus one query
%   per task without typed roles. Those factors are the rows of every task of the NEEM; for
%   a few tasks (a kept history's new actions, oracle.historycache) task_call/2 per task
%   reads less: one query each, of that task's rows alone.
task_calls(Ts, Pairs) :-
    sort(Ts, Distinct),
    length(Distinct, N),
    (   few_tasks(N)
    ->  findall(T-C, ( member(T, Distinct), task_call(T, C) ), Pairs)
    ;   factor_calls(Distinct, Pairs)
    ).

%!  task_calls(+Tasks, +Reaches, -Pairs) is det.
%   The Task-Call pairs of at least Tasks, where Reaches, a list of `Reach-Task` goals, reach
%   every one of them: for a few tasks task_calls/2's; for more, those of every typed task the
%   goals reach (reached_factors/4, each joined as written), so that the reads start from the
%   goals (the intervals begun in a slice of the NEEM, say) instead of spanning every task of
%   the NEEM as task_calls/2's do.
task_calls(Ts, Reaches, Pairs) :-
    sort(Ts, Distinct),
    length(Distinct, N),
    (   few_tasks(N)
    ->  task_calls(Distinct, Pairs)
    ;   findall(P, ( member(Reach-T, Reaches), reached_factors(Reach, T, [plan(written)], Ps), member(P, Ps) ), All),
        sort(All, Pairs)
    ).

%   reached_factors(+Reach, ?Task, +Options, -Pairs): the Task-Call pairs of every typed task
%   the kb_call goal Reach binds Task to, read as factor_calls/2 reads them: the tasks' types,
%   and their role-object pairs with the roles' types, two store queries from Reach (Options:
%   how they are joined), and the types of the few distinct objects one query each. The rows read are
%   the sum of the factors, not their product as in task_calls_reached/4 (~11 rows a role):
%   a slice of 2,000 actions read its calls in 0.33 s that way, in ~0.12 s this way.
reached_factors(Reach, T, Options, Pairs) :-
    kb_findall(T-C, ( Reach, triple(T, rdf:type, C) ), any, Options, TCs),
    % the role-object pairs with the roles' types in one read: a pair whose role has no type
    % is no argument (odb_pair/2), and a role's type repeated per object changes no call
    kb_findall(T-(R-O)-RC, ( Reach, task_role(T, R), has_role(O, R), triple(R, rdf:type, RC) ), any, Options,
               Roles),
    findall(T1-RO, member(T1-RO-_, Roles), TROs),
    findall(R1-RC1, member(_-(R1-_)-RC1, Roles), RCs),
    findall(O, member(_-(_-O), TROs), Os0),
    sort(Os0, Os),
    findall(O-OC, ( member(O, Os), kb_call(triple(O, rdf:type, OC), any) ), OCs),
    ordered_groups(TROs, RolesOf),
    append([TCs, RCs, OCs], Typed),
    ordered_groups(Typed, TypesOf),
    findall(Tk, member(Tk-_, TCs), Ts0),
    sort(Ts0, Ts),
    findall(Tk-Call, ( member(Tk, Ts), factored_call(TypesOf, RolesOf, Tk, Call) ), Pairs).

%   A typed task's call from the factors: task_call_from/4, but for a task with no role
%   classifying an odb object the name of its first odb type from its types already read (the
%   call rows_call/3 gives it with a store query of its own).
factored_call(TypesOf, RolesOf, T, Call) :-
    (   get_assoc(T, RolesOf, ROs0) -> true ; ROs0 = [] ),
    (   include(odb_pair(TypesOf), ROs0, [])
    ->  types_of(TypesOf, T, TTs),
        first_odb(TTs, C),
        odb_iri(Call, C)
    ;   task_call_from(TypesOf, RolesOf, T, Call)
    ).

%   Up to this many tasks, one store query per task is the fastest way to their calls.
few_tasks(N) :-
    N =< 64.

%!  task_calls_reached(+Reach, ?Task, -Pairs) is det.
%   task_calls/2 for the tasks the kb_call goal Reach binds Task to (the tasks an imagining
%   found available), in two store queries however many tasks: the rows task_call/2 reads,
%   of all of them in one join after Reach, and their types (the class of a task without
%   roles). A join comes in the ids of its patterns in order, so each task's rows come in
%   the order task_call/2 reads them and the calls are its calls.
task_calls_reached(Reach, T, Pairs) :-
    task_calls_reached(Reach, T, [], Pairs).

%!  task_calls_reached(+Reach, ?Task, +Options, -Pairs) is det.
%   task_calls_reached/3 with the store-query Options of kb_findall/5 for both joins:
%   `[plan(written)]` joins them in the order written, from Reach (a Reach that starts at the
%   interval begins found by value, where SQLite's own plan would start from every typed
%   individual).
task_calls_reached(Reach, T, Options, Pairs) :-
    task_role_rows(T, C, R, RC, OC, Rows),
    kb_findall(T-(C-R-RC-OC), ( Reach, Rows ), any, Options, Found),
    kb_findall(T-TC, ( Reach, triple(T, rdf:type, TC) ), any, Options, Types),
    ordered_groups(Found, RowsOf),
    ordered_groups(Types, TypesOf),
    assoc_to_keys(TypesOf, Ts),
    findall(Tk-Call, ( member(Tk, Ts), reached_call(RowsOf, TypesOf, Tk, Call) ), Pairs).

reached_call(RowsOf, _, T, Call) :-
    get_assoc(T, RowsOf, Rows), !,
    rows_call(T, Rows, Call).
reached_call(_, TypesOf, T, Name) :-
    get_assoc(T, TypesOf, TCs),
    once(( member(C, TCs), odb_iri(Name, C) )).

%   factor_calls(+Distinct, -Pairs): task_calls/2 from the four factors, however few tasks.
factor_calls(Distinct, Pairs) :-
    kb_findall(T-(R-O), ( task_role(T, R), has_role(O, R) ), any, TROs),
    kb_findall(T-C, ( task_role(T, _), triple(T, rdf:type, C) ), any, TCs),
    kb_findall(R-RC, ( task_role(_, R), triple(R, rdf:type, RC) ), any, RCs),
    kb_findall(O-OC, ( has_role(O, _), triple(O, rdf:type, OC) ), any, OCs),
    ordered_groups(TROs, RolesOf),
    append([TCs, RCs, OCs], Typed),
    ordered_groups(Typed, TypesOf),
    findall(T-C, ( member(T, Distinct), task_call_from(TypesOf, RolesOf, T, C) ), Pairs).

%   Key-Value pairs as an AVL tree of Key -> Values in their first order (duplicates kept).
ordered_groups(Pairs, Assoc) :-
    sort(1, @=<, Pairs, ByKey),             % stable: each key's values in the store's order
    group_pairs_by_key(ByKey, Groups),
    list_to_assoc(Groups, Assoc).

%   A task's call from the factors of task_role_rows/6: the rows that exist are those of a
%   type of T and a role-object pair whose role and object are typed; without one, the call
%   of a task without roles. The call's class is the first odb type of T; the roles are those
%   of pairs whose object has an odb type, each role's classes all its types, its object the
%   first odb type of its first such object (the first row task_call/2 meets).
task_call_from(TypesOf, RolesOf, T, Call) :-
    types_of(TypesOf, T, TTs),
    (   get_assoc(T, RolesOf, ROs0) -> true ; ROs0 = [] ),
    include(odb_pair(TypesOf), ROs0, ROs),
    (   ( TTs == [] ; ROs == [] )
    ->  rows_call(T, [], Call)
    ;   first_odb(TTs, C),
        findall(R-RC-OC, ( member(R-O, ROs), types_of(TypesOf, O, OTs), first_odb(OTs, OC),
                           types_of(TypesOf, R, RTs), member(RC, RTs) ),
                RoleRows),
        RoleRows \== [],
        role_args(C, RoleRows, Args),
        odb_iri(Name, C),
        Call =.. [Name|Args]
    ).

types_of(TypesOf, X, Types) :-
    (   get_assoc(X, TypesOf, Types0) -> Types = Types0 ; Types = [] ).

%   A typed role classifying an object of an odb type (not an agent's role).
odb_pair(TypesOf, R-O) :-
    get_assoc(R, TypesOf, _),
    get_assoc(O, TypesOf, OTs),
    once(( member(OC, OTs), odb_iri(_, OC) )).

first_odb(Types, C) :-
    member(C, Types), odb_iri(_, C), !.

%!  call_tasks(+Call, -Tasks) is det.
%   The task individuals whose call is Call (the logger makes one per action, and one per
%   call for the plans). Only the tasks of the call's class with a role classifying an object
%   of the first argument's class are read, with the rows task_call/2 reads of each, in one
%   store query joined in the order written, from the object's class (a call without
%   arguments: every task of its class, then each one's call).
call_tasks(Call, Tasks) :-
    candidate_tasks(Call, T, Candidates),
    (   Call =.. [_, _|_]
    ->  % A task without role rows has a call without arguments: only tasks with rows count.
        task_role_rows(T, C, R, RC, OC, Goal),
        kb_findall(T-(C-R-RC-OC), ( Candidates, Goal ), any, [plan(written)], Rows),
        sort(1, @=<, Rows, ByTask),         % stable: each task's rows in the store's order
        group_pairs_by_key(ByTask, Groups),
        findall(T1, ( member(T1-Rows1, Groups), rows_call(T1, Rows1, C1), C1 = Call ), Tasks)
    ;   findall(T, kb_call(Candidates, any), Ts0),
        sort(Ts0, Ts),
        findall(T, ( member(T, Ts), task_call(T, C), C = Call ), Tasks)
    ).

%   candidate_tasks(+Call, ?T, -Goal): Goal binds T to the tasks of the call's class with a
%   role classifying an object of the first argument's class (every task of the class when
%   there is no argument): a superset of the tasks whose call is Call.
candidate_tasks(Call, T, Goal) :-
    call_classes(Call, TC, OCs),
    (   OCs = [OC1|_]
    ->  Goal = ( triple(O1, rdf:type, OC1), has_role(O1, R1), task_role(T, R1), triple(T, rdf:type, TC) )
    ;   Goal = triple(T, rdf:type, TC)
    ).

%!  call_task_times(+Call, +Tasks, -Times) is det.
%   `Begin-End` of every action that executed one of Tasks, tasks whose call is Call
%   (call_tasks/2): one store query over the actions of Call's candidate tasks.
call_task_times(Call, Tasks, Times) :-
    list_to_ord_set(Tasks, Set),
    candidate_tasks(Call, T, Candidates),
    kb_findall(T-B-E, ( Candidates, executes_task(A, T), event_interval(A, B, E) ), any, [plan(written)], Rows),
    findall(B-E, ( member(T1-B-E, Rows), ord_memberchk(T1, Set) ), Times).

%!  call_time(+Call, ?BeginTest, ?EndTest, -Begin) is semidet.
%!  call_time(+Call, ?BeginTest, ?EndTest, +Dir, -Begin) is semidet.
%   The least (Dir `asc`, the default) or greatest (`desc`) begin of an action that executed
%   a task whose call is Call, among the actions whose begin and end pass the tests
%   (`>(T)`, `=<(T)`, ... on a number; unbound: any). The store compares, orders and sends
%   the candidates (call_tasks/2's superset) a chunk at a time, growing, and only the tasks
%   of the rows looked at get their call: a few queries however often Call was done.
call_time(Call, BTest, ETest, B) :-
    call_time(Call, BTest, ETest, asc, B).

call_time(Call, BTest, ETest, Dir, B) :-
    must_be(oneof([asc, desc]), Dir),
    call_time_(Call, BTest, ETest, Dir, 16, B).

call_time_(Call, BTest, ETest, Dir, _, B) :-
    far_bound(Dir, BTest), !,
    % Ordered from the far side of the bound, the store would scan every begin before it
    % (asc) or after it (desc): all rows from the tasks instead, ordered here.
    first_of_all(Call, BTest, ETest, Dir, B).
call_time_(Call, BTest, ETest, Dir, N, B) :-
    Key =.. [Dir, B0],
    candidate_times(Call, BTest, ETest, [order([Key]), limit(N)], B0, Rows),
    length(Rows, Got),
    (   Got < N
    ->  first_of_call(Call, Rows, B)
    ;   last(Rows, Last-_),
        exclude(begins_at(Last), Rows, Complete),   % the last begin may have more rows
        (   first_of_call(Call, Complete, B)
        ->  true
        ;   resume_test(Dir, Last, BTest, BTest1)
        ->  N1 is N*4,
            call_time_(Call, BTest1, ETest, Dir, N1, B)
        ;   first_of_all(Call, BTest, ETest, Dir, B)   % no bound to resume from
        )
    ).

%   The first matching row of all the candidates' rows, ordered in Prolog.
first_of_all(Call, BTest, ETest, Dir, B) :-
    candidate_times(Call, BTest, ETest, [], _, All),
    (   Dir == asc -> sort(0, @=<, All, Sorted) ; sort(0, @>=, All, Sorted) ),
    first_of_call(Call, Sorted, B).

%   Begin-Task rows of the candidate tasks' actions whose interval passes the tests.
candidate_times(Call, BTest, ETest, Options, B, Rows) :-
    candidate_tasks(Call, T, Candidates),
    value_spec(BTest, B, BSpec),
    value_spec(ETest, _, ESpec),
    kb_findall(B-T, ( Candidates, executes_task(A, T), has_time_interval(A, I),
                      triple(I, soma:hasIntervalBegin, BSpec), triple(I, soma:hasIntervalEnd, ESpec) ),
               any, [plan(written)|Options], Rows).

value_spec(Test, V, V) :- var(Test), !.
value_spec(Test, V, (Test -> V)).

%   The begin test that resumes after the rows with begins before Last, from Last itself
%   (ties included): it replaces BTest when Last passes BTest and the new test implies it.
resume_test(asc, Last, BTest, >=(Last)) :-
    number(Last),
    ( var(BTest) ; BTest = >(_) ; BTest = >=(_) ), !.
resume_test(desc, Last, BTest, =<(Last)) :-
    number(Last),
    ( var(BTest) ; BTest = <(_) ; BTest = =<(_) ), !.

far_bound(asc, BTest) :- nonvar(BTest), ( BTest = <(_) ; BTest = =<(_) ), !.
far_bound(desc, BTest) :- nonvar(BTest), ( BTest = >(_) ; BTest = >=(_) ), !.

begins_at(Last, B-_) :- B == Last.

first_of_call(Call, Rows, B) :-
    member(B-T, Rows),
    number(B),
    task_call(T, C), C = Call, !.

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
