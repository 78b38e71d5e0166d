:- begin_tests(dul_object_types).

:- use_module(dul_object_types).
:- use_module('../neem_store').
:- use_module('../lang/query').
:- use_module('../lang/holds').
:- use_module(object).
:- use_module('../fixtures/owl_world').

test(types_and_relations, [nondet, setup(load_owl_world), cleanup(store_reset)]) :-
    ow(cup1, C), ow(colour1, Col), ow(ti1, TI), ow(table1, T), ow(handle1, H), ow('Red', Red), ow('Cup', Cup),
    is_quality(Col), \+ is_quality(C), is_time_interval(TI),
    has_location(C, T), has_part(C, H),
    has_quality_type(Col, Red), has_object_type(C, Cup), \+ has_object_type(Col, _),
    \+ is_region(C).

:- end_tests(dul_object_types).
