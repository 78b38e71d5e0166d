:- module(plowl,
    [ owl_subclass_of/2,        % ?Sub, ?Sup
      owl_subproperty_of/2,     % ?Sub, ?Sup
      owl_property_range/3,     % ?Class, ?Property, ?Range
      owl_property_cardinality/5, % ?Class, ?Property, ?Range, ?Min, ?Max
      owl_individual_of/3,      % ?Individual, ?Class, +Scope
      owl_satisfied_by/3,       % +Class, ?Individual, +Scope
      owl_has/4,                % ?Subject, ?Property, ?Object, +Scope
      owl_cardinality/5         % ?Subject, ?Property, ?Class, ?Count, +Scope
    ]).
/** <module> OWL reasoning over the store (KnowRob 2.x src/reasoning/OWL/plowl)

Class-level reasoning through restrictions: owl_subclass_of/2 also holds when Sub's
restrictions imply a described Sup (`only(P, R)`: every range Sub allows on P is below R;
`some`/`min`/`max`/`exactly`: the cardinality bounds Sub's restrictions give),
owl_property_range/3 gives the most specific ranges a class allows on a property (rdfs:range
and `only` restrictions of its superclasses), owl_property_cardinality/5 the bounds of its
cardinality restrictions. Individual-level reasoning: owl_individual_of/3 checks an
individual against a class's description (its equivalent classes' restrictions, unions and
intersections), owl_has/4 follows owl:sameAs, transitive and symmetric properties, inverses,
property chains and `value` restrictions, owl_cardinality/5 counts distinct values.

Each store question is a kb_call/2 (the restriction's triples and the subclass test are one
store query, model/owl_description); the combination (ranges, bounds, counts) is Prolog,
as in KnowRob. Scope arguments are KnowRob's: `QScope->FScope`, `[Options, QScope]->FScope`
or a plain question scope (`scope(S, U)`, `any`, a scope dictionary).
*/

:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module(library(aggregate)).
:- use_module('../lang/query', [kb_call/1, kb_call/2]).
:- use_module('../lang/triple', [kb_iri/2]).
:- use_module('../lang/scope', [universal_scope/1]).
:- use_module('../model/rdfs', [subclass_of/2, subproperty_of/2, has_range/2, instance_of/2]).
:- use_module('../model/owl', [has_inverse_property/2, has_equivalent_class/2, same_as/2,
                               is_transitive_property/1, is_symmetric_property/1, has_property_chain/2,
                               is_class/1, is_object_property/1]).
:- use_module('../model/owl_description', [has_description/2, is_owl_term/1]).

                 /*******************************
                 *          CLASSES             *
                 *******************************/

%!  owl_subclass_of(?Sub, ?Sup) is nondet.
%   Sub is below Sup: stated (rdfs:subClassOf, its closure), through an equivalent class, as
%   a member of an intersection Sub is equivalent to, or (Sup a restriction, or a class
%   description term) implied by Sub's own restrictions.
owl_subclass_of(Sub0, Sup0) :-
    kb_iri(Sub0, Sub), iri_or_term(Sup0, Sup),
    (   var(Sup)
    ->  distinct(Sup, ( subclass_of(Sub, Sup) ; has_equivalent_class(Sub, Sup) ))
    ;   is_owl_term(Sup)
    ->  subclass_of_term(Sub, Sup)
    ;   once(( subclass_of(Sub, Sup)
             ; ground(Sub), has_equivalent_class(Sub, Sup)
             ; ground(Sub), has_equivalent_class(Sub, EQ), has_description(EQ, intersection_of(Cs)),
               member(C, Cs), ( C == Sup ; subclass_of(C, Sup) )
             ; has_description(Sup, D), subclass_of_term(Sub, D)
             ))
    ).

iri_or_term(T, T) :- var(T), !.
iri_or_term(T, I) :- is_owl_term(T), !, T =.. [F|As], maplist(iri_or_term, As, Is), I =.. [F|Is].
iri_or_term(L, Is) :- is_list(L), !, maplist(iri_or_term, L, Is).
iri_or_term(T, I) :- kb_iri(T, I).

subclass_of_term(Sub, D) :- subclass_of(Sub, D), !.        % a superclass is that restriction
subclass_of_term(Sub, only(P, R)) :-
    ground(Sub), ground(P), ground(R),
    findall(X, owl_property_range(Sub, P, X), Xs),
    Xs \== [],
    forall(member(X, Xs), ( X == R ; subclass_of(X, R) )).
