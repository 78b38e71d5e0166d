:- begin_tests(kb_holds).

:- use_module(holds).
:- use_module('../neem_store').
:- use_module('../fixtures/test_episode').

n(L, I) :- atom_concat('http://example.org/neem#', L, I).

test(holds_uses_property_closure, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    store_assert(triple('http://www.ease-crc.org/ont/SOMA.owl#isPerformedBy',
                        'http://www.w3.org/2000/01/rdf-schema#subPropertyOf',
                        'http://www.ontologydesignpatterns.org/ont/dul/DUL.owl#hasParticipant')),
    n(a1, A1), n(edan, Edan),
    holds(A1, dul:hasParticipant, Edan).

:- end_tests(kb_holds).
