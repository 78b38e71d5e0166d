:- begin_tests(odb_routines).

:- use_module(routines).
:- use_module('../neem_store').
:- use_module('../fixtures/test_episode').
:- use_module('../fixtures/triples', [fixture_assert/4]).

%   The test episode's objects, and a workflow wf1 "Tea" of two steps written out of order:
%   s2 pours the thermos into the green mug after s1 picks the apple.
workflow :-
    load_test_episode,
    Q = fixture_assert('http://example.org/neem#'),
    forall(member(q(S, P, O),
                  [ q(wf1, rdf:type, dul:'Workflow'), q(wf1, rdfs:label, 'Tea'),
                    q(wf1, soma:hasStep, s2), q(wf1, soma:hasStep, s1), q(wf1, soma:hasFirstStep, s1),
                    q(s1, soma:before, s2), q(s2, soma:after, s1),
                    q(s1, rdf:type, odb:pick), q(s1, dul:isTaskOf, s1r), q(s1r, rdf:type, soma:'MovedObject'),
                    q(s1r, dul:classifies, apple1),
                    q(s2, rdf:type, odb:pour), q(s2, dul:isTaskOf, s2a), q(s2a, rdf:type, soma:'PouredObject'),
                    q(s2a, dul:classifies, thermos1), q(s2, dul:isTaskOf, s2b),
                    q(s2b, rdf:type, soma:'RecipientRole'), q(s2b, dul:classifies, mug1) ]),
           call(Q, S, P, O)).

test(workflow_is_found, [nondet, setup(workflow), cleanup(store_reset)]) :-
    findall(W, routine_workflow(W), Ws), Ws == ['http://example.org/neem#wf1'].

test(workflow_calls_follow_first_step_and_before, [nondet, setup(workflow), cleanup(store_reset)]) :-
    workflow_calls('http://example.org/neem#wf1', Calls),
    Calls == [pick(apple), pour(thermos, green_mug)].

test(stored_routines_json_names_steps, [nondet, setup(workflow), cleanup(store_reset)]) :-
    stored_routines_json(J),
    sub_string(J, _, _, _, "Tea\""),                     % the fixture makes the label an IRI
    sub_string(J, _, _, _, "\"steps\":[\"pick(apple)\",\"pour(thermos, green_mug)\"]"),
    sub_string(J, _, _, _, "\"by_user\":false").

test(no_workflow_no_routines, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    stored_routines_json(J), J == "[]".

:- end_tests(odb_routines).
