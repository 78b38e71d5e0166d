:- module(kb_aggregate,
    [ aggregate/1               % +Goals
    ]).
/** <module> aggregate/1: a list of triple goals asked as one conjunction

KnowRob 2.0 (src/lang/terms/triple.pl, September 2020 to January 2021) asked a conjunction of
triple/3 terms as one MongoDB aggregate pipeline, `ask(aggregate([triple(S, P, O), ...]))`.
The mongolog rewrite dropped the predicate, but openEASE's rules still call it
(ease-crc/knowrob_openease, `src/backends/timeline.pl`: the events of a timeline). Here it is
the list's conjunction, compiled as any kb_call/1 goal (one store query per step, the scopes
of the facts joined intersected, as KnowRob joined them): `aggregate(Goals)` inside
ask/kb_call unfolds into Goals, and the predicate asks kb_call/1 of it (question scope now).
*/

:- use_module(library(error)).
:- use_module(query, [kb_call/1]).

:- multifile kb_query:kb_rule/2.
kb_query:kb_rule(aggregate(Goals), Goals).

%!  aggregate(+Goals) is nondet.
%   The conjunction of the goals of the list Goals (triple/3 terms in KnowRob 2.0).
aggregate(Goals) :-
    must_be(list, Goals),
    kb_call(aggregate(Goals)).