subclass_of_term(Sub, some(P, R)) :- subclass_of_term(Sub, min(P, 1, R)).
subclass_of_term(Sub, min(P, N, R)) :-
    owl_property_cardinality(Sub, P, R, Min, _), Min >= N.
subclass_of_term(Sub, max(P, N, R)) :-
    owl_property_cardinality(Sub, P, R, _, Max), Max \== inf, Max =< N.
subclass_of_term(Sub, exactly(P, N, R)) :-
    owl_property_cardinality(Sub, P, R, N, N).
subclass_of_term(Sub, intersection_of(Cs)) :-
    forall(member(C, Cs), owl_subclass_of(Sub, C)).
subclass_of_term(Sub, union_of(Cs)) :-
    member(C, Cs), owl_subclass_of(Sub, C), !.

%   Class and its superclasses, named or anonymous (restrictions), nearest first.
class_and_ancestors(Class, All) :-
    findall(S, kb_call(triple(Class, include_parents(rdfs:subClassOf), S), any), Sups),
    list_to_set([Class|Sups], All).

%!  owl_property_range(?Class, ?Property, ?Range) is nondet.
%   Range is a most specific class that values of Property of Class's instances belong to:
%   from Property's rdfs:range and Class's `only` restrictions (and `some`/`min`/`exactly`
%   ones through their inverse property), none of the others below it.
owl_property_range(Cls0, P0, Range) :-
    kb_iri(Cls0, Cls), kb_iri(P0, P),
    (   var(Cls) -> distinct(Cls, kb_call(is_class(Cls))) ; true ),
    (   var(P) -> distinct(P, kb_call(is_object_property(P))) ; true ),
    findall(R, range_candidate(Cls, P, R), Rs0),
    list_to_set(Rs0, Rs),
    most_specific(Rs, Specific),
    member(Range, Specific).

range_candidate(_, P, R) :- kb_call(has_range(P, R), any).
range_candidate(Cls, P, R) :-
    class_and_ancestors(Cls, All),
    member(C, All),
    has_description(C, D),
    description_range(D, P, R).

description_range(only(P, R), P, R).
description_range(intersection_of(Cs), P, R) :- member(C, Cs), range_candidate(C, P, R).
description_range(union_of(Cs), P, R) :-       % a range every member of the union has
    Cs = [C0|Rest],
    range_candidate(C0, P, R),
    forall(member(C, Rest), ( range_candidate(C, P, R1), ( R1 == R ; subclass_of(R1, R) ) )).

most_specific(Rs, Specific) :-
    include(none_below(Rs), Rs, Specific).

none_below(Rs, R) :- \+ ( member(X, Rs), X \== R, subclass_of(X, R) ).

