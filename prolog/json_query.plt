:- begin_tests(json_query).

:- use_module(json_query).
:- use_module(answers).

:- use_module(neem_store).
:- use_module(fixtures/test_episode).
:- use_module(library(http/json)).
:- use_module(user:lang/query).  % service queries run in user, where the bridge loads the modules
:- use_module(user:model/event).

reply(Text, Bindings, Offset, Limit, Dict) :-
    json_query([Text, Bindings, Offset, Limit, 5.0, false], JSON),
    atom_json_dict(JSON, Dict, []).

%   The solutions as sorted Key-Value lists (dict tags are fresh variables).
rows(Dict, Rows) :- findall(P, ( member(S, Dict.solutions), dict_pairs(S, _, P) ), Rows).

contains(String, Part) :- once(sub_string(String, _, _, _, Part)).

test(pages_with_more_flag) :-
    reply("member(X, [a, b, c])", [], 0, 2, D1),
    rows(D1, R1), R1 == [['X'-"a"], ['X'-"b"]], D1.more == true,
    reply("member(X, [a, b, c])", [], 2, 2, D2),
    rows(D2, R2), R2 == [['X'-"c"]], D2.more == false.

test(bindings_are_terms_not_text) :-
    Tricky = 'a\'), halt, (\'',
    reply("atom_length(X, N)", [['X', Tricky]], 0, 10, D),
    atom_length(Tricky, L),
    atom_string(Tricky, S),
    rows(D, R), R == [['N'-L, 'X'-S]].

test(halt_refused_also_inside_kb_call) :-
    reply("halt", [], 0, 1, D1), contains(D1.error, "halt/0 is not allowed"),
    reply("kb_call(halt)", [], 0, 1, D2), contains(D2.error, "halt/0 is not allowed"),
    reply("X = halt, call(X)", [], 0, 1, D3), contains(D3.error, "call/1 is not allowed").

test(writes_refused) :-
    reply("kb_project(triple(a, b, c))", [], 0, 1, D1), contains(D1.error, "kb_project/1"),
    reply("kb_query:kb_project(triple(a, b, c))", [], 0, 1, D2), contains(D2.error, "kb_project/1"),
    reply("assertz(foo)", [], 0, 1, D3), contains(D3.error, "assertz/1").

test(variable_goal_refused) :-
    reply("G = true, findall(x, G, _)", [], 0, 1, D), contains(D.error, "instantiation").

test(syntax_error_is_one_message) :-
    reply("member(X, [a", [], 0, 1, D), string_concat("syntax error", _, D.error).

test(unknown_binding_name) :-
    reply("X = 1", [['Y', 2]], 0, 1, D), contains(D.error, "no variable of that name").

test(model_query_over_the_store, [setup(load_test_episode), cleanup(store_reset)]) :-
    reply("kb_call(executes_task(A, T))", [], 0, 100, D),
    D.solutions \== [],
    forall(member(S, D.solutions), ( string(S.'A'), string(S.'T') )).

test(values_as_json) :-
    reply("X = f(y), Y = [1, 2.5], Z = \"s\", W = _", [], 0, 1, D),
    rows(D, R), R == [['W'-null, 'X'-"f(y)", 'Y'-[1, 2.5], 'Z'-"s"]].

test(one_clause_only) :-
    reply("true. halt", [], 0, 1, D1), contains(D1.error, "one clause"),
    reply("true. halt.", [], 0, 1, D2), contains(D2.error, "one clause"),
    reply("X = 1.", [], 0, 1, D3), rows(D3, [['X'-1]]),
    reply("X = 'a. b'", [], 0, 1, D4), rows(D4, [['X'-"a. b"]]),
    reply("   ", [], 0, 1, D5), contains(D5.error, "empty").

test(writers_and_loaders_refused_by_name) :-
    forall(member(Q-Name, [ "kb_unproject(triple(S, P, O))"-"kb_unproject/1",
                            "load_owl('/etc/hostname', [graph(odb)])"-"load_owl/2",
                            "kb_call(load_owl('/etc/hostname'))"-"load_owl/1",
                            "forall(true, kb_db:load_owl(x))"-"load_owl/1",
                            "findall(x, retract(foo), _)"-"retract/1",
                            "aggregate_all(count, kb_call((is_action(A), kb_project(triple(A, b, c)))), N)"-"kb_project/1",
                            "kb_call([is_action(A), call(store_reset)])"-"store_reset/0",
                            "exists_file('/etc/hostname')"-"exists_file/1",
                            "neem_store:store_match(P, M)"-"store_match/2",
                            "no_such_predicate(x)"-"no_such_predicate/1",
                            "kb_query:run_plan(P)"-"run_plan/1",
                            "system:halt"-"halt/0" ]),
           ( reply(Q, [], 0, 1, D), D.refused == true, contains(D.error, Name) )).

test(writes_only_when_allowed) :-
    safe_query(kb_project(triple(a, b, c)), [read, write]),
    catch(safe_query(kb_project(triple(a, b, c)), [read]), error(permission_error(_, _, _), _), true),
    catch(safe_query(load_owl(x), [read, write]), error(permission_error(_, _, PI), _), true),
    PI == load_owl/1.

test(bound_variable_goal_checked_after_binding) :-
    reply("G", [['G', halt]], 0, 1, D), contains(D.error, "halt/0").

%   A long time limit: on a starved core (make test runs plunit niced beside pytest) 5 s of wall
%   time can pass before the stacks fill, and the time limit would answer first.
test(a_huge_term_is_a_resource_error_not_a_grown_process) :-
    json_query(["findall(X, between(1, 100000000, X), L), length(L, N)", [], 0, 1, 120.0, false], JSON),
    atom_json_dict(JSON, D, []),
    contains(D.error, "memory").

:- end_tests(json_query).
