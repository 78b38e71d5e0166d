:- module(kb_holds,
    [ holds/1,                  % ?Query
      holds/3                   % ?Subject, ?Property, ?Value
    ]).
/** <module> holds/3 (KnowRob 2.x src/lang/terms/holds.pl)

`holds(S, P, O)`: the relation P holds between S and O, a triple goal whose property is
closed over its sub-properties (`p*`), with the same value operators as triple/3, and
unit terms: `holds(S, P, cm(X))` converts the stored SI value (metres) to centimetres,
`kb_project(holds(S, P, m(6.5)))` stores 6.5. `holds(P(S, O))` is `holds(S, P, O)`.
*/

:- use_module(query, [kb_call/1]).

%!  holds(?Subject, ?Property, ?Value) is nondet.
%   kb_call/1 of the goal (the question scope is now).
holds(S, P, O) :- kb_call(holds(S, P, O)).

%!  holds(?Query) is nondet.
%   Query is `Property(Subject, Value)`.
holds(Q) :- kb_call(holds(Q)).
