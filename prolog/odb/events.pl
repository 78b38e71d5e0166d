:- module(odb_events,
    [ event_time_of_day/2,        % ?Event, ?Part
      is_idle_action/1,           % ?Action
      idle_action/3,              % ?Action, ?Begin, ?End
      perceived_at/2              % +ObjectName, +Time
    ]).
/** <module> odb events: time of day, idle actions and perception (thesis 3.4)

The logger types an event's time interval odb:Morning/Midday/Evening/Night, logs the
robot in shared grasping for 20 s or more as an action executing an odb:IdleTask, and
scopes an object's type triple from its first perception.
*/

:- use_module(library(error)).
:- use_module(library(lists)).
:- use_module('../lang/query', [kb_call/2]).
:- use_module('../neem_store', [store_match/3]).
:- use_module('../lang/triple', [kb_iri/2]).
:- use_module('../model/rdfs', []).
:- use_module('../model/event', []).
:- use_module('../model/object', []).
:- use_module('../model/situation', []).
:- use_module(names, [odb_iri/2]).

%!  event_time_of_day(?Event, ?Part) is nondet.
%   Part (`'Morning'`, `'Midday'`, `'Evening'` or `'Night'`) is the odb:TimeOfDay class of
%   the event's time interval.
event_time_of_day(E, Part) :-
    member(Part, ['Morning', 'Midday', 'Evening', 'Night']),
    odb_iri(Part, C),
    kb_call(( has_time_interval(E, I), triple(I, rdf:type, C) ), any).

%!  is_idle_action(?Action) is nondet.
%   Action executes an odb:IdleTask (the robot in shared grasping for 20 s or more).
is_idle_action(A) :-
    idle_action(A, _, _).

%!  idle_action(?Action, ?Begin, ?End) is nondet.
idle_action(A, B, E) :-
    odb_iri('IdleTask', Idle),
    kb_call(( executes_task(A, T), instance_of(T, Idle), event_interval(A, B, E) ), any).

%!  perceived_at(+ObjectName, +Time) is semidet.
%   Some object of the odb class ObjectName was known at Time: the logger scopes an
%   object's type triple from its first perception.
perceived_at(Name, Time) :-
    must_be(atom, Name), must_be(number, Time),
    odb_iri(Name, C),
    % instance_of(_, C) during Time, as one row of the store (in the written order the
    % class's closure ids drive the type index, not a scan of every type triple).
    kb_iri(rdf:type, Type),
    once(store_match([t(_, Type, C)], scope(Time, Time), [limit(1), plan(written)])).
