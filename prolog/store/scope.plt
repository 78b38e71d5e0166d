:- begin_tests(store_scope).

:- use_module(scope).

test(now_is_a_point) :-
    get_time(T0),
    store_scope_now(scope(S, U)),
    S == U, S >= T0.

test(a_fact_needs_an_extent) :-
    store_in_scope(any, 1.0, 2.0),
    \+ store_in_scope(any, 2.0, 2.0),
    \+ store_in_scope(scope(2.0, 2.0), 2.0, 2.0).

test(the_fact_contains_the_question) :-
    Inf is inf,
    store_in_scope(scope(5.0, 8.0), 0.0, Inf),
    store_in_scope(scope(5.0, 8.0), 5.0, 8.0),
    \+ store_in_scope(scope(4.0, 8.0), 5.0, 10.0),
    \+ store_in_scope(scope(5.0, 11.0), 5.0, 10.0).

test(intersection) :-
    Inf is inf,
    store_scope_intersection(scope(0.0, Inf), 3.0, 9.0, S1), S1 == scope(3.0, 9.0),
    store_scope_intersection(scope(5.0, Inf), 0.0, Inf, S2), S2 == scope(5.0, Inf),
    \+ store_scope_intersection(scope(0.0, 3.0), 3.0, 9.0, _).

test(bad_scope, [error(type_error(scope, scope(now, 1)))]) :-
    store_check_scope(scope(now, 1)).

test(scopes) :-
    store_check_scope(any),
    store_check_scope(scope(1, 2.5)).

test(graphs_filter_only_inside_the_goal) :-
    \+ store_query_graphs(_),
    store_in_graphs([g1, g2], store_query_graphs(Gs)),
    Gs == [g1, g2],
    store_in_graphs([g1], store_in_graphs(all, \+ store_query_graphs(_))),
    \+ store_query_graphs(_).

test(the_filter_is_restored_on_retry, [nondet]) :-
    findall(G-Gs, store_in_graphs([g1], ( member(G, [a, b]), store_query_graphs(Gs) )), L),
    L == [a-[g1], b-[g1]].

test(no_graph_at_all, [error(domain_error(non_empty_graph_list, []))]) :-
    store_in_graphs([], true).

test(graphs_are_atoms, [error(type_error(_, _))]) :-
    store_in_graphs([g1, "g2"], true).

:- end_tests(store_scope).
