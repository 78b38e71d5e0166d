:- begin_tests(query_policy).

:- use_module(query_policy).
:- use_module(library(apply)).
:- use_module(library(lists)).
:- use_module(library(filesex)).

%   Every module file under prolog/ (found by reading each .pl file's first term, loading
%   nothing) and its exported predicates.
module_export(Module, PI) :-
    module_property(query_policy, file(Self)),
    file_directory_name(Self, Dir),
    directory_member(Dir, File, [recursive(true), extensions([pl])]),
    setup_call_cleanup(open(File, read, In), catch(read_term(In, Head, []), _, fail), close(In)),
    Head = (:- module(Module, Exports)),
    member(PI, Exports),
    PI = _/_.

test(every_exported_predicate_is_classified) :-
    findall(M:PI, ( module_export(M, PI), \+ exposed(M, PI, _) ), Missing),
    (   Missing == []
    ->  true
    ;   format(user_error, "~nExports with no line in prolog/query_policy.pl (add exposed(Module, Name/Arity, read|write|hidden)):~n", []),
        forall(member(X, Missing), format(user_error, "    ~q~n", [X])),
        fail
    ).

test(every_line_names_a_real_predicate) :-
    findall(M:PI, ( exposed(M, PI, _), \+ memberchk(M, [system, lists, pairs]), \+ module_export(M, PI) ), Stale),
    Stale == [].

test(library_lines_name_their_defining_module) :-
    forall(( exposed(M, N/A, _), memberchk(M, [system, lists, pairs]) ),
           ( functor(G, N, A),
             (   predicate_property(user:G, imported_from(M))
             ;   M == system, predicate_property(system:G, built_in)
             ) )).

test(one_class_per_predicate) :-
    findall(M:PI, ( exposed(M, PI, C1), exposed(M, PI, C2), C1 \== C2 ), []),
    forall(exposed(_, _, C), memberchk(C, [read, write, hidden])).

test(goal_arguments_only_on_readers) :-
    forall(goal_argument(M, PI, _), exposed(M, PI, read)).

:- end_tests(query_policy).
