:- module(model_rdfs,
    [ instance_of/2,            % ?Individual, ?Class
      subclass_of/2,            % ?Class, ?SuperClass
      subproperty_of/2,         % ?Property, ?SuperProperty
      has_type/2,               % ?Individual, ?Class
      is_resource/1,            % ?Entity
      is_property/1,            % ?Entity
      has_range/2,              % ?Property, ?Range
      has_domain/2,             % ?Property, ?Domain
      rdf_list/2,               % ?RDFList, ?List
      rdf_list_head/2,          % ?SubList, ?Head
      new_iri/1,                % -IRI
      new_iri/2,                % -IRI, +Type
      is_literal/1,             % ?Entity
      is_datatype/1,            % ?Entity
      is_a/2,                   % +Resource, ?Type
      get_unique_name/2,        % +Prefix, -Name
      is_unique_name/1          % +Name
    ]).
/** <module> RDFS vocabulary (KnowRob 2.x src/model/RDFS.pl)

instance_of/2 and subclass_of/2 are taxonomic triple goals: a bound class matches the
asserted class and its ancestors (`o*`), a free class binds the asserted one. has_type/2
is instance_of/2 that refuses compound class expressions (with a free class, every asserted
type, owl:NamedIndividual included, as KnowRob's). is_resource/1 and is_property/1 are typed rdfs:Resource and
rdf:Property; rdf_list/2 reads (and, through kb_project/1, writes) an rdf:first/rdf:rest
list; new_iri/1,2 make an IRI not used as a subject yet.
*/

:- use_module(library(lists)).
:- use_module(library(error)).
:- use_module('../lang/query', [kb_call/1, kb_call/2]).
:- use_module('../lang/triple', [kb_iri/2]).

:- multifile kb_query:kb_rule/2.
kb_query:kb_rule(instance_of(A, B), ( pragma(\+ model_rdfs:owl_term(B)), triple(A, rdf:type, B) )).
kb_query:kb_rule(subclass_of(A, B), ( pragma(\+ model_rdfs:owl_term(B)), triple(A, rdfs:subClassOf, B) )).
kb_query:kb_rule(subproperty_of(A, B), triple(A, rdfs:subPropertyOf, B)).
kb_query:kb_rule(is_resource(A), ( member(C, [rdfs:'Resource', rdfs:'Class', owl:'Class']), has_type(A, C) )).
kb_query:kb_rule(is_property(A), ( member(C, [rdf:'Property', owl:'ObjectProperty', owl:'DatatypeProperty',
                                             owl:'AnnotationProperty']), has_type(A, C) )).
kb_query:kb_rule(has_range(P, R), triple(P, rdfs:range, R)).
kb_query:kb_rule(is_literal(A), has_type(A, rdfs:'Literal')).
kb_query:kb_rule(is_datatype(A), has_type(A, rdfs:'Datatype')).
kb_query:kb_rule(has_domain(P, D), triple(P, rdfs:domain, D)).

:- multifile kb_query:kb_projection/2.
kb_query:kb_projection(rdf_list(L, Xs), [has_type(L, rdf:'List')|Triples]) :-
    must_be(ground, L-Xs), must_be(list, Xs),
    list_triples(L, Xs, 1, Triples).

list_triples(L, [], _, [triple(L, rdf:rest, rdf:nil)]) :- !.   % only for the empty tail
list_triples(L, [X], _, [triple(L, rdf:first, X), triple(L, rdf:rest, rdf:nil)]) :- !.
list_triples(L, [X|Xs], I, [triple(L, rdf:first, X), triple(L, rdf:rest, Next)|Ts]) :-
    kb_iri(L, L1), atomic_list_concat([L1, '_', I], Next),
    I1 is I + 1,
    list_triples(Next, Xs, I1, Ts).

%   A class description of OWL (`only(P, C)`, `union_of(Cs)`, ...): model/owl_description
%   answers instance_of/2 and subclass_of/2 for these.
owl_term(T) :-
    compound(T), T \= _:_,
    functor(T, F, N),
    memberchk(F/N, [union_of/1, intersection_of/1, complement_of/1, one_of/1, only/2, some/2, value/2,
                    min/2, min/3, max/2, max/3, exactly/2, exactly/3, class/1]).

%!  instance_of(?Individual, ?Class) is nondet.
instance_of(A, B) :- kb_call(instance_of(A, B)).

%!  subclass_of(?Class, ?SuperClass) is nondet.
subclass_of(A, B) :- kb_call(subclass_of(A, B)).

%!  subproperty_of(?Property, ?SuperProperty) is nondet.
subproperty_of(A, B) :- kb_call(subproperty_of(A, B)).

