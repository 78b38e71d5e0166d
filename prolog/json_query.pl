:- module(json_query,
    [ json_query/2,               % +Request, -JSON
      safe_query/1,               % +Goal
      safe_query/2                % +Goal, +Classes
    ]).
/** <module> Client queries over the live service, answered as JSON solutions

The way rosprolog/json_prolog serve KnowRob queries, without their state: the client sends a
query text, values for some of its variables, an offset and a limit, and gets a page of
solutions. The text must be exactly one clause (text after its full stop is refused, not
ignored) and is read as a term: it is never concatenated with values. Before anything runs,
every goal in it (inside control constructs, findall/forall/aggregate_all and kb_call bodies
alike) is resolved to the module that defines it and looked up in query_policy's allow-list:
only `read` predicates run (and `write` ones when the service allows writes). A predicate
that loads or reads files, writes, or is not on the table is refused, naming it. The query runs
under a time limit and a stack limit. Every failure becomes `{"error": Message}` (plus
`"refused": true` for a refused predicate); nothing is thrown to the caller.
*/

:- use_module(library(error)).
:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module(library(time)).
:- use_module(library(http/json)).
:- use_module(query_policy, [exposed/3, goal_argument/3]).
% the rosprolog and rosbridge doors ask for rosprolog_json:rosprolog_solution/2 through json_query/2
:- use_module(rosprolog_json, []).

%!  json_query(+Request, -JSON) is det.
%   Request is `[Text, Bindings, Offset, Limit, Seconds, Writes]`: the query text, a list of
%   `[Name, Value]` pairs binding the query's variables by name, how many solutions to skip,
%   at most how many to return, the time limit in seconds and `true` when `write` predicates
%   may run (`false` otherwise). JSON is a string:
%   `{"solutions": [{Var: Value}], "more": Bool, "offset": N}` or `{"error": Message}`.
json_query(Request, JSON) :-
    catch(page(Request, Dict), Error, error_dict(Error, Dict)),
    !,
    with_output_to(string(JSON0), json_write_dict(current_output, Dict, [width(0)])),
    query_answer_limit(Max),
    (   string_length(JSON0, Length), Length > Max
    ->  format(string(Message), "the answer is ~d characters, more than a service query may return (~d); ask for fewer solutions (limit) or smaller values", [Length, Max]),
        with_output_to(string(JSON), json_write_dict(current_output, _{error: Message}, [width(0)]))
    ;   JSON = JSON0
    ).

%   The longest answer (characters of its JSON) a query may return: the page is built here, in
%   the query's process, and refused before it travels to the service.
query_answer_limit(4 000 000).

%   The tables a query may fill (bytes of table space): tabling is memory outside the stacks.
query_table_space(64 000 000).

%   The stack a query may use (bytes): a query building a huge term fails alone, the
%   service does not grow by gigabytes.
query_stack_limit(64 000 000).

page([Text, Bindings, Offset, Limit, Seconds, Writes], _{solutions: Solutions, more: More, offset: Offset}) :-
    must_be(nonneg, Offset),
    must_be(positive_integer, Limit),
    must_be(number, Seconds),
    must_be(boolean, Writes),
    one_clause(Text, Goal, Names),
    maplist(bind(Names), Bindings),
    (   Writes == true -> safe_query(Goal, [read, write]) ; safe_query(Goal, [read]) ),
    Take is Limit + 1,
    query_stack_limit(Stack),
    query_table_space(Tables),
    current_prolog_flag(stack_limit, Old),
    current_prolog_flag(table_space, OldTables),
    setup_call_cleanup(
        ( set_prolog_flag(stack_limit, Stack), set_prolog_flag(table_space, Tables) ),
        call_with_time_limit(Seconds, findall(Names, limit(Take, offset(Offset, user:Goal)), Rows)),
        ( set_prolog_flag(stack_limit, Old), set_prolog_flag(table_space, OldTables) )),
    length(Rows, Got),
    (   Got > Limit
    ->  More = true, length(Page, Limit), append(Page, _, Rows)
    ;   More = false, Page = Rows
    ),
    maplist(solution_dict, Page, Solutions).

%   one_clause(+Text, -Goal, -Names): Text holds exactly one term (the final full stop may be
%   left out); anything after it is a syntax error, never silently dropped.
one_clause(Text, Goal, Names) :-
    must_be(string, Text),
    split_string(Text, "", " \t\r\n", [Trimmed]),
    (   Trimmed == "" -> domain_error(query_text, empty) ; true ),
    (   sub_string(Trimmed, _, 1, 0, ".") -> Full = Trimmed ; string_concat(Trimmed, "\n.", Full) ),
    setup_call_cleanup(
        open_string(Full, In),
        ( read_term(In, Goal, [variable_names(Names), syntax_errors(error), module(user)]),
          read_term(In, Rest, [syntax_errors(error), module(user)]) ),
        close(In)),
    (   Rest == end_of_file -> true ; domain_error(query_text, more_than_one_clause) ).

bind(Names, [Name, Value]) :-
    (   memberchk(Name = Var, Names)
    ->  Var = Value
    ;   domain_error(query_variable, Name)
    ).

solution_dict(Names, Dict) :-
    exclude(anonymous, Names, Shown),
    findall(Key-JSON, ( member(Key = Value, Shown), json_value(Value, JSON) ), Pairs),
    dict_pairs(Dict, _, Pairs).

anonymous(Name = _) :- sub_atom(Name, 0, 1, _, '_').

