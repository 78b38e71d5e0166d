:- module(model_owl_description,
    [ is_owl_term/1,            % @Term
      is_restriction_term/1,    % @Term
      is_restriction/2,         % ?Restriction, ?Description
      is_union_of/2,            % ?Class, ?union_of(Classes)
      is_intersection_of/2,     % ?Class, ?intersection_of(Classes)
      is_complement_of/2,       % ?Class, ?complement_of(Class)
      has_description/2,        % +Class, ?Description
      instance_of_description/2 % ?Individual, +Description
    ]).
/** <module> OWL class descriptions (KnowRob 2.x src/model/OWL.pl)

A class description is a term: `only(P, C)`, `some(P, C)`, `value(P, V)`, `min(P, N)`,
`min(P, N, C)`, `max(P, N[, C])`, `exactly(P, N[, C])` (restrictions), `union_of(Cs)`,
`intersection_of(Cs)`, `complement_of(C)`. has_description/2 reads the description of an
anonymous class (a restriction's blank node) from its triples.

As in KnowRob, instance_of/2, subclass_of/2 and holds/3 accept descriptions:
`subclass_of(C, only(P, R))` holds when a superclass of C is that restriction,
`instance_of(I, some(P, C))` when a type of I is below it, `holds(I, P, only(C))` is
`instance_of(I, only(P, C))`, and `instance_of(I, intersection_of([A, B]))` is both
instance_of/2 goals. Each is a kb_rule/2: the restriction's triples and the subclass test
become one store query (the test reads the class's `o*` closure, which holds its
restrictions), where KnowRob's mongolog follows `transitive(rdfs:subClassOf)`.
*/

:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module('../lang/query', [kb_call/1]).
:- use_module('../lang/triple', [kb_iri/2]).
:- use_module(rdfs, [rdf_list/2]).

:- multifile kb_query:kb_rule/2.
kb_query:kb_rule(is_restriction(R, only(P, O)), ( triple(R, owl:onProperty, P), triple(R, owl:allValuesFrom, O) )).
kb_query:kb_rule(is_restriction(R, some(P, O)), ( triple(R, owl:onProperty, P), triple(R, owl:someValuesFrom, O) )).
kb_query:kb_rule(is_restriction(R, value(P, O)), ( triple(R, owl:onProperty, P), triple(R, owl:hasValue, O) )).
kb_query:kb_rule(is_restriction(R, min(P, M, O)),
                 ( triple(R, owl:onProperty, P), triple(R, owl:minQualifiedCardinality, M), triple(R, owl:onClass, O) )).
kb_query:kb_rule(is_restriction(R, min(P, M)), ( triple(R, owl:onProperty, P), triple(R, owl:minCardinality, M) )).
kb_query:kb_rule(is_restriction(R, max(P, M, O)),
                 ( triple(R, owl:onProperty, P), triple(R, owl:maxQualifiedCardinality, M), triple(R, owl:onClass, O) )).
kb_query:kb_rule(is_restriction(R, max(P, M)), ( triple(R, owl:onProperty, P), triple(R, owl:maxCardinality, M) )).
kb_query:kb_rule(is_restriction(R, exactly(P, M, O)),
                 ( triple(R, owl:onProperty, P), triple(R, owl:qualifiedCardinality, M), triple(R, owl:onClass, O) )).
kb_query:kb_rule(is_restriction(R, exactly(P, M)), ( triple(R, owl:onProperty, P), triple(R, owl:cardinality, M) )).
kb_query:kb_rule(is_union_of(C, union_of(L)), ( triple(C, owl:unionOf, RL), rdf_list(RL, L) )).
kb_query:kb_rule(is_intersection_of(C, intersection_of(L)), ( triple(C, owl:intersectionOf, RL), rdf_list(RL, L) )).
kb_query:kb_rule(is_complement_of(C, complement_of(X)), triple(C, owl:complementOf, X)).
kb_query:kb_rule(has_description(C, D),
                 ( is_restriction(C, D) ; is_union_of(C, D) ; is_intersection_of(C, D) ; is_complement_of(C, D) )).
kb_query:kb_rule(instance_of(S, D), ( pragma(model_rdfs:owl_term(D)), instance_of_description(S, D) )).
kb_query:kb_rule(subclass_of(C, D), ( pragma(model_rdfs:owl_term(D)), subclass_of_description(C, D) )).
kb_query:kb_rule(instance_of_description(S, D), ( pragma(model_owl_description:combination(S, D, G)), G )).
kb_query:kb_rule(instance_of_description(S, D),
                 ( pragma(\+ model_owl_description:combination(S, D, _)),
                   has_description(X, D), triple(S, rdf:type, X) )).
kb_query:kb_rule(subclass_of_description(C, D), ( has_description(X, D), triple(C, rdfs:subClassOf, X) )).

%!  is_owl_term(@Term) is semidet.
%   Term is a class description term (restriction, union_of/1, intersection_of/1,
%   complement_of/1, one_of/1).
is_owl_term(T) :- nonvar(T), ( memberchk_functor(T, [union_of/1, intersection_of/1, complement_of/1, one_of/1]) -> true ; is_restriction_term(T) ).

%!  is_restriction_term(@Term) is semidet.
is_restriction_term(T) :-
    nonvar(T),
    memberchk_functor(T, [only/2, some/2, value/2, min/2, min/3, max/2, max/3, exactly/2, exactly/3]).

memberchk_functor(T, Fs) :- compound(T), functor(T, F, N), memberchk(F/N, Fs).

%!  is_restriction(?Restriction, ?Description) is nondet.
%   Restriction (an owl:Restriction, usually a blank node) restricts as Description says.
is_restriction(R, D) :- kb_call(is_restriction(R, D)).
%!  is_union_of(?Class, ?Union) is nondet.
%   Union is `union_of(Classes)`, Class's owl:unionOf.
is_union_of(C, D) :- kb_call(is_union_of(C, D)).
%!  is_intersection_of(?Class, ?Intersection) is nondet.
is_intersection_of(C, D) :- kb_call(is_intersection_of(C, D)).
%!  is_complement_of(?Class, ?Complement) is nondet.
is_complement_of(C, D) :- kb_call(is_complement_of(C, D)).

%!  has_description(+Class, ?Description) is semidet.
%   The description of an anonymous class; fails for a free Class (as KnowRob).
has_description(C, D) :-
    nonvar(C),
    once(kb_call(has_description(C, D))).

%!  instance_of_description(?Individual, +Description) is nondet.
%   Individual is an instance of the described class: of each class of an intersection_of/1,
%   of one of a union_of/1, or of a type below the restriction.
instance_of_description(S, D) :-
    must_be(nonvar, D),
    kb_call(instance_of_description(S, D)).

%   combination(+S, +D, -Goal): the instance_of/2 goals a union or intersection stands for.
combination(S, D, G) :-
    nonvar(D),
    (   D = intersection_of(Cs) -> must_be(list, Cs), maplist(instance_goal(S), Cs, Gs), conj(Gs, G)
    ;   D = union_of(Cs) -> must_be(list, Cs), maplist(instance_goal(S), Cs, Gs), disj(Gs, G)
    ;   D = class(C) -> G = instance_of(S, C)
    ).

instance_goal(S, C, instance_of(S, C)).
conj([], true).
conj([G], G) :- !.
conj([G|Gs], (G, R)) :- conj(Gs, R).
disj([], fail).
disj([G], G) :- !.
disj([G|Gs], (G ; R)) :- disj(Gs, R).
