:- begin_tests(soma_object).

:- use_module(soma_object).
:- use_module(object).
:- use_module(dul_object_types).
:- use_module(owl_description).
:- use_module('../neem_store').
:- use_module('../lang/query').
:- use_module('../fixtures/owl_world').

test(roles, [nondet, setup(load_owl_world), cleanup(store_reset)]) :-
    ow(cup1, C), ow(box1, B),
    is_patient(C), \+ is_patient(B), \+ is_instrument(C).

test(dispositions, [nondet, setup(load_owl_world), cleanup(store_reset)]) :-
    ow(cup1, C), ow(disp1, D), ow('Containment', T),
    has_disposition(C, D), has_disposition_type(C, D, T).

test(trigger_type, [nondet, setup(load_owl_world), cleanup(store_reset)]) :-
    ow(disp1, D), ow(trigger, Tr), ow(r7, R7), ow(r8, R8), ow('Cup', Cup),
    kb_project(( subclass_of('http://example.org/owl#Containment', R7),
                 triple(R7, owl:onProperty, soma:affordsTrigger), triple(R7, owl:allValuesFrom, Tr),
                 subclass_of(Tr, R8), triple(R8, owl:onProperty, dul:classifies), triple(R8, owl:allValuesFrom, Cup) )),
    disposition_trigger_type(D, X), X == Cup.

:- end_tests(soma_object).
