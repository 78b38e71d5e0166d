:- module(knowrob_model,
    [ kb_call/1,                % :Goal
      kb_call/2,                % :Goal, +Scope
      kb_call_stepwise/1,       % :Goal
      kb_call_stepwise/2,       % :Goal, +Scope
      kb_compile/3,             % +Goal, +Scope, -Plan
      kb_project/1,             % +Statement
      triple/3, holds/3,
      instance_of/2, subclass_of/2, subproperty_of/2, has_type/2,
      is_action/1, is_event/1, is_task/1, is_role/1, is_agent/1, is_episode/1,
      is_physical_object/1, is_object/1, is_mental_action/1, is_physical_task/1,
      executes_task/2, is_performed_by/2, has_participant/2, has_role/2, task_role/2,
      is_classified_by/2, plan_defines_task/2, has_subevent/2,
      has_time_interval/2, has_interval_begin/2, has_interval_end/2,
      event_interval/3, occurs/1,
      during/2, since/2, until/2,
      kb_iri/2,                 % +Term, -IRI
      op(800, yfx, during),
      op(800, yfx, since),
      op(800, yfx, until)
    ]).
/** <module> KnowRob 2.x model predicates over the NEEM store

The names, arities and semantics of KnowRob 2.x's query language (`kb_call/1`,
`kb_project/1`, `triple/3`, the files under src/model/), evaluated over neem_store. A KnowRob user's
query about an action, its task, participants, roles and interval runs unchanged:

    ?- kb_call(( is_action(A), executes_task(A, T), instance_of(T, odb:pick),
                 has_participant(A, O), event_interval(A, B, E) )).

Like mongolog, kb_call/1 *compiles* its goal: model predicates are unfolded into triple
goals (their definitions are the kb_rule/2 facts below, extensible by other modules), and
each maximal run of triple goals under one scope becomes ONE store_match/2 call — one SQL
join or one aggregation pipeline. kb_call_stepwise/1 evaluates the same goal one triple
at a time, as a plain Prolog conjunction would; both give the same solutions.

Scopes: the default question scope is "now" (facts true at the current time; NEEM facts
have universal scope). `Goal during [T0,T1]` asks for facts true during the whole
interval, `Goal during Event` uses the event's interval, `Goal since T` for facts true
since T and still now, `Goal until T` for facts true at T.

Values may carry KnowRob's operators in the object of triple/3 and holds/3:
`<(V)`, `=<(V)`, `>(V)`, `>=(V)`, `in(List)`, `nin(List)`, `regex(Pattern)`, and
`Op->Var` to get the actual value back. IRIs may be written `prefix:'Local'` for the
registered prefixes (rdf, rdfs, owl, xsd, dul, soma, knowrob, odb).
*/

:- use_module(library(error)).
:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module(library(pcre), []).
:- use_module(library(semweb/rdf_prefixes)).
:- use_module(neem_store).

:- op(800, yfx, user:during).
:- op(800, yfx, user:since).
:- op(800, yfx, user:until).

:- rdf_register_prefix(dul, 'http://www.ontologydesignpatterns.org/ont/dul/DUL.owl#', [keep(true)]).
:- rdf_register_prefix(soma, 'http://www.ease-crc.org/ont/SOMA.owl#', [keep(true)]).
:- rdf_register_prefix(knowrob, 'http://knowrob.org/kb/knowrob.owl#', [keep(true)]).
:- rdf_register_prefix(odb, 'https://ontology.dlr.de/soma/odb#', [keep(true)]).

:- meta_predicate
    kb_call(0), kb_call(0, +), kb_call_stepwise(0), kb_call_stepwise(0, +),
    during(0, +), since(0, +), until(0, +).

