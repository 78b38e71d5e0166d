:- module(json_query,
    [ json_query/2,               % +Request, -JSON
      safe_query/1                % +Goal
    ]).
/** <module> Client queries over the live service, answered as JSON solutions

The way rosprolog/json_prolog serve KnowRob queries, without their state: the client sends a
query text, values for some of its variables, an offset and a limit, and gets a page of
solutions. A query is read as a term (its text is never concatenated with values), checked against a
whitelist so that it can only read: KnowRob's query language and model predicates (lang/,
model/), the odb model (odb/),
the robot's answers, control constructs and pure builtins; never halt, I/O, assert or a store
write, also not hidden inside kb_call/1 (which would call an unknown goal as Prolog). It runs
under a time limit. Every failure becomes `{"error": Message}`; nothing is thrown to the caller.
*/

:- use_module(library(error)).
:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module(library(time)).
:- use_module(library(http/json)).


%!  json_query(+Request, -JSON) is det.
%   Request is `[Text, Bindings, Offset, Limit, Seconds]`: the query text, a list of
%   `[Name, Value]` pairs binding the query's variables by name, how many solutions to skip,
%   at most how many to return, and the time limit in seconds. JSON is a string:
%   `{"solutions": [{Var: Value}], "more": Bool, "offset": N}` or `{"error": Message}`.
json_query(Request, JSON) :-
    catch(page(Request, Dict), Error, error_dict(Error, Dict)),
    !,
    with_output_to(string(JSON), json_write_dict(current_output, Dict, [width(0)])).

page([Text, Bindings, Offset, Limit, Seconds], _{solutions: Solutions, more: More, offset: Offset}) :-
    must_be(nonneg, Offset),
    must_be(positive_integer, Limit),
    must_be(number, Seconds),
    term_string(Goal, Text, [variable_names(Names)]),
    maplist(bind(Names), Bindings),
    safe_query(Goal),
    Take is Limit + 1,
    call_with_time_limit(Seconds, findall(Names, limit(Take, offset(Offset, user:Goal)), Rows)),
    length(Rows, Got),
    (   Got > Limit
    ->  More = true, length(Page, Limit), append(Page, _, Rows)
    ;   More = false, Page = Rows
    ),
    maplist(solution_dict, Page, Solutions).

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

error_dict(Error, _{error: Message}) :-
    error_message(Error, Message).

error_message(time_limit_exceeded, "the query ran past its time limit") :- !.
error_message(error(permission_error(call, service_query, PI), _), M) :- !,
    format(string(M), "~q is not allowed in a service query (only KnowRob model predicates, the odb model, the answers and pure builtins)", [PI]).
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
%   True when Goal only reads; otherwise raises `permission_error(call, service_query, PI)`
%   naming the first predicate that is not allowed (or an instantiation error for a variable).
safe_query(Goal) :-
    var(Goal), !,
    instantiation_error(Goal).
safe_query(Module:Goal) :- !,
    (   atom(Module), model_module(Module), callable(Goal), functor(Goal, N, A), exported(Module, N/A)
    ->  safe_query(Goal)
    ;   permission_error(call, service_query, Module:Goal)
    ).
safe_query(Goal) :-
    control(Goal, Inner), !,
    maplist(safe_query, Inner).
safe_query(Goal) :-
    callable(Goal),
    functor(Goal, Name, Arity),
    (   builtin(Name/Arity)
    ->  true
    ;   meta_model(Name/Arity, Index)
    ->  arg(Index, Goal, Inner),
        safe_query(Inner)
    ;   model_module(M), exported(M, Name/Arity), \+ writer(Name/Arity)
    ->  true
    ;   permission_error(call, service_query, Name/Arity)
    ).

%   The project's model modules: every module loaded from this folder's lang/, model/ and
%   odb/ (KnowRob's layout) and the answers; never the store itself, this module or fixtures.
:- dynamic prolog_dir/1.
:- prolog_load_context(directory, Dir), atom_concat(Dir, '/', Prefix),
   retractall(prolog_dir(_)), assertz(prolog_dir(Prefix)).

model_module(Module) :-
    prolog_dir(Prefix),
    module_property(Module, file(File)),
    atom_concat(Prefix, Relative, File),
    (   sub_atom(Relative, 0, _, _, 'lang/')
    ;   sub_atom(Relative, 0, _, _, 'model/')
    ;   sub_atom(Relative, 0, _, _, 'odb/')
    ;   Relative == 'answers.pl'
    ).

exported(Module, PI) :-
    module_property(Module, exports(List)),
    memberchk(PI, List).

%   Exported predicates that change state: the robot API writes, queries do not.
writer(kb_project/1).
writer(odb_set_namespace/1).
writer(odb_set_task_roles/3).
writer(answer_json/1).

%   Model predicates whose argument Index is itself a goal (compiled, or called).
meta_model(kb_call/1, 1).
meta_model(kb_call/2, 1).
meta_model(kb_call_stepwise/1, 1).
meta_model(kb_call_stepwise/2, 1).
meta_model(kb_compile/3, 1).
meta_model(during/2, 1).
meta_model(since/2, 1).
meta_model(until/2, 1).

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
control(aggregate_all(_, A, _), [A]).
control(limit(_, A), [A]).
control(offset(_, A), [A]).
control(order_by(_, A), [A]).

builtin(true/0). builtin(fail/0). builtin(false/0).
builtin((=)/2). builtin((\=)/2). builtin((==)/2). builtin((\==)/2).
builtin((@<)/2). builtin((@>)/2). builtin((@=<)/2). builtin((@>=)/2). builtin(compare/3).
builtin((is)/2). builtin((<)/2). builtin((>)/2). builtin((=<)/2). builtin((>=)/2).
builtin((=:=)/2). builtin((=\=)/2).
builtin(var/1). builtin(nonvar/1). builtin(atom/1). builtin(number/1). builtin(integer/1).
builtin(float/1). builtin(string/1). builtin(is_list/1). builtin(compound/1). builtin(ground/1).
builtin(functor/3). builtin(arg/3). builtin((=..)/2).
builtin(atom_concat/3). builtin(sub_atom/5). builtin(atom_string/2). builtin(atom_length/2).
builtin(atom_number/2). builtin(term_to_atom/2). builtin(atomic_list_concat/2).
builtin(atomic_list_concat/3). builtin(split_string/4). builtin(string_concat/3).
builtin(member/2). builtin(memberchk/2). builtin(length/2). builtin(nth0/3). builtin(nth1/3).
builtin(last/2). builtin(append/3). builtin(reverse/2). builtin(msort/2). builtin(sort/2).
builtin(sort/4).
builtin(list_to_set/2). builtin(sum_list/2). builtin(max_list/2). builtin(min_list/2).
builtin(between/3). builtin(succ/2). builtin(plus/3). builtin(pairs_keys_values/3).
