:- begin_tests(kb_rules).

:- use_module(rules).
:- use_module(query).
:- use_module('../neem_store').
:- use_module('../model/rdfs').

%   A rule file as a KnowRob user writes it, loaded into a module of its own.
rule_file(File) :-
    tmp_file_stream(text, File, S),
    format(S, ":- module(my_rules, [my_thing/1, my_colour/2]).~n", []),
    format(S, "my_thing(X) ?> triple(X, rdf:type, 'http://my#Thing').~n", []),
    format(S, "my_thing(X) ?> triple(X, rdf:type, 'http://my#Other').~n", []),
    format(S, "my_colour(O, C) ?+> triple(O, 'http://my#colour', C).~n", []),
    close(S).

load_rules :-
    store_reset,
    (   module_property(my_rules, file(_)) -> true ; rule_file(F), load_files(F, []) ),
    store_assert(triple(b, 'http://www.w3.org/1999/02/22-rdf-syntax-ns#type', 'http://my#Other')),
    store_assert(triple(c, 'http://www.w3.org/1999/02/22-rdf-syntax-ns#type', 'http://my#Thing')).

test(rules_load_and_answer, [setup(load_rules), cleanup(store_reset)]) :-
    findall(X, my_rules:my_thing(X), Xs), msort(Xs, [b, c]),
    kb_project(my_rules:my_colour(b, red)),
    findall(X-C, kb_call(( my_rules:my_colour(X, C), my_rules:my_thing(X) )), [b-red]).

test(compiled_like_the_models_rules, [nondet, setup(load_rules), cleanup(store_reset)]) :-
    kb_compile(my_colour(a, C), any, Plan), Plan = [match([t(a, 'http://my#colour', C)], any)].

test(add_expand_drop, [setup(load_rules), cleanup(store_reset)]) :-
    kb_add_rule(red_thing(X), ( my_thing(X), my_colour(X, red) )),
    kb_expand(red_thing(Y), E), E = (((triple(Y, _, _) ; triple(Y, _, _))), triple(Y, _, red)),
    kb_project(my_colour(c, red)),
    findall(X, kb_call(red_thing(X)), [c]),
    kb_drop_rule(red_thing(_)), \+ catch(kb_call(red_thing(_)), error(existence_error(_, _), _), fail),
    kb_drop_rule(my_thing(_)), \+ my_rules:my_thing(_).

:- end_tests(kb_rules).
