:- module(json_text,
    [ json_text/2                 % +Term, -String
    ]).
/** <module> JSON text of the answers and the history read

The bridge reads every answer and history as JSON text. These are small terms of a few
shapes (dicts, lists, atoms, strings, numbers), so they are written here rather than with
library(http/json), whose loading costs about 45 ms of CPU in every Prolog process (most
CLI calls take 0.25-0.35 s in all). The service's query module (json_query.pl) still uses
library(http/json): it runs in one long-lived process.
*/

:- use_module(library(error)).

%!  json_text(+Term, -String) is det.
%   Term as JSON text: a dict is an object (its keys in standard order, as dict_pairs/3 gives
%   them), a list an array, a string a string, the atoms `true`, `false` and `null` their
%   literals and any other atom a string, an integer or a finite float a number. Characters
%   outside ASCII are written as they are; `"`, `\` and the control characters are escaped.
%   Raises an instantiation error for a variable, a domain error for an infinite or NaN
%   float and a type error for any other term (a compound that is not a list).
json_text(Term, String) :-
    with_output_to(string(String), write_json(Term)).

write_json(X) :-
    var(X), !,
    instantiation_error(X).
write_json(X) :-
    is_dict(X), !,
    dict_pairs(X, _, Pairs),
    write('{'),
    write_members(Pairs),
    write('}').
write_json(X) :-
    is_list(X), !,
    write('['),
    write_items(X),
    write(']').
write_json(X) :-
    string(X), !,
    write_string(X).
write_json(X) :-
    atom(X), !,
    (   literal(X) -> write(X) ; write_string(X) ).
write_json(X) :-
    integer(X), !,
    write(X).
write_json(X) :-
    float(X), !,
    float_class(X, Class),
    (   memberchk(Class, [infinite, nan])
    ->  domain_error(finite_float, X)
    ;   write(X)
    ).
write_json(X) :-
    type_error(json, X).

literal(true).
literal(false).
literal(null).

write_members([]).
write_members([K-V|Pairs]) :-
    write_key(K), write(':'), write_json(V),
    forall(member(K1-V1, Pairs), ( write(','), write_key(K1), write(':'), write_json(V1) )).

write_key(K) :-
    (   atom(K) -> write_string(K) ; number_string(K, S), write_string(S) ).

write_items([]).
write_items([X|Xs]) :-
    write_json(X),
    forall(member(Y, Xs), ( write(','), write_json(Y) )).

%   A JSON string: the text in double quotes, `"` and `\` escaped, control characters as
%   \n, \t, \r, \b, \f or \u00XX.
write_string(Text) :-
    atom_codes(Text, Codes),
    put_char('"'),
    maplist(put_json_code, Codes),
    put_char('"').

put_json_code(0'") :- !, write('\\"').
put_json_code(0'\\) :- !, write('\\\\').
put_json_code(C) :-
    C < 0x20, !,
    (   escape(C, E) -> write(E) ; format('\\u~|~`0t~16r~4+', [C]) ).
put_json_code(C) :-
    put_code(C).

escape(0'\n, '\\n').
escape(0'\t, '\\t').
escape(0'\r, '\\r').
escape(0'\b, '\\b').
escape(0'\f, '\\f').
