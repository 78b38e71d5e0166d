:- module(json_text,
    [ json_text/2,                % +Term, -String
      json_data_text/2            % +Term, -String
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
    with_output_to(string(String), write_json(literals, Term)).

%!  json_data_text(+Term, -String) is det.
%   As json_text/2, but every atom is a string, `true`, `false` and `null` too: the text of
%   data whose atoms are names (a store request's IRIs and values), not JSON literals. An
%   infinite or NaN float is written `Infinity`, `-Infinity` or `NaN`, as Python's json
%   module reads them (not standard JSON: this text is for the bridge alone).
json_data_text(Term, String) :-
    with_output_to(string(String), write_json(names, Term)).

%   write_json(+Atoms, +Term): Atoms `literals` writes true, false and null as literals.
write_json(_, X) :-
    var(X), !,
    instantiation_error(X).
write_json(Atoms, X) :-
    is_dict(X), !,
    dict_pairs(X, _, Pairs),
    write('{'),
    write_members(Pairs, Atoms),
    write('}').
write_json(Atoms, X) :-
    is_list(X), !,
    write('['),
    write_items(X, Atoms),
    write(']').
write_json(_, X) :-
    string(X), !,
    write_string(X).
write_json(Atoms, X) :-
    atom(X), !,
    (   Atoms == literals, literal(X) -> write(X) ; write_string(X) ).
write_json(_, X) :-
    integer(X), !,
    write(X).
write_json(Atoms, X) :-
    float(X), !,
    float_class(X, Class),
    (   \+ memberchk(Class, [infinite, nan])
    ->  write(X)
    ;   Atoms == names
    ->  non_finite(X, Text), write(Text)
    ;   domain_error(finite_float, X)
    ).
write_json(_, X) :-
    type_error(json, X).

%   The tokens Python's json module reads for the floats JSON has no number for (a scope
%   that lasts for ever ends at inf).
non_finite(X, 'NaN') :- X =\= X, !.
non_finite(X, 'Infinity') :- X > 0, !.
non_finite(_, '-Infinity').

literal(true).
literal(false).
literal(null).

write_members(Pairs, Atoms) :-
    write_separated(write_member(Atoms), Pairs).

write_member(Atoms, K-V) :-
    (   atom(K) -> write_string(K) ; number_string(K, S), write_string(S) ),
    write(':'),
    write_json(Atoms, V).

write_items(Xs, Atoms) :-
    write_separated(write_json(Atoms), Xs).

%   Each element written by Goal, with commas between them.
write_separated(_, []).
write_separated(Goal, [X|Xs]) :-
    call(Goal, X),
    forall(member(Y, Xs), ( write(','), call(Goal, Y) )).

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
