:- module(dul_object,
    [ is_object/1,              % ?Object
      is_physical_object/1,     % ?Object
      is_agent/1,               % ?Agent
      is_role/1,                % ?Role
      has_role/2,               % ?Object, ?Role
      is_classified_by/2,       % ?Entity, ?Concept
      has_region/2              % ?Entity, ?Region
    ]).
/** <module> Objects, agents and roles (KnowRob 2.x src/model/DUL/Object.pl)

Each predicate is a kb_rule/2 over DUL properties and, called from Prolog, kb_call/1 of
itself. `has_role(O, R)`: the role R classifies the object O (dul:classifies).
*/

:- use_module('../lang/query', [kb_call/1]).

:- multifile kb_query:kb_rule/2.
kb_query:kb_rule(is_object(A), has_type(A, dul:'Object')).
kb_query:kb_rule(is_physical_object(A), has_type(A, dul:'PhysicalObject')).
kb_query:kb_rule(is_agent(A), has_type(A, dul:'Agent')).
kb_query:kb_rule(is_role(A), has_type(A, dul:'Role')).
kb_query:kb_rule(has_role(O, R), holds(R, dul:classifies, O)).
kb_query:kb_rule(is_classified_by(E, C), holds(E, dul:isClassifiedBy, C)).
kb_query:kb_rule(has_region(E, R), holds(E, dul:hasRegion, R)).

%!  is_object(?Object) is nondet.
is_object(A) :- kb_call(is_object(A)).
%!  is_physical_object(?Object) is nondet.
is_physical_object(A) :- kb_call(is_physical_object(A)).
%!  is_agent(?Agent) is nondet.
is_agent(A) :- kb_call(is_agent(A)).
%!  is_role(?Role) is nondet.
is_role(A) :- kb_call(is_role(A)).
%!  has_role(?Object, ?Role) is nondet.
has_role(O, R) :- kb_call(has_role(O, R)).
%!  is_classified_by(?Entity, ?Concept) is nondet.
is_classified_by(E, C) :- kb_call(is_classified_by(E, C)).
%!  has_region(?Entity, ?Region) is nondet.
%   A quality or entity and the region (value) it has, e.g. a colour's RGB region.
has_region(E, R) :- kb_call(has_region(E, R)).
