:- begin_tests(model_qudt).

:- use_module(qudt).

test(units) :-
    qudt_unit(cm, K, 0.01, 0.0), qudt_unit(km, K, 1000.0, _),
    K == 'http://data.nasa.gov/qudt/owl/quantity#Length', \+ qudt_unit(furlong, _, _, _).

test(conversion) :-
    qudt_conv(km, m, 2, X), X =:= 2000, qudt_conv(cm, mm, 6.5, Y), abs(Y - 65) < 1.0e-9,
    qudt_conv(m, m, 3, 3).

test(wrong_units, [error(domain_error(unit_of_kind(_), kg))]) :- qudt_conv(m, kg, 1, _).
test(unbound_unit, [error(instantiation_error, qudt_conv(input_type))]) :- qudt_conv(_, kg, 1, _).

:- end_tests(model_qudt).
