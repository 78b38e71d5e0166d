:- begin_tests(odb_calls).

:- use_module(calls).
:- use_module('../neem_store').
:- use_module('../fixtures/test_episode').
:- use_module('../fixtures/history_reference').
:- use_module('../fixtures/triples', [fixture_assert/4]).
:- use_module('../lang/query', [kb_call/2]).

n(L, I) :- atom_concat('http://example.org/neem#', L, I).

test(task_call_orders_reference_first, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    n(pour1, T), task_call(T, C), C == pour(thermos, green_mug).

test(action_call, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    findall(C-B, action_call(_, C, B, _), L), msort(L, S),
    S == ['IdleTask'-110, pick(apple)-201, pour(thermos, green_mug)-101].

test(chain_before_skips_idle, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    n(a3, A3), chain_before(A3, 5, C), C == [pour(thermos, green_mug)],
    chain_before(A3, 0, []).

test(times_done, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    times_done(pick(apple), [action(201, 205, _)]).

%   Odd tasks of the test episode's kind: two odb types, a role whose object has a non-odb
%   type first, a role classifying nothing typed, a role-less task, an untyped task.
odd_tasks :-
    forall(member(q(S, P, O),
                  [ q(t1, rdf:type, dul:'Task'), q(t1, rdf:type, odb:pick), q(t1, rdf:type, odb:pour),
                    q(t1, dul:isTaskOf, r1), q(r1, dul:classifies, o1), q(r1, rdf:type, soma:'MovedObject'),
                    q(o1, rdf:type, dul:'PhysicalObject'), q(o1, rdf:type, odb:apple),
                    q(o1, rdf:type, odb:banana),
                    q(t1, dul:isTaskOf, r2), q(r2, dul:classifies, o2), q(r2, rdf:type, soma:'PouredObject'),
                    q(t2, rdf:type, odb:pick), q(t2, dul:isTaskOf, r3), q(r3, rdf:type, soma:'MovedObject'),
                    q(t3, rdf:type, odb:pick),
                    q(t4, dul:isTaskOf, r4), q(r4, dul:classifies, o1), q(r4, rdf:type, soma:'MovedObject') ]),
           fixture_assert('http://example.org/neem#', S, P, O)).

test(task_calls_equals_task_call, [cleanup(store_reset)]) :-
    forall(member(Load, [load_generated_episode(200, 5), ( load_test_episode, odd_tasks )]),
           ( call(Load),
             findall(T, ( kb_call(triple(T, rdf:type, C), any), atom(C) ), Ts0), sort(Ts0, Ts),
             task_calls(Ts, Pairs),
             findall(T-Call, ( member(T, Ts), task_call(T, Call) ), Expected),
             assertion(Pairs == Expected) )).

:- end_tests(odb_calls).
