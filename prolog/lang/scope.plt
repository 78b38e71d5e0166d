:- begin_tests(kb_scope).

:- use_module(scope).

test(universal) :-
    universal_scope(scope(S, U)), S =:= 0, U =:= inf.

test(check, [error(type_error(scope, now))]) :-
    scope_check(now).

test(overlaps) :-
    scope_overlaps(any, 1, 2),
    scope_overlaps(scope(5, 6), 1, 5),
    \+ scope_overlaps(scope(5, 6), 1, 4).

test(runtime_during_free_interval) :-
    runtime_scope(during, [_, _], S), S == any.

test(runtime_until) :-
    runtime_scope(until, 4, S), S == scope(4, 4),
    runtime_scope(until, _, A), A == any.

test(knowrob_scope_dicts) :-
    time_scope(=(double(5)), >=(double(20)), D),
    time_scope_data(D, Data), Data == [5, >=(20)],
    wildcard_scope(W), scope_intersect(W, D, D1), D1 == D,
    scope_intersect(scope(0.0, 12.0), D, I), time_scope_data(I, [S, U]), S == 5, U == 12.0,
    \+ scope_intersect(scope(0.0, 4.0), D, _),
    subscope_of(scope(6.0, 8.0), D), \+ subscope_of(D, scope(6.0, 8.0)).

:- end_tests(kb_scope).
