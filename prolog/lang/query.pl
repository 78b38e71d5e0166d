:- module(kb_query,
    [ kb_call/1,                % :Goal
      kb_call/2,                % :Goal, +Scope
      kb_call_stepwise/1,       % :Goal
      kb_call_stepwise/2,       % :Goal, +Scope
      kb_compile/3,             % +Goal, +Scope, -Plan
      kb_findall/4,             % +Template, :Goal, +Scope, -List
      kb_findall/5,             % +Template, :Goal, +Scope, +Options, -List
      kb_group/5,               % +Key, +Var, :Goal, +Scope, -Groups
      kb_call/3,                % :Goal, +QueryScope, -FactScope
      kb_call/4,                % :Goal, +QueryScope, -FactScope, +Options
      kb_project/1,             % +Statement
      kb_project/2,             % +Statement, +Scope
      kb_project/3,             % +Statement, +Scope, +Options
      kb_unproject/1,           % +Statement
      kb_unproject/2,           % +Statement, +Scope
      kb_unproject/3,           % +Statement, +Scope, +Options
      ask/1,                    % :Statement
      ask/2,                    % :Statement, +Scope
      is_callable_with/2,       % ?Backend, :Goal
      call_with/3               % +Backend, :Goal, +Options
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
(no compound class expressions; with the type free, every asserted type, owl:NamedIndividual
included, as KnowRob) and
`occurs/1` (an event whose interval overlaps the question scope). Any other goal is
called as Prolog in the caller's module.

kb_project/1 asserts statements built from the same vocabulary (see kb_project/1).
*/

:- use_module(library(error)).
:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module(library(pairs)).
:- use_module(library(yall)).
:- use_module('../neem_store', [store_match/2, store_match/3, store_match_scoped/3, store_insert/3,
                                 store_retract/1, store_in_graphs/2]).
:- use_module('../store/annotations', [store_annotation/3, store_insert_annotations/1]).
:- use_module(subgraph, [graph_filter/2]).
:- use_module(triple, [kb_iri/2, iri_term/1, triple_steps/6, unit_factor/2]).
:- use_module(scope, [current_scope/1, scope_check/1, scope_overlaps/3, runtime_scope/3,
                       scope_term/2, scope_dict/2, universal_scope/1, time_scope/3]).

:- meta_predicate
    kb_call(0), kb_call(0, +), kb_call(0, +, -), kb_call(0, +, -, +), kb_call_stepwise(0), kb_call_stepwise(0, +),
    kb_findall(?, 0, +, -), kb_findall(?, 0, +, +, -), kb_group(?, ?, 0, +, -), ask(0), ask(0, +).

%!  kb_scoped_goal(+Goal, +Scope, -Call) is semidet.
%   Goal is not made of triples but depends on the question scope (e.g. is_at/2 reads tf
%   data at the scope's time): Call answers it in Scope. Multifile.
:- multifile kb_scoped_goal/3.

%!  kb_rule(?Head, ?Body) is nondet.
%   Head is defined by Body, a conjunction of triple/3 goals, other model predicates and
%   Prolog goals (KnowRob's `?>` rules). Multifile: the model modules add their own.
:- multifile kb_rule/2.
:- dynamic kb_rule/2.                     % kb_add_rule/2 (kb_rules) adds to it at run time

%!  is_callable_with(?Backend, ?Goal) is nondet.
%!  call_with(+Backend, +Goal, +Options) is nondet.
%   KnowRob's query backends: a goal some Backend says it can answer (is_callable_with/2) is
%   answered by call_with/3 of each such backend, their solutions one after the other, where it
%   stands in the compiled goal. Dynamic and multifile: a backend adds its clauses.
:- multifile is_callable_with/2, call_with/3.
:- dynamic is_callable_with/2, call_with/3.

%!  fresh_individual(-Individual, +Class) is det.
%   How kb_project/1 names an individual whose has_type/2 statement leaves it unbound
%   (multifile: prolog/compat/neem_interface.pl names it as new_iri/2 does, which
%   neem-interface's add_participant_with_role/3 needs); without a clause, an instantiation
%   error as KnowRob 2.x raises (a known KnowRob bug).
:- multifile fresh_individual/2.
:- dynamic fresh_individual/2.

%!  kb_call(:Goal) is nondet.
%!  kb_call(:Goal, +Scope) is nondet.
%   Solve Goal, compiled: every run of triple goals becomes one store query. Scope is
%   `scope(Since, Until)` or `any`; kb_call/1 asks about now.
kb_call(Goal) :-
    current_scope(Scope),
    kb_call(Goal, Scope).
kb_call(Goal, Scope0) :-
    scope_term(Scope0, Scope),
    kb_compile(Goal, Scope, compiled, Plan),
    run_plan(Plan).

%!  kb_call(:Goal, +QueryScope, -FactScope) is nondet.
%   kb_call/2 with KnowRob's scope dictionaries: QueryScope is `dict{}` (any time) or
%   `dict{time: dict{since: =<(T0), until: >=(T1)}}` (also `scope(T0,T1)` or `any`).
%   FactScope, `dict{time: dict{since: S, until: U}}`, says when the facts of the solution
%   hold together: the intersection of the scopes of the documents matched (mongolog's
%   `v_scope`), universal for a solution that matched none.
kb_call(Goal, QScope, FScope) :-
    scope_term(QScope, Scope),
    kb_call_scoped(Goal, Scope, scope(S, U)),
    scope_dict(scope(S, U), FScope).

%!  kb_call(:Goal, +QueryScope, -FactScope, +Options) is nondet.
%   kb_call/3 with KnowRob's option `graph(G)`: the store documents of G and the graphs above
%   it (kb_subgraph). `graph(user)`, the default, and `graph('*')` read every graph;
%   `graph(=(G))` reads G alone; a graph nothing is stored in gives no solutions.
kb_call(Goal, QScope, FScope, Options) :-
    must_be(list, Options),
    option_graph(Options, user, G),
    graph_filter(G, Filter),
    store_in_graphs(Filter, kb_call(Goal, QScope, FScope)).

option_graph(Options, Default, G) :-
    (   memberchk(graph(G0), Options) -> G = G0 ; G = Default ).

%   kb_call_scoped(:Goal, +Scope, -FactScope): kb_call/2 threading the facts' scope.
kb_call_scoped(Goal, Scope, FS) :-
    kb_compile(Goal, Scope, compiled, Plan),
    universal_scope(FS0),
    run_plan_fs(Plan, FS0, FS).

%!  kb_call_stepwise(:Goal) is nondet.
%!  kb_call_stepwise(:Goal, +Scope) is nondet.
%   Solve Goal one triple goal at a time (no conjunction compilation); same solutions.
kb_call_stepwise(Goal) :-
    current_scope(Scope),
    kb_call_stepwise(Goal, Scope).
kb_call_stepwise(Goal, Scope) :-
    kb_compile(Goal, Scope, stepwise, Plan),
    run_plan(Plan).

%!  kb_findall(+Template, :Goal, +Scope, -List) is det.
%   findall/3 of kb_call/2: when Goal compiles to one store query (and filters after it),
%   the store sends back only the variables Template and the filters need, so collecting a
%   few values of many rows does not pay for the others.
kb_findall(Template, Goal, Scope, List) :-
    kb_findall(Template, Goal, Scope, [], List).

%!  kb_findall(+Template, :Goal, +Scope, +Options, -List) is det.
%   kb_findall/4 with Options for that one store query: `plan(written)` joins its patterns
%   in the order Goal names them (store_match/3), for a join SQLite would plan badly;
%   `order(Keys)` and `limit(N)` order and cut the solutions in the store (store_match/3).
%   These two need a Goal that compiles to one store query with nothing after it (a filter
%   after a limit would drop solutions the limit counted): for another Goal they raise a
%   domain error.
kb_findall(Template, Goal, Scope, Options, List) :-
    must_be(list, Options),
    kb_compile(Goal, Scope, compiled, Plan),
    include(plan_option, Options, Plans),
    (   Plan = [match(Ts, S)|Rest],
        \+ ( member(Step, Rest), Step \= call(_) ),
        ( Rest == [] ; \+ ( member(O, Plans), O \= plan(_) ) )
    ->  term_variables(Template-Rest, Keep),
        maplist(expand_pattern, Ts, Ts1),
        findall(Template, ( store_match(Ts1, S, [select(Keep)|Plans]), run_plan(Rest) ), List)
    ;   member(O, Plans), O \= plan(_)
    ->  domain_error(single_store_query, Goal)
    ;   findall(Template, run_plan(Plan), List)
    ).

plan_option(plan(written)).
plan_option(order(_)).
plan_option(limit(_)).

%!  kb_group(+Key, +Var, :Goal, +Scope, -Groups) is det.
%   Groups is the sorted list of `Key-Values`, one per distinct Key of the solutions of
%   kb_call(Goal, Scope), Values the sorted list (duplicates kept) of Var's values in them:
%   what `findall(Key-Var, ...)`, msort/2 and group_pairs_by_key/2 give. When Goal compiles
%   to one store query binding Key and Var, the store groups the rows, so each group crosses
%   once however many values it holds (a history read's imaginings with their plans).
kb_group(Key, Var, Goal, Scope, Groups) :-
    must_be(var, Var),
    kb_compile(Goal, Scope, compiled, Plan),
    (   Plan = [match(Ts, S)],
        term_variables(Ts, All),
        term_variables(Key, KeyVars),
        forall(member(V, [Var|KeyVars]), ( member(X, All), X == V )),
        \+ ( member(V, KeyVars), V == Var )
    ->  maplist(expand_pattern, Ts, Ts1),
        findall(Key-Values,
                ( store_match(Ts1, S, [select(Key-Var), group(Var, Values0)]), msort(Values0, Values) ),
                Pairs),
        keysort(Pairs, Groups)
    ;   findall(Key-Var, run_plan(Plan), Pairs),
        msort(Pairs, Sorted),
        group_pairs_by_key(Sorted, Groups)
    ).

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
unfold((A ; B), Mod, Scope, S0, S) :- !,
    branch_steps(A, Mod, Scope, SA),
    branch_steps(B, Mod, Scope, SB),
    (   SA == fail -> SB \== fail, append(SB, S, S0)      % a branch no pragma allows is left out
    ;   SB == fail -> append(SA, S, S0)
    ;   group(compiled, SA, PA), group(compiled, SB, PB),
        S0 = [or(PA, PB)|S]
    ).
unfold((C -> T), Mod, Scope, [ite(PC, PT, [call(fail)])|S], S) :- !,
    sub_plan(C, Mod, Scope, PC), sub_plan(T, Mod, Scope, PT).
unfold(\+ G, Mod, Scope, [not(P)|S], S) :- !,
    sub_plan(G, Mod, Scope, P).
unfold(true, _, _, S, S) :- !.
unfold(assign(X, V), _, _, [call(X = V)|S], S) :- !.     % mongolog's assign/2
unfold([], _, _, S, S) :- !.
unfold([G|Gs], Mod, Scope, S0, S) :- !,      % a list of goals is their conjunction
    unfold(G, Mod, Scope, S0, S1),
    unfold(Gs, Mod, Scope, S1, S).
unfold(call(G), Mod, Scope, S0, S) :- !,
    unfold(G, Mod, Scope, S0, S).
unfold(call_with_context(G, Options), Mod, _, S0, S) :- !,   % mongolog: scope(Dict) option
    must_be(list, Options),
    (   memberchk(scope(D), Options) -> true ; D = dict{} ),
    S0 = [scoped(context, Mod:G, D)|S].
unfold(holds(Q), Mod, Scope, S0, S) :- !,
    query_triple(Q, Su, P, O),
    unfold(holds(Su, P, O), Mod, Scope, S0, S).
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
unfold(holds(Su, P, O), Mod, Scope, S0, S) :-    % holds(S, P, only(C)): OWL's class descriptions
    owl_value(O, P, D), !,
    unfold(instance_of_description(Su, D), Mod, Scope, S0, S).
unfold(G, _, Scope, [call(Call)|S], S) :-      % computable triples (kb_computable), ...
    ( G = triple(_, _, _) ; G = holds(_, _, _) ),
    kb_scoped_goal(G, Scope, Call), !.
unfold(triple(Su, P, O), _, Scope, S0, S) :- !,
    triple_steps(Su, P, O, Scope, S0, S).
unfold(holds(Su, P, O), _, Scope, S0, S) :-
    unit_term(O, F, V), !,
    triple_steps(Su, P, X, Scope, S0, [call(kb_query:unit_value(F, V, X))|S]).
unfold(holds(Su, P, O), _, Scope, S0, S) :- !,
    triple_steps(Su, P, O, Scope, S0, S).
unfold(has_type(A, B), Mod, Scope, S0, S) :- !,
    (   nonvar(B), \+ iri_term(B)
    ->  S0 = [call(fail)|S]          % compound class expressions are not types
    ;   unfold(instance_of(A, B), Mod, Scope, S0, S)
    ).
unfold(occurs(E), Mod, Scope, S0, S) :- !,
    unfold(event_interval(E, B, End), Mod, any, S0, [call(kb_scope:scope_overlaps(Scope, B, End))|S]).
unfold(pragma(G), Mod, _, S, S) :- !,         % KnowRob: evaluated when the goal is compiled
    call(Mod:G).
unfold(context(Option), _, Scope, [call(kb_query:query_context(Option, Scope))|S], S) :- !.
unfold(G, Mod, Scope, S0, S) :-
    callable(G), functor(G, F, N), functor(G0, F, N),
    once(kb_rule(G0, _)), !,                      % a model predicate (no rule may fit this call)
    findall(H-B, ( copy_term(G, H), kb_rule(H, B) ), Rules),
    include(possible_rule(G, Mod, Scope), Rules, Possible),
    (   Possible == []
    ->  S0 = [call(fail)|S]
    ;   rule_branches(Possible, G, Branches),
        unfold(Branches, Mod, Scope, S0, S)
    ).
unfold(G, _, Scope, [call(Call)|S], S) :-
    kb_scoped_goal(G, Scope, Call), !.
unfold(annotation(Su, P, V), _, _, [call(kb_query:annotation_value(Su, P, V))|S], S) :- !.
unfold(G, _, _, [call(kb_query:backend_call(G))|S], S) :-
    \+ \+ is_callable_with(_, G), !.
unfold(G, Mod, _, [call(Mod:G)|S], S).

%   holds(P(S,O)): the relation P between S and O.
%   holds(prefix:'P'(S,O)) reads as Prefix:P (KnowRob marks this case blocked).
query_triple(Q, Su, P, O) :-
    must_be(callable, Q),
    (   Q = Prefix:Q1, atom(Prefix), compound(Q1), Q1 =.. [L, Su, O]
    ->  P = Prefix:L
    ;   Q =.. [P, Su, O]
    ).

%   A unit term Unit(Value) (KnowRob: `m(6.5)`, `cm(X)`): Factor converts to the SI unit the
%   store holds.
unit_term(O, F, V) :-
    compound(O), O =.. [U, V], atom(U), unit_factor(U, F).

%!  unit_value(+Factor, ?Value, +Stored) is semidet.
unit_value(F, V, X) :-
    number(X),
    from_si(F, X, V1),
    (   var(V) -> V = V1 ; abs(V - V1) =< 1.0e-9 * max(1.0, abs(V1)) ).

%   `G during I` with I a variable or `[S, U]` of two variables.
free_interval(I) :- var(I), !.
free_interval([T0, T1]) :- var(T0), var(T1).

%   A unit's factor below 1 is applied through its inverse (100 for cm), which floats
%   hold exactly: 6.5 m is 650.0 cm, not 649.9999999999999.
from_si(F, X, V) :- ( integral_inverse(F, Inv) -> V is X * Inv ; V is X / F ).
to_si(F, V, X) :- ( integral_inverse(F, Inv) -> X is V / Inv ; X is V * F ).

integral_inverse(F, Inv) :-
    F < 1, Inv0 is 1 / F, Inv is round(Inv0), abs(Inv0 - Inv) < 1.0e-6.

sub_plan(G, Mod, Scope, Plan) :-
    (   unfold(G, Mod, Scope, Steps, [])
    ->  group(compiled, Steps, Plan)
    ;   Plan = [call(fail)]             % a pragma of G failed: G has no solution
    ).

%   The steps of a branch of a disjunction, or `fail` when its pragmas rule it out.
branch_steps(G, Mod, Scope, Steps) :-
    (   unfold(G, Mod, Scope, Steps0, []), Steps0 \= [call(fail)|_]
    ->  Steps = Steps0
    ;   Steps = fail
    ).

%   A rule of several for a goal is kept when its head unifies with the goal and its pragmas
%   hold for it (KnowRob's rules dispatch on them: `pragma(\+ compound(Type))`); the rules
%   kept become a disjunction (rule_branch/3).
possible_rule(G, Mod, Scope, H-B) :-
    \+ \+ ( G = H, catch(unfold(B, Mod, Scope, _, []), _, true) ).

rule_branches([Rule], G, Branch) :- !,
    rule_branch(Rule, G, Branch).
rule_branches([Rule|Rules], G, (Branch ; Rest)) :-
    rule_branch(Rule, G, Branch),
    rule_branches(Rules, G, Rest).

%   A head more general than the goal is unified with it now (the body's patterns then hold
%   the goal's constants); another (`is_union_of(C, union_of(L))` for a free description) at
%   run time, so that the bindings it makes stay in its branch.
rule_branch(H-B, G, B) :- subsumes_term(H, G), !, H = G.
rule_branch(H-B, G, (G = H, B)).

%   holds(S, P, only(C)) and its kin (KnowRob's OWL language extension): S is an instance of
%   the class description on P.
owl_value(O, P, D) :-
    compound(O), O =.. [F|Args],
    memberchk(F/N, [only/1, some/1, value/1, min/2, max/2, exactly/2]),
    length(Args, N),
    D =.. [F, P|Args].

%   mongolog's context/1: the options of the query being answered, `scope(Dict)` its question
%   scope as KnowRob's scope dictionary.
query_context(scope(D), Scope) :- !,
    (   Scope = scope(S, U) -> time_scope(=<(S), >=(U), D) ; D = dict{} ).
query_context(Option, _) :- domain_error(query_context_option, Option).

%   A goal query backends answer: each backend that can, in turn.
backend_call(G) :-
    findall(B, is_callable_with(B, G), Bs0),
    list_to_set(Bs0, Bs),
    member(B, Bs),
    call_with(B, G, []).

%   annotation/3 inside kb_call: subject and property must be known when it runs (KnowRob's
%   instantiation error otherwise).
annotation_value(Su0, P0, V) :-
    kb_iri(Su0, Su), kb_iri(P0, P),
    (   var(Su) -> instantiation_error(annotation(Su, P, V)) ; true ),
    (   var(P) -> instantiation_error(annotation(Su, P, V)) ; true ),
    store_annotation(Su, P, V).

                 /*******************************
                 *           GROUPING           *
                 *******************************/

%   compiled: consecutive patterns under one scope become one match/2 step; the filters
%   of their value operators follow it. stepwise: one match per pattern.
group(_, [], []).
group(Mode, [once_pattern(T, Scope)|Steps], Plan) :- !,
    group(Mode, [pattern(T, Scope)|Steps], Plan).
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
take_patterns([once_pattern(T, Scope1)|Steps], Scope, [T|Ts], Fs, Rest) :-
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
    ground_tests(Ts1, Tests, Rest),
    (   Tests == [] -> true ; once(store_match(Tests, Scope)) ),  % a ground goal succeeds once (KnowRob)
    (   Rest == [] -> true ; store_match(Rest, Scope) ).
run_step(call(G)) :- call(G).
run_step(or(A, B)) :- ( run_plan(A) ; run_plan(B) ).
run_step(ite(C, T, E)) :- ( run_plan(C) -> run_plan(T) ; run_plan(E) ).
run_step(not(P)) :- \+ run_plan(P).
run_step(scoped(Kind, G, Arg)) :-
    (   free_argument(Kind, Arg)
    ->  universal_scope(FS0),
        bind_scope(Kind, G, Arg, FS0, _)
    ;   runtime_scope(Kind, Arg, Scope),
        kb_call(G, Scope)
    ).

%   The plan threading the facts' scope `scope(Since, Until)` (see kb_call/3): a match
%   intersects it with the scopes of the documents it matched; a solution whose facts never
%   held together is dropped.
run_plan_fs([], FS, FS).
run_plan_fs([Step|Steps], FS0, FS) :-
    run_step_fs(Step, FS0, FS1),
    run_plan_fs(Steps, FS1, FS).

run_step_fs(match(Ts, Scope), FS0, FS) :-
    maplist(expand_pattern, Ts, Ts1),
    ground_tests(Ts1, Tests, Rest),
    (   Tests == []
    ->  FS1 = FS0
    ;   once(store_match_scoped(Tests, Scope, FT)),
        intersect_fs(FS0, FT, FS1)
    ),
    (   Rest == []
    ->  FS = FS1
    ;   store_match_scoped(Rest, Scope, FR),
        intersect_fs(FS1, FR, FS)
    ).
run_step_fs(call(G), FS, FS) :- call(G).
run_step_fs(or(A, B), FS0, FS) :- ( run_plan_fs(A, FS0, FS) ; run_plan_fs(B, FS0, FS) ).
run_step_fs(ite(C, T, E), FS0, FS) :-
    (   run_plan_fs(C, FS0, FS1) -> run_plan_fs(T, FS1, FS) ; run_plan_fs(E, FS0, FS) ).
run_step_fs(not(P), FS, FS) :- \+ run_plan(P).
run_step_fs(scoped(Kind, G, Arg), FS0, FS) :-
    (   free_argument(Kind, Arg)
    ->  bind_scope(Kind, G, Arg, FS0, FS)
    ;   runtime_scope(Kind, Arg, Scope),
        kb_call_scoped(G, Scope, FS1),
        intersect_fs(FS0, FS1, FS)
    ).

%   ground_tests(+Patterns, -Tests, -Rest): the leading ground patterns of a compiled group
%   are tests, as goal by goal: each succeeds once however many documents match it. A store
%   query joins from its first pattern, so a ground one there would give one solution per
%   matching document (two type triples of one subject, one through the class closure); a
%   ground pattern after a variable-binding one is already a test in every store's compiler
%   (SqlCompiler.semi_joins, the Mongo pipeline's `$limit`).
ground_tests([T|Ts], [T|Tests], Rest) :-
    ground(T), !,
    ground_tests(Ts, Tests, Rest).
ground_tests(Ts, [], Ts).

%   KnowRob's free instants and intervals (decided when the step runs: an event of
%   `G during E` may be bound by an earlier goal): `G during [S,U]` (or `G during I`) asks
%   at any time and binds [S,U] to the facts' scope, `G since T` asks for facts still true
%   now and binds T to their begin, `G until T` asks at any time and binds T to their end.
free_argument(during, I) :- free_interval(I).
free_argument(since, T) :- var(T).
free_argument(until, T) :- var(T).

bind_scope(Kind, G, Arg, FS0, FS) :-
    free_question(Kind, Scope),
    kb_call_scoped(G, Scope, FS1),
    FS1 = scope(S, U),
    (   Kind == during -> Arg = [S, U]
    ;   Kind == since -> Arg = S
    ;   Arg = U
    ),
    intersect_fs(FS0, FS1, FS).

free_question(since, scope(Inf, Now)) :- !, Inf is inf, get_time(Now).
free_question(_, any).

intersect_fs(scope(S0, U0), scope(S1, U1), scope(S, U)) :-
    ( S0 >= S1 -> S = S0 ; S = S1 ),
    ( U0 =< U1 -> U = U0 ; U = U1 ),
    S =< U.

expand_pattern(t(S, P, O), t(S1, P1, O1)) :-
    kb_iri(S, S1), kb_iri(P, P1), kb_iri(O, O1).

                 /*******************************
                 *          PROJECTION          *
                 *******************************/

%!  kb_project(+Statement) is det.
%!  kb_project(+Statement, +Scope) is det.
%   Assert Statement: triple/3, holds/1,3 (unit terms `m(6.5)` are stored in the SI unit),
%   model predicates defined by triples, event_interval/3 (creates the time interval),
%   `occurs(E)`, lists and conjunctions of these, optionally scoped: `Statement during
%   [T0,T1]`, `Statement during Event` (the event's interval), `Statement since T`,
%   `Statement until T`, or Scope (`scope(T0,T1)` or a KnowRob scope dictionary). Universal
%   scope otherwise, as NEEM narrative facts are. A stored triple whose scope overlaps the
%   new one is merged with it (union of the scopes); `until`/`since` narrow a stored triple
%   instead (intersection), as KnowRob does.
kb_project(Statement) :-
    Inf is inf,
    kb_project_(Statement, 0.0, Inf).

kb_project(Statement, Scope0) :-
    scope_term(Scope0, Scope),
    (   Scope = scope(S, U) -> true ; S = 0.0, U is inf ),
    kb_project_(Statement, S, U).

%!  kb_project(+Statement, +Scope, +Options) is det.
%   kb_project/2 with KnowRob's option `graph(G)`: the statements go into named graph G
%   (default `user`, as kb_project/1,2) and merge with their copies there. `graph('*')`
%   names no graph to write to: a domain error.
kb_project(Statement, Scope0, Options) :-
    must_be(list, Options),
    option_graph(Options, user, G),
    must_be(atom, G),
    (   G == '*' -> domain_error(graph_to_write, G) ; true ),
    scope_term(Scope0, Scope),
    (   Scope = scope(S, U) -> true ; S = 0.0, U is inf ),
    kb_project_(Statement, S, U, G).

kb_project_(Statement, S, U) :-
    kb_project_(Statement, S, U, user).

kb_project_(Statement, S, U, Graph) :-
    (   narrowing(Statement) -> Merge = intersect ; Merge = union ),
    project(Statement, S, U, Items, []),
    partition([X]>>(X = annotation(_, _, _)), Items, Annotations, Triples),
    (   Annotations == [] -> true ; store_insert_annotations(Annotations) ),
    store_insert(Triples, Merge, Graph).

narrowing(_:G) :- !, narrowing(G).
narrowing(until(_, _)).
narrowing(since(_, _)).

%!  ask(:Statement) is nondet.
%!  ask(:Statement, +Scope) is nondet.
%   KnowRob's deprecated names of kb_call/1 and kb_call/2.
ask(Statement) :- kb_call(Statement).
ask(Statement, Scope) :- kb_call(Statement, Scope).

%!  kb_unproject(+Statement, +Scope) is det.
%!  kb_unproject(+Statement, +Scope, +Options) is det.
%   kb_unproject/1 with KnowRob's scope and options: Scope must be a scope (checked), and the
%   matching documents are deleted whatever their scopes; `graph(G)` is accepted.
kb_unproject(Statement, Scope) :-
    scope_term(Scope, _),
    kb_unproject(Statement).
kb_unproject(Statement, Scope, Options) :-
    must_be(list, Options),
    kb_unproject(Statement, Scope).

%!  kb_unproject(+Statement) is det.
%   Delete the triples Statement stands for (triple/3, holds/3, model predicates defined by
%   triples, conjunctions); unbound arguments match anything.
kb_unproject(Statement) :-
    unproject(Statement, Patterns, []),
    store_retract(Patterns).

unproject(V, _, _) :-
    var(V), !, instantiation_error(V).
unproject(_:G, T0, T) :- !, unproject(G, T0, T).
unproject((A, B), T0, T) :- !, unproject(A, T0, T1), unproject(B, T1, T).
unproject(triple(S, P, O), [t(S1, P1, O1)|T], T) :- !,
    kb_iri(S, S1), kb_iri(P, P1),
    (   var(O) -> O1 = O ; value_atomic(O, O1) ).
unproject(holds(S, P, O), T0, T) :- !, unproject(triple(S, P, O), T0, T).
unproject(pragma(G), T, T) :- !, call(G).
unproject(has_type(A, B), T0, T) :- !, unproject(triple(A, rdf:type, B), T0, T).
unproject(G, T0, T) :-
    kb_rule(G, Body), !,
    unproject(Body, T0, T).
unproject(G, _, _) :-
    domain_error(unprojectable_statement, G).

project(V, _, _, _, _) :-
    var(V), !, instantiation_error(V).
project(_:G, S, U, T0, T) :- !,
    project(G, S, U, T0, T).
project((A, B), S, U, T0, T) :- !,
    project(A, S, U, T0, T1),
    project(B, S, U, T1, T).
project([], _, _, T, T) :- !.
project(true, _, _, T, T) :- !.
project(ask(G), _, _, T, T) :- !,          % KnowRob's deprecated alias of kb_call/1
    once(kb_call(G)).
project(pragma(G), _, _, T, T) :- !,
    call(G).
project([G|Gs], S, U, T0, T) :- !,
    project(G, S, U, T0, T1),
    project(Gs, S, U, T1, T).
project(during(G, I), _, _, T0, T) :- !,
    (   nonvar(I), I = [S, U]
    ->  must_be(number, S), must_be(number, U)
    ;   runtime_scope(during, I, scope(S, U))
    ),
    project(G, S, U, T0, T).
project(since(G, S), _, _, T0, T) :- !,
    must_be(number, S), Inf is inf,
    project(G, S, Inf, T0, T).
project(until(G, U), _, _, T0, T) :- !,
    must_be(number, U),
    project(G, 0.0, U, T0, T).
project(triple(S, P, O), Since0, Until0, [triple(S1, P1, O1, Since, Until)|T], T) :- !,
    (   ground(triple(S, P, O)) -> true
    ;   throw(error(instantiation_error, project(triple(S, P, O))))   % KnowRob's context
    ),
    to_float(Since0, Since), to_float(Until0, Until),    % scopes are doubles, as in KnowRob
    kb_iri(S, S1), kb_iri(P, P1), value_atomic(O, O1),
    must_be(atom, S1), must_be(atom, P1), must_be(atomic, O1).
project(holds(Q), Since, Until, T0, T) :- !,
    query_triple(Q, S, P, O),
    project(holds(S, P, O), Since, Until, T0, T).
project(holds(S, P, O), Since, Until, T0, T) :- !,
    (   unit_term(O, F, V)
    ->  must_be(number, V), to_si(F, V, X)
    ;   X = O
    ),
    project(triple(S, P, X), Since, Until, T0, T).
project(annotation(Su, P, V), _, _, [annotation(Su1, P1, V)|T], T) :- !,
    (   ground(annotation(Su, P, V)) -> true
    ;   throw(error(instantiation_error, project(annotation(Su, P, V))))   % KnowRob's context
    ),
    kb_iri(Su, Su1), kb_iri(P, P1),
    must_be(atom, Su1), must_be(atom, P1).
project(has_type(A, B), Since, Until, T0, T) :- !,
    (   var(A), clause(fresh_individual(_, _), _) -> fresh_individual(A, B) ; true ),
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
    kb_projection(G, G1), !,
    project(G1, S, U, T0, T).
project(G, S, U, T0, T) :-
    kb_rule(G, Body), !,
    project(Body, S, U, T0, T).
project(G, _, _, _, _) :-
    domain_error(projectable_statement, G).

to_float(X, F) :- float(X), !, F = X.       % `is float(inf)` overflows
to_float(X, F) :- must_be(number, X), F is float(X).

%   `term(T)` values are stored as their text (KnowRob's term/1), other values as they are.
value_atomic(term(T), A) :- !, must_be(ground, T), term_to_atom(T, A).
value_atomic(O, X) :-                       % KnowRob's typed values: double(V), int(V), ...
    compound(O), O =.. [Type, V], memberchk(Type, [double, float, number, int, integer, long, short, byte]), !,
    (   V == 'Infinity' -> X is inf ; V == '-Infinity' -> X is -inf ; must_be(number, V), X = V ).
value_atomic(O, O1) :- kb_iri(O, O1).

%!  kb_projection(?Statement, ?Expanded) is nondet.
%   Statement is projected as Expanded (multifile: for model predicates whose projection is
%   not their query rule, e.g. rdf_list/2).
:- multifile kb_projection/2.
