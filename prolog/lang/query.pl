:- module(kb_query,
    [ kb_call/1,                % :Goal
      kb_call/2,                % :Goal, +Scope
      kb_call_stepwise/1,       % :Goal
      kb_call_stepwise/2,       % :Goal, +Scope
      kb_compile/3,             % +Goal, +Scope, -Plan
      kb_project/1              % +Statement
    ]).
/** <module> The query language: kb_call and kb_project (KnowRob 2.x src/lang/query.pl)

Like mongolog, kb_call/1 *compiles* its goal: model predicates are unfolded into triple
goals (their definitions are kb_rule/2 facts, added by the model modules), and each
maximal run of triple goals under one scope becomes ONE store_match/2 call: one SQL join
or one aggregation pipeline. kb_call_stepwise/1 evaluates the same goal one triple at a
time, as a plain Prolog conjunction would; both give the same solutions.

    ?- kb_call(( is_action(A), executes_task(A, T), instance_of(T, odb:pick),
                 has_participant(A, O), event_interval(A, B, E) )).

The compiler knows the control constructs (`,`, `;`, `->`, `\+`), triple/3 and holds/3
(kb_triple), the scope modifiers `during`, `since` and `until` (kb_scope), `has_type/2`
(no compound class expressions, no owl:NamedIndividual when the type is free) and
`occurs/1` (an event whose interval overlaps the question scope). Any other goal is
called as Prolog in the caller's module.

kb_project/1 asserts statements built from the same vocabulary (see kb_project/1).
*/

:- use_module(library(error)).
:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module('../neem_store', [store_match/2, store_insert/1]).
:- use_module(triple, [kb_iri/2, iri_term/1, triple_steps/6]).
:- use_module(scope, [current_scope/1, scope_check/1, scope_overlaps/3, runtime_scope/3]).

:- meta_predicate
    kb_call(0), kb_call(0, +), kb_call_stepwise(0), kb_call_stepwise(0, +).

