:- begin_tests(kb_query).

:- use_module(query).
:- use_module(temporal).
:- use_module('../neem_store').
:- use_module('../model/rdfs').
:- use_module('../model/event').
:- use_module('../model/object').
:- use_module('../model/situation').
:- use_module('../fixtures/test_episode').

n(L, I) :- atom_concat('http://example.org/neem#', L, I).

test(knowrob_query_runs_unchanged, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    n(a1, A1),
    findall(T-O-B-E, kb_call(( is_action(A1), executes_task(A1, T), instance_of(T, odb:pour),
                               has_participant(A1, O), event_interval(A1, B, E) )), Rows),
    length(Rows, 2),
    forall(member(_-_-B-E, Rows), (B =:= 101, E =:= 110)).

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

:- end_tests(kb_query).
