:- module(dul_event,
    [ is_event/1,               % ?Event
      is_action/1,              % ?Action
      is_mental_action/1,       % ?Action
      executes_task/2,          % ?Action, ?Task
      is_performed_by/2,        % ?Action, ?Agent
      has_participant/2,        % ?Event, ?Object
      has_subevent/2,           % ?Event, ?SubEvent
      has_time_interval/2,      % ?Event, ?Interval
      has_interval_begin/2,     % ?Interval, ?Begin
      has_interval_end/2,       % ?Interval, ?End
      event_interval/3,         % ?Event, ?Begin, ?End
      has_participant/3         % ?Event, ?Object, ?Class
    ]).
/** <module> Events and actions (KnowRob 2.x src/model/DUL/Event.pl, SOMA's interval)

Each predicate is a kb_rule/2 over DUL/SOMA properties and, called from Prolog, kb_call/1
of itself (question scope now). Relations are holds/3 goals, so sub-properties count
(`has_participant` finds soma:isPerformedBy facts).
*/

:- use_module('../lang/query', [kb_call/1]).

:- multifile kb_query:kb_rule/2.
kb_query:kb_rule(is_event(A), has_type(A, dul:'Event')).
kb_query:kb_rule(is_action(A), has_type(A, dul:'Action')).
kb_query:kb_rule(is_mental_action(A), has_type(A, soma:'MentalAction')).
kb_query:kb_rule(executes_task(A, T), holds(A, dul:executesTask, T)).
kb_query:kb_rule(is_performed_by(A, Agent), holds(A, soma:isPerformedBy, Agent)).
kb_query:kb_rule(has_participant(E, O), holds(E, dul:hasParticipant, O)).
kb_query:kb_rule(has_participant(E, O, C), ( holds(E, dul:hasParticipant, O), has_type(O, C),
                                             C \== 'http://www.w3.org/2002/07/owl#NamedIndividual' )).
kb_query:kb_rule(has_subevent(E, S), holds(E, dul:hasConstituent, S)).
kb_query:kb_rule(has_time_interval(E, I), triple(E, dul:hasTimeInterval, I)).
kb_query:kb_rule(has_interval_begin(I, B), triple(I, soma:hasIntervalBegin, B)).
kb_query:kb_rule(has_interval_end(I, B), triple(I, soma:hasIntervalEnd, B)).
kb_query:kb_rule(event_interval(E, B, End),
                 ( has_time_interval(E, I), has_interval_begin(I, B), has_interval_end(I, End) )).

%!  is_event(?Event) is nondet.
is_event(A) :- kb_call(is_event(A)).
%!  is_action(?Action) is nondet.
is_action(A) :- kb_call(is_action(A)).
%!  is_mental_action(?Action) is nondet.
is_mental_action(A) :- kb_call(is_mental_action(A)).
%!  executes_task(?Action, ?Task) is nondet.
executes_task(A, T) :- kb_call(executes_task(A, T)).
%!  is_performed_by(?Action, ?Agent) is nondet.
is_performed_by(A, B) :- kb_call(is_performed_by(A, B)).
%!  has_participant(?Event, ?Object) is nondet.
has_participant(E, O) :- kb_call(has_participant(E, O)).
%!  has_subevent(?Event, ?SubEvent) is nondet.
has_subevent(E, S) :- kb_call(has_subevent(E, S)).
%!  has_time_interval(?Event, ?Interval) is nondet.
has_time_interval(E, I) :- kb_call(has_time_interval(E, I)).
%!  has_interval_begin(?Interval, ?Begin) is nondet.
has_interval_begin(I, B) :- kb_call(has_interval_begin(I, B)).
%!  has_interval_end(?Interval, ?End) is nondet.
has_interval_end(I, B) :- kb_call(has_interval_end(I, B)).
%!  event_interval(?Event, ?Begin, ?End) is nondet.
%   The begin and end of the event's time interval (unix seconds).
event_interval(E, B, End) :- kb_call(event_interval(E, B, End)).
%!  has_participant(?Event, ?Object, ?Class) is nondet.
%   Object takes part in Event and is an instance of Class (with Class free: its asserted
%   types but owl:NamedIndividual).
has_participant(E, O, C) :- kb_call(has_participant(E, O, C)).
