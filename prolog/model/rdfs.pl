:- module(model_rdfs,
    [ instance_of/2,            % ?Individual, ?Class
      subclass_of/2,            % ?Class, ?SuperClass
      subproperty_of/2,         % ?Property, ?SuperProperty
      has_type/2                % ?Individual, ?Class
    ]).
/** <module> RDFS vocabulary (KnowRob 2.x src/model/RDFS.pl)

instance_of/2 and subclass_of/2 are taxonomic triple goals: a bound class matches the
asserted class and its ancestors (`o*`), a free class binds the asserted one. has_type/2
is instance_of/2 that refuses compound class expressions and, with a free class, leaves
out owl:NamedIndividual.
*/

:- use_module('../lang/query', [kb_call/1]).

:- multifile kb_query:kb_rule/2.
kb_query:kb_rule(instance_of(A, B), triple(A, rdf:type, B)).
kb_query:kb_rule(subclass_of(A, B), triple(A, rdfs:subClassOf, B)).
kb_query:kb_rule(subproperty_of(A, B), triple(A, rdfs:subPropertyOf, B)).

%!  instance_of(?Individual, ?Class) is nondet.
instance_of(A, B) :- kb_call(instance_of(A, B)).

%!  subclass_of(?Class, ?SuperClass) is nondet.
subclass_of(A, B) :- kb_call(subclass_of(A, B)).

%!  subproperty_of(?Property, ?SuperProperty) is nondet.
subproperty_of(A, B) :- kb_call(subproperty_of(A, B)).

%!  has_type(?Individual, ?Class) is nondet.
has_type(A, B) :- kb_call(has_type(A, B)).
