:- begin_tests(soma_shape).

:- use_module(soma_shape).
:- use_module('../neem_store').
:- use_module('../lang/query').
:- use_module('../fixtures/owl_world').

test(colour_dimensions_shape, [nondet, setup(load_owl_world), cleanup(store_reset)]) :-
    ow(cup1, C), ow(rgb1, RGB),
    kb_project(triple(RGB, soma:hasRGBValue, term([1, 0, 0]))),
    object_color_rgb(C, 1, 0, 0), object_dimensions(C, 0.1, 0.2, 0.3),
    object_shape_type(C, 'http://www.ease-crc.org/ont/SOMA.owl#BoxShape'),
    object_shape(C, Frame, Shape, _, _), Frame == cup1, Shape == box(0.1, 0.2, 0.3),
    \+ object_mesh_path(C, _).

:- end_tests(soma_shape).
