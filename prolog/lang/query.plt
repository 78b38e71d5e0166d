:- begin_tests(kb_query).

:- use_module(query).
:- use_module(temporal).
:- use_module('../neem_store').
:- use_module('../model/rdfs').
:- use_module('../model/event').
:- use_module('../model/object').
:- use_module('../model/situation').
:- use_module('../fixtures/test_episode').

n(L, I) :- atom_concat('http://example.org/neem#', L, I).

test(knowrob_query_runs_unchanged, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    n(a1, A1),
    findall(T-O-B-E, kb_call(( is_action(A1), executes_task(A1, T), instance_of(T, odb:pour),
                               has_participant(A1, O), event_interval(A1, B, E) )), Rows),
    length(Rows, 2),
    forall(member(_-_-B-E, Rows), (B =:= 101, E =:= 110)).

test(compiled_equals_stepwise, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    G = ( executes_task(A, T), task_role(T, R), has_role(O, R), instance_of(O, C) ),
    findall(A-T-R-O-C, kb_call(G, any), L1),
    findall(A-T-R-O-C, kb_call_stepwise(G, any), L2),
    msort(L1, S), msort(L2, S), S \== [].

test(group_equals_findall_grouped, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    forall(member(G-K-V, [ ( executes_task(A, T), has_participant(A, O) )-(A-T)-O,
                           ( has_participant(A, O), atom(O) )-A-O ]),   % one match; match + filter
           ( kb_group(K, V, G, any, Groups),
             findall(K-V, kb_call(G, any), Pairs), msort(Pairs, Sorted),
             group_pairs_by_key(Sorted, Expected),
             assertion(Groups == Expected), Groups \== [] )).

test(findall_order_limit_in_the_store, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    G = ( executes_task(A, _), event_interval(A, B, _) ),
    kb_findall(B, G, any, [order([desc(B)]), limit(2)], Latest),
    findall(B, kb_call(G, any), All), sort(0, @>=, All, [B1, B2|_]),
    Latest == [B1, B2].

test(findall_limit_needs_one_query, [setup(load_test_episode), cleanup(store_reset),
                                     error(domain_error(single_store_query, _))]) :-
    kb_findall(A, ( executes_task(A, T), T \== x ), any, [limit(1)], _).

test(compile_one_match_per_conjunction, [nondet]) :-
    kb_compile(( is_action(A), executes_task(A, T), event_interval(A, _, _), T \== x ), any, Plan),
    Plan = [match(Ps, any), call(_)], length(Ps, 5).

test(project_and_query, [nondet, setup(store_reset), cleanup(store_reset)]) :-
    kb_project(( is_action(act), event_interval(act, 5.0, 9.0) )),
    is_action(act),
    event_interval(act, B, E), B =:= 5.0, E =:= 9.0.

test(project_needs_ground, [setup(store_reset), cleanup(store_reset), error(instantiation_error)]) :-
    kb_project(triple(_, p, o)).

test(names_with_prolog_syntax, [nondet, setup(store_reset), cleanup(store_reset)]) :-
    S = 'http://e.org/x#it''s a "test", (really) :- fail.',
    kb_project(triple(S, rdf:type, dul:'Action')),
    findall(X, is_action(X), [S]).

test(bad_scope, [error(type_error(scope, later))]) :-
    kb_call(true, later).

test(project_merges_overlapping_scopes, [nondet, setup(store_reset), cleanup(store_reset)]) :-
    kb_project(triple(s, p, o), scope(10, 20)),
    kb_project(triple(s, p, o), scope(5, 12)),
    findall(S-U, store_memory:mem_triple(s, p, o, S, U, user), L), L == [5.0-20.0],
    kb_call(triple(s, p, o), scope(6, 19)),
    kb_project(triple(s, p, o), scope(30, 40)),
    findall(S-U, store_memory:mem_triple(s, p, o, S, U, user), L2), msort(L2, [5.0-20.0, 30.0-40.0]).

test(until_narrows, [nondet, setup(store_reset), cleanup(store_reset)]) :-
    kb_project(triple(q, region, green)),
    kb_project(triple(q, region, green) until 300),
    kb_project(triple(q, region, red) since 300),
    kb_call(triple(q, region, red)),
    \+ kb_call(triple(q, region, green)),
    kb_call(triple(q, region, green) during [200, 250]),
    findall(U, store_memory:mem_triple(q, region, green, _, U, user), [300.0]).

test(project_during_event, [nondet, setup(store_reset), cleanup(store_reset)]) :-
    kb_project(event_interval(act, 10.0, 20.0)),
    kb_project(triple(obj, hasRole, r1) during act),
    kb_call(triple(obj, hasRole, r1) during act),
    \+ kb_call(triple(obj, hasRole, r1)).

test(unproject, [nondet, setup(store_reset), cleanup(store_reset)]) :-
    kb_project((triple(a, b, c), triple(a, b, d), triple(x, b, c))),
    kb_unproject(triple(a, b, _)),
    \+ kb_call(triple(a, b, _)),
    kb_call(triple(x, b, c)).

test(goal_list_and_call, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    n(a1, A1),
    findall(T, kb_call([executes_task(A1, T), call(instance_of(T, odb:pour))]), Ts),
    n(pour1, P), Ts == [P].

test(scope_dicts, [nondet, setup(store_reset), cleanup(store_reset)]) :-
    kb_project(triple(s, p, o), dict{time: dict{since: =(double(5)), until: =(double(10))}}),
    kb_call(triple(s, p, o), dict{time: dict{since: =<(double(6)), until: >=(double(9))}}, F),
    F = dict{time: dict{since: 5.0, until: 10.0}},       % the fact's scope
    \+ kb_call(triple(s, p, o), dict{time: dict{since: =<(4), until: >=(9)}}, _),
    kb_call(triple(s, p, o), dict{}, _).

test(free_interval_bound_to_fact_scope, [nondet, setup(store_reset), cleanup(store_reset)]) :-
    kb_project(triple(lea, number, n1) during [10, 34]),
    kb_call(triple(lea, number, n1) during [S, U]), [S, U] == [10.0, 34.0],
    kb_call(triple(lea, number, n1) during I), I == [10.0, 34.0],
    kb_call(triple(lea, number, n1) until E), E == 34.0,
    \+ kb_call(triple(lea, number, n1) since _),          % not true now
    kb_project(triple(lea, number, n2) since 800),
    kb_call(triple(lea, number, n2) since B), B == 800.0.

test(fact_scope_is_the_intersection, [nondet, setup(store_reset), cleanup(store_reset)]) :-
    kb_project(triple(a, p, b) during [0, 50]),
    kb_project(triple(b, p, c) during [20, 80]),
    kb_call((triple(a, p, X), triple(X, p, c)), dict{}, F),
    F == dict{time: dict{since: 20.0, until: 50.0}},
    kb_project(triple(b, p, d) during [60, 90]),
    \+ kb_call((triple(a, p, Y), triple(Y, p, d)), dict{}, _).   % never held together

test(free_event_of_during_bound_at_runtime, [nondet, setup(store_reset), cleanup(store_reset)]) :-
    kb_project((is_action(act), event_interval(act, 10.0, 20.0))),
    kb_project(triple(obj, hasRole, r1) during act),
    kb_call(( is_action(A), triple(obj, hasRole, R) during A )), A == act, R == r1.

test(options_graph, [nondet, setup(store_reset), cleanup(store_reset)]) :-
    kb_project(triple(s, p, o), dict{}, [graph(user)]),
    kb_project(triple(s, p, o2), dict{}, [graph(onto)]),
    kb_call(triple(s, p, o), dict{}, _, [graph('*')]),
    findall(O, kb_call(triple(s, p, O), dict{}, _, [graph(user)]), All), msort(All, [o, o2]),
    findall(O, kb_call(triple(s, p, O), dict{}, _, [graph(onto)]), [o2]),
    findall(O, kb_call(triple(s, p, O), dict{}, _, [graph(=(user))]), [o]),
    \+ kb_call(triple(s, p, _), dict{}, _, [graph(nothing_here)]),
    findall(O, kb_call(triple(s, p, O)), All2), msort(All2, [o, o2]).   % no filter left behind

test(options_graph_filter_undone_between_solutions, [nondet, setup(store_reset), cleanup(store_reset)]) :-
    kb_project(triple(s, p, o), dict{}, [graph(user)]),
    kb_project(triple(a, p, b), dict{}, [graph(onto)]),
    kb_project(triple(a, p, c), dict{}, [graph(onto)]),
    findall(O-N, ( kb_call(triple(a, p, O), dict{}, _, [graph(onto)]),
                   aggregate_all(count, kb_call(triple(_, p, _)), N) ), Rows),
    msort(Rows, [b-3, c-3]).

test(project_into_graph_merges_there, [nondet, setup(store_reset), cleanup(store_reset)]) :-
    kb_project(triple(s, p, o), scope(10, 20), [graph(onto)]),
    kb_project(triple(s, p, o), scope(5, 12), [graph(onto)]),
    kb_project(triple(s, p, o), scope(5, 12)),
    findall(G-S-U, store_memory:mem_triple(s, p, o, S, U, G), L),
    msort(L, [onto-5.0-20.0, user-5.0-12.0]).

test(project_graph_star, [error(domain_error(graph_to_write, '*'))]) :-
    kb_project(triple(s, p, o), dict{}, [graph('*')]).

test(unknown_graph_option_value, [error(type_error(atom, f(x)))]) :-
    kb_call(true, dict{}, _, [graph(f(x))]).

test(term_values, [nondet, setup(store_reset), cleanup(store_reset)]) :-
    kb_project(triple(lecturer, hairColor, term([255, 99, 71]))),
    kb_call(triple(lecturer, hairColor, term([255, 99, 71]))),
    kb_call(triple(lecturer, hairColor, term(X))), X == [255, 99, 71].

test(unproject_python_is_an_error, [setup(store_reset), cleanup(store_reset),
                                    error(instantiation_error)]) :-
    kb_unproject(_).

test(project_error_context, [setup(store_reset), cleanup(store_reset),
                              error(instantiation_error, project(triple(a, b, _)))]) :-
    kb_project(triple(a, b, _)).

test(call_with_context, [nondet, setup(store_reset), cleanup(store_reset)]) :-
    kb_project(triple(s, p, o), scope(10, 20)),
    kb_call(call_with_context(triple(s, p, o), [scope(dict{time: dict{since: =<(15), until: >=(15)}})])),
    \+ kb_call(call_with_context(triple(s, p, o), [scope(dict{time: dict{since: =<(25), until: >=(25)}})])).

test(ask_in_projection, [nondet, setup(store_reset), cleanup(store_reset)]) :-
    kb_project((ask(C = g), triple(e, f, C))),
    kb_call(triple(e, f, g)).

test(ask_and_scoped_unproject, [nondet, cleanup(store_reset)]) :-
    store_reset,
    kb_project(triple(e, f, g)),
    ask(triple(e, f, X)), X == g, ask(triple(e, f, g), dict{}),
    kb_unproject(triple(e, f, g), dict{}), \+ ask(triple(e, f, _)),
    kb_project(triple(e, f, h)), kb_unproject(triple(e, f, _), dict{}, [graph(user)]), \+ ask(triple(e, _, _)),
    catch(kb_unproject(triple(e, f, g), _), error(instantiation_error, _), true).

test(several_rules_are_alternatives, [nondet, cleanup(( store_reset, retractall(kb_query:kb_rule(two_ways(_), _)) ))]) :-
    store_reset,
    assertz(kb_query:kb_rule(two_ways(X), triple(X, p, a))),
    assertz(kb_query:kb_rule(two_ways(X), ( pragma(true), triple(X, q, b) ))),
    assertz(kb_query:kb_rule(two_ways(only), ( pragma(fail), triple(_, never, _) ))),
    kb_project(( triple(s1, p, a), triple(s2, q, b) )),
    findall(X, kb_call(two_ways(X)), Xs), msort(Xs, [s1, s2]),
    kb_compile(two_ways(only), any, Plan), Plan = [or(_, _)].

test(context_gives_the_question_scope, [nondet]) :-
    kb_call(context(scope(D)), scope(10, 20)),
    get_dict(time, D, T), get_dict(since, T, S), get_dict(until, T, U), S == =<(10), U == >=(20).

test(pragma_runs_when_compiled, [nondet]) :-
    kb_compile(( pragma(X = 3), triple(s, p, X) ), any, Plan),
    Plan == [match([t(s, p, 3)], any)].

:- end_tests(kb_query).
