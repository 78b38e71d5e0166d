:- begin_tests(dul_object).

:- use_module(object).
:- use_module('../lang/query').
:- use_module('../lang/temporal').
:- use_module('../neem_store').
:- use_module('../fixtures/test_episode').

n(L, I) :- atom_concat('http://example.org/neem#', L, I).

test(has_role_direction, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    n(thermos1, O), has_role(O, R), n(pour1_role1, R).

test(no_agent_typed, [setup(load_test_episode), cleanup(store_reset)]) :-
    \+ is_agent(_).

test(region_transition, [nondet, setup(store_reset), cleanup(store_reset)]) :-
    kb_project(has_region(colour, green) until 300),
    kb_project(has_region(colour, red) since 300),
    has_region(colour, red), \+ has_region(colour, green),
    kb_call(has_region(colour, green) during [200, 250]).

:- end_tests(dul_object).
