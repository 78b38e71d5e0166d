:- begin_tests(kb_temporal).

:- use_module(temporal).
:- use_module(triple).
:- use_module('../neem_store').
:- use_module('../model/event').
:- use_module('../fixtures/test_episode').

n(L, I) :- atom_concat('http://example.org/neem#', L, I).

test(occurs_during, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    n(a1, A1),
    findall(E, (occurs(E) during [102, 103]), Es), Es == [A1],
    \+ occurs(A1).

test(during_event, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    n(a1, A1),
    findall(X, (is_action(X) during A1), Xs), length(Xs, 7).

test(scoped_facts, [nondet, setup(store_reset), cleanup(store_reset)]) :-
    store_assert(triple(s, p, o), 10.0, 20.0),
    \+ triple(s, p, o),
    triple(s, p, o) during [12, 18],
    \+ triple(s, p, o) during [5, 18],
    triple(s, p, o) until 15,
    \+ triple(s, p, o) since 15.

:- end_tests(kb_temporal).
