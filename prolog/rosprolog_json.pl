:- module(rosprolog_json,
    [ rosprolog_solution/2,         % +Text, -JSON
      rosprolog_solution_writing/2, % +Text, -JSON
      rosprolog_encode/2            % +Term, -Value
    ]).
/** <module> Solutions as rosprolog encodes them, for the rosprolog and rosbridge doors

KnowRob's clients (rosprolog_client, neem_interface_python, openEASE) read each solution of a
query as one JSON object: a compound as `{"term": [Functor, Arg...]}`, an unbound variable as
`"_"`, a string as its quoted text, atoms, numbers and lists as themselves. The doors ask
json_query/2 for `rosprolog_json:rosprolog_solution(Q, S)` with the client's text bound to `Q`:
json_query checks and limits that call like any other, and this module checks the client's own
goal with the same allow-list (json_query:safe_query/2) before it runs it. Nothing is
concatenated: the text arrives as a bound value and is read as one term.
*/

:- use_module(library(error)).
:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module(library(http/json)).

%!  rosprolog_solution(+Text, -JSON) is nondet.
%   One solution of the query Text (one clause, run in module `user`) per answer, JSON the
%   string of `{Var: Value}` for its named variables (not those starting with `_`), each value
%   encoded by rosprolog_encode/2. Only `read` predicates of prolog/query_policy.pl may run.
rosprolog_solution(Text, JSON) :-
    solution(Text, [read], JSON).

%!  rosprolog_solution_writing(+Text, -JSON) is nondet.
%   As rosprolog_solution/2, and the query may also call `write` predicates (kb_project/1, ...).
%   It is itself classed `write`: a service that does not allow writes refuses it.
rosprolog_solution_writing(Text, JSON) :-
    solution(Text, [read, write], JSON).

solution(Text, Classes, JSON) :-
    must_be(text, Text),
    one_term(Text, Goal, Names),
    json_query:safe_query(Goal, Classes),
    call(user:Goal),
    exclude(anonymous, Names, Shown),
    findall(Name-Value, ( member(Name = Term, Shown), rosprolog_encode(Term, Value) ), Pairs),
    dict_pairs(Dict, _, Pairs),
    with_output_to(string(JSON), json_write_dict(current_output, Dict, [width(0)])).

%   one_term(+Text, -Goal, -Names): the one term Text holds, read exactly as json_query reads
%   /api/prolog's text (text after its full stop is a syntax error, never dropped).
one_term(Text, Goal, Names) :-
    text_to_string(Text, String),
    json_query:one_clause(String, Goal, Names).

anonymous(Name = _) :- sub_atom(Name, 0, 1, _, '_').

%!  rosprolog_encode(@Term, -Value) is det.
%   Term as rosprolog sends it: `'_'` for a variable, a list element by element, a string as
%   its quoted text (`"s"` becomes `'"s"'`), atoms, numbers and dicts as they are, any other
%   compound as `_{term: [Functor|Args]}` with its arguments encoded. Where rosprolog has no
%   answer (a variable inside a compound or list loops there; inf and nan are not JSON; a blob)
%   this gives `'_'` for the variable and the quoted text of the number or blob.
rosprolog_encode(Var, '_') :-
    var(Var), !.
rosprolog_encode(List, Values) :-
    is_list(List), !,
    maplist(rosprolog_encode, List, Values).
rosprolog_encode(String, Quoted) :-
    string(String), !,
    term_to_atom(String, Quoted).
rosprolog_encode(Number, Text) :-
    float(Number), \+ ( Number =:= Number, abs(Number) =\= inf ), !,
    format(atom(Text), '~q', [Number]).
rosprolog_encode(Atomic, Atomic) :-
    ( atom(Atomic) ; number(Atomic) ), !.
rosprolog_encode(Dict, Encoded) :-
    is_dict(Dict), !,
    dict_pairs(Dict, Tag, Pairs),
    findall(K-V, ( member(K-T, Pairs), rosprolog_encode(T, V) ), Encoded0),
    dict_pairs(Encoded, Tag, Encoded0).
rosprolog_encode(Term, _{term: [Functor|Values]}) :-
    compound(Term), !,
    compound_name_arguments(Term, Functor, Args),
    maplist(rosprolog_encode, Args, Values).
rosprolog_encode(Other, Text) :-
    format(atom(Text), '~q', [Other]).
