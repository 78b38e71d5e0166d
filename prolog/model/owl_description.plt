:- begin_tests(model_owl_description).

:- use_module(owl_description).
:- use_module(rdfs).
:- use_module('../neem_store').
:- use_module('../lang/query').
:- use_module('../lang/holds').
:- use_module('../fixtures/owl_world').

hp('http://www.ontologydesignpatterns.org/ont/dul/DUL.owl#hasPart').

test(terms) :-
    is_owl_term(only(p, c)), is_owl_term(union_of([a])), is_restriction_term(min(p, 1, c)),
    \+ is_restriction_term(union_of([a])), \+ is_owl_term(_), \+ is_owl_term(foo(a)).

test(restrictions, [nondet, setup(load_owl_world), cleanup(store_reset)]) :-
    hp(HP), ow(r1, R1), ow(r3, R3), ow('Part', Part), ow('Lid', Lid), ow(hasLid, L), ow(r5, R5),
    is_restriction(R1, only(HP, Part)), is_restriction(R3, max(L, 1, Lid)),
    is_restriction(R5, value(_, V)), V == 'http://example.org/owl#green',
    findall(D, is_restriction(_, D), Ds), length(Ds, 6),
    is_restriction(R, some(HP, _)), R == 'http://example.org/owl#r2'.

test(union_intersection_complement, [nondet, setup(load_owl_world), cleanup(store_reset)]) :-
    ow('Vessel', V), ow(i1, I), ow('Cup', C), ow('Bottle', B), ow(r2, R2), ow('NotCup', N),
    is_union_of(V, union_of(L)), L == [C, B],
    is_union_of(V2, union_of([C, B])), V2 == V,
    is_intersection_of(I, intersection_of([C, R2])),
    is_complement_of(N, complement_of(C)),
    has_description(R2, some(_, _)), has_description(V, union_of(_)), \+ has_description(C, _),
    \+ has_description(_, _).

test(subclass_of_a_description, [nondet, setup(load_owl_world), cleanup(store_reset)]) :-
    hp(HP), ow('Cup', C), ow('Container', Co), ow('Part', P), ow('Handle', H), ow('Bottle', B),
    subclass_of(C, only(HP, P)), subclass_of(Co, only(HP, P)), subclass_of(C, some(HP, H)),
    \+ subclass_of(B, some(HP, H)),
    findall(X, subclass_of(X, some(HP, H)), [C]).

test(one_store_query, [nondet, setup(load_owl_world), cleanup(store_reset)]) :-
    hp(HP), ow('Cup', C),
    kb_compile(subclass_of(C, only(HP, _)), any, Plan),
    Plan = [match(Patterns, any)], length(Patterns, 3).

test(instance_of_a_description, [nondet, setup(load_owl_world), cleanup(store_reset)]) :-
    hp(HP), ow(cup1, C1), ow(box1, Box), ow('Handle', H), ow('Part', P), ow('Cup', C), ow('Bottle', B),
    ow(bottle1, B1),
    instance_of(C1, some(HP, H)), \+ instance_of(Box, some(HP, H)), instance_of(Box, only(HP, P)),
    instance_of(C1, union_of([B, C])), \+ instance_of(C1, intersection_of([B, C])),
    instance_of_description(B1, union_of([B, C])),
    holds(C1, HP, some(H)), holds(Box, HP, only(P)), \+ holds(Box, HP, some(H)).

:- end_tests(model_owl_description).
