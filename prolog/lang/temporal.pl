:- module(kb_temporal,
    [ during/2,                 % :Goal, +Interval
      since/2,                  % :Goal, +Instant
      until/2,                  % :Goal, +Instant
      occurs/1,                 % ?Event
      op(800, yfx, during),
      op(800, yfx, since),
      op(800, yfx, until)
    ]).
/** <module> Time-scoped questions (KnowRob 2.x src/lang/temporal.pl)

`Goal during [T0,T1]` asks for facts true during the whole interval, `Goal during Event`
uses the event's interval, `Goal since T` for facts true since T and still now, `Goal
until T` for facts true at T. The operators are also declared in `user`, so a query typed
at the toplevel reads them.
*/

:- use_module(query, [kb_call/1]).

:- op(800, yfx, user:during).
:- op(800, yfx, user:since).
:- op(800, yfx, user:until).

:- meta_predicate during(0, +), since(0, +), until(0, +).

%!  occurs(?Event) is nondet.
%   Event has an interval that overlaps the question scope (now, unless called as
%   `occurs(E) during [T0,T1]`, `occurs(E) since T` or `occurs(E) until T`).
occurs(E) :- kb_call(occurs(E)).

%!  during(:Goal, +Interval) is nondet.
%   Goal with the question scope Interval: `[Since, Until]` or an event with an interval.
during(G, I) :- kb_call(during(G, I)).

%!  since(:Goal, +Instant) is nondet.
%   Goal with the question scope from Instant to now.
since(G, T) :- kb_call(since(G, T)).

%!  until(:Goal, +Instant) is nondet.
%   Goal with the question scope Instant.
until(G, T) :- kb_call(until(G, T)).
