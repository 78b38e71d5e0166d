:- begin_tests(store_pattern).

:- use_module(pattern).

test(three_taxonomic_properties) :-
    findall(P, store_taxonomic(P), Ps),
    Ps == ['http://www.w3.org/1999/02/22-rdf-syntax-ns#type',
           'http://www.w3.org/2000/01/rdf-schema#subClassOf',
           'http://www.w3.org/2000/01/rdf-schema#subPropertyOf'].

test(closures_climb_subclass_and_subproperty_not_type) :-
    findall(P, store_closure_edge(P), Ps),
    Ps == ['http://www.w3.org/2000/01/rdf-schema#subClassOf',
           'http://www.w3.org/2000/01/rdf-schema#subPropertyOf'],
    \+ store_closure_edge('http://www.w3.org/1999/02/22-rdf-syntax-ns#type').

test(good_patterns) :-
    store_check_pattern(t(_, _, _)),
    store_check_pattern(t(s, p, 1.5)),
    store_check_pattern(t(s, p, cmp(>=, 3, _))),
    store_check_pattern(t(s, p, cmp(>, 3, =<, 4.5, _))).

test(range_operators, [error(type_error(oneof([<, =<, >, >=]), =))]) :-
    store_check_pattern(t(s, p, cmp(>, 3, =, 4, _))).

test(range_with_numbers, [error(type_error(number, four))]) :-
    store_check_pattern(t(s, p, cmp(>, 3, <, four, _))).

test(pattern_not_a_triple, [error(type_error(triple_pattern, triple(a, b, c)))]) :-
    store_check_pattern(triple(a, b, c)).

test(compound_term, [error(type_error(atomic_or_var, f(x)))]) :-
    store_check_pattern(t(s, f(x), _)).

test(comparison_operator, [error(type_error(oneof([<, =<, >, >=]), =))]) :-
    store_check_pattern(t(s, p, cmp(=, 3, _))).

test(comparison_with_a_number, [error(type_error(number, three))]) :-
    store_check_pattern(t(s, p, cmp(<, three, _))).

test(term_checks) :-
    store_check_term(_),
    store_check_term(a),
    store_check_term("text"),
    catch(store_check_term([a]), error(type_error(atomic_or_var, [a]), _), true).

test(comparisons) :-
    store_compare(<, 1, 2), \+ store_compare(<, 2, 2),
    store_compare(=<, 2, 2), \+ store_compare(=<, 3, 2),
    store_compare(>, 3, 2), \+ store_compare(>, 2, 2),
    store_compare(>=, 2, 2.0), \+ store_compare(>=, 1, 2).

:- end_tests(store_pattern).
