:- begin_tests(rosprolog_json).

:- use_module(json_query).
:- use_module(rosprolog_json).
:- use_module(library(http/json)).
:- use_module(user:lang/query).  % service queries run in user, where the bridge loads the modules

%   The door's call: json_query/2 running rosprolog_solution/2 on the client's text.
door(Text, Writes, Dict) :-
    (   Writes == true -> P = "rosprolog_json:rosprolog_solution_writing(_Q, S)" ; P = "rosprolog_json:rosprolog_solution(_Q, S)" ),
    atom_string(Q, Text),
    json_query([P, [['_Q', Q]], 0, 100, 5.0, Writes], JSON),
    atom_json_dict(JSON, Dict, []).

solutions(Text, Solutions) :-
    door(Text, false, Dict),
    findall(S, ( member(R, Dict.solutions), atom_json_dict(R.'S', S, [value_string_as(atom)]) ), Solutions).

contains(String, Part) :- once(sub_string(String, _, _, _, Part)).

test(compound_as_term) :-
    solutions("X = foo(a, [1, 2.5], \"str\")", [S]),
    S.'X'.term == [foo, a, [1, 2.5], '"str"'].

test(unbound_as_underscore) :-
    solutions("X = _, Y = f(_)", [S]),
    S.'X' == '_', S.'Y'.term == [f, '_'].

test(atoms_numbers_lists_strings) :-
    solutions("member(X, [a, 1, [b, 2.5], \"s\"])", Sols),
    findall(V, member(_{'X': V}, Sols), Vs),
    Vs == [a, 1, [b, 2.5], '"s"'].

test(underscore_names_hidden) :-
    solutions("_Hidden = 1, Shown = 2", [S]),
    dict_pairs(S, _, Pairs), Pairs == ['Shown'-2].

test(no_solution_is_empty) :-
    solutions("member(X, [])", []).

test(read_only_refuses_writes) :-
    door("kb_project(triple(a, b, c))", false, D),
    contains(D.error, "kb_project/1"), D.refused == true.

test(writing_form_refused_without_writes) :-
    atom_string(Q, "X = 1"),
    json_query(["rosprolog_json:rosprolog_solution_writing(_Q, S)", [['_Q', Q]], 0, 1, 5.0, false], JSON),
    atom_json_dict(JSON, D, []),
    contains(D.error, "rosprolog_solution_writing/2").

test(inner_goal_checked) :-
    door("X = halt, call(X)", false, D1), contains(D1.error, "call/1 is not allowed"),
    door("halt", false, D2), contains(D2.error, "halt/0").

test(more_than_one_clause_refused) :-
    door("X = 1. halt", false, D), contains(D.error, "one clause").

test(syntax_error_message) :-
    door("member(X, [a", false, D), string_concat("syntax error", _, D.error).

test(encode_special_float) :-
    Inf is inf, rosprolog_encode(Inf, T), atom(T).

:- end_tests(rosprolog_json).
