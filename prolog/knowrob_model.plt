:- begin_tests(knowrob_model).

:- use_module(knowrob_model).
:- use_module(neem_store).
:- use_module(test_episode).

n(L, I) :- atom_concat('http://example.org/neem#', L, I).

test(is_action_uses_class_closure, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    findall(A, is_action(A), As), length(As, 7),
    n(a1, A1), memberchk(A1, As).

test(knowrob_query_runs_unchanged, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    n(a1, A1),
    findall(T-O-B-E, kb_call(( is_action(A1), executes_task(A1, T), instance_of(T, odb:pour),
                               has_participant(A1, O), event_interval(A1, B, E) )), Rows),
    length(Rows, 2),
    forall(member(_-_-B-E, Rows), (B =:= 101, E =:= 110)).

test(has_participant_includes_performed_by, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    store_assert(triple('http://www.ease-crc.org/ont/SOMA.owl#isPerformedBy',
                        'http://www.w3.org/2000/01/rdf-schema#subPropertyOf',
                        'http://www.ontologydesignpatterns.org/ont/dul/DUL.owl#hasParticipant')),
    n(a1, A1), n(edan, Edan),
    has_participant(A1, Edan), is_performed_by(A1, Edan).

test(has_role_direction, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    n(thermos1, O), has_role(O, R), n(pour1_role1, R).

test(value_operators, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    findall(I, triple(I, soma:hasIntervalBegin, >=(200)), Is), length(Is, 3),
    findall(V, triple(_, soma:hasIntervalBegin, <(101)->V), Vs), msort(Vs, [100, 100]),
    n(a1_ti, I1), n(a3_ti, I3),
    findall(I, triple(I, soma:hasIntervalBegin, in([101, 201])), Both), msort(Both, [I1, I3]),
    findall(S, triple(S, rdf:type, regex('neem#(apple|thermos)')), Objs), length(Objs, 0),
    findall(S, triple(S, soma:hasIntervalBegin, regex('^10')), _).

test(occurs_during, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    n(a1, A1),
    findall(E, (occurs(E) during [102, 103]), Es), Es == [A1],
    \+ occurs(A1).

test(during_event, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    n(a1, A1),
    findall(X, (is_action(X) during A1), Xs), length(Xs, 7).

test(scoped_facts, [nondet, setup(store_reset), cleanup(store_reset)]) :-
    store_assert(triple(s, p, o), 10.0, 20.0),
    \+ triple(s, p, o),
    triple(s, p, o) during [12, 18],
    \+ triple(s, p, o) during [5, 18],
    triple(s, p, o) until 15,
    \+ triple(s, p, o) since 15.

test(compiled_equals_stepwise, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    G = ( executes_task(A, T), task_role(T, R), has_role(O, R), instance_of(O, C) ),
    findall(A-T-R-O-C, kb_call(G, any), L1),
    findall(A-T-R-O-C, kb_call_stepwise(G, any), L2),
    msort(L1, S), msort(L2, S), S \== [].

test(compile_one_match_per_conjunction, [nondet]) :-
    kb_compile(( is_action(A), executes_task(A, T), event_interval(A, _, _), T \== x ), any, Plan),
    Plan = [match(Ps, any), call(_)], length(Ps, 5).

test(project_and_query, [nondet, setup(store_reset), cleanup(store_reset)]) :-
    kb_project(( is_action(act), event_interval(act, 5.0, 9.0) )),
    is_action(act),
    event_interval(act, B, E), B =:= 5.0, E =:= 9.0.

test(project_needs_ground, [setup(store_reset), cleanup(store_reset), error(instantiation_error)]) :-
    kb_project(triple(_, p, o)).

test(names_with_prolog_syntax, [nondet, setup(store_reset), cleanup(store_reset)]) :-
    S = 'http://e.org/x#it''s a "test", (really) :- fail.',
    kb_project(triple(S, rdf:type, dul:'Action')),
    findall(X, is_action(X), [S]).

test(bad_scope, [error(type_error(scope, later))]) :-
    kb_call(true, later).

:- end_tests(knowrob_model).
