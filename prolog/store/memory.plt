:- begin_tests(store_memory).

:- use_module(memory).
:- use_module(scope, [store_in_graphs/2]).
:- use_module(neem, [store_reset/0]).

type('http://www.w3.org/1999/02/22-rdf-syntax-ns#type').
sub('http://www.w3.org/2000/01/rdf-schema#subClassOf').
subp('http://www.w3.org/2000/01/rdf-schema#subPropertyOf').

stored(S, P, O, Rows) :-
    findall(G-Since-Until, store_memory:mem_triple(S, P, O, Since, Until, G), Rows0),
    msort(Rows0, Rows).

test(assert_has_universal_scope_in_graph_user, [cleanup(store_reset)]) :-
    store_reset,
    store_assert(triple(s, p, o)),
    Inf is inf,
    stored(s, p, o, [user-0.0-Inf]).

test(assert_checks_its_triple, [error(type_error(triple, t(s, p, o)))]) :-
    store_assert(t(s, p, o)).

test(assert_checks_the_subject, [error(type_error(atom, 1))]) :-
    store_assert(triple(1, p, o)).

test(union_merges_overlapping_scopes, [cleanup(store_reset)]) :-
    store_reset,
    store_memory_insert(union, g, triple(s, p, o, 5.0, 10.0)),
    store_memory_insert(union, g, triple(s, p, o, 8.0, 20.0)),
    store_memory_insert(union, g, triple(s, p, o, 30.0, 40.0)),
    store_memory_insert(union, h, triple(s, p, o, 0.0, 1.0)),
    stored(s, p, o, [g-5.0-20.0, g-30.0-40.0, h-0.0-1.0]).

test(intersect_narrows_the_stored_scope, [cleanup(store_reset)]) :-
    store_reset,
    store_memory_insert(union, g, triple(s, p, o, 5.0, 20.0)),
    store_memory_insert(intersect, g, triple(s, p, o, 10.0, 30.0)),
    stored(s, p, o, [g-10.0-20.0]),
    store_memory_insert(intersect, g, triple(s, p, o, 40.0, 50.0)),
    stored(s, p, o, [g-10.0-20.0, g-40.0-50.0]).

test(infinite_scopes_merge, [cleanup(store_reset)]) :-
    store_reset,
    Inf is inf,
    store_memory_insert(union, g, triple(s, p, o, 0.0, Inf)),
    store_memory_insert(union, g, triple(s, p, o, 3.0, Inf)),
    stored(s, p, o, [g-0.0-Inf]).

test(retract_and_drop_graph, [cleanup(store_reset)]) :-
    store_reset,
    store_memory_insert(union, g, triple(s, p, o, 0.0, 1.0)),
    store_memory_insert(union, g, triple(s, q, o, 0.0, 1.0)),
    store_memory_insert(union, h, triple(s, q, o, 0.0, 1.0)),
    store_memory_retract(t(_, p, _)),
    stored(s, p, o, []),
    store_memory_drop_graph(g),
    stored(s, q, o, [h-0.0-1.0]).

test(match_closes_types_and_properties, [cleanup(store_reset)]) :-
    store_reset,
    type(T), sub(SC), subp(SP),
    store_assert(triple(cup, SC, container)),
    store_assert(triple(container, SC, thing)),
    store_assert(triple(has_part, SP, related_to)),
    store_assert(triple(a, T, cup)),
    store_assert(triple(a, has_part, b)),
    findall(X, store_memory_match([t(X, T, thing)], any, _), [a]),
    findall(C, store_memory_match([t(a, T, C)], any, _), [cup]),
    findall(O, store_memory_match([t(a, related_to, O)], any, _), [b]),
    \+ store_memory_match([t(a, has_part, thing)], any, _).

test(match_intersects_the_fact_scopes, [cleanup(store_reset)]) :-
    store_reset,
    store_assert(triple(a, p, b), 0.0, 10.0),
    store_assert(triple(b, p, c), 5.0, 20.0),
    store_assert(triple(c, p, d), 10.0, 20.0),
    findall(Y-FS, store_memory_match([t(a, p, X), t(X, p, Y)], any, FS), [c-scope(5.0, 10.0)]),
    \+ store_memory_match([t(a, p, _), t(_, p, _), t(_, p, d)], any, _),
    \+ store_memory_match([t(a, p, _)], scope(5.0, 12.0), _).

test(match_compares_numbers, [cleanup(store_reset)]) :-
    store_reset,
    store_assert(triple(a, weight, 2)),
    store_assert(triple(b, weight, 5)),
    store_assert(triple(c, weight, heavy)),
    findall(S-W, store_memory_match([t(S, weight, cmp(>, 3, W))], any, _), [b-5]).

test(match_reads_only_the_graphs_asked_for, [cleanup(store_reset)]) :-
    store_reset,
    store_memory_insert(union, g, triple(a, p, b, 0.0, 1.0)),
    store_memory_insert(union, h, triple(a, p, c, 0.0, 1.0)),
    findall(O, store_in_graphs([h], store_memory_match([t(a, p, O)], any, _)), [c]),
    findall(O, store_memory_match([t(a, p, O)], any, _), Os), msort(Os, [b, c]).

:- end_tests(store_memory).
