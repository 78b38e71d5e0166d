:- begin_tests(kb_computable).

:- use_module(computable).
:- use_module(query).
:- use_module('../neem_store').

double(X, Y) :- Y is 2 * X.
distance_to(S, D) :- atom_length(S, D).

test(predicate, [nondet, setup(store_assert(triple(a, size, 3))), cleanup(( store_reset, drop_computable_predicate(plunit_kb_computable) ))]) :-
    add_computable_predicate(twice/2, plunit_kb_computable:double),
    kb_call(( triple(a, size, N), twice(N, M) )), M == 6,
    drop_computable_predicate(plunit_kb_computable, twice/2),
    \+ catch(kb_call(twice(1, _)), error(existence_error(_, _), _), fail).

test(property, [nondet, cleanup(drop_computable_property(plunit_kb_computable))]) :-
    add_computable_property('http://my#length', plunit_kb_computable:distance_to),
    kb_call(triple(abcd, 'http://my#length', L)), L == 4,
    kb_call(holds(ab, 'http://my#length', 2)).

test(declarations, [nondet, cleanup(drop_computable_predicate(plunit_kb_computable))]) :-
    computables(plunit_kb_computable:(double(2, [functor(doubled)]))),
    kb_call(doubled(4, X)), X == 8.

:- end_tests(kb_computable).