%!  kb_rule(?Head, ?Body) is nondet.
%   Head is defined by Body, a conjunction of triple/3 goals, other model predicates and
%   Prolog goals (KnowRob's `?>` rules). Multifile: the model modules add their own.
:- multifile kb_rule/2.

%!  kb_call(:Goal) is nondet.
%!  kb_call(:Goal, +Scope) is nondet.
%   Solve Goal, compiled: every run of triple goals becomes one store query. Scope is
%   `scope(Since, Until)` or `any`; kb_call/1 asks about now.
kb_call(Goal) :-
    current_scope(Scope),
    kb_call(Goal, Scope).
kb_call(Goal, Scope) :-
    kb_compile(Goal, Scope, compiled, Plan),
    run_plan(Plan).

%!  kb_call_stepwise(:Goal) is nondet.
%!  kb_call_stepwise(:Goal, +Scope) is nondet.
%   Solve Goal one triple goal at a time (no conjunction compilation); same solutions.
kb_call_stepwise(Goal) :-
    current_scope(Scope),
    kb_call_stepwise(Goal, Scope).
kb_call_stepwise(Goal, Scope) :-
    kb_compile(Goal, Scope, stepwise, Plan),
    run_plan(Plan).

%!  kb_compile(+Goal, +Scope, -Plan) is det.
%   The plan kb_call/2 runs: a list of `match(Patterns, Scope)`, `call(Goal)`,
%   `or(P1, P2)`, `ite(C, T, E)`, `not(P)` and `scoped(Kind, Goal, Arg)` steps.
kb_compile(Goal, Scope, Plan) :-
    kb_compile(Goal, Scope, compiled, Plan).

kb_compile(Goal, Scope, Mode, Plan) :-
    scope_check(Scope),
    strip_module(Goal, M, G),
    unfold(G, M, Scope, Steps, []),
    group(Mode, Steps, Plan).

                 /*******************************
                 *          UNFOLDING           *
                 *******************************/

%   unfold(+Goal, +Module, +Scope, -Steps, ?Tail): Module is the caller's context, used for
%   goals that are not model predicates.
unfold(G, _, _, _, _) :-
    var(G), !,
    instantiation_error(G).
unfold(M:G, _, Scope, S0, S) :-
    atom(M), !,
    unfold(G, M, Scope, S0, S).
unfold((A, B), Mod, Scope, S0, S) :- !,
    unfold(A, Mod, Scope, S0, S1),
    unfold(B, Mod, Scope, S1, S).
unfold((C -> T ; E), Mod, Scope, [ite(PC, PT, PE)|S], S) :- !,
    sub_plan(C, Mod, Scope, PC), sub_plan(T, Mod, Scope, PT), sub_plan(E, Mod, Scope, PE).
unfold((A ; B), Mod, Scope, [or(PA, PB)|S], S) :- !,
    sub_plan(A, Mod, Scope, PA), sub_plan(B, Mod, Scope, PB).
unfold((C -> T), Mod, Scope, [ite(PC, PT, [call(fail)])|S], S) :- !,
    sub_plan(C, Mod, Scope, PC), sub_plan(T, Mod, Scope, PT).
unfold(\+ G, Mod, Scope, [not(P)|S], S) :- !,
    sub_plan(G, Mod, Scope, P).
unfold(true, _, _, S, S) :- !.
unfold(during(G, I), Mod, _, S0, S) :- !,
    (   nonvar(I), I = [T0, T1], number(T0), number(T1)
    ->  unfold(G, Mod, scope(T0, T1), S0, S)
    ;   S0 = [scoped(during, Mod:G, I)|S]
    ).
unfold(since(G, T), Mod, _, S0, S) :- !,
    (   number(T)
    ->  get_time(Now), unfold(G, Mod, scope(T, Now), S0, S)
    ;   S0 = [scoped(since, Mod:G, T)|S]
    ).
unfold(until(G, T), Mod, _, S0, S) :- !,
    (   number(T)
    ->  unfold(G, Mod, scope(T, T), S0, S)
    ;   S0 = [scoped(until, Mod:G, T)|S]
    ).
unfold(triple(Su, P, O), _, Scope, S0, S) :- !,
    triple_steps(Su, P, O, Scope, S0, S).
unfold(holds(Su, P, O), _, Scope, S0, S) :- !,
    triple_steps(Su, P, O, Scope, S0, S).
unfold(has_type(A, B), Mod, Scope, S0, S) :- !,
    (   nonvar(B), \+ iri_term(B)
    ->  S0 = [call(fail)|S]          % compound class expressions are not types
    ;   var(B)
    ->  unfold(instance_of(A, B), Mod, Scope, S0, [call(kb_query:not_named_individual(B))|S])
    ;   unfold(instance_of(A, B), Mod, Scope, S0, S)
    ).
unfold(occurs(E), Mod, Scope, S0, S) :- !,
    unfold(event_interval(E, B, End), Mod, any, S0, [call(kb_scope:scope_overlaps(Scope, B, End))|S]).
unfold(G, Mod, Scope, S0, S) :-
    kb_rule(G, Body), !,
    unfold(Body, Mod, Scope, S0, S).
unfold(G, Mod, _, [call(Mod:G)|S], S).

sub_plan(G, Mod, Scope, Plan) :-
    unfold(G, Mod, Scope, Steps, []),
    group(compiled, Steps, Plan).

not_named_individual(B) :-
    B \== 'http://www.w3.org/2002/07/owl#NamedIndividual'.

                 /*******************************
                 *           GROUPING           *
                 *******************************/

%   compiled: consecutive patterns under one scope become one match/2 step; the filters
%   of their value operators follow it. stepwise: one match per pattern.
group(_, [], []).
group(Mode, [pattern(T, Scope)|Steps], [match([T|Ts1], Scope)|Plan]) :- !,
    (   Mode == compiled
    ->  take_patterns(Steps, Scope, Ts1, Filters, Rest)
    ;   Ts1 = [], Filters = [], Rest = Steps
    ),
    append(Filters, Plan1, Plan),
    group(Mode, Rest, Plan1).
group(Mode, [Step|Steps], [Step|Plan]) :-
    group(Mode, Steps, Plan).

take_patterns([pattern(T, Scope1)|Steps], Scope, [T|Ts], Fs, Rest) :-
    Scope1 == Scope, !,
    take_patterns(Steps, Scope, Ts, Fs, Rest).
take_patterns([call(F)|Steps], Scope, Ts, [call(F)|Fs], Rest) :-
    F = kb_triple:value_test(_, _, _), !,
    take_patterns(Steps, Scope, Ts, Fs, Rest).
take_patterns(Steps, _, [], [], Steps).

                 /*******************************
                 *           RUNNING            *
                 *******************************/

run_plan([]).
run_plan([Step|Steps]) :-
    run_step(Step),
    run_plan(Steps).

run_step(match(Ts, Scope)) :-
    maplist(expand_pattern, Ts, Ts1),
    store_match(Ts1, Scope).
run_step(call(G)) :- call(G).
run_step(or(A, B)) :- ( run_plan(A) ; run_plan(B) ).
run_step(ite(C, T, E)) :- ( run_plan(C) -> run_plan(T) ; run_plan(E) ).
run_step(not(P)) :- \+ run_plan(P).
run_step(scoped(Kind, G, Arg)) :-
    runtime_scope(Kind, Arg, Scope),
    kb_call(G, Scope).

expand_pattern(t(S, P, O), t(S1, P1, O1)) :-
    kb_iri(S, S1), kb_iri(P, P1), kb_iri(O, O1).

                 /*******************************
                 *          PROJECTION          *
                 *******************************/

%!  kb_project(+Statement) is det.
%   Assert Statement: triple/3, model predicates defined by triples, event_interval/3
%   (creates the time interval), `occurs(E)` and conjunctions of these, optionally
%   scoped: `Statement during [T0,T1]`, `Statement since T`, `Statement until T`.
%   Universal scope otherwise, as NEEM narrative facts are.
kb_project(Statement) :-
    Inf is inf,
    project(Statement, 0.0, Inf, Triples, []),
    store_insert(Triples).

project(V, _, _, _, _) :-
    var(V), !, instantiation_error(V).
project(_:G, S, U, T0, T) :- !,
    project(G, S, U, T0, T).
project((A, B), S, U, T0, T) :- !,
    project(A, S, U, T0, T1),
    project(B, S, U, T1, T).
project(during(G, [S, U]), _, _, T0, T) :- !,
    must_be(number, S), must_be(number, U),
    project(G, S, U, T0, T).
project(since(G, S), _, _, T0, T) :- !,
    must_be(number, S), Inf is inf,
    project(G, S, Inf, T0, T).
project(until(G, U), _, _, T0, T) :- !,
    must_be(number, U),
    project(G, 0.0, U, T0, T).
project(triple(S, P, O), Since, Until, [triple(S1, P1, O1, Since, Until)|T], T) :- !,
    must_be(ground, triple(S, P, O)),
    kb_iri(S, S1), kb_iri(P, P1), kb_iri(O, O1),
    must_be(atom, S1), must_be(atom, P1), must_be(atomic, O1).
project(holds(S, P, O), Since, Until, T0, T) :- !,
    project(triple(S, P, O), Since, Until, T0, T).
project(has_type(A, B), Since, Until, T0, T) :- !,
    project(triple(A, rdf:type, B), Since, Until, T0, T).
project(event_interval(E, B, End), Since, Until, T0, T) :- !,
    must_be(number, B), must_be(number, End),
    kb_iri(E, E1), must_be(atom, E1),
    (   once(kb_call(has_time_interval(E1, I0), any))
    ->  I = I0
    ;   atom_concat(E1, '_TimeInterval', I)
    ),
    project(( triple(E1, dul:hasTimeInterval, I),
              triple(I, rdf:type, dul:'TimeInterval'),
              triple(I, soma:hasIntervalBegin, B),
              triple(I, soma:hasIntervalEnd, End) ), Since, Until, T0, T).
project(occurs(E), Since, Until, T0, T) :- !,
    Inf is inf,
    (   Until =:= Inf -> End = Since ; End = Until ),
    project((has_type(E, dul:'Event'), event_interval(E, Since, End)), 0.0, Inf, T0, T).
project(G, S, U, T0, T) :-
    kb_rule(G, Body), !,
    project(Body, S, U, T0, T).
project(G, _, _, _, _) :-
    domain_error(projectable_statement, G).
