:- module(store_pattern,
    [ store_taxonomic/1,        % ?Property
      store_closure_edge/1,     % ?Property
      store_check_pattern/1,    % @Pattern
      store_check_term/1,       % @Term
      store_compare/3           % +Operator, +Value, +Number
    ]).
/** <module> What a store pattern may say

A store query is a list of triple patterns `t(S, P, O)`: each term a variable or an atomic
value, the object also `cmp(Op, Number, X)` (the stored object compared with a number, X
bound to it) or `cmp(Op1, Number1, Op2, Number2, X)` (with two numbers: a range, which the
store answers with one index range where two patterns would scan from one bound on). This module checks them at the boundary and holds the rule of KnowRob 2.x's
`p*`/`o*` semantics (knowrob-2x-facts §5) that every backend shares: which properties are
taxonomic, so that a bound object is matched against its class closure `o*` instead of
the property against its closure `p*`.
*/

:- use_module(library(error)).

rdf_type('http://www.w3.org/1999/02/22-rdf-syntax-ns#type').
subclass_of_iri('http://www.w3.org/2000/01/rdf-schema#subClassOf').
subproperty_of_iri('http://www.w3.org/2000/01/rdf-schema#subPropertyOf').

%!  store_taxonomic(?Property) is nondet.
%   Property is one of the three taxonomic properties whose object is closed over `o*`.
store_taxonomic(P) :- rdf_type(P).
store_taxonomic(P) :- subclass_of_iri(P).
store_taxonomic(P) :- subproperty_of_iri(P).

%!  store_closure_edge(?Property) is nondet.
%   Property is rdfs:subClassOf or rdfs:subPropertyOf: the edges a closure (`o*`, `p*`)
%   climbs from a class or property to its ancestors.
store_closure_edge(P) :- subclass_of_iri(P).
store_closure_edge(P) :- subproperty_of_iri(P).

%!  store_check_pattern(@Pattern) is det.
%   Pattern is `t(S, P, O)` with S and P variables or atomic and O also `cmp(Op, Number, X)`
%   or `cmp(Op1, Number1, Op2, Number2, X)` (each Op one of `<`, `=<`, `>`, `>=`); raises a
%   type or domain error otherwise.
store_check_pattern(t(S,P,O)) :-
    !,
    store_check_term(S), store_check_term(P), check_object(O).
store_check_pattern(X) :-
    type_error(triple_pattern, X).

%   cmp(Op, Number, X): the object compared with a number in the database; X binds it.
%   cmp(Op1, Number1, Op2, Number2, X): compared with two numbers (both must hold).
check_object(C) :-
    nonvar(C), C = cmp(Op, A, _), !,
    check_comparison(Op, A).
check_object(C) :-
    nonvar(C), C = cmp(Op1, A1, Op2, A2, _), !,
    check_comparison(Op1, A1),
    check_comparison(Op2, A2).
check_object(O) :-
    store_check_term(O).

check_comparison(Op, A) :-
    must_be(oneof([<, =<, >, >=]), Op),
    must_be(number, A).

%!  store_check_term(@Term) is det.
%   Term is a variable or atomic; raises `type_error(atomic_or_var, Term)` otherwise.
store_check_term(X) :- var(X), !.
store_check_term(X) :- atomic(X), !.
store_check_term(X) :- type_error(atomic_or_var, X).

%!  store_compare(+Operator, +Value, +Number) is semidet.
%   Value stands in relation Operator (`<`, `=<`, `>`, `>=`) to Number: the test of a
%   `cmp(Operator, Number, Value)` object.
store_compare(<, X, A) :- X < A.
store_compare(=<, X, A) :- X =< A.
store_compare(>, X, A) :- X > A.
store_compare(>=, X, A) :- X >= A.
