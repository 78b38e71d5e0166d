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

:- end_tests(kb_scope).
