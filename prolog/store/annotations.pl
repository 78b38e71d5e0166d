:- module(store_annotations,
    [ store_annotation/3,       % ?Subject, ?Property, ?Value
      store_insert_annotations/1 % +Annotations
    ]).
/** <module> Annotations: labels, comments and other annotation values

KnowRob keeps these in the `annotations` collection, apart from the triples: no scopes, no
closures, no graphs.
*/

:- use_module(library(error)).
:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module(neem, [store_backend/1]).
:- use_module(python, [store_python_call/3]).
:- use_module(pattern, [store_check_term/1]).

:- dynamic mem_annotation/3.    % S, P, Value

:- multifile store_neem:memory_facts/1.
store_neem:memory_facts(store_annotations:mem_annotation(_, _, _)).

%!  store_annotation(?Subject, ?Property, ?Value) is nondet.
%   A label, comment or other annotation value of Subject (atomic or a variable) under
%   Property (atomic or a variable).
store_annotation(S, P, V) :-
    store_check_term(S), store_check_term(P),
    (   store_backend(python(Neem))
    ->  ( atom(S) -> S1 = S ; S1 = '' ),
        ( atom(P) -> P1 = P ; P1 = '' ),
        store_python_call(annotations, [Neem, S1, P1], Rows),
        member([S, P, V], Rows)
    ;   mem_annotation(S, P, V)
    ).

%!  store_insert_annotations(+Annotations) is det.
%   Store a list of `annotation(S, P, Value)` in the annotations collection (a copy of one
%   stored already is not added again).
store_insert_annotations(As) :-
    must_be(list, As),
    maplist(check_annotation, As),
    (   store_backend(python(Neem))
    ->  findall([S, P, V], member(annotation(S, P, V), As), Rows),
        store_python_call(annotate, [Neem|Rows], _)
    ;   forall(member(annotation(S, P, V), As),
               ( mem_annotation(S, P, V) -> true ; assertz(mem_annotation(S, P, V)) ))
    ).

check_annotation(annotation(S, P, V)) :- !,
    must_be(atom, S), must_be(atom, P), must_be(atomic, V).
check_annotation(A) :-
    type_error(annotation, A).
