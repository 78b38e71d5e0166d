:- module(soma_types,
    [ is_manipulation_action/1, % ?Entity
      is_mental_task/1,         % ?Entity
      is_computational_agent/1, % ?Entity
      is_digital_object/1,      % ?Entity
      is_kino_dynamic_data/1,   % ?Entity
      is_chemical_process/1,    % ?Entity
      is_physical_process/1,    % ?Entity
      is_process_flow/1,        % ?Entity
      is_process_type/1,        % ?Entity
      is_motion/1,              % ?Entity
      is_force_interaction/1,   % ?Entity
      is_progression/1,         % ?Entity
      is_state/1,               % ?Entity
      is_physical_state/1,      % ?Entity
      is_social_state/1,        % ?Entity
      is_configuration/1,       % ?Entity
      is_state_type/1,          % ?Entity
      is_binding/1,             % ?Entity
      is_succeedence/1          % ?Entity
    ]).
/** <module> SOMA's action, process, state and description types (KnowRob 2.x src/model/SOMA.pl)

The type tests of SOMA's classes that the event and situation modules do not hold. Each is a
kb_rule/2 (has_type/2 of the class) and, called from Prolog, kb_call/1 of itself.
*/

:- use_module('../lang/query', [kb_call/1]).

:- multifile kb_query:kb_rule/2.
kb_query:kb_rule(is_manipulation_action(E), has_type(E, soma:'ManipulationAction')).
kb_query:kb_rule(is_mental_task(E), has_type(E, soma:'MentalTask')).
kb_query:kb_rule(is_computational_agent(E), has_type(E, soma:'ComputationalAgent')).
kb_query:kb_rule(is_digital_object(E), has_type(E, soma:'DigitalObject')).
kb_query:kb_rule(is_kino_dynamic_data(E), has_type(E, soma:'KinoDynamicData')).
kb_query:kb_rule(is_chemical_process(E), has_type(E, soma:'ChemicalProcess')).
kb_query:kb_rule(is_physical_process(E), has_type(E, soma:'PhysicalProcess')).
kb_query:kb_rule(is_process_flow(E), has_type(E, soma:'ProcessFlow')).
kb_query:kb_rule(is_process_type(E), has_type(E, soma:'ProcessType')).
kb_query:kb_rule(is_motion(E), has_type(E, soma:'Motion')).
kb_query:kb_rule(is_force_interaction(E), has_type(E, soma:'ForceInteraction')).
kb_query:kb_rule(is_progression(E), has_type(E, soma:'Progression')).
kb_query:kb_rule(is_state(E), has_type(E, soma:'State')).
kb_query:kb_rule(is_physical_state(E), has_type(E, soma:'PhysicalState')).
kb_query:kb_rule(is_social_state(E), has_type(E, soma:'SocialState')).
kb_query:kb_rule(is_configuration(E), has_type(E, soma:'Configuration')).
kb_query:kb_rule(is_state_type(E), has_type(E, soma:'StateType')).
kb_query:kb_rule(is_binding(E), has_type(E, soma:'Binding')).
kb_query:kb_rule(is_succeedence(E), has_type(E, soma:'Succeedence')).

%!  is_manipulation_action(?Entity) is nondet.
%   Typed soma:'ManipulationAction' (or a subclass).
is_manipulation_action(Entity) :- kb_call(is_manipulation_action(Entity)).
%!  is_mental_task(?Entity) is nondet.
%   Typed soma:'MentalTask' (or a subclass).
is_mental_task(Entity) :- kb_call(is_mental_task(Entity)).
%!  is_computational_agent(?Entity) is nondet.
%   Typed soma:'ComputationalAgent' (or a subclass).
is_computational_agent(Entity) :- kb_call(is_computational_agent(Entity)).
%!  is_digital_object(?Entity) is nondet.
%   Typed soma:'DigitalObject' (or a subclass).
is_digital_object(Entity) :- kb_call(is_digital_object(Entity)).
%!  is_kino_dynamic_data(?Entity) is nondet.
%   Typed soma:'KinoDynamicData' (or a subclass).
is_kino_dynamic_data(Entity) :- kb_call(is_kino_dynamic_data(Entity)).
%!  is_chemical_process(?Entity) is nondet.
%   Typed soma:'ChemicalProcess' (or a subclass).
is_chemical_process(Entity) :- kb_call(is_chemical_process(Entity)).
%!  is_physical_process(?Entity) is nondet.
%   Typed soma:'PhysicalProcess' (or a subclass).
is_physical_process(Entity) :- kb_call(is_physical_process(Entity)).
%!  is_process_flow(?Entity) is nondet.
%   Typed soma:'ProcessFlow' (or a subclass).
is_process_flow(Entity) :- kb_call(is_process_flow(Entity)).
%!  is_process_type(?Entity) is nondet.
%   Typed soma:'ProcessType' (or a subclass).
is_process_type(Entity) :- kb_call(is_process_type(Entity)).
%!  is_motion(?Entity) is nondet.
%   Typed soma:'Motion' (or a subclass).
is_motion(Entity) :- kb_call(is_motion(Entity)).
%!  is_force_interaction(?Entity) is nondet.
%   Typed soma:'ForceInteraction' (or a subclass).
is_force_interaction(Entity) :- kb_call(is_force_interaction(Entity)).
%!  is_progression(?Entity) is nondet.
%   Typed soma:'Progression' (or a subclass).
is_progression(Entity) :- kb_call(is_progression(Entity)).
%!  is_state(?Entity) is nondet.
%   Typed soma:'State' (or a subclass).
is_state(Entity) :- kb_call(is_state(Entity)).
%!  is_physical_state(?Entity) is nondet.
%   Typed soma:'PhysicalState' (or a subclass).
is_physical_state(Entity) :- kb_call(is_physical_state(Entity)).
%!  is_social_state(?Entity) is nondet.
%   Typed soma:'SocialState' (or a subclass).
is_social_state(Entity) :- kb_call(is_social_state(Entity)).
%!  is_configuration(?Entity) is nondet.
%   Typed soma:'Configuration' (or a subclass).
is_configuration(Entity) :- kb_call(is_configuration(Entity)).
%!  is_state_type(?Entity) is nondet.
%   Typed soma:'StateType' (or a subclass).
is_state_type(Entity) :- kb_call(is_state_type(Entity)).
%!  is_binding(?Entity) is nondet.
%   Typed soma:'Binding' (or a subclass).
is_binding(Entity) :- kb_call(is_binding(Entity)).
%!  is_succeedence(?Entity) is nondet.
%   Typed soma:'Succeedence' (or a subclass).
is_succeedence(Entity) :- kb_call(is_succeedence(Entity)).
