:- module(allen_interval,
    [ interval/2,               % +IntervalOrEvent, -[Begin, End]
      interval_before/2,        % +I1, +I2
      interval_after/2,
      interval_meets/2,
      interval_met_by/2,
      interval_overlaps/2,
      interval_overlapped_by/2,
      interval_starts/2,
      interval_started_by/2,
      interval_during/2,
      interval_contains/2,
      interval_finishes/2,
      interval_finished_by/2,
      interval_equals/2
    ]).
/** <module> Allen's interval relations (KnowRob 2.x src/model/... interval predicates)

Each argument is `[Begin, End]` (unix seconds) or an event with a time interval (its
event_interval/3). The thirteen relations are exclusive for proper intervals.
*/

:- use_module(library(error)).
:- use_module('../lang/query', [kb_call/2]).
:- use_module('../lang/triple', [kb_iri/2]).
:- use_module(event, []).

%!  interval(+IntervalOrEvent, -Interval) is semidet.
%   `[Begin, End]` of an interval term or an event.
interval(I, [B, E]) :-
    nonvar(I), I = [B, E], !,
    must_be(number, B), must_be(number, E).
interval(Ev0, [B, E]) :-
    must_be(nonvar, Ev0),
    kb_iri(Ev0, Ev),
    once(kb_call(event_interval(Ev, B, E), any)).

%!  interval_before(+I1, +I2) is semidet.
%   I1 ends before I2 begins.
interval_before(I1, I2) :- interval(I1, [_, E1]), interval(I2, [B2, _]), E1 < B2.
%!  interval_after(+I1, +I2) is semidet.
interval_after(I1, I2) :- interval_before(I2, I1).
%!  interval_meets(+I1, +I2) is semidet.
%   I1 ends when I2 begins.
interval_meets(I1, I2) :- interval(I1, [_, E1]), interval(I2, [B2, _]), E1 =:= B2.
%!  interval_met_by(+I1, +I2) is semidet.
interval_met_by(I1, I2) :- interval_meets(I2, I1).
%!  interval_overlaps(+I1, +I2) is semidet.
%   I1 begins first and ends inside I2.
interval_overlaps(I1, I2) :-
    interval(I1, [B1, E1]), interval(I2, [B2, E2]),
    B1 < B2, E1 > B2, E1 < E2.
%!  interval_overlapped_by(+I1, +I2) is semidet.
interval_overlapped_by(I1, I2) :- interval_overlaps(I2, I1).
%!  interval_starts(+I1, +I2) is semidet.
%   Both begin together and I1 ends first.
interval_starts(I1, I2) :-
    interval(I1, [B1, E1]), interval(I2, [B2, E2]),
    B1 =:= B2, E1 < E2.
%!  interval_started_by(+I1, +I2) is semidet.
interval_started_by(I1, I2) :- interval_starts(I2, I1).
%!  interval_during(+I1, +I2) is semidet.
%   I1 lies strictly inside I2.
interval_during(I1, I2) :-
    interval(I1, [B1, E1]), interval(I2, [B2, E2]),
    B1 > B2, E1 < E2.
%!  interval_contains(+I1, +I2) is semidet.
interval_contains(I1, I2) :- interval_during(I2, I1).
%!  interval_finishes(+I1, +I2) is semidet.
%   Both end together and I1 begins later.
interval_finishes(I1, I2) :-
    interval(I1, [B1, E1]), interval(I2, [B2, E2]),
    E1 =:= E2, B1 > B2.
%!  interval_finished_by(+I1, +I2) is semidet.
interval_finished_by(I1, I2) :- interval_finishes(I2, I1).
%!  interval_equals(+I1, +I2) is semidet.
interval_equals(I1, I2) :-
    interval(I1, [B1, E1]), interval(I2, [B2, E2]),
    B1 =:= B2, E1 =:= E2.
