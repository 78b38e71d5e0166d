:- begin_tests(kb_mongolog).

:- use_module(mongolog).
:- use_module('../neem_store').
:- use_module('../model/rdfs').

test(call, [nondet, setup(store_assert(triple(a, b, c))), cleanup(store_reset)]) :-
    mongolog_call(triple(a, b, X)), X == c,
    mongolog_call(triple(a, b, c), [scope(any)]).

test(predicates) :-
    is_mongolog_predicate(triple/3), is_mongolog_predicate(instance_of/2), is_mongolog_predicate(holds(_, _, _)),
    \+ is_mongolog_predicate(append/3).

:- end_tests(kb_mongolog).
