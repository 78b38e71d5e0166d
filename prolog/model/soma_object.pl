:- module(soma_object,
    [ is_feature/1,             % ?Entity
      is_affordance/1,          % ?Entity
      is_disposition/1,         % ?Entity
      is_physical_quality/1,    % ?Entity
      is_social_quality/1,      % ?Entity
      is_intrinsic/1,           % ?Entity
      is_extrinsic/1,           % ?Entity
      object_feature/2,         % ?Object, ?Feature
      object_feature_type/3,    % ?Object, ?Feature, ?Type
      has_disposition/2,        % ?Object, ?Disposition
      has_disposition_type/3,   % ?Object, ?Disposition, ?Type
      disposition_trigger_type/2,% ?Disposition, ?TriggerType
      is_patient/1,             % ?Entity
      is_instrument/1,          % ?Entity
      is_location/1,            % ?Entity
      is_destination/1,         % ?Entity
      is_origin/1               % ?Entity
    ]).
/** <module> Features, dispositions, qualities and the roles objects play (KnowRob 2.x src/model/SOMA.pl)

SOMA's object-side vocabulary: features, affordances and dispositions (with their trigger
types, read from `only` restrictions), physical and social qualities, and whether an object
plays a patient, instrument, location, destination or origin role (has_role/2 and the role's
type). Each is a kb_rule/2 and, called from Prolog, kb_call/1 of itself.
*/

:- use_module('../lang/query', [kb_call/1]).

:- multifile kb_query:kb_rule/2.
kb_query:kb_rule(is_feature(E), has_type(E, soma:'Feature')).
kb_query:kb_rule(is_affordance(E), has_type(E, soma:'Affordance')).
kb_query:kb_rule(is_disposition(E), has_type(E, soma:'Disposition')).
kb_query:kb_rule(is_physical_quality(E), has_type(E, soma:'PhysicalQuality')).
kb_query:kb_rule(is_social_quality(E), has_type(E, soma:'SocialQuality')).
kb_query:kb_rule(is_intrinsic(E), has_type(E, soma:'Intrinsic')).
kb_query:kb_rule(is_extrinsic(E), has_type(E, soma:'Extrinsic')).
kb_query:kb_rule(object_feature(O, F), holds(O, soma:hasFeature, F)).
kb_query:kb_rule(object_feature_type(O, F, T), ( holds(O, soma:hasFeature, F), has_object_type(F, T) )).
kb_query:kb_rule(has_disposition(O, D), holds(O, soma:hasDisposition, D)).
kb_query:kb_rule(has_disposition_type(O, D, T), ( holds(O, soma:hasDisposition, D), has_quality_type(D, T) )).
kb_query:kb_rule(disposition_trigger_type(D, T), ( holds(D, soma:affordsTrigger, only(R)), subclass_of(R, only(dul:classifies, T)) )).
kb_query:kb_rule(is_patient(E), ( has_role(E, R), has_object_type(R, soma:'Patient') )).
kb_query:kb_rule(is_instrument(E), ( has_role(E, R), has_object_type(R, soma:'Instrument') )).
kb_query:kb_rule(is_location(E), ( has_role(E, R), has_object_type(R, soma:'Location') )).
kb_query:kb_rule(is_destination(E), ( has_role(E, R), has_object_type(R, soma:'Destination') )).
kb_query:kb_rule(is_origin(E), ( has_role(E, R), has_object_type(R, soma:'Origin') )).

%!  is_feature(?Entity) is nondet.
%   Typed soma:'Feature' (or a subclass).
is_feature(Entity) :- kb_call(is_feature(Entity)).
%!  is_affordance(?Entity) is nondet.
%   Typed soma:'Affordance' (or a subclass).
is_affordance(Entity) :- kb_call(is_affordance(Entity)).
%!  is_disposition(?Entity) is nondet.
%   Typed soma:'Disposition' (or a subclass).
is_disposition(Entity) :- kb_call(is_disposition(Entity)).
%!  is_physical_quality(?Entity) is nondet.
%   Typed soma:'PhysicalQuality' (or a subclass).
is_physical_quality(Entity) :- kb_call(is_physical_quality(Entity)).
%!  is_social_quality(?Entity) is nondet.
%   Typed soma:'SocialQuality' (or a subclass).
is_social_quality(Entity) :- kb_call(is_social_quality(Entity)).
%!  is_intrinsic(?Entity) is nondet.
%   Typed soma:'Intrinsic' (or a subclass).
is_intrinsic(Entity) :- kb_call(is_intrinsic(Entity)).
%!  is_extrinsic(?Entity) is nondet.
%   Typed soma:'Extrinsic' (or a subclass).
is_extrinsic(Entity) :- kb_call(is_extrinsic(Entity)).
%!  object_feature(?Object, ?Feature) is nondet.
object_feature(Object, Feature) :- kb_call(object_feature(Object, Feature)).
%!  object_feature_type(?Object, ?Feature, ?Type) is nondet.
object_feature_type(Object, Feature, Type) :- kb_call(object_feature_type(Object, Feature, Type)).
%!  has_disposition(?Object, ?Disposition) is nondet.
has_disposition(Object, Disposition) :- kb_call(has_disposition(Object, Disposition)).
%!  has_disposition_type(?Object, ?Disposition, ?Type) is nondet.
%   A disposition of Object and a type of it below dul:Quality.
has_disposition_type(Object, Disposition, Type) :- kb_call(has_disposition_type(Object, Disposition, Type)).
%!  disposition_trigger_type(?Disposition, ?TriggerType) is nondet.
%   The class of objects the trigger role of Disposition's class classifies (two `only` restrictions).
disposition_trigger_type(Disposition, TriggerType) :- kb_call(disposition_trigger_type(Disposition, TriggerType)).
%!  is_patient(?Entity) is nondet.
%   Some role of type soma:Patient classifies Entity.
is_patient(Entity) :- kb_call(is_patient(Entity)).
%!  is_instrument(?Entity) is nondet.
is_instrument(Entity) :- kb_call(is_instrument(Entity)).
%!  is_location(?Entity) is nondet.
is_location(Entity) :- kb_call(is_location(Entity)).
%!  is_destination(?Entity) is nondet.
is_destination(Entity) :- kb_call(is_destination(Entity)).
%!  is_origin(?Entity) is nondet.
is_origin(Entity) :- kb_call(is_origin(Entity)).
