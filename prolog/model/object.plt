:- begin_tests(dul_object).

:- use_module(object).
:- use_module('../neem_store').
:- use_module('../fixtures/test_episode').

n(L, I) :- atom_concat('http://example.org/neem#', L, I).

test(has_role_direction, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    n(thermos1, O), has_role(O, R), n(pour1_role1, R).

test(no_agent_typed, [setup(load_test_episode), cleanup(store_reset)]) :-
    \+ is_agent(_).

:- end_tests(dul_object).
