:- module(kb_urdf,
    [ urdf_load/2,              % +Object, +File
      urdf_load/3,              % +Object, +File, +Options
      is_urdf_link/1,           % ?Entity
      is_urdf_joint/1,          % ?Entity
      has_base_link_name/2,     % ?Object, ?Name
      has_urdf_prefix/2,        % ?Object, ?Prefix
      has_base_link/2,          % ?Object, ?Link
      has_child_link/2,         % ?Joint, ?Link
      has_parent_link/2         % ?Joint, ?Link
    ]).
/** <module> Robot and environment descriptions into the NEEM (KnowRob 2.x src/ros/urdf/URDF.pl)

urdf_load/3 reads a URDF file (XML, with SWI-Prolog's library(sgml); no ROS urdf parser) and
writes what KnowRob's urdf module writes: the object's kinematics file (a
soma:KinoDynamicData individual that dul:isAbout the object, realized by a
soma:DigitalResource with the file's name as its soma:hasPersistentIdentifier and format
`URDF`), its base link name (urdf:hasBaseLinkName, the link no joint has as child) and name
prefix, and with option `load_rdf` one individual per link (typed urdf:Link) and per joint
(typed urdf:RevoluteJoint, ... by its type, with urdf:hasChildLink and urdf:hasParentLink),
named as KnowRob names them: the object's IRI namespace followed by the URDF name. The
object's tf frame is attached to its base link's frame (a transform stamped 0, unless the
object is named as that frame), as KnowRob does for its tf memory.
*/

:- use_module(library(error)).
:- use_module(library(lists)).
:- use_module(library(option)).
:- use_module(library(sgml)).
:- use_module('../lang/query', [kb_call/2, kb_project/1, kb_project/3]).
:- use_module('../lang/triple', [kb_iri/2]).
:- use_module('../store/tf', [store_assert_pose/3]).
:- use_module('../model/rdfs', [new_iri/2]).
:- use_module('../model/tf', [object_frame_name/2]).
:- use_module('../model/soma_workflow', []).         % has_kinematics_file/3's rule (KnowRob's model/SOMA.pl)

urdf(Local, IRI) :- atom_concat('http://knowrob.org/kb/urdf.owl#', Local, IRI).

:- multifile kb_query:kb_rule/2.
kb_query:kb_rule(is_urdf_link(E), has_type(E, 'http://knowrob.org/kb/urdf.owl#Link')).
kb_query:kb_rule(is_urdf_joint(E), has_type(E, 'http://knowrob.org/kb/urdf.owl#Joint')).
kb_query:kb_rule(has_base_link_name(O, N), triple(O, 'http://knowrob.org/kb/urdf.owl#hasBaseLinkName', N)).
kb_query:kb_rule(has_urdf_prefix(O, P), triple(O, 'http://knowrob.org/kb/urdf.owl#hasNamePrefix', P)).
kb_query:kb_rule(has_base_link(O, L), triple(O, 'http://knowrob.org/kb/urdf.owl#hasBaseLink', L)).
kb_query:kb_rule(has_child_link(J, L), triple(J, 'http://knowrob.org/kb/urdf.owl#hasChildLink', L)).
kb_query:kb_rule(has_parent_link(J, L), triple(J, 'http://knowrob.org/kb/urdf.owl#hasParentLink', L)).

%!  is_urdf_link(?Entity) is nondet.
is_urdf_link(E) :- kb_call(is_urdf_link(E), any).
%!  is_urdf_joint(?Entity) is nondet.
is_urdf_joint(E) :- kb_call(is_urdf_joint(E), any).
%!  has_base_link_name(?Object, ?Name) is nondet.
has_base_link_name(O, N) :- kb_call(has_base_link_name(O, N), any).
%!  has_urdf_prefix(?Object, ?Prefix) is nondet.
has_urdf_prefix(O, P) :- kb_call(has_urdf_prefix(O, P), any).
%!  has_base_link(?Object, ?Link) is nondet.
has_base_link(O, L) :- kb_call(has_base_link(O, L), any).
%!  has_child_link(?Joint, ?Link) is nondet.
has_child_link(J, L) :- kb_call(has_child_link(J, L), any).
%!  has_parent_link(?Joint, ?Link) is nondet.
has_parent_link(J, L) :- kb_call(has_parent_link(J, L), any).

%!  urdf_load(+Object, +File) is det.
urdf_load(Object, File) :- urdf_load(Object, File, []).