%!  owl_property_cardinality(?Class, ?Property, ?Range, ?Min, ?Max) is nondet.
%   Class's restrictions bound the number of Property values in Range of its instances
%   between Min and Max (`inf` for none): the largest lower and smallest upper bound of its
%   some/min/max/exactly restrictions (and its superclasses'), on sub-properties and
%   sub-classes for lower bounds, super-properties and super-classes for upper ones.
%   Fails when neither bound says anything (Min 0 and Max inf).
owl_property_cardinality(Cls0, P0, Range0, Min, Max) :-
    kb_iri(Cls0, Cls), kb_iri(P0, P), kb_iri(Range0, Range),
    (   var(Cls) -> distinct(Cls, kb_call(is_class(Cls))) ; true ),
    class_and_ancestors(Cls, All),
    findall(b(P1, R1, Lo, Hi), ( member(C, All), has_description(C, D), bound(D, P1, R1, Lo, Hi) ), Bounds),
    Bounds \== [],
    (   var(P) -> setof(P1, R^L^H^member(b(P1, R, L, H), Bounds), Ps), member(P, Ps) ; true ),
    (   var(Range) -> setof(R1, P2^L^H^( member(b(P2, R1, L, H), Bounds), sub_property(P2, P) ), Rs), member(Range, Rs)
    ;   true ),
    aggregate_all(max(L), ( member(b(P3, R3, L, _), Bounds), sub_property(P3, P), sub_class(R3, Range) ), Min0),
    findall(H, ( member(b(P4, R4, _, H), Bounds), H \== inf, sub_property(P, P4), sub_class(Range, R4) ), Hs),
    (   Min0 == -inf -> Min1 = 0 ; Min1 = Min0 ),
    (   Hs == [] -> Max1 = inf ; min_list(Hs, Max1) ),
    ( Min1 > 0 ; Max1 \== inf ), !,
    Min = Min1, Max = Max1.

bound(some(P, R), P, R, 1, inf).
bound(min(P, N, R), P, R, N, inf).
bound(min(P, N), P, 'http://www.w3.org/2002/07/owl#Thing', N, inf).
bound(max(P, N, R), P, R, 0, N).
bound(max(P, N), P, 'http://www.w3.org/2002/07/owl#Thing', 0, N).
bound(exactly(P, N, R), P, R, N, N).
bound(exactly(P, N), P, 'http://www.w3.org/2002/07/owl#Thing', N, N).

sub_property(P, P) :- !.
sub_property(P, Q) :- subproperty_of(P, Q), !.
sub_class(C, C) :- !.
sub_class(_, 'http://www.w3.org/2002/07/owl#Thing') :- !.
sub_class(C, D) :- subclass_of(C, D), !.

%!  owl_subproperty_of(?Sub, ?Sup) is nondet.
%   Sub is below Sup: stated (rdfs:subPropertyOf, its closure), or their inverses are.
owl_subproperty_of(Sub0, Sup0) :-
    kb_iri(Sub0, Sub), kb_iri(Sup0, Sup),
    distinct(Sub-Sup,
      (   subproperty_of(Sub, Sup)
      ;   ( ground(Sub) ; ground(Sup) ),
          (   ground(Sub)
          ->  has_inverse_property(Sub, SubInv), subproperty_of(SubInv, SupInv), has_inverse_property(Sup, SupInv)
          ;   has_inverse_property(Sup, SupInv), subproperty_of(SubInv, SupInv), has_inverse_property(Sub, SubInv)
          )
      )).

                 /*******************************
                 *         INDIVIDUALS          *
                 *******************************/

%   question_scope(+ScopeArgument, -QScope, -FScope)
question_scope(Arg, Q, F) :-
    (   var(Arg) -> universal_scope(Q)
    ;   Arg = (Q0 -> F) -> question_scope(Q0, Q, _)
    ;   Arg = [_Options, Q] -> true
    ;   Q = Arg
    ),
    (   var(F) -> F = Q ; true ).

%!  owl_individual_of(?Individual, ?Class, +Scope) is nondet.
%   Individual is an instance of Class: typed with it, or satisfying its description (with
%   Class free: its types and their superclasses).
owl_individual_of(S0, C0, Scope) :-
    kb_iri(S0, S), kb_iri(C0, C),
    question_scope(Scope, Q, _),
    (   var(C)
    ->  distinct(C, ( kb_call(has_type(S, T), Q), ( C = T ; subclass_of(T, C) ) ))
    ;   ground(S), kb_call(instance_of(S, C), Q)
    ->  true
    ;   owl_satisfied_by(C, S, Scope)
    ).

%!  owl_satisfied_by(+Class, ?Individual, +Scope) is nondet.
%   Individual satisfies the description of Class (an anonymous class, or a named class
%   through its equivalent classes).
owl_satisfied_by(C0, S0, Scope) :-
    nonvar(C0), kb_iri(C0, C), kb_iri(S0, S),
    question_scope(Scope, Q, _),
    (   ground(S) -> once(satisfies_class(C, S, Q, [])) ; distinct(S, satisfies_class(C, S, Q, [])) ).

satisfies_class(C, S, Q, Seen) :-
    \+ memberchk(C, Seen),
    (   has_description(C, D)
    ->  satisfies(D, S, Q, [C|Seen])
    ;   has_equivalent_class(C, EQ), EQ \== C,
        (   has_description(EQ, D) -> satisfies(D, S, Q, [C|Seen]) ; kb_call(has_type(S, EQ), Q) )
    ).

satisfies(intersection_of(Cs), S, Q, Seen) :-
    Cs = [C0|Rest],
    class_member(C0, S, Q, Seen),
    forall(member(C, Rest), class_member(C, S, Q, Seen)).
satisfies(union_of(Cs), S, Q, Seen) :- member(C, Cs), class_member(C, S, Q, Seen).
satisfies(complement_of(C), S, Q, Seen) :- ground(S), \+ class_member(C, S, Q, Seen).
satisfies(some(P, C), S, Q, _) :- kb_call(( holds(S, P, O), instance_of(O, C) ), Q).
satisfies(value(P, V), S, Q, _) :- owl_has(S, P, V, Q).
satisfies(only(P, C), S, Q, _) :-
    ground(S),
    forall(kb_call(holds(S, P, O), Q), kb_call(instance_of(O, C), Q)).
satisfies(min(P, N, C), S, Q, _) :- owl_cardinality(S, P, C, K, Q), K >= N.
satisfies(min(P, N), S, Q, _) :- owl_cardinality(S, P, _, K, Q), K >= N.
satisfies(max(P, N, C), S, Q, _) :- ground(S), ( owl_cardinality(S, P, C, K, Q) -> K =< N ; true ).
satisfies(max(P, N), S, Q, _) :- ground(S), ( owl_cardinality(S, P, _, K, Q) -> K =< N ; true ).
satisfies(exactly(P, N, C), S, Q, _) :- owl_cardinality(S, P, C, N, Q).
satisfies(exactly(P, N), S, Q, _) :- owl_cardinality(S, P, _, N, Q).

class_member(C, S, Q, Seen) :-
    (   kb_call(instance_of(S, C), Q) ; satisfies_class(C, S, Q, Seen) ), !.

%!  owl_has(?Subject, ?Property, ?Object, +Scope) is nondet.
%   Subject has Object as value of Property: stated (sub-properties included), stated
%   between individuals the same as them (owl:sameAs), through a transitive property's
%   chain, a symmetric property or the inverse property stated the other way, a property
%   chain (owl:propertyChainAxiom), or a `value` restriction on a type of Subject.
owl_has(S0, P0, O0, Scope) :-
    kb_iri(S0, S), kb_iri(P0, P), kb_iri(O0, O),
    question_scope(Scope, Q, _),
    distinct(S-P-O,
      (   ground(S)
      ->  same_as(S, S1), has_transitive(S1, P, O1, Q, [S1]), same_as(O1, O)
      ;   ground(O)
      ->  same_as(O, O1), has_transitive(S1, P, O1, Q, [O1]), same_as(S1, S)
      ;   has_transitive(S, P, O, Q, [])
      )).

has_transitive(S, P, O, Q, _) :- has_symmetric(S, P, O, Q).
has_transitive(S, P, O, Q, Seen) :-
    ground(P), is_transitive_property(P),
    (   nonvar(S)
    ->  has_symmetric(S, P, X, Q), \+ memberchk(X, Seen), has_transitive(X, P, O, Q, [X|Seen])
    ;   nonvar(O)
    ->  has_symmetric(X, P, O, Q), \+ memberchk(X, Seen), has_transitive(S, P, X, Q, [X|Seen])
    ).

has_symmetric(S, P, O, Q) :- has_direct(S, P, O, Q).
has_symmetric(S, P, O, Q) :- ground(P), is_symmetric_property(P), has_direct(O, P, S, Q).
has_symmetric(S, P, O, Q) :- ground(P), has_inverse_property(P, Inv), has_direct(O, Inv, S, Q).

has_direct(S, P, O, Q) :-
    kb_call(triple(S, P, O), Q),
    P \== 'http://www.w3.org/1999/02/22-rdf-syntax-ns#type'.
has_direct(S, P, O, Q) :-
    ground(P), has_property_chain(P, Chain),
    (   nonvar(S) -> chain_forward(S, Chain, O, Q)
    ;   reverse(Chain, Rev), chain_backward(O, Rev, S, Q)
    ).
has_direct(S, P, O, Q) :-
    nonvar(S), ground(P),
    kb_call(( has_type(S, T), triple(T, rdfs:subClassOf, R), triple(R, owl:onProperty, P),
              triple(R, owl:hasValue, O) ), Q).

chain_forward(O, [], O, _).
chain_forward(S, [P|Ps], O, Q) :- owl_has(S, P, X, Q), chain_forward(X, Ps, O, Q).
chain_backward(S, [], S, _).
chain_backward(O, [P|Ps], S, Q) :- owl_has(X, P, O, Q), chain_backward(X, Ps, S, Q).

%!  owl_cardinality(?Subject, ?Property, ?Class, ?Count, +Scope) is nondet.
%   Count (> 0 when unbound) distinct values of Property of Subject are instances of Class.
owl_cardinality(S0, P0, C0, Count, Scope) :-
    kb_iri(S0, S), kb_iri(P0, P), kb_iri(C0, C),
    question_scope(Scope, Q, _),
    findall(S-P-C-V, kb_call(( triple(S, P, V), instance_of(V, C) ), Q), Facts0),
    Facts0 \== [],
    sort(Facts0, Facts),
    setof(S-P-C, V^member(S-P-C-V, Facts), Keys),
    member(S-P-C, Keys),
    aggregate_all(count, member(S-P-C-_, Facts), N),
    (   var(Count) -> N > 0 ; true ),
    Count = N.
