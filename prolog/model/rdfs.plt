:- begin_tests(model_rdfs).

:- use_module(rdfs).
:- use_module('../lang/query').
:- use_module('../neem_store').
:- use_module('../fixtures/test_episode').

n(L, I) :- atom_concat('http://example.org/neem#', L, I).

test(instance_of_closure, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    n(pick1, P), instance_of(P, dul:'Task'),
    subclass_of(odb:pick, dul:'Task').

test(has_type_names_every_asserted_type, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    n(apple1, A),                                 % owl:NamedIndividual too, as KnowRob's
    findall(C, has_type(A, C), Cs0), msort(Cs0, Cs),
    Cs == ['http://www.w3.org/2002/07/owl#NamedIndividual', 'https://ontology.dlr.de/soma/odb#apple'],
    \+ has_type(A, some(x)).

test(resource_and_property, [nondet, setup(store_reset), cleanup(store_reset)]) :-
    kb_project((has_type(adult, rdfs:'Resource'), has_type(hasNumber, rdf:'Property'))),
    is_resource(adult), \+ is_resource(hasNumber),
    is_property(hasNumber), \+ is_property(adult), \+ is_property(nothing).

test(rdf_list_round_trip, [nondet, setup(store_reset), cleanup(store_reset)]) :-
    kb_project(rdf_list(chain, [hasParent, hasAncestor])),
    rdf_list(chain, L), L == [hasParent, hasAncestor],
    rdf_list(chain, [hasParent, hasAncestor]),
    \+ rdf_list(chain, [hasAncestor, hasParent]),
    rdf_list(Head, [hasParent, hasAncestor]), Head == chain.

test(new_iri, [nondet, setup(store_reset), cleanup(store_reset)]) :-
    new_iri(I, dul:'Action'), atom(I),
    sub_atom(I, 0, _, _, 'http://www.ontologydesignpatterns.org/ont/dul/DUL.owl#Action_'),
    new_iri(J), I \== J.

test(literal_datatype_is_a, [nondet, cleanup(store_reset)]) :-
    store_reset,
    kb_project(( has_type(x, rdfs:'Literal'), has_type(d, rdfs:'Datatype'), has_type(c, owl:'Class'),
                 subclass_of(c, k), has_type(i, c) )),
    is_literal(x), \+ is_literal(d), is_datatype(d),
    is_a(c, k), \+ is_a(c, c2), is_a(i, c), is_a(i, k), \+ is_a(i, i).

test(unique_names, [cleanup(store_reset)]) :-
    store_reset,
    kb_project(triple(taken, p, o)),
    \+ is_unique_name(taken), is_unique_name(free),
    get_unique_name(dul:'Action', N), sub_atom(N, 0, _, 8, 'http://www.ontologydesignpatterns.org/ont/dul/DUL.owl#Action_'),
    is_unique_name(N).

:- end_tests(model_rdfs).
