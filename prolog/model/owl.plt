:- begin_tests(model_owl).

:- use_module(owl).
:- use_module(owl_description).
:- use_module(rdfs).
:- use_module('../neem_store').
:- use_module('../lang/query').
:- use_module('../fixtures/owl_world').

test(classes_and_properties, [nondet, setup(load_owl_world), cleanup(store_reset)]) :-
    ow('Cup', Cup), ow(cup1, C1), ow(hasLid, L), ow(near, N), ow(weight, W),
    is_class(Cup), is_class('http://www.w3.org/2002/07/owl#Thing'), \+ is_class(C1),
    is_individual(C1), \+ is_individual(Cup),
    is_object_property(L), \+ is_object_property(W), is_data_property(W),
    is_functional_property(L), is_symmetric_property(N), \+ is_transitive_property(N),
    is_transitive_property('http://www.ontologydesignpatterns.org/ont/dul/DUL.owl#hasPart').

test(inverse_and_chain, [nondet, setup(load_owl_world), cleanup(store_reset)]) :-
    HP = 'http://www.ontologydesignpatterns.org/ont/dul/DUL.owl#hasPart',
    PO = 'http://www.ontologydesignpatterns.org/ont/dul/DUL.owl#isPartOf',
    has_inverse_property(HP, PO), has_inverse_property(PO, HP),
    ow(grandPart, G), has_property_chain(G, Chain), Chain == [HP, HP],
    has_property_chain(G2, [HP, HP]), G2 == G.

test(equivalence_and_identity, [nondet, setup(load_owl_world), cleanup(store_reset)]) :-
    ow('Mug', M), ow(i1, I), ow(cup1, C1), ow(cup2, C2),
    has_equivalent_class(M, X), X == I, has_equivalent_class(I, M),
    \+ has_equivalent_class(_, _),
    same_as(C1, C1), same_as(C2, C1), same_as(C1, C2).

test(disjoint, [nondet, setup(load_owl_world), cleanup(store_reset)]) :-
    ow('Bottle', B), ow('Cup', C), ow('Handle', H), ow('Lid', L),
    disjoint_with_direct(B, C), disjoint_with_direct(C, B), disjoint_with_direct(H, L),
    \+ disjoint_with_direct(B, H),
    findall(X, disjoint_with_direct(C, X), [B]).
test(disjoint_through_superclasses, [nondet, setup(load_owl_world), cleanup(store_reset)]) :-
    ow('Bottle', B), ow(i1, I),
    kb_project(subclass_of(I, 'http://example.org/owl#Cup')),
    disjoint_with(I, B), \+ disjoint_with_direct(I, B).

:- end_tests(model_owl).
