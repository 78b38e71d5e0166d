:- module(model_owl,
    [ is_class/1,               % ?Entity
      is_restriction/1,         % ?Entity
      is_individual/1,          % ?Entity
      is_all_disjoint_classes/1, % ?Entity
      is_object_property/1,     % ?Entity
      is_data_property/1,       % ?Entity
      is_functional_property/1, % ?Entity
      is_transitive_property/1, % ?Entity
      is_symmetric_property/1,  % ?Entity
      has_inverse_property/2,   % ?Property, ?Inverse
      has_property_chain/2,     % ?Property, ?Chain
      has_equivalent_class/2,   % ?Class1, ?Class2
      same_as/2,                % ?Individual1, ?Individual2
      disjoint_with/2,          % ?Class1, ?Class2
      disjoint_with_direct/2    % ?Class1, ?Class2
    ]).
/** <module> OWL axioms (KnowRob 2.x src/model/OWL.pl)

Each predicate is a kb_rule/2 over the OWL vocabulary's triples, so it is compiled into the
store query of the kb_call/1 around it; called from Prolog it is kb_call/1 of itself. The
class descriptions (restrictions, unions, ...) are model/owl_description.pl.

owl:Thing and owl:Nothing are classes here as in KnowRob, which loads OWL's own axioms; a
NEEM does not carry them.
*/

:- use_module('../lang/query', [kb_call/1]).
:- use_module('../lang/triple', [kb_iri/2]).
:- use_module(rdfs, [rdf_list/2, rdf_list_head/2]).

:- multifile kb_query:kb_rule/2.
kb_query:kb_rule(is_class(E), ( has_type(E, owl:'Class') ; model_owl:owl_builtin_class(E) )).
kb_query:kb_rule(is_restriction(E), has_type(E, owl:'Restriction')).
kb_query:kb_rule(is_individual(E), has_type(E, owl:'NamedIndividual')).
kb_query:kb_rule(is_all_disjoint_classes(E), has_type(E, owl:'AllDisjointClasses')).
kb_query:kb_rule(is_object_property(E), has_type(E, owl:'ObjectProperty')).
kb_query:kb_rule(is_data_property(E), has_type(E, owl:'DatatypeProperty')).
kb_query:kb_rule(is_functional_property(E), has_type(E, owl:'FunctionalProperty')).
kb_query:kb_rule(is_transitive_property(E), has_type(E, owl:'TransitiveProperty')).
kb_query:kb_rule(is_symmetric_property(E), has_type(E, owl:'SymmetricProperty')).
kb_query:kb_rule(has_inverse_property(P, Q), ( triple(P, owl:inverseOf, Q) ; triple(Q, owl:inverseOf, P) )).
kb_query:kb_rule(has_property_chain(P, Chain), ( triple(P, owl:propertyChainAxiom, L), rdf_list(L, Chain) )).
kb_query:kb_rule(same_as(X, Y), ( X = Y ; triple(X, owl:sameAs, Y) ; triple(Y, owl:sameAs, X) )).
kb_query:kb_rule(disjoint_with_direct(A, B),
                 ( triple(A, owl:disjointWith, B)
                 ; triple(B, owl:disjointWith, A)
                 ; pragma(ground(A)), model_owl:disjoint_members(A, B) )).

%   owl:Thing and owl:Nothing.
owl_builtin_class(E) :-
    member(E, ['http://www.w3.org/2002/07/owl#Thing', 'http://www.w3.org/2002/07/owl#Nothing']).

%!  is_class(?Entity) is nondet.
is_class(E) :- kb_call(is_class(E)).
%!  is_restriction(?Entity) is nondet.
is_restriction(E) :- kb_call(is_restriction(E)).
%!  is_individual(?Entity) is nondet.
%   Typed owl:NamedIndividual.
is_individual(E) :- kb_call(is_individual(E)).
%!  is_all_disjoint_classes(?Entity) is nondet.
is_all_disjoint_classes(E) :- kb_call(is_all_disjoint_classes(E)).
%!  is_object_property(?Entity) is nondet.
is_object_property(E) :- kb_call(is_object_property(E)).
%!  is_data_property(?Entity) is nondet.
is_data_property(E) :- kb_call(is_data_property(E)).
%!  is_functional_property(?Entity) is nondet.
is_functional_property(E) :- kb_call(is_functional_property(E)).
%!  is_transitive_property(?Entity) is nondet.
is_transitive_property(E) :- kb_call(is_transitive_property(E)).
%!  is_symmetric_property(?Entity) is nondet.
is_symmetric_property(E) :- kb_call(is_symmetric_property(E)).
%!  has_inverse_property(?Property, ?Inverse) is nondet.
%   owl:inverseOf, stated either way.
has_inverse_property(P, Q) :- kb_call(has_inverse_property(P, Q)).
%!  has_property_chain(?Property, ?Chain) is nondet.
%   Chain is the list of properties of P's owl:propertyChainAxiom.
has_property_chain(P, Chain) :- kb_call(has_property_chain(P, Chain)).
%!  same_as(?X, ?Y) is nondet.
%   X = Y, or owl:sameAs stated either way.
same_as(X, Y) :- kb_call(same_as(X, Y)).

%!  has_equivalent_class(?Class1, ?Class2) is nondet.
%   owl:equivalentClass stated either way, or reached over a chain of them; one of the two
%   must be bound (as KnowRob, which fails when both are free).
has_equivalent_class(X, Y) :-
    (   ground(X) -> kb_call(triple(X, transitive(owl:equivalentClass), Y))
    ;   ground(Y) -> kb_call(triple(X, transitive(owl:equivalentClass), Y))
    ;   fail
    ).
has_equivalent_class(X, Y) :-
    (   ground(X) -> kb_call(triple(Y, transitive(owl:equivalentClass), X)), Y \== X
    ;   ground(Y) -> kb_call(triple(Y, transitive(owl:equivalentClass), X)), X \== Y
    ).

%!  disjoint_with_direct(?Class1, ?Class2) is nondet.
%   owl:disjointWith stated either way, or both members of one owl:AllDisjointClasses
%   (Class1 bound).
disjoint_with_direct(A, B) :- kb_call(disjoint_with_direct(A, B)).

%!  disjoint_with(?Class1, ?Class2) is nondet.
%   Directly disjoint, or (one of them bound) through their superclasses.
disjoint_with(A, B) :- disjoint_with_direct(A, B).
disjoint_with(A, B) :-
    (   ground(A) -> disjoint_indirect(A, B)
    ;   ground(B) -> disjoint_indirect(B, A)
    ).

%   A's superclass SupA is disjoint with SupB, and B is SupB or below it.
disjoint_indirect(A, B) :-
    kb_call(( triple(A, include_parents(rdfs:subClassOf), SupA), SupA \== A )),
    disjoint_with_direct(SupA, SupB),
    (   var(B) -> B = SupB
    ;   B == SupB -> true
    ;   kb_call(triple(B, rdfs:subClassOf, SupB))
    ).

%   A and B are members of one owl:AllDisjointClasses.
disjoint_members(A0, B) :-
    kb_iri(A0, A),
    kb_call(triple(Cell, rdf:first, A)),
    rdf_list_head(Cell, Head),
    kb_call(( triple(DC, owl:members, Head), is_all_disjoint_classes(DC) )),
    rdf_list(Head, Members),
    member(B, Members),
    B \== A.
