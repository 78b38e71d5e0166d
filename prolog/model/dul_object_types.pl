:- module(dul_object_types,
    [ is_quality/1,             % ?Entity
      is_concept/1,             % ?Entity
      is_physical_artifact/1,   % ?Entity
      is_social_object/1,       % ?Entity
      is_region/1,              % ?Entity
      is_parameter/1,           % ?Entity
      is_time_interval/1,       % ?Entity
      is_space_region/1,        % ?Entity
      is_amount/1,              % ?Entity
      is_physical_attribute/1,  % ?Entity
      is_social_attribute/1,    % ?Entity
      has_object_type/2,        % ?Entity, ?Type
      has_quality_type/2,       % ?Entity, ?Type
      has_location/2,           % ?Object, ?Location
      has_part/2,               % ?Entity, ?Part
      has_data_value/2          % ?Entity, ?Value
    ]).
/** <module> Objects, qualities, concepts and regions (KnowRob 2.x src/model/DUL.pl)

The DUL type tests and relations of objects, qualities and regions that model/object.pl
does not hold. Each predicate is a kb_rule/2 (compiled into the store query of the kb_call/1
around it) and, called from Prolog, kb_call/1 of itself.
*/

:- use_module('../lang/query', [kb_call/1]).

:- multifile kb_query:kb_rule/2.
kb_query:kb_rule(is_quality(E), has_type(E, dul:'Quality')).
kb_query:kb_rule(is_concept(E), has_type(E, dul:'Concept')).
kb_query:kb_rule(is_physical_artifact(E), has_type(E, dul:'PhysicalArtifact')).
kb_query:kb_rule(is_social_object(E), has_type(E, dul:'SocialObject')).
kb_query:kb_rule(is_region(E), has_type(E, dul:'Region')).
kb_query:kb_rule(is_parameter(E), has_type(E, dul:'Parameter')).
kb_query:kb_rule(is_time_interval(E), has_type(E, dul:'TimeInterval')).
kb_query:kb_rule(is_space_region(E), has_type(E, dul:'SpaceRegion')).
kb_query:kb_rule(is_amount(E), has_type(E, dul:'Amount')).
kb_query:kb_rule(is_physical_attribute(E), has_type(E, dul:'PhysicalAttribute')).
kb_query:kb_rule(is_social_attribute(E), has_type(E, dul:'SocialAttribute')).
kb_query:kb_rule(has_object_type(E, T), ( has_type(E, T), triple(T, rdfs:subClassOf, dul:'Object') )).
kb_query:kb_rule(has_quality_type(E, T), ( has_type(E, T), triple(T, rdfs:subClassOf, dul:'Quality') )).
kb_query:kb_rule(has_location(O, L), holds(O, dul:hasLocation, L)).
kb_query:kb_rule(has_part(E, P), holds(E, dul:hasPart, P)).
kb_query:kb_rule(has_data_value(E, V), triple(E, dul:hasDataValue, V)).

%!  is_quality(?Entity) is nondet.
%   Typed dul:'Quality' (or a subclass).
is_quality(Entity) :- kb_call(is_quality(Entity)).
%!  is_concept(?Entity) is nondet.
%   Typed dul:'Concept' (or a subclass).
is_concept(Entity) :- kb_call(is_concept(Entity)).
%!  is_physical_artifact(?Entity) is nondet.
%   Typed dul:'PhysicalArtifact' (or a subclass).
is_physical_artifact(Entity) :- kb_call(is_physical_artifact(Entity)).
%!  is_social_object(?Entity) is nondet.
%   Typed dul:'SocialObject' (or a subclass).
is_social_object(Entity) :- kb_call(is_social_object(Entity)).
%!  is_region(?Entity) is nondet.
%   Typed dul:'Region' (or a subclass).
is_region(Entity) :- kb_call(is_region(Entity)).
%!  is_parameter(?Entity) is nondet.
%   Typed dul:'Parameter' (or a subclass).
is_parameter(Entity) :- kb_call(is_parameter(Entity)).
%!  is_time_interval(?Entity) is nondet.
%   Typed dul:'TimeInterval' (or a subclass).
is_time_interval(Entity) :- kb_call(is_time_interval(Entity)).
%!  is_space_region(?Entity) is nondet.
%   Typed dul:'SpaceRegion' (or a subclass).
is_space_region(Entity) :- kb_call(is_space_region(Entity)).
%!  is_amount(?Entity) is nondet.
%   Typed dul:'Amount' (or a subclass).
is_amount(Entity) :- kb_call(is_amount(Entity)).
%!  is_physical_attribute(?Entity) is nondet.
%   Typed dul:'PhysicalAttribute' (or a subclass).
is_physical_attribute(Entity) :- kb_call(is_physical_attribute(Entity)).
%!  is_social_attribute(?Entity) is nondet.
%   Typed dul:'SocialAttribute' (or a subclass).
is_social_attribute(Entity) :- kb_call(is_social_attribute(Entity)).
%!  has_object_type(?Entity, ?Type) is nondet.
%   A type of Entity below dul:Object (the asserted types; KnowRob reads the most specific).
has_object_type(Entity, Type) :- kb_call(has_object_type(Entity, Type)).
%!  has_quality_type(?Entity, ?Type) is nondet.
%   A type of Entity below dul:Quality.
has_quality_type(Entity, Type) :- kb_call(has_quality_type(Entity, Type)).
%!  has_location(?Object, ?Location) is nondet.
has_location(Object, Location) :- kb_call(has_location(Object, Location)).
%!  has_part(?Entity, ?Part) is nondet.
%   dul:hasPart (and its sub-properties).
has_part(Entity, Part) :- kb_call(has_part(Entity, Part)).
%!  has_data_value(?Entity, ?Value) is nondet.
has_data_value(Entity, Value) :- kb_call(has_data_value(Entity, Value)).
