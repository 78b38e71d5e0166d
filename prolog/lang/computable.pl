:- module(kb_computable,
    [ computables/1,            % +Declarations
      add_computable_predicate/2, % +Indicator, :Goal
      add_computable_property/2,  % +Property, :Goal
      drop_computable_predicate/1, % +Module
      drop_computable_predicate/2, % +Module, +Indicator
      drop_computable_property/1,  % +Module
      drop_computable_property/2   % +Module, +Property
    ]).
/** <module> Computable predicates and properties (KnowRob 2.x src/lang/computable.pl)

A computable predicate is a model predicate answered by Prolog code instead of stored
triples: `add_computable_predicate(distance/3, my_module:compute_distance)` makes
`distance(A, B, D)` inside kb_call/1 call `my_module:compute_distance(A, B, D)`. A
computable property makes `triple(S, P, O)` and `holds(S, P, O)` for that property call
`Module:Goal(S, O)`. The compiler calls them where they stand in the goal, between the
store queries of the triple goals before and after (kb_query:kb_scoped_goal/3).
*/

:- use_module(library(error)).
:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module(triple, [kb_iri/2]).

:- dynamic computable_predicate/3.      % Name/Arity, Module, Functor
:- dynamic computable_property/3.       % Property, Module, Functor

:- meta_predicate add_computable_predicate(+, :), add_computable_property(+, :).

%!  add_computable_predicate(+Indicator, :Goal) is det.
%   Name/Arity inside kb_call/1 is answered by Goal (a predicate name, called with the
%   goal's arguments).
add_computable_predicate(Ind, M:Goal) :-
    must_be(ground, Ind), Ind = Name/Arity, must_be(atom, Name), must_be(nonneg, Arity),
    must_be(atom, Goal),
    assertz(computable_predicate(Ind, M, Goal)).

%!  add_computable_property(+Property, :Goal) is det.
%   triple(S, Property, O) inside kb_call/1 is answered by Goal(S, O).
add_computable_property(P0, M:Goal) :-
    kb_iri(P0, P), must_be(atom, P), must_be(atom, Goal),
    assertz(computable_property(P, M, Goal)).

%!  drop_computable_predicate(+Module) is det.
%!  drop_computable_predicate(+Module, +Indicator) is det.
drop_computable_predicate(M) :- must_be(atom, M), retractall(computable_predicate(_, M, _)).
drop_computable_predicate(M, Ind) :- must_be(atom, M), must_be(ground, Ind), retractall(computable_predicate(Ind, M, _)).

%!  drop_computable_property(+Module) is det.
%!  drop_computable_property(+Module, +Property) is det.
drop_computable_property(M) :- must_be(atom, M), retractall(computable_property(_, M, _)).
drop_computable_property(M, P0) :-
    must_be(atom, M), kb_iri(P0, P), must_be(atom, P),
    retractall(computable_property(P, M, _)).

%!  computables(+Declarations) is det.
%   KnowRob's declaration `computables(M:(Name/Arity, ...))`: each `Functor(Arity)` or
%   `Functor(Arity, Options)` of module M, with `functor(LangName)` (the name in queries,
%   default Functor) or `property(P)` (a computable property, arity 2).
computables(M:Decls) :-
    must_be(atom, M),
    comma_list(Decls, List),
    maplist(computable(M), List).

computable(M, Decl) :-
    Decl =.. [F, Arity|Rest],
    (   Rest == [] -> Options = [] ; Rest = [Options] ),
    (   ( memberchk(property(P), Options) ; memberchk(propery(P), Options) )   % KnowRob's spelling too
    ->  must_be(oneof([2]), Arity), add_computable_property(P, M:F)
    ;   ( memberchk(functor(Name), Options) -> true ; Name = F ),
        add_computable_predicate(Name/Arity, M:F)
    ).

:- multifile kb_query:kb_scoped_goal/3.
kb_query:kb_scoped_goal(G, _, Call) :-
    computed(G, Call).

computed(G, M:G1) :-
    G \= triple(_, _, _), G \= holds(_, _, _),
    functor(G, F, N),
    computable_predicate(F/N, M, Functor), !,
    G =.. [_|Args], G1 =.. [Functor|Args].
computed(G, M:G1) :-
    ( G = triple(S, P0, O) ; G = holds(S, P0, O) ),
    nonvar(P0), kb_iri(P0, P), atom(P),
    computable_property(P, M, Functor), !,
    G1 =.. [Functor, S, O].
