:- begin_tests(kb_holds).

:- use_module(holds).
:- use_module(query).
:- use_module(triple).
:- use_module('../neem_store').
:- use_module('../fixtures/test_episode').

n(L, I) :- atom_concat('http://example.org/neem#', L, I).

test(holds_uses_property_closure, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    store_assert(triple('http://www.ease-crc.org/ont/SOMA.owl#isPerformedBy',
                        'http://www.w3.org/2000/01/rdf-schema#subPropertyOf',
                        'http://www.ontologydesignpatterns.org/ont/dul/DUL.owl#hasParticipant')),
    n(a1, A1), n(edan, Edan),
    holds(A1, dul:hasParticipant, Edan).

test(holds_query_term, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    n(a1, A1), n(pour1, T),
    kb_iri(dul:executesTask, P),
    Q =.. [P, A1, X], holds(Q), X == T.

test(unit_terms, [nondet, setup(store_reset), cleanup(store_reset)]) :-
    kb_project(holds(lea, height, m(6.5))),
    holds(lea, height, cm(650)), holds(lea, height, cm(650.0)),
    \+ holds(lea, height, cm(750.0)),
    holds(lea, height, cm(X)), abs(X - 650.0) < 1.0e-9,
    holds(lea, height, mm(Y)), abs(Y - 6500.0) < 1.0e-6,
    triple(lea, height, V), V =:= 6.5.

test(project_holds, [nondet, setup(store_reset), cleanup(store_reset)]) :-
    \+ holds(lea, hasNumber, '+49'),
    kb_project(holds(lea, hasNumber, '+49')),
    holds(lea, hasNumber, '+49').

:- end_tests(kb_holds).
