:- begin_tests(soma_types).

:- use_module(soma_types).
:- use_module('../neem_store').
:- use_module('../lang/query').
:- use_module('../fixtures/owl_world').

test(types, [nondet, setup(load_owl_world), cleanup(store_reset)]) :-
    ow(s1, S), ow(a1, A),
    kb_project(( has_type(S, soma:'PhysicalState'), has_type(A, soma:'ManipulationAction'),
                 subclass_of(soma:'PhysicalState', soma:'State') )),
    is_state(S), is_physical_state(S), \+ is_social_state(S), is_manipulation_action(A), \+ is_state(A).

:- end_tests(soma_types).
