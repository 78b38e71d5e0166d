:- begin_tests(model_rdfs).

:- use_module(rdfs).
:- use_module('../neem_store').
:- use_module('../fixtures/test_episode').

n(L, I) :- atom_concat('http://example.org/neem#', L, I).

test(instance_of_closure, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    n(pick1, P), instance_of(P, dul:'Task'),
    subclass_of(odb:pick, dul:'Task').

test(has_type_skips_named_individual, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    n(apple1, A),
    findall(C, has_type(A, C), Cs), Cs == ['https://ontology.dlr.de/soma/odb#apple'],
    \+ has_type(A, some(x)).

:- end_tests(model_rdfs).
