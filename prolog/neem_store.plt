:- begin_tests(neem_store).

:- use_module(neem_store).
:- use_module(store/graph).
:- use_module(store/annotations).
:- use_module(store/tf).

ex(Local, IRI) :- atom_concat('http://example.org/t#', Local, IRI).
type(IRI) :- IRI = 'http://www.w3.org/1999/02/22-rdf-syntax-ns#type'.
sub(IRI) :- IRI = 'http://www.w3.org/2000/01/rdf-schema#subClassOf'.
subp(IRI) :- IRI = 'http://www.w3.org/2000/01/rdf-schema#subPropertyOf'.

setup :-
    store_reset,
    type(T), sub(SC), subp(SP),
    maplist(ex, [a, b, 'Cup', 'Container', 'Thing', hasPart, relatedTo, 'it''s (odd)'],
            [A, B, Cup, Container, Thing, HasPart, Related, Odd]),
    store_assert(triple(Cup, SC, Container)),
    store_assert(triple(Container, SC, Thing)),
    store_assert(triple(HasPart, SP, Related)),
    store_assert(triple(A, T, Cup)),
    store_assert(triple(B, T, Container)),
    store_assert(triple(A, HasPart, B)),
    store_assert(triple(Odd, T, Cup)),
    store_assert(triple(A, HasPart, Odd), 10.0, 20.0).

test(type_closure, [setup(setup), cleanup(store_reset)]) :-
    maplist(ex, [a, b, 'Thing', 'it''s (odd)'], [A, B, Thing, Odd]),
    type(T),
    findall(X, store_match([t(X, T, Thing)], any), Xs),
    msort(Xs, Sorted), msort([A, B, Odd], Sorted).

test(free_object_binds_asserted_type, [setup(setup), cleanup(store_reset)]) :-
    maplist(ex, [a, 'Cup'], [A, Cup]), type(T),
    findall(C, store_match([t(A, T, C)], any), Cs),
    Cs == [Cup].

test(property_closure, [setup(setup), cleanup(store_reset)]) :-
    maplist(ex, [a, b, relatedTo, 'it''s (odd)'], [A, B, Related, Odd]),
    findall(O, store_match([t(A, Related, O)], any), Os),
    msort(Os, Sorted), msort([B, Odd], Sorted).

test(scope_containment, [setup(setup), cleanup(store_reset)]) :-
    maplist(ex, [a, hasPart, 'it''s (odd)'], [A, HasPart, Odd]),
    store_match([t(A, HasPart, Odd)], scope(12.0, 18.0)),
    \+ store_match([t(A, HasPart, Odd)], scope(5.0, 18.0)),
    \+ store_match([t(A, HasPart, Odd)], scope(30.0, 30.0)).

test(no_extent_no_fact, [setup(setup), cleanup(store_reset)]) :-
    % KnowRob drops a fact whose scope has no extent (since < until fails), whatever the
    % question scope, and a conjunction whose facts' scopes do not share one.
    maplist(ex, [c, d, e, hasPart], [C, D, E, HasPart]),
    store_assert(triple(C, HasPart, D), 5.0, 5.0),
    store_assert(triple(D, HasPart, E), 1.0, 5.0),
    store_assert(triple(E, HasPart, C), 5.0, 9.0),
    \+ store_match([t(C, HasPart, _)], any),
    \+ store_match([t(C, HasPart, _)], scope(5.0, 5.0)),
    store_match([t(D, HasPart, E)], scope(2.0, 3.0)),
    \+ store_match([t(D, HasPart, E), t(E, HasPart, C)], any),
    \+ store_match_scoped([t(D, HasPart, E), t(E, HasPart, C)], any, _).

test(conjunction_join, [setup(setup), cleanup(store_reset)]) :-
    maplist(ex, [a, b, hasPart, 'Container'], [A, B, HasPart, Container]), type(T),
    findall(X-Y, store_match([t(X, HasPart, Y), t(Y, T, Container)], scope(100.0, 100.0)), Ps),
    Ps == [A-B].

test(limit, [setup(setup), cleanup(store_reset)]) :-
    ex('Thing', Thing), type(T),
    findall(X, store_match([t(X, T, Thing)], any, [limit(1)]), Xs),
    length(Xs, 1).

test(group_collects_the_values_of_each_key, [setup(setup), cleanup(store_reset)]) :-
    maplist(ex, [a, b, hasPart, 'Cup', 'it''s (odd)'], [A, B, HasPart, Cup, Odd]), type(T),
    findall(X-Ys, store_match([t(X, HasPart, Y)], any, [select(X-Y), group(Y, Ys)]), Groups),
    Groups = [A-Ys], msort(Ys, [B, Odd]),
    findall(C-Xs, store_match([t(X, T, C)], any, [select(C-X), group(X, Xs)]), Groups2),
    memberchk(Cup-Cs, Groups2), msort(Cs, [A, Odd]).

test(group_variable_must_be_selected, [setup(setup), cleanup(store_reset),
                                       error(domain_error(selected_variable, _))]) :-
    type(T),
    store_match([t(X, T, C)], any, [select(X), group(C, _)]).

test(group_takes_no_limit, [setup(setup), cleanup(store_reset),
                            error(domain_error(group_without_limit_or_order, _))]) :-
    type(T),
    store_match([t(X, T, C)], any, [select(X-C), group(C, _), limit(1)]).

test(bad_pattern, [error(type_error(atomic_or_var, f(x)))]) :-
    store_match([t(f(x), _, _)], any).

test(bad_scope, [error(type_error(scope, now))]) :-
    store_match([t(_, _, _)], now).

test(insert_memory, [cleanup(store_reset)]) :-
    store_reset,
    store_insert([triple(s, p, o, 0.0, 5.0)]),
    store_match([t(s, p, X)], scope(1.0, 2.0)),
    X == o.

test(facade_exports_the_store_api) :-
    module_property(neem_store, exports(Exports)),
    length(Exports, 19),
    forall(member(N/A, Exports),
           ( functor(H, N, A),
             predicate_property(neem_store:H, imported_from(Home)),
             sub_atom(Home, 0, _, _, store_) )).

test(reset_forgets_every_memory_fact) :-
    store_reset,
    store_assert(triple(s, p, o)),
    store_insert_annotations([annotation(s, label, 'S')]),
    store_assert_pose(s, 1.0, [map, [0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 1.0]]),
    store_set_graph_version(onto, '1.0', g),
    store_reset,
    \+ store_match([t(_, _, _)], any),
    \+ store_annotation(_, _, _),
    \+ store_pose(s, any, _, _),
    \+ store_graph_version(g, _),
    store_backend(memory).

:- end_tests(neem_store).
