:- begin_tests(odb_names).

:- use_module(names).
:- use_module('../neem_store').
:- use_module('../fixtures/test_episode').

n(L, I) :- atom_concat('http://example.org/neem#', L, I).

test(odb_iri_both_ways) :-
    odb_iri(pick, I), I == 'https://ontology.dlr.de/soma/odb#pick',
    odb_iri(L, I), L == pick.

test(call_classes) :-
    call_classes(pour(thermos, green_mug), T, Os),
    odb_iri(pour, T), maplist(odb_iri, [thermos, green_mug], Os).

:- end_tests(odb_names).
