:- begin_tests(allen_interval).

:- use_module(interval).
:- use_module('../neem_store').
:- use_module('../fixtures/test_episode').
:- use_module('../lang/triple', [kb_iri/2]).

n(L, I) :- atom_concat('http://example.org/neem#', L, I).

test(relations) :-
    interval_before([1, 2], [3, 4]), interval_after([3, 4], [1, 2]), \+ interval_before([1, 3], [3, 4]),
    interval_meets([1, 3], [3, 4]), interval_met_by([3, 4], [1, 3]),
    interval_overlaps([1, 4], [3, 6]), interval_overlapped_by([3, 6], [1, 4]),
    interval_starts([1, 2], [1, 5]), interval_started_by([1, 5], [1, 2]),
    interval_during([2, 3], [1, 5]), interval_contains([1, 5], [2, 3]),
    interval_finishes([3, 5], [1, 5]), interval_finished_by([1, 5], [3, 5]),
    interval_equals([1, 5], [1.0, 5.0]), \+ interval_during([1, 6], [1, 5]).

test(during_includes_a_shared_begin_or_end) :-       % KnowRob's test: B2 =< B1, E1 =< E2
    interval_during([1, 3], [1, 5]), interval_during([3, 5], [1, 5]), interval_during([1, 5], [1, 5]).

%   Events without times, related by SOMA's Allen properties (KnowRob's interval_constraint/3).
stated :-
    store_reset,
    forall(member(S-P-O, [a-before-b, b-meets-c, d-during-c, e-starts-c]),
           ( n(S, S1), n(O, O1), kb_iri(soma:P, P1), store_assert(triple(S1, P1, O1)) )).

test(stated_relations, [setup(stated), cleanup(store_reset)]) :-
    n(a, A), n(b, B), n(c, C), n(d, D), n(e, E),
    interval_before(A, B), interval_after(B, A), interval_meets(B, C), interval_before(A, C),
    interval_during(D, C), interval_before(A, D), interval_starts(E, C),
    \+ interval_before(C, A), \+ interval_meets(A, B), \+ interval_during(C, D).

test(constraints_and_queries, [nondet, setup(stated), cleanup(store_reset)]) :-
    n(a, A), n(b, B), n(c, C),
    findall(X, interval_constraint(A, X), [<(A, B)]),
    interval_constraint(B, m(B, C), C),
    interval_query(<(A, C)), interval_query(>(C, A)), \+ interval_query(d(A, C)),
    catch(interval_query(zz(A, C)), error(domain_error(allen_constraint, _), _), true).

test(order_of_stated_intervals, [setup(stated), cleanup(store_reset)]) :-
    n(a, A), n(b, B), n(c, C),
    interval_order([C, A, B], [A, B, C]),
    interval_order([[3, 4], [1, 2]], [[1, 2], [3, 4]]).

test(events, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    n(a1, A1), n(a2, A2), n(a3, A3),
    interval_meets(A1, A2), interval_before(A1, A3), interval_during([102, 103], A1).

:- end_tests(allen_interval).