%!  has_type(?Individual, ?Class) is nondet.
has_type(A, B) :- kb_call(has_type(A, B)).

%!  is_resource(?Entity) is nondet.
%   Typed rdfs:Resource, rdfs:Class or owl:Class (KnowRob reads these through the OWL
%   vocabulary's own axioms, which a NEEM does not carry).
is_resource(A) :- distinct(A, kb_call(is_resource(A))).
%!  is_property(?Entity) is nondet.
%   Typed rdf:Property or one of OWL's property classes.
is_property(A) :- distinct(A, kb_call(is_property(A))).
%!  has_range(?Property, ?Range) is nondet.
has_range(P, R) :- kb_call(has_range(P, R)).
%!  has_domain(?Property, ?Domain) is nondet.
has_domain(P, D) :- kb_call(has_domain(P, D)).

%!  rdf_list(?RDFList, ?List) is nondet.
%   List holds the rdf:first elements along the rdf:rest chain of RDFList. With RDFList
%   free, a list whose first element is List's first (List must be bound then).
rdf_list(L0, Xs) :-
    kb_iri(L0, L),
    (   var(L)
    ->  must_be(list, Xs), Xs = [First0|_], kb_iri(First0, First),
        kb_call(triple(L, rdf:first, First)),
        \+ kb_call(triple(_, rdf:rest, L))
    ;   true
    ),
    findall(X, kb_call(( triple(L, reflexive(transitive(rdf:rest)), Y), triple(Y, rdf:first, X) )), Ys),
    (   var(Xs) -> Xs = Ys ; maplist(kb_iri, Xs, Xs1), Xs1 == Ys ).

%!  rdf_list_head(?SubList, ?Head) is nondet.
%   Head is the first cell of the rdf:first/rdf:rest list that SubList (a cell of it) is the
%   rest of, or SubList itself when it is a list's first cell.
rdf_list_head(Sub0, Head0) :-
    kb_iri(Sub0, Sub), kb_iri(Head0, Head),
    (   var(Sub) -> kb_call(triple(Sub, rdf:first, _), any) ; true ),
    kb_call(triple(H, transitive(reflexive(rdf:rest)), Sub), any),
    \+ kb_call(triple(_, rdf:rest, H), any),
    Head = H.

%!  new_iri(-IRI) is det.
%!  new_iri(-IRI, +Type) is det.
%   An IRI that is no subject in the store: Type's IRI (rdfs:Resource by default) followed
%   by `_` and random letters.
new_iri(IRI) :- new_iri(IRI, rdfs:'Resource').
new_iri(IRI, Type0) :-
    kb_iri(Type0, Type),
    must_be(atom, Type),
    repeat,
    random_name(Name),
    atomic_list_concat([Type, '_', Name], IRI),
    \+ kb_call(triple(IRI, _, _), any), !.

random_name(Name) :-
    length(Cs, 10),
    maplist([C]>>(random_between(0, 51, I), nth0(I, `ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz`, C)), Cs),
    atom_codes(Name, Cs).

%!  is_literal(?Entity) is nondet.
%   Typed rdfs:Literal.
is_literal(A) :- kb_call(is_literal(A)).
%!  is_datatype(?Entity) is nondet.
%   Typed rdfs:Datatype.
is_datatype(A) :- kb_call(is_datatype(A)).

%!  is_a(+Resource, ?Type) is nondet.
%   subclass_of/2 for a class (typed owl:Class or rdfs:Class), instance_of/2 otherwise
%   (KnowRob's model/terms.pl).
is_a(A0, B) :-
    kb_iri(A0, A),
    must_be(atom, A),
    (   kb_call(( member(C, [owl:'Class', rdfs:'Class']), has_type(A, C) ))
    ->  kb_call(subclass_of(A, B))
    ;   kb_call(instance_of(A, B))
    ).

%!  get_unique_name(+Prefix, -Name) is det.
%   Prefix followed by `_` and eight random capitals, no subject in the store yet.
get_unique_name(Prefix0, Name) :-
    kb_iri(Prefix0, Prefix),
    must_be(atom, Prefix),
    repeat,
    length(Cs, 8),
    maplist([C]>>random_between(0'A, 0'Z, C), Cs),
    atom_codes(Sub, Cs),
    atomic_list_concat([Prefix, '_', Sub], Name),
    is_unique_name(Name), !.

%!  is_unique_name(+Name) is semidet.
%   No triple has Name as its subject.
is_unique_name(Name0) :-
    kb_iri(Name0, Name),
    must_be(atom, Name),
    \+ kb_call(triple(Name, _, _), any).