%!  json_value(+Term, -JSON) is det.
%   A solution's value as JSON: numbers as numbers, atoms and strings as strings, lists as
%   arrays, unbound as null, any other term as its quoted text.
json_value(V, null) :- var(V), !.
json_value(V, V) :- number(V), \+ float_special(V), !.
json_value(V, S) :- atom(V), !, atom_string(V, S).
json_value(V, V) :- string(V), !.
json_value(V, J) :- is_list(V), !, maplist(json_value, V, J).
json_value(V, S) :- format(string(S), '~q', [V]).

float_special(V) :- float(V), ( V =:= inf ; V =:= -inf ; V =\= V ).

error_dict(error(permission_error(call, service_query, PI), _), _{error: Message, refused: true}) :- !,
    format(string(Message), "~q is not allowed in a service query (only predicates on the read-only allow-list, prolog/query_policy.pl)", [PI]).
error_dict(Error, _{error: Message}) :-
    error_message(Error, Message).

error_message(time_limit_exceeded, "the query ran past its time limit") :- !.
error_message(error(resource_error(_), _), "the query needed more memory than a service query may use") :- !.
error_message(error(domain_error(query_text, more_than_one_clause), _), "the query must be one clause: text after its full stop is not allowed") :- !.
error_message(error(domain_error(query_text, empty), _), "the query is empty") :- !.
error_message(error(syntax_error(What), context(_, _)), M) :- !,
    format(string(M), "syntax error in the query: ~w", [What]).
error_message(error(syntax_error(What), string(_, At)), M) :- !,
    format(string(M), "syntax error in the query: ~w (at character ~w)", [What, At]).
error_message(error(syntax_error(What), _), M) :- !,
    format(string(M), "syntax error in the query: ~w", [What]).
error_message(error(domain_error(query_variable, Name), _), M) :- !,
    format(string(M), "binding ~w: the query has no variable of that name", [Name]).
error_message(error(existence_error(procedure, PI), _), M) :- !,
    format(string(M), "unknown predicate ~q", [PI]).
error_message(error(Formal, _), M) :- !,
    format(string(M), "~q", [Formal]).
error_message(Error, M) :-
    format(string(M), "~q", [Error]).

%!  safe_query(+Goal) is det.
%!  safe_query(+Goal, +Classes) is det.
%   True when every predicate Goal calls is on query_policy's table in one of Classes (default
%   `[read]`); otherwise raises `permission_error(call, service_query, PI)` naming the first
%   that is not (or an instantiation error for a goal that is a variable). Goals are resolved
%   in module `user`, where the service runs them.
safe_query(Goal) :-
    safe_query(Goal, [read]).
safe_query(Goal, Classes) :-
    must_be(list(oneof([read, write])), Classes),
    safe_goal(Goal, user, prolog, Classes).

%   safe_goal(+Goal, +Module, +Language, +Classes): Language is `prolog`, or `kb` inside a
%   kb_call body, where a few more forms mean a goal (lang/query.pl's unfold/5).
safe_goal(Goal, _, _, _) :-
    var(Goal), !,
    instantiation_error(Goal).
safe_goal(Module:Goal, _, Language, Classes) :- !,
    (   atom(Module), current_module(Module)
    ->  safe_goal(Goal, Module, Language, Classes)
    ;   permission_error(call, service_query, Module:Goal)
    ).
safe_goal(Goal, Module, Language, Classes) :-
    control(Goal, Inner), !,
    maplist([G]>>safe_goal(G, Module, Language, Classes), Inner).
safe_goal(Goal, Module, kb, Classes) :-
    kb_form(Goal, Inner), !,
    maplist([G]>>safe_goal(G, Module, kb, Classes), Inner).
safe_goal(Goal, Module, _, Classes) :-
    (   callable(Goal) -> true ; type_error(callable, Goal) ),
    functor(Goal, Name, Arity),
    (   defining_module(Module, Goal, Home),
        exposed(Home, Name/Arity, Class),
        memberchk(Class, Classes)
    ->  forall(goal_argument(Home, Name/Arity, Index),
               ( arg(Index, Goal, Inner), safe_goal(Inner, Module, kb, Classes) ))
    ;   permission_error(call, service_query, Name/Arity)
    ).

%   The module whose predicate Goal calls from Module; fails for an unknown one. Checking
%   `defined` first loads nothing that is not loaded (no autoloading of an unknown name).
defining_module(Module, Goal, Home) :-
    predicate_property(Module:Goal, imported_from(Home)), !.
defining_module(_, Goal, system) :-
    predicate_property(system:Goal, built_in), !.
defining_module(Module, Goal, Module) :-
    predicate_property(Module:Goal, defined).

control((A, B), [A, B]).
control((A ; B), [A, B]).
control((A -> B), [A, B]).
control((A *-> B), [A, B]).
control(\+ A, [A]).
control(once(A), [A]).
control(ignore(A), [A]).
control(forall(A, B), [A, B]).
control(findall(_, A, _), [A]).
control(findall(_, A, _, _), [A]).
control(aggregate_all(count, A, _), [A]).
control(aggregate_all(sum(_), A, _), [A]).
control(aggregate_all(max(_), A, _), [A]).
control(aggregate_all(min(_), A, _), [A]).
control(aggregate_all(bag(_), A, _), [A]).
control(aggregate_all(set(_), A, _), [A]).
control(limit(_, A), [A]).
control(offset(_, A), [A]).
control(order_by(_, A), [A]).
control(distinct(_, A), [A]).

%   Forms a kb_call body gives a meaning of its own (lang/query.pl unfold/5).
kb_form([], []).
kb_form([G|Gs], [G, Gs]).
kb_form(call(G), [G]).
kb_form(call_with_context(G, _), [G]).
kb_form(assign(_, _), []).
kb_form(triple(_, _, _), []).
kb_form(holds(_, _, _), []).
kb_form(holds(_), []).
kb_form(has_type(_, _), []).
kb_form(occurs(_), []).
