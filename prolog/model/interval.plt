:- begin_tests(allen_interval).

:- use_module(interval).
:- use_module('../neem_store').
:- use_module('../fixtures/test_episode').

n(L, I) :- atom_concat('http://example.org/neem#', L, I).

test(relations) :-
    interval_before([1, 2], [3, 4]), interval_after([3, 4], [1, 2]), \+ interval_before([1, 3], [3, 4]),
    interval_meets([1, 3], [3, 4]), interval_met_by([3, 4], [1, 3]),
    interval_overlaps([1, 4], [3, 6]), interval_overlapped_by([3, 6], [1, 4]),
    interval_starts([1, 2], [1, 5]), interval_started_by([1, 5], [1, 2]),
    interval_during([2, 3], [1, 5]), interval_contains([1, 5], [2, 3]),
    interval_finishes([3, 5], [1, 5]), interval_finished_by([1, 5], [3, 5]),
    interval_equals([1, 5], [1.0, 5.0]), \+ interval_during([1, 5], [1, 5]).

test(events, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    n(a1, A1), n(a2, A2), n(a3, A3),
    interval_meets(A1, A2), interval_before(A1, A3), interval_during([102, 103], A1).

:- end_tests(allen_interval).
