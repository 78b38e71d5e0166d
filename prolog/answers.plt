:- begin_tests(answers).

:- use_module(answers).
:- use_module(neem_store).
:- use_module(fixtures/test_episode).

test(why_not_ranked_lower, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    findall(R, why_not(pick(apple), 105, R), Rs),
    Rs == [ ranked_lower(pick(apple), 100, rank(2, 0.7), [ranked(pour(thermos, green_mug), 1, 0.2)]),
            user_chose(pour(thermos, green_mug), 101),
            done_later(pick(apple), 201) ].

test(why_not_object_not_perceived, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    why_not(pick(banana), R), R == not_available(pick(banana), 200, object_not_perceived(banana)).

test(why_not_perceived_later, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    Inf is inf,
    store_assert(triple('http://example.org/neem#banana1', 'http://www.w3.org/1999/02/22-rdf-syntax-ns#type',
                        'https://ontology.dlr.de/soma/odb#banana'), 300.0, Inf),
    why_not(pick(banana), 250, R1), !,
    R1 == not_available(pick(banana), 200, object_not_perceived(banana)),
    store_assert(triple('http://example.org/neem#banana2', 'http://www.w3.org/1999/02/22-rdf-syntax-ns#type',
                        'https://ontology.dlr.de/soma/odb#banana'), 150.0, Inf),
    why_not(pick(banana), 250, R2), !,
    R2 == not_available(pick(banana), 200, precondition_failed).

test(why_not_precondition, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    why_not(pour(apple, green_mug), 150, R), !,
    R == not_available(pour(apple, green_mug), 100, precondition_failed).

test(why_not_done_earlier, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    findall(R, why_not(pour(thermos, green_mug), 250, R), Rs),
    memberchk(done_earlier(pour(thermos, green_mug), 101), Rs).

test(why_not_but_done, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    findall(R, why_not(pick(apple), 203, R), [done(pick(apple), 201)]).

test(what_next, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    what_next(C), C == [ranked(pick(apple), 1, 0.1)].

test(something_else_proposed, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    something_else(pour(thermos, green_mug), A), A == pick(apple).

test(something_else_current_none, [nondet, setup(load_test_episode), cleanup(store_reset), fail]) :-
    something_else(_, _).

test(answer_json_why_not, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    store_set_request([why_not, pick, [banana], none]),
    answer_json(J),
    sub_string(J, _, _, _, "object_not_perceived").

test(call_text) :-
    call_text(pour(thermos, green_mug), T), T == "pour(thermos, green_mug)".

test(bad_call, [error(type_error(atom, f(x)))]) :-
    why_not(pick(f(x)), 1, _).

:- end_tests(answers).