%!  urdf_load(+Object, +File, +Options) is det.
%   Load the URDF description File (a path or `file://...`) of Object (an IRI). Options:
%   `load_rdf` (links and joints as individuals), `prefix(P)` (the names' tf prefix).
%   A file that is missing or no URDF is an error naming it.
urdf_load(Object0, URL, Options) :-
    kb_iri(Object0, Object),
    must_be(atom, Object), must_be(list, Options),
    file_of(URL, File),
    urdf_model(File, Links, Joints),
    file_base_name(File, Base), file_name_extension(Id, _, Base),
    option(prefix(Prefix), Options, ''),
    root_link(Links, Joints, Root),
    new_iri(IO, soma:'KinoDynamicData'),
    new_iri(IR, soma:'DigitalResource'),
    urdf(hasBaseLinkName, HasBaseLinkName),
    kb_project([ has_type(IO, soma:'KinoDynamicData'), has_type(IR, soma:'DigitalResource'),
                 triple(IO, dul:isAbout, Object), triple(IR, dul:realizes, IO),
                 triple(IR, soma:hasPersistentIdentifier, Id), triple(IR, soma:hasDataFormat, 'URDF'),
                 triple(Object, HasBaseLinkName, Root) ]),
    (   Prefix == '' -> true ; urdf(hasNamePrefix, HasPrefix), kb_project(triple(Object, HasPrefix, Prefix)) ),
    atom_concat(Prefix, Root, RootFrame),
    object_frame_name(Object, ObjectFrame),
    (   ObjectFrame == RootFrame -> true
    ;   store_assert_pose(ObjectFrame, 0.0, [RootFrame, [0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 1.0]])
    ),
    (   option(load_rdf, Options) -> load_rdf(Object, Root, Links, Joints) ; true ).

file_of(URL, File) :-
    must_be(atomic, URL),
    (   atom_concat('file://', F, URL) -> true
    ;   atom_concat('package://', _, URL) -> existence_error(ros_package_file, URL)
    ;   F = URL
    ),
    (   exists_file(F) -> File = F ; existence_error(urdf_file, URL) ).

%   The names of the links and name-type-parent-child of the joints of a URDF file.
urdf_model(File, Links, Joints) :-
    catch(load_structure(File, DOM, [dialect(xml), space(remove)]), E,
          ( message_to_codes(E, Text), throw(error(syntax_error(urdf(File, Text)), _)) )),
    (   DOM = [element(robot, _, Children)]
    ->  true
    ;   memberchk(element(robot, _, Children), DOM) -> true
    ;   domain_error(urdf_file, File)
    ),
    findall(N, ( member(element(link, A, _), Children), memberchk(name=N, A) ), Links),
    findall(joint(N, T, P, C),
            ( member(element(joint, A, Es), Children), memberchk(name=N, A), memberchk(type=T, A),
              memberchk(element(parent, PA, _), Es), memberchk(link=P, PA),
              memberchk(element(child, CA, _), Es), memberchk(link=C, CA) ),
            Joints),
    (   Links == [] -> domain_error(urdf_file_with_links, File) ; true ).

message_to_codes(E, Text) :- message_to_codes(E, _, Text0), !, Text = Text0.
message_to_codes(E, Text) :- term_to_atom(E, Text).

root_link(Links, Joints, Root) :-
    (   member(Root, Links), \+ memberchk(joint(_, _, _, Root), Joints) -> true ; Links = [Root|_] ).

load_rdf(Object, Root, Links, Joints) :-
    joint_taxonomy,
    forall(member(L, Links), ( link_iri(Object, L, I), urdf('Link', C), kb_project(has_type(I, C)) )),
    forall(member(joint(N, T, P, Ch), Joints),
           ( link_iri(Object, N, J), link_iri(Object, P, PI), link_iri(Object, Ch, CI),
             joint_class(T, JC),
             urdf(hasChildLink, HasChild), urdf(hasParentLink, HasParent),
             kb_project([has_type(J, JC), triple(J, HasChild, CI), triple(J, HasParent, PI)]) )),
    link_iri(Object, Root, RootIRI),
    (   RootIRI == Object -> true ; urdf(hasBaseLink, HB), kb_project(triple(Object, HB, RootIRI)) ).

%   KnowRob's urdf_iri/4: the object's IRI namespace followed by the URDF name.
link_iri(Object, Name, IRI) :-
    (   sub_atom(Object, B, 1, _, '#'), \+ ( sub_atom(Object, B1, 1, _, '#'), B1 > B )
    ->  L is B + 1, sub_atom(Object, 0, L, _, NS)
    ;   sub_atom(Object, B, 1, _, '/'), \+ ( sub_atom(Object, B1, 1, _, '/'), B1 > B )
    ->  L is B + 1, sub_atom(Object, 0, L, _, NS)
    ;   NS = ''
    ),
    atom_concat(NS, Name, IRI).

%   The joint classes below urdf:Joint, as KnowRob's URDF.owl states them (KnowRob loads that
%   file at start; here the few axioms is_urdf_joint/1 needs go into graph `urdf`).
joint_taxonomy :-
    urdf('Joint', Joint),
    findall(triple(C, rdfs:subClassOf, Joint),
            ( member(L, ['RevoluteJoint', 'ContinuousJoint', 'PrismaticJoint', 'FixedJoint', 'FloatingJoint',
                         'PlanarJoint']), urdf(L, C) ), Axioms),
    kb_project(Axioms, dict{}, [graph(urdf)]).

joint_class(Type, Class) :-
    (   memberchk(Type-Local, [revolute-'RevoluteJoint', continuous-'ContinuousJoint', prismatic-'PrismaticJoint',
                               fixed-'FixedJoint', floating-'FloatingJoint', planar-'PlanarJoint'])
    ->  urdf(Local, Class)
    ;   domain_error(urdf_joint_type, Type)
    ).