%!  kb_rule(?Head, ?Body) is nondet.
%   Head is defined by Body, a conjunction of triple/3 goals, other model predicates and
%   Prolog goals (KnowRob's `?>` rules). Multifile: other modules add their own.
:- multifile kb_rule/2.
:- discontiguous kb_rule/2.

kb_rule(instance_of(A, B), triple(A, rdf:type, B)).
kb_rule(subclass_of(A, B), triple(A, rdfs:subClassOf, B)).
kb_rule(subproperty_of(A, B), triple(A, rdfs:subPropertyOf, B)).
kb_rule(is_action(A), has_type(A, dul:'Action')).
kb_rule(is_event(A), has_type(A, dul:'Event')).
kb_rule(is_task(A), has_type(A, dul:'Task')).
kb_rule(is_role(A), has_type(A, dul:'Role')).
kb_rule(is_agent(A), has_type(A, dul:'Agent')).
kb_rule(is_episode(A), has_type(A, soma:'Episode')).
kb_rule(is_physical_object(A), has_type(A, dul:'PhysicalObject')).
kb_rule(is_object(A), has_type(A, dul:'Object')).
kb_rule(is_mental_action(A), has_type(A, soma:'MentalAction')).
kb_rule(is_physical_task(A), has_type(A, soma:'PhysicalTask')).
kb_rule(executes_task(A, T), holds(A, dul:executesTask, T)).
kb_rule(is_performed_by(A, Agent), holds(A, soma:isPerformedBy, Agent)).
kb_rule(has_participant(E, O), holds(E, dul:hasParticipant, O)).
kb_rule(has_role(O, R), holds(R, dul:classifies, O)).
kb_rule(task_role(T, R), holds(T, dul:isTaskOf, R)).
kb_rule(is_classified_by(E, C), holds(E, dul:isClassifiedBy, C)).
kb_rule(plan_defines_task(P, T), holds(P, soma:isPlanFor, T)).
kb_rule(has_subevent(E, S), holds(E, dul:hasConstituent, S)).
kb_rule(has_time_interval(E, I), triple(E, dul:hasTimeInterval, I)).
kb_rule(has_interval_begin(I, B), triple(I, soma:hasIntervalBegin, B)).
kb_rule(has_interval_end(I, B), triple(I, soma:hasIntervalEnd, B)).
kb_rule(event_interval(E, B, End),
        ( has_time_interval(E, I), has_interval_begin(I, B), has_interval_end(I, End) )).

%   The exported predicates are kb_call/1 of themselves (KnowRob: `is_action(A)` called
%   from Prolog is `kb_call(is_action(A))`).
triple(S, P, O) :- kb_call(triple(S, P, O)).
holds(S, P, O) :- kb_call(holds(S, P, O)).
instance_of(A, B) :- kb_call(instance_of(A, B)).
subclass_of(A, B) :- kb_call(subclass_of(A, B)).
subproperty_of(A, B) :- kb_call(subproperty_of(A, B)).
has_type(A, B) :- kb_call(has_type(A, B)).
is_action(A) :- kb_call(is_action(A)).
is_event(A) :- kb_call(is_event(A)).
is_task(A) :- kb_call(is_task(A)).
is_role(A) :- kb_call(is_role(A)).
is_agent(A) :- kb_call(is_agent(A)).
is_episode(A) :- kb_call(is_episode(A)).
is_physical_object(A) :- kb_call(is_physical_object(A)).
is_object(A) :- kb_call(is_object(A)).
is_mental_action(A) :- kb_call(is_mental_action(A)).
is_physical_task(A) :- kb_call(is_physical_task(A)).
executes_task(A, T) :- kb_call(executes_task(A, T)).
is_performed_by(A, B) :- kb_call(is_performed_by(A, B)).
has_participant(E, O) :- kb_call(has_participant(E, O)).
has_role(O, R) :- kb_call(has_role(O, R)).
task_role(T, R) :- kb_call(task_role(T, R)).
is_classified_by(E, C) :- kb_call(is_classified_by(E, C)).
plan_defines_task(P, T) :- kb_call(plan_defines_task(P, T)).
has_subevent(E, S) :- kb_call(has_subevent(E, S)).
has_time_interval(E, I) :- kb_call(has_time_interval(E, I)).
has_interval_begin(I, B) :- kb_call(has_interval_begin(I, B)).
has_interval_end(I, B) :- kb_call(has_interval_end(I, B)).
event_interval(E, B, End) :- kb_call(event_interval(E, B, End)).

%!  occurs(?Event) is nondet.
%   Event has an interval that overlaps the question scope (now, unless called as
%   `occurs(E) during [T0,T1]`, `occurs(E) since T` or `occurs(E) until T`).
occurs(E) :- kb_call(occurs(E)).

%!  during(:Goal, +Interval) is nondet.
%!  since(:Goal, +Instant) is nondet.
%!  until(:Goal, +Instant) is nondet.
%   Scope modifiers; Interval is `[Since, Until]` or an event with an interval.
during(G, I) :- kb_call(during(G, I)).
since(G, T) :- kb_call(since(G, T)).
until(G, T) :- kb_call(until(G, T)).

%!  kb_call(:Goal) is nondet.
%!  kb_call(:Goal, +Scope) is nondet.
%   Solve Goal, compiled: every run of triple goals becomes one store query. Scope is
%   `scope(Since, Until)` or `any`; kb_call/1 asks about now.
kb_call(Goal) :-
    store_scope_now(Scope),
    kb_call(Goal, Scope).
kb_call(Goal, Scope) :-
    kb_compile(Goal, Scope, compiled, Plan),
    run_plan(Plan).

%!  kb_call_stepwise(:Goal) is nondet.
%!  kb_call_stepwise(:Goal, +Scope) is nondet.
%   Solve Goal one triple goal at a time (no conjunction compilation); same solutions.
kb_call_stepwise(Goal) :-
    store_scope_now(Scope),
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
    must_be(ground, Scope),
    (   Scope == any -> true
    ;   Scope = scope(S, U), number(S), number(U) -> true
    ;   type_error(scope, Scope)
    ),
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
    ->  unfold(instance_of(A, B), Mod, Scope, S0, [call(not_named_individual(B))|S])
    ;   unfold(instance_of(A, B), Mod, Scope, S0, S)
    ).
