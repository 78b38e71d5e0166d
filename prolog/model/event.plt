:- begin_tests(dul_event).

:- use_module(event).
:- use_module('../neem_store').
:- use_module('../fixtures/test_episode').

n(L, I) :- atom_concat('http://example.org/neem#', L, I).

test(is_action_uses_class_closure, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    findall(A, is_action(A), As), length(As, 7),
    n(a1, A1), memberchk(A1, As).

test(has_participant_includes_performed_by, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    store_assert(triple('http://www.ease-crc.org/ont/SOMA.owl#isPerformedBy',
                        'http://www.w3.org/2000/01/rdf-schema#subPropertyOf',
                        'http://www.ontologydesignpatterns.org/ont/dul/DUL.owl#hasParticipant')),
    n(a1, A1), n(edan, Edan),
    has_participant(A1, Edan), is_performed_by(A1, Edan).

test(event_interval, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    n(a3, A3), event_interval(A3, B, E), B =:= 201, E =:= 205.

test(has_participant_class, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    n(a1, A1), n(thermos1, Th),
    findall(O-C, has_participant(A1, O, C), Rows),
    memberchk(Th-'https://ontology.dlr.de/soma/odb#thermos', Rows),
    has_participant(A1, Th, odb:thermos).

:- end_tests(dul_event).
