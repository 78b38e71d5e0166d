:- module(store_write,
    [ store_insert/1,           % +Triples
      store_insert/2,           % +Triples, +Merge
      store_insert/3,           % +Triples, +Merge, +Graph
      store_retract/1           % +Patterns
    ]).
/** <module> Triple writes: kb_project/1 and kb_unproject/1 on the current backend

Both backends merge a new fact with its stored copies the same way (the Python stores in
python/oracle/store/project.py, the memory backend in store_memory).
*/

:- use_module(library(error)).
:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module(neem, [store_backend/1]).
:- use_module(python, [store_python_call/3]).
:- use_module(memory, [store_memory_insert/3, store_memory_retract/1]).
:- use_module(pattern, [store_check_pattern/1]).

%!  store_insert(+Triples) is det.
%!  store_insert(+Triples, +Merge) is det.
%   Write a list of `triple(S,P,O,Since,Until)` into the current backend (kb_project/1).
%   Merge says what happens to a stored triple with the same S, P, O whose scope overlaps
%   the new one: `union` (the default, KnowRob's kb_project) replaces both by one triple
%   over the union of their scopes; `intersect` (KnowRob's `until`/`since` projection)
%   narrows the stored triple to the intersection instead of adding the new one. Both
%   backends do it (the Python stores in python/oracle/store/project.py).
store_insert(Triples) :-
    store_insert(Triples, union).

store_insert(Triples, Merge) :-
    store_insert(Triples, Merge, user).

%!  store_insert(+Triples, +Merge, +Graph) is det.
%   store_insert/2 into the named graph Graph (KnowRob's `graph` of a document: `user` for
%   kb_project, the ontology's name for load_owl). A fact merges with its copies in the same
%   graph.
store_insert(Triples, Merge, Graph) :-
    must_be(list, Triples),
    must_be(oneof([union, intersect]), Merge),
    must_be(atom, Graph),
    maplist(check_insert, Triples),
    (   store_backend(python(Neem))
    ->  maplist(insert_row, Triples, Rows),
        store_python_call(insert, [Neem, Merge, Graph|Rows], _)
    ;   forall(member(T, Triples), store_memory_insert(Merge, Graph, T))
    ).

check_insert(triple(S,P,O,Since,Until)) :-
    !,
    must_be(atom, S), must_be(atom, P), must_be(atomic, O),
    must_be(number, Since), must_be(number, Until).
check_insert(T) :-
    type_error(triple, T).

insert_row(triple(S,P,O,Since,Until), [S,P,O,Since,Until]).

%!  store_retract(+Patterns) is det.
%   Delete every stored triple matching one of the `t(S,P,O)` patterns (kb_unproject/1);
%   an unbound term matches any value.
store_retract(Patterns) :-
    must_be(list, Patterns),
    maplist(store_check_pattern, Patterns),
    (   store_backend(python(Neem))
    ->  maplist(retract_row, Patterns, Rows),
        store_python_call(retract, [Neem|Rows], _)
    ;   forall(member(P, Patterns), store_memory_retract(P))
    ).

retract_row(t(S, P, O), [S1, P1, O1]) :-
    maplist(retract_term, [S, P, O], [S1, P1, O1]).

retract_term(T, R) :-
    (   var(T) -> R = []
    ;   atomic(T) -> R = [T]
    ;   domain_error(retract_value, T)
    ).
