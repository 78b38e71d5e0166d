:- begin_tests(store_write).

:- use_module(write).
:- use_module(read, [store_match/2]).
:- use_module(neem, [store_reset/0, store_use_python/1]).

% The python backend, stood in for: py_insert/2 and py_retract/2 keep the request they got
% (made at run time, see python.plt), py_match/2 answers nothing.
python_stub :-
    forall(member(Name-Reply, [py_match-"r(d,[])", py_insert-"[]", py_retract-"[]"]),
           ( Head =.. [Name, Request, Reply],
             assertz((store_python:Head :- nb_setval(store_sent, Name-Request))) )),
    store_use_python(n1).

python_unstub :-
    forall(member(Name, [py_match, py_insert, py_retract]), abolish(store_python:Name/2)),
    store_reset.

test(insert_then_match, [cleanup(store_reset)]) :-
    store_reset,
    store_insert([triple(s, p, o, 0.0, 5.0)]),
    store_match([t(s, p, X)], scope(1.0, 2.0)),
    X == o,
    \+ store_match([t(s, p, _)], scope(4.0, 6.0)).

test(insert_merges_by_union_unless_told, [cleanup(store_reset)]) :-
    store_reset,
    store_insert([triple(s, p, o, 0.0, 5.0)]),
    store_insert([triple(s, p, o, 4.0, 9.0)]),
    store_match([t(s, p, o)], scope(1.0, 8.0)),
    store_insert([triple(s, p, o, 6.0, 7.0)], intersect),
    \+ store_match([t(s, p, o)], scope(1.0, 8.0)),
    store_match([t(s, p, o)], scope(6.0, 7.0)).

test(insert_into_a_graph, [cleanup(store_reset)]) :-
    store_reset,
    store_insert([triple(s, p, o, 0.0, 5.0)], union, onto),
    findall(G, store_memory:mem_triple(s, p, o, _, _, G), [onto]).

test(insert_checks_every_triple, [error(type_error(triple, t(s, p, o)))]) :-
    store_insert([triple(s, p, o, 0.0, 1.0), t(s, p, o)]).

test(insert_checks_the_merge, [error(_)]) :-
    store_insert([], both).

test(retract_every_match, [cleanup(store_reset)]) :-
    store_reset,
    store_insert([triple(s, p, o, 0.0, 5.0), triple(s, q, o, 0.0, 5.0), triple(t, p, o, 0.0, 5.0)]),
    store_retract([t(s, _, _)]),
    \+ store_match([t(s, _, _)], any),
    store_match([t(t, p, o)], any).

test(retract_checks_its_patterns, [error(type_error(triple_pattern, s))]) :-
    store_retract([s]).

test(python_insert_request, [cleanup(python_unstub)]) :-
    python_stub,
    store_insert([triple(s, p, 'it''s', 0.0, 5.0)], intersect, g),
    nb_getval(store_sent, Sent),
    Sent == py_insert-[n1, intersect, g, [s, p, 'it''s', 0.0, 5.0]].

test(python_retract_request_free_terms_as_empty_lists, [cleanup(python_unstub)]) :-
    python_stub,
    store_retract([t(s, _, 3)]),
    nb_getval(store_sent, Sent),
    Sent == py_retract-[n1, [[s], [], [3]]].

test(python_retract_takes_no_comparison, [cleanup(python_unstub),
                                          error(domain_error(retract_value, cmp(<, 3, _)))]) :-
    python_stub,
    store_retract([t(s, p, cmp(<, 3, _))]).

:- end_tests(store_write).
