:- module(soma_shape,
    [ object_localization/2,    % ?Object, ?Localization
      object_shape_type/2,      % ?Object, ?ShapeType
      object_mesh_path/2,       % ?Object, ?FilePath
      object_color_rgb/4,       % ?Object, ?R, ?G, ?B
      object_dimensions/4,      % ?Object, ?Depth, ?Width, ?Height
      object_shape/5            % ?Object, ?Frame, ?ShapeTerm, ?Origin, ?Material
    ]).
/** <module> Shapes, colours, sizes and localizations of objects (KnowRob 2.x src/model/SOMA.pl)

An object has a shape (soma:hasShape) and a colour (soma:hasColor), qualities whose regions
(dul:hasRegion) carry the values: a mesh's file path, a box's depth, width and height, a
cylinder's length and radius, a sphere's radius, an RGB value stored as the text of a list
(KnowRob's `term([R,G,B])`). Values stated on the object itself are read when the object has
no such quality, as in KnowRob.
*/

:- use_module(library(lists)).
:- use_module(library(semweb/rdf_prefixes), [rdf_meta/1]).
:- use_module('../lang/query', [kb_call/1]).
:- use_module('../lang/triple', [kb_iri/2]).

% KnowRob's export list gives these their argument modes (`r`: an IRI, `prefix:'Local'` too):
% code compiled against them has a prefixed IRI expanded; a query asked at run time reaches
% kb_iri/2 (object_shape/5 reads the IRI's local name itself).
:- rdf_meta((
    object_localization(r, r),
    object_shape_type(r, r),
    object_mesh_path(r, ?),
    object_color_rgb(r, ?, ?, ?),
    object_dimensions(r, ?, ?, ?),
    object_shape(r, ?, ?, ?, ?) )).

:- multifile kb_query:kb_rule/2.
kb_query:kb_rule(object_localization(O, L), holds(O, soma:hasLocalization, L)).
kb_query:kb_rule(object_shape_type(O, T),
                 ( holds(O, soma:hasShape, S), holds(S, dul:hasRegion, R), has_type(R, T) )).

%!  object_localization(?Object, ?Localization) is nondet.
object_localization(O, L) :- kb_call(object_localization(O, L)).
%!  object_shape_type(?Object, ?ShapeType) is nondet.
%   A type of the region of Object's shape.
object_shape_type(O, T) :- kb_call(object_shape_type(O, T)).

%!  object_mesh_path(?Object, ?FilePath) is nondet.
%   The mesh file of Object's shape region (the first), or a file path stated on Object.
object_mesh_path(O, F) :-
    (   once(kb_call(( holds(O, soma:hasShape, S), holds(S, dul:hasRegion, R), holds(R, soma:hasFilePath, F0) )))
    ->  F = F0
    ;   kb_call(holds(O, soma:hasFilePath, F))
    ).

%!  object_color_rgb(?Object, ?R, ?G, ?B) is nondet.
%   The RGB value of Object's colour region (the first), or one stated on Object.
object_color_rgb(O, R, G, B) :-
    (   once(kb_call(( holds(O, soma:hasColor, C), holds(C, dul:hasRegion, Reg), holds(Reg, soma:hasRGBValue, term([R0, G0, B0])) )))
    ->  [R, G, B] = [R0, G0, B0]
    ;   kb_call(holds(O, soma:hasRGBValue, term([R, G, B])))
    ).

%!  object_dimensions(?Object, ?Depth, ?Width, ?Height) is nondet.
%   The bounding box of Object's shape region (the first), or stated on Object.
object_dimensions(O, D, W, H) :-
    (   once(kb_call(( holds(O, soma:hasShape, S), holds(S, dul:hasRegion, R), bbox(R, D0, W0, H0) )))
    ->  [D, W, H] = [D0, W0, H0]
    ;   kb_call(bbox(O, D, W, H))
    ).

kb_query:kb_rule(bbox(R, D, W, H),
                 ( holds(R, soma:hasDepth, D), holds(R, soma:hasWidth, W), holds(R, soma:hasHeight, H) )).

%!  object_shape(?Object, ?Frame, ?ShapeTerm, ?Origin, ?Material) is nondet.
%   The shape of Object for a visualisation: Frame its IRI's local name, ShapeTerm
%   `mesh(File, [SX,SY,SZ])`, `box(D,W,H)`, `cylinder(Radius, Length)` or `sphere(Radius)`,
%   Origin `[Frame, Position, Orientation]` (unbound when the region states none), Material
%   `material(rgba(R,G,B,A))` (unbound parts when no colour is stated).
object_shape(O0, Frame, Shape, [Frame, Pos, Rot], material(rgba(R, G, B, A))) :-
    kb_iri(O0, O),
    kb_call(triple(O, soma:hasShape, S)),
    iri_local_name(O, Frame),
    once(kb_call(triple(S, dul:hasRegion, SR))),
    once(shape_term(SR, Shape)),
    ignore(once(kb_call(( triple(SR, 'http://knowrob.org/kb/urdf.owl#hasOrigin', Or),
                          triple(Or, soma:hasPositionVector, term(Pos)),
                          triple(Or, soma:hasOrientationVector, term(Rot)) )))),
    ignore(once(kb_call(( triple(O, soma:hasColor, C), triple(C, dul:hasRegion, CR) )))),
    ignore(( nonvar(CR), once(kb_call(triple(CR, soma:hasRGBValue, term([R, G, B])))) )),
    ignore(( nonvar(CR), once(kb_call(triple(CR, soma:hasTransparencyValue, A))) )).

shape_term(SR, mesh(File, [X, Y, Z])) :-
    kb_call(( triple(SR, soma:hasFilePath, File),
              triple(SR, knowrob:hasXScale, X), triple(SR, knowrob:hasYScale, Y), triple(SR, knowrob:hasZScale, Z) )).
shape_term(SR, mesh(File, [1, 1, 1])) :- kb_call(triple(SR, soma:hasFilePath, File)).
shape_term(SR, box(X, Y, Z)) :- kb_call(bbox(SR, X, Y, Z)).
shape_term(SR, cylinder(Radius, Length)) :-
    kb_call(( triple(SR, soma:hasLength, Length), triple(SR, soma:hasRadius, Radius) )).
shape_term(SR, sphere(Radius)) :- kb_call(triple(SR, soma:hasRadius, Radius)).

iri_local_name(IRI, Name) :-
    (   sub_atom(IRI, _, _, _, '#') -> atomic_list_concat(Parts, '#', IRI), last(Parts, Name)
    ;   file_base_name(IRI, Name)
    ).
