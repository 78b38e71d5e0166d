:- begin_tests(store_python).

:- use_module(python).

% Stand-ins for the foreign predicates the bridge registers, answering Reply (Python's reply
% text). Made at run time and abolished after: a clause for them written in this file would
% define them at load time, for every suite loaded with it (store_use_python/1 checks them).
stub(Reply) :-
    unstub,
    forall(member(Name, [py_match, py_graph]),
           ( Head =.. [Name, _, Reply], assertz(store_python:Head) )).

unstub :-
    abolish(store_python:py_match/2),
    abolish(store_python:py_graph/2).

test(compact_reply_rows_are_positions_in_its_table) :-
    store_python:match_reply("r(d('http://x#a', 2.5, -0.0), [[1,2],[3,[1,3]]])", Table, Rows),
    findall(Vs, ( member(Row, Rows), store_python:row_values(Row, Table, Vs) ), Values),
    Values == [['http://x#a', 2.5], [-0.0, ['http://x#a', -0.0]]].

test(compact_reply_position_outside_its_table,
     [error(neem_store_error(unexpected_reply(3)), _)]) :-
    store_python:match_reply("r(d(a, b), [[1,3]])", Table, [Row]),
    store_python:row_values(Row, Table, _).

test(compact_reply_error_and_garbage) :-
    catch(store_python:match_reply("error('no store')", _, _), error(neem_store_error(M), _), true),
    M == 'no store',
    catch(store_python:match_reply("r(d(a), [[X]])", _, _), error(neem_store_error(U), _), true),
    U = unexpected_reply(_).

test(grouped_reply_gives_each_row_its_group, [cleanup(unstub)]) :-
    stub("r(d(a, b, c), g([2, 3]), [[1, 4]])"),
    findall(Vs, store_python_rows([n, -1, -1, -1, 2, [], 1, store], Vs), Rows),
    Rows == [[a, [b, c]]].

test(rows_are_read_as_data_never_called, [cleanup(unstub)]) :-
    stub("[[a, 'it''s'], [1, 2.5]]"),
    store_python_call(graph, [n, get, g, '', ''], Rows),
    Rows == [[a, 'it''s'], [1, 2.5]],
    stub("[[X]]"),
    catch(store_python_call(graph, [n], _), error(neem_store_error(E), _), true),
    E = unexpected_reply(_),
    stub("error('disk full')"),
    catch(store_python_call(graph, [n], _), error(neem_store_error(M), _), true),
    M == 'disk full'.

test(unknown_foreign_predicate, [error(domain_error(store_foreign_predicate, shell))]) :-
    store_python_call(shell, [], _).

test(a_request_set_in_prolog_is_read_once) :-
    store_set_request([a, 1, [b]]),
    store_python_request(R),
    R == [a, 1, [b]],
    catch(store_python_request(_), error(existence_error(python_request, _), _), Raised = true),
    Raised == true.

:- end_tests(store_python).
