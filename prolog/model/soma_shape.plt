:- begin_tests(soma_shape).

:- use_module(soma_shape).
:- use_module(library(semweb/rdf_prefixes)).
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

test(a_prefixed_iri_as_knowrob_takes_it, [nondet, setup(load_owl_world), cleanup(store_reset)]) :-
    rdf_register_prefix(ow, 'http://example.org/owl#', [force(true)]),
    Goal = object_shape(ow:cup1, Frame, Shape, _, _),   % built at run time: no rdf_meta expansion
    call(Goal), Frame == cup1, Shape == box(0.1, 0.2, 0.3),
    object_shape_type(ow:cup1, 'http://www.ease-crc.org/ont/SOMA.owl#BoxShape'),
    object_dimensions(ow:cup1, 0.1, 0.2, 0.3).

test(rdf_meta_as_knowrob_declares_it) :-
    rdf_prefixes:rdf_meta_specification(object_shape(_, _, _, _, _), soma_shape, Spec),
    Spec == object_shape(r, ?, ?, ?, ?).

:- end_tests(soma_shape).
