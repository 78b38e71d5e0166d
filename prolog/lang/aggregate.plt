:- begin_tests(kb_aggregate).

:- use_module(aggregate).
:- use_module(query).
:- use_module(triple).
:- use_module('../neem_store').
:- use_module('../fixtures/test_episode').

n(L, I) :- atom_concat('http://example.org/neem#', L, I).

test(a_list_of_triples_is_their_conjunction, [setup(load_test_episode), cleanup(store_reset)]) :-
    n(a1, A1),
    findall(T-B, aggregate([ triple(A1, dul:executesTask, T),
                             triple(A1, dul:hasTimeInterval, I),
                             triple(I, soma:hasIntervalBegin, B) ]), Rows),
    findall(T-B, kb_call(( triple(A1, dul:executesTask, T),
                           triple(A1, dul:hasTimeInterval, I),
                           triple(I, soma:hasIntervalBegin, B) )), Expected),
    Rows == Expected, Rows = [_|_].

test(asked_inside_kb_call_as_openease_asks_it, [setup(load_test_episode), cleanup(store_reset)]) :-
    n(a1, A1),
    findall(T, kb_call(aggregate([triple(A1, dul:executesTask, T)])), Ts),
    findall(T, triple(A1, dul:executesTask, T), Expected),
    Ts == Expected, Ts = [_|_].

test(a_goal_that_fails_fails_the_whole, [fail, setup(load_test_episode), cleanup(store_reset)]) :-
    n(a1, A1),
    aggregate([triple(A1, dul:executesTask, _), triple(A1, dul:executesTask, nothing_here)]).

test(not_a_list, [error(type_error(list, triple(_, _, _))), setup(store_reset)]) :-
    aggregate(triple(_, _, _)).

:- end_tests(kb_aggregate).
