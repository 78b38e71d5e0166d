:- begin_tests(plowl).

:- use_module(plowl).
:- use_module('../model/owl').
:- use_module('../model/owl_description').
:- use_module('../model/rdfs').
:- use_module('../neem_store').
:- use_module('../lang/query').
:- use_module('../fixtures/owl_world').

hp('http://www.ontologydesignpatterns.org/ont/dul/DUL.owl#hasPart').
po('http://www.ontologydesignpatterns.org/ont/dul/DUL.owl#isPartOf').

test(subclass_through_restrictions, [nondet, setup(load_owl_world), cleanup(store_reset)]) :-
    hp(HP), ow('Cup', C), ow('Container', Co), ow('Part', P), ow('Handle', H), ow('Lid', L), ow('Bottle', B),
    ow(hasLid, HL), ow('Mug', M),
    owl_subclass_of(C, Co), owl_subclass_of(C, only(HP, P)),
    owl_subclass_of(C, some(HP, H)), owl_subclass_of(C, min(HP, 1, H)), \+ owl_subclass_of(Co, some(HP, H)),
    owl_subclass_of(C, max(HL, 1, L)), \+ owl_subclass_of(C, max(HL, 0, L)),
    owl_subclass_of(B, exactly(HL, 1, L)), \+ owl_subclass_of(C, exactly(HL, 1, L)),
    owl_subclass_of(M, C).

test(property_range, [nondet, setup(load_owl_world), cleanup(store_reset)]) :-
    hp(HP), ow('Cup', C), ow('Part', P),
    findall(R, owl_property_range(C, HP, R), [P]).

test(property_cardinality, [nondet, setup(load_owl_world), cleanup(store_reset)]) :-
    hp(HP), ow('Cup', C), ow('Handle', H), ow(hasLid, HL), ow('Lid', L), ow('Bottle', B),
    owl_property_cardinality(C, HP, H, 1, inf), owl_property_cardinality(C, HL, L, 0, 1),
    owl_property_cardinality(B, HL, L, 1, 1),
    \+ owl_property_cardinality(C, HL, H, _, _).

test(individual_through_a_description, [nondet, setup(load_owl_world), cleanup(store_reset)]) :-
    ow(cup1, C1), ow(box1, Box), ow(bottle1, B1), ow('Mug', M), ow('Vessel', V), ow('Container', Co),
    owl_individual_of(C1, M, dict{}), owl_individual_of(C1, V, dict{}), owl_individual_of(B1, V, dict{}),
    \+ owl_individual_of(Box, M, dict{}), \+ owl_individual_of(Box, V, dict{}),
    owl_individual_of(Box, Co, dict{}),
    findall(X, owl_individual_of(C1, X, dict{}), Xs), memberchk(Co, Xs),
    owl_satisfied_by(M, C1, dict{}->_).

test(owl_has, [nondet, setup(load_owl_world), cleanup(store_reset)]) :-
    hp(HP), po(PO), ow(cup1, C1), ow(cup2, C2), ow(handle1, H1), ow(screw1, S1), ow(near, N), ow(plate1, P1),
    ow(grandPart, G), ow(bottle1, B1), ow(colour, Col), ow(green, Green),
    owl_has(C1, HP, S1, dict{}),                 % transitive
    owl_has(P1, N, C1, dict{}),                  % symmetric
    owl_has(H1, PO, C1, dict{}),                 % inverse
    owl_has(C2, HP, H1, dict{}),                 % same as
    owl_has(C1, G, S1, dict{}), \+ owl_has(C1, G, H1, dict{}),   % property chain
    owl_has(B1, Col, Green, dict{}),             % value restriction
    findall(X, owl_has(C1, HP, X, dict{}), Xs), msort(Xs, [H1, S1]).

test(cardinality, [nondet, setup(load_owl_world), cleanup(store_reset)]) :-
    hp(HP), ow(cup1, C1), ow('Handle', H), ow(box1, Box),
    owl_cardinality(C1, HP, H, 1, dict{}), \+ owl_cardinality(Box, _, 'http://example.org/owl#Lid', _, dict{}).

test(subproperty_through_inverses, [nondet, setup(load_owl_world), cleanup(store_reset)]) :-
    hp(HP), po(PO),
    kb_project(subproperty_of('http://example.org/owl#hasHandle', HP)),
    kb_project(triple('http://example.org/owl#handleOf', owl:inverseOf, 'http://example.org/owl#hasHandle')),
    owl_subproperty_of('http://example.org/owl#handleOf', PO).

:- end_tests(plowl).