unfold(occurs(E), Mod, Scope, S0, S) :- !,
    unfold(event_interval(E, B, End), Mod, any, S0, [call(overlaps_scope(Scope, B, End))|S]).
unfold(G, Mod, Scope, S0, S) :-
    kb_rule(G, Body), !,
    unfold(Body, Mod, Scope, S0, S).
unfold(G, Mod, _, [call(Mod:G)|S], S).

sub_plan(G, Mod, Scope, Plan) :-
    unfold(G, Mod, Scope, Steps, []),
    group(compiled, Steps, Plan).

%   A triple goal as a pattern plus the filters its value operator needs.
triple_steps(Su, P, O, Scope, [pattern(t(Su, P, X), Scope)|S0], S) :-
    value_filter(O, X, S0, S).

%   A comparison with a number known when the goal is compiled is evaluated by the store
%   (`cmp(Op, Number, Value)` as the pattern's object); other operators filter afterwards.
value_filter(O, cmp(Op, Arg, V), S, S) :-
    nonvar(O), O = (C -> V), var(V), store_comparison(C, Op, Arg), !.
value_filter(O, X, S0, S) :-
    nonvar(O), O = (Op -> V), !,
    value_filter(Op, X, S0, [call(V = X)|S]).
value_filter(O, cmp(Op, Arg, _), S, S) :-
    store_comparison(O, Op, Arg), !.
value_filter(O, X, [call(value_test(Op, Arg, X))|S], S) :-
    nonvar(O), O =.. [Op, Arg],
    memberchk(Op, [<, =<, >, >=, in, nin, regex]), !.
value_filter(O, O, S, S).

store_comparison(O, Op, Arg) :-
    nonvar(O), O =.. [Op, Arg],
    memberchk(Op, [<, =<, >, >=]), number(Arg).

%!  value_test(+Op, +Arg, +Value) is semidet.
value_test(<, A, X) :- number(X), X < A.
value_test(=<, A, X) :- number(X), X =< A.
value_test(>, A, X) :- number(X), X > A.
value_test(>=, A, X) :- number(X), X >= A.
value_test(in, L, X) :- must_be(list, L), maplist(kb_iri, L, L1), memberchk(X, L1).
value_test(nin, L, X) :- must_be(list, L), maplist(kb_iri, L, L1), \+ memberchk(X, L1).
value_test(regex, Pattern, X) :-
    atomic(X), atom_string(X, Text), text_to_string(Pattern, Re),
    pcre:re_match(Re, Text).

not_named_individual(B) :-
    B \== 'http://www.w3.org/2002/07/owl#NamedIndividual'.

overlaps_scope(any, _, _) :- !.
overlaps_scope(scope(S, U), B, End) :-
    B =< U,
    End >= S.

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
take_patterns([call(value_test(Op, A, X))|Steps], Scope, Ts, [call(value_test(Op, A, X))|Fs], Rest) :-
    !,
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

runtime_scope(during, I, any) :-
    I = [T0, T1], var(T0), var(T1), !.
runtime_scope(during, [T0, T1], scope(T0, T1)) :- !,
    must_be(number, T0), must_be(number, T1).
runtime_scope(during, E, scope(B, End)) :-
    must_be(atomic, E),
    kb_iri(E, E1),
    once(kb_call(event_interval(E1, B, End), any)).
runtime_scope(since, T, scope(T1, Now)) :-
    get_time(Now),
    ( number(T) -> T1 = T ; T1 = Now ).
runtime_scope(until, T, Scope) :-
    (   var(T) -> Scope = any ; must_be(number, T), Scope = scope(T, T) ).

expand_pattern(t(S, P, O), t(S1, P1, O1)) :-
    kb_iri(S, S1), kb_iri(P, P1), kb_iri(O, O1).

%!  kb_iri(+Term, -IRI) is det.
%   `prefix:'Local'` as the full IRI atom; anything else unchanged.
kb_iri(T, T) :- var(T), !.
kb_iri(Prefix:Local, IRI) :-
    atom(Prefix), atom(Local), !,
    rdf_global_id(Prefix:Local, IRI).
kb_iri(T, T).

iri_term(T) :- atomic(T), !.
iri_term(P:L) :- atom(P), atom(L).

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
