:- begin_tests(soma_workflow).

:- use_module(soma_workflow).
:- use_module(dul_description).
:- use_module(event).
:- use_module('../neem_store').
:- use_module('../lang/query').
:- use_module('../fixtures/owl_world').

test(workflow, [nondet, setup(load_owl_world), cleanup(store_reset)]) :-
    ow(plan1, P), ow(mix1, M), ow(bake1, B), ow(task1, T),
    workflow_first_step(P, M), findall(S, workflow_step(P, S), Ss), msort(Ss, [B, M]),
    workflow_constituent(P, T),
    workflow_sequence(P, [M, B]), workflow_sequence([B, M], [M, B]).

test(intervals, [nondet, setup(load_owl_world), cleanup(store_reset)]) :-
    ow(ti1, I1), ow(ti2, I2),
    has_interval_duration(I1, 2.5), is_interval_equal(I1, I2).

test(kinematics_file, [nondet, setup(load_owl_world), cleanup(store_reset)]) :-
    ow(cup1, C),
    kb_project(has_kinematics_file(C, 'cup.urdf', urdf)),
    has_kinematics_file(C, Id, F), Id == 'cup.urdf', F == urdf.

test(task_effect, [nondet, setup(load_owl_world), cleanup(store_reset)]) :-
    ow(task2, T), ow(role2, R), ow(r9, R9), ow('Cup', Cup),
    kb_project(( triple(T, dul:isTaskOf, R), has_type(R, soma:'CreatedObject'), subclass_of(soma:'CreatedObject', R9),
                 triple(R9, owl:onProperty, dul:classifies), triple(R9, owl:allValuesFrom, Cup) )),
    task_effect(T, created(X)), X == Cup, \+ task_effect(T, destroyed(_)).

:- end_tests(soma_workflow).
