:- module(model_qudt,
    [ qudt_unit/4,              % ?Symbol, ?Kind, ?Multiplier, ?Offset
      qudt_conv/4               % +UnitIn, +UnitOut, +ValueIn, -ValueOut
    ]).
/** <module> Units of measure (KnowRob 2.x src/model/QUDT.pl)

The units holds/3 reads and writes (`holds(S, P, cm(X))`), with their quantity kinds in
QUDT's namespace and the factor to the SI unit the store holds (kb_triple:unit_factor/2):
length (m, km, dm, cm, mm), mass (kg, g), time (s, ms, min, h) and plane angle (rad, deg).
KnowRob reads the same figures from QUDT's `unit.owl`, which holds many more units.
*/

:- use_module(library(error)).
:- use_module('../lang/triple', [unit_factor/2]).

kind(m, 'Length'). kind(km, 'Length'). kind(dm, 'Length'). kind(cm, 'Length'). kind(mm, 'Length').
kind(kg, 'Mass'). kind(g, 'Mass').
kind(s, 'Time'). kind(ms, 'Time'). kind(min, 'Time'). kind(h, 'Time').
kind(rad, 'PlaneAngle'). kind(deg, 'PlaneAngle').

%!  qudt_unit(?Symbol, ?Kind, ?Multiplier, ?Offset) is nondet.
%   A value in unit Symbol times Multiplier plus Offset is the value in the SI unit of Kind
%   (an IRI of QUDT's quantity namespace).
qudt_unit(Symbol, Kind, Multiplier, 0.0) :-
    kind(Symbol, K),
    atom_concat('http://data.nasa.gov/qudt/owl/quantity#', K, Kind),
    unit_factor(Symbol, Multiplier).

%!  qudt_conv(+UnitIn, +UnitOut, +ValueIn, -ValueOut) is det.
%   ValueIn in UnitIn is ValueOut in UnitOut (units of one kind; an error names the others).
qudt_conv(I, O, V, W) :-
    (   var(I) -> throw(error(instantiation_error, qudt_conv(input_type)))
    ;   var(O) -> throw(error(instantiation_error, qudt_conv(output_type)))
    ;   var(V) -> throw(error(instantiation_error, qudt_conv(input_value)))
    ;   true
    ),
    must_be(number, V),
    (   I == O -> W = V
    ;   ( qudt_unit(I, K, MI, OI) -> true ; domain_error(qudt_unit, I) ),
        ( qudt_unit(O, K2, MO, OO) -> true ; domain_error(qudt_unit, O) ),
        ( K == K2 -> true ; domain_error(unit_of_kind(K), O) ),
        W is ((V * MI + OI) - OO) / MO
    ).
