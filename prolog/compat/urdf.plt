:- begin_tests(kb_urdf).

:- use_module(urdf).
:- use_module('../neem_store').
:- use_module('../store/tf').
:- use_module('../lang/query').
:- use_module('../model/soma_workflow', [has_kinematics_file/3]).

urdf_file(F) :-
    tmp_file_stream(text, F, S),
    format(S, '<?xml version="1.0"?>~n<robot name="arm"><link name="base_link"/><link name="tool"/>~c', [10]),
    format(S, '<joint name="j1" type="prismatic"><parent link="base_link"/><child link="tool"/></joint></robot>~n', []),
    close(S).

test(links_joints_and_the_kinematics_file, [nondet, setup(store_reset), cleanup(store_reset)]) :-
    urdf_file(F),
    urdf_load('http://e.org/r#Arm', F, [load_rdf, prefix('r_')]),
    has_base_link_name('http://e.org/r#Arm', N), N == base_link,
    has_urdf_prefix('http://e.org/r#Arm', P), P == r_,
    has_base_link('http://e.org/r#Arm', L), L == 'http://e.org/r#base_link',
    findall(X, is_urdf_link(X), Ls), msort(Ls, ['http://e.org/r#base_link', 'http://e.org/r#tool']),
    is_urdf_joint(J), J == 'http://e.org/r#j1',
    has_child_link(J, C), C == 'http://e.org/r#tool',
    has_parent_link(J, Pa), Pa == 'http://e.org/r#base_link',
    has_kinematics_file('http://e.org/r#Arm', Id, Format), Format == 'URDF',
    file_base_name(F, B), file_name_extension(Id, _, B),
    % the object's frame hangs below its base link's frame
    store_pose('Arm', any, [Ref|_], _), Ref == r_base_link.

test(missing_file, [setup(store_reset), cleanup(store_reset), error(existence_error(urdf_file, '/no/such.urdf'))]) :-
    urdf_load('http://e.org/r#Arm', '/no/such.urdf', []).

test(not_a_urdf, [setup(store_reset), cleanup(store_reset), error(domain_error(urdf_file, _))]) :-
    tmp_file_stream(text, F, S), format(S, '<?xml version="1.0"?><scene/>~n', []), close(S),
    urdf_load('http://e.org/r#Arm', F, []).

:- end_tests(kb_urdf).
