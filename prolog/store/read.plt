:- begin_tests(store_read).

:- use_module(read).
:- use_module(memory, [store_assert/1, store_assert/3]).
:- use_module(scope, [store_in_graphs/2]).
:- use_module(neem, [store_reset/0, store_use_python/1]).
:- use_module(library(http/json), [atom_json_term/3]).

weights :-
    store_reset,
    forall(member(S-W, [a-3, b-1, c-2, d-2]), store_assert(triple(S, weight, W))),
    store_assert(triple(a, colour, red)).

% The python backend, stood in for: py_match/2 keeps the request it got (JSON text, made
% at run time, see python.plt) and answers Reply; py_scopes/2 answers Scopes.
python_stub(Reply, Scopes) :-
    Match =.. [py_match, Request, Reply],
    assertz((store_python:Match :- nb_setval(store_sent, Request))),
    Doc =.. [py_scopes, _, Scopes],
    assertz(store_python:Doc),
    store_use_python(n1).

python_unstub :-
    abolish(store_python:py_match/2),
    abolish(store_python:py_scopes/2),
    store_reset.

sent(Request) :-
    nb_getval(store_sent, Text),
    atom_string(Atom, Text),
    atom_json_term(Atom, Request, []).

test(order_then_limit, [setup(weights), cleanup(store_reset)]) :-
    findall(S, store_match([t(S, weight, W)], any, [order([desc(W), asc(S)])]), [a, c, d, b]),
    findall(S, store_match([t(S, weight, W)], any, [order([asc(W)]), limit(2)]), [b, _]).

test(limit_must_be_positive, [setup(weights), cleanup(store_reset), error(type_error(positive_integer, 0))]) :-
    store_match([t(_, weight, _)], any, [limit(0)]).

test(order_keys_are_variables, [setup(weights), cleanup(store_reset), error(type_error(order_key, desc(3)))]) :-
    store_match([t(_, weight, _)], any, [order([desc(3)])]).

test(group_by_the_selected_key, [setup(weights), cleanup(store_reset)]) :-
    findall(W-Ss, store_match([t(S, weight, W)], any, [select(W-S), group(S, Ss)]), Groups),
    msort(Groups, [1-[b], 2-[c, d], 3-[a]]).

test(no_patterns_no_answer, [setup(weights), cleanup(store_reset)]) :-
    \+ store_match([], any).

test(a_bound_comparison_is_its_value, [setup(weights), cleanup(store_reset)]) :-
    once(store_match([t(a, weight, cmp(>, 2, 3))], any)),
    \+ store_match([t(a, weight, cmp(<, 2, 3))], any).

test(scoped_match_says_when, [cleanup(store_reset)]) :-
    store_reset,
    store_assert(triple(a, p, b), 0.0, 10.0),
    store_assert(triple(b, p, c), 5.0, 20.0),
    findall(FS, store_match_scoped([t(a, p, X), t(X, p, _)], any, FS), [scope(5.0, 10.0)]).

test(python_request, [cleanup(python_unstub)]) :-
    python_stub("r(d(b, 'it''s', 2.5), [[1, 3], [2, 3]])", "[]"),
    findall(O-W, store_match([t(a, p, O), t(O, w, cmp(>, 1, W))], scope(1.0, 2.0), [limit(5), order([desc(W)])]),
            Rows),
    Rows == [b-2.5, 'it''s'-2.5],
    sent(Request),
    Request == [n1, 1.0, 2.0, 5, 2, [[1, desc]], -1, store,
                [c, a, c, p, v, 0], [v, 0, c, w, cmp, [>, 1, 1]]].

test(two_comparisons_of_one_value_are_one_range, [cleanup(python_unstub)]) :-
    python_stub("r(d(i1, 2.5, 7), [[1, 2, 3]])", "[]"),
    findall(I-B, store_match([t(a, p, I), t(I, begin, cmp(>, 1, B)), t(I, end, _), t(I, begin, cmp(=<, 3, B))], any),
            Rows),
    Rows == [i1-2.5],
    sent(Request),
    Request == [n1, -1, -1, -1, 3, [], -1, store,
                [c, a, c, p, v, 0], [v, 0, c, begin, cmp2, [>, 1, =<, 3, 1]], [v, 0, c, end, v, 2]].

test(comparisons_of_other_values_stay_apart, [cleanup(python_unstub)]) :-
    python_stub("r(d(i1, 2.5), [])", "[]"),
    \+ store_match([t(I, begin, cmp(>, 1, _)), t(I, begin, cmp(=<, 3, _)), t(I, end, cmp(<, 9, E)),
                    t(j, end, cmp(>, 0, E))], any),
    sent(Request),
    Request = [_, _, _, _, _, _, _, _|Patterns],
    length(Patterns, 4),
    \+ ( member(P, Patterns), memberchk(cmp2, P) ).

test(a_range_in_memory, [setup(weights), cleanup(store_reset)]) :-
    findall(S, store_match([t(S, weight, cmp(>, 1, =<, 2, _))], any), Ss), msort(Ss, [c, d]),
    once(store_match([t(a, weight, cmp(>=, 3, <, 4, 3))], any)),
    \+ store_match([t(a, weight, cmp(>, 1, <, 3, 3))], any).

test(python_request_selects_groups_and_reads_graphs, [cleanup(python_unstub)]) :-
    python_stub("r(d(a, b, c), g([2, 3]), [[1, 4]])", "[]"),
    findall(S-Os, store_in_graphs([g1], store_match([t(S, p, O)], any, [select(S-O), group(O, Os), plan(written)])),
            Rows),
    Rows == [a-[b, c]],
    sent(Request),
    Request == [n1, -1, -1, -1, 2, [], 1, written, [v, 0, c, p, v, 1, g, [g1]]].

test(python_scoped_match_asks_each_documents_scope, [cleanup(python_unstub)]) :-
    python_stub("r(d(b), [[1]])", "[[0.0, 10.0], [20.0, 30.0], [3.0, 3.0]]"),
    findall(FS, store_match_scoped([t(a, p, _)], any, FS), Scopes),
    Scopes == [scope(0.0, 10.0), scope(20.0, 30.0)].

:- end_tests(store_read).
