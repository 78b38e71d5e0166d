:- begin_tests(store_graph).

:- use_module(graph).
:- use_module(memory, [store_memory_insert/3, store_memory_match/3]).
:- use_module(neem, [store_reset/0, store_use_python/1]).

% The python backend, stood in for: py_graph/2 keeps the request it got and answers Reply
% (made at run time, see python.plt).
python_stub(Reply) :-
    Graph =.. [py_graph, Request, Reply],
    assertz((store_python:Graph :- nb_setval(store_sent, Request))),
    Match =.. [py_match, _, "r(d,[])"],
    assertz(store_python:Match),
    store_use_python(n1).

python_unstub :-
    abolish(store_python:py_graph/2),
    abolish(store_python:py_match/2),
    store_reset.

test(version_of_a_graph, [cleanup(store_reset)]) :-
    store_reset,
    \+ store_graph_version(soma, _),
    store_set_graph_version('http://e.org/soma', '1.2', soma),
    store_graph_version(soma, V), V == '1.2',
    \+ store_graph_version(dul, _).

test(drop_takes_the_graphs_triples_and_version, [cleanup(store_reset)]) :-
    store_reset,
    store_set_graph_version(o, 1, soma),
    store_memory_insert(union, soma, triple(a, p, b, 0.0, 1.0)),
    store_memory_insert(union, user, triple(a, p, c, 0.0, 1.0)),
    store_drop_graph(soma),
    \+ store_graph_version(soma, _),
    findall(O, store_memory_match([t(a, p, O)], any, _), [c]).

test(graph_is_an_atom, [error(type_error(atom, "soma"))]) :-
    store_drop_graph("soma").

test(python_version_read, [cleanup(python_unstub)]) :-
    python_stub("[['http://e.org/soma', '1.2']]"),
    store_graph_version(soma, V),
    V == '1.2',
    nb_getval(store_sent, [n1, get, soma, '', '']).

test(python_no_version, [cleanup(python_unstub)]) :-
    python_stub("[]"),
    \+ store_graph_version(soma, _).

test(python_set_and_drop, [cleanup(python_unstub)]) :-
    python_stub("[]"),
    store_set_graph_version(o, 3, soma),
    nb_getval(store_sent, [n1, set, soma, o, 3]),
    store_drop_graph(soma),
    nb_getval(store_sent, [n1, drop, soma, '', '']).

:- end_tests(store_graph).
