:- module(odb_names,
    [ odb_iri/2,                  % ?Local, ?IRI
      odb_set_namespace/1,        % +Namespace
      odb_set_task_roles/3,       % +TaskClass, +TargetRole, +RefRole
      odb_task_roles/3,           % ?TaskClass, ?TargetRole, ?RefRole
      call_classes/3              % +Call, -TaskClass, -ObjectClasses
    ]).
/** <module> odb names: IRIs of the odb ontology and the chain terms that name them

A call is a term whose functor is the odb task's local name and whose arguments are the
odb object local names, reference role first (chains.py), e.g. `pour(thermos, green_mug)`.
The namespace and which role of each task is the target and which the reference come
from the ontology (set by the Python bridge).
*/

:- use_module(library(error)).
:- use_module(library(apply)).
:- use_module(library(semweb/rdf_prefixes)).
:- use_module('../lang/triple', []).      % registers the odb prefix's default

:- dynamic task_roles_/3.         % TaskClass, TargetRole|none, RefRole|none

%!  odb_set_namespace(+Namespace) is det.
%   Use Namespace for the `odb` prefix (the ontology's, when not the default).
odb_set_namespace(NS) :-
    must_be(atom, NS),
    rdf_register_prefix(odb, NS, [force(true)]).

%!  odb_iri(?Local, ?IRI) is semidet.
%   IRI is Local in the odb namespace.
odb_iri(Local, IRI) :-
    rdf_current_prefix(odb, NS),
    (   nonvar(IRI)
    ->  atom(IRI), atom_concat(NS, Local, IRI), Local \== ''
    ;   must_be(atom, Local), atom_concat(NS, Local, IRI)
    ).

%!  odb_set_task_roles(+TaskClass, +TargetRole, +RefRole) is det.
%   Which role class is the target and which the reference of an odb task (`none` when
%   the task has none); orders the arguments of task calls. Set by the bridge from the
%   ontology.
odb_set_task_roles(Task, Target, Ref) :-
    must_be(atom, Task), must_be(atom, Target), must_be(atom, Ref),
    retractall(task_roles_(Task, _, _)),
    assertz(task_roles_(Task, Target, Ref)).

%!  odb_task_roles(?TaskClass, ?TargetRole, ?RefRole) is nondet.
%   The roles set by odb_set_task_roles/3.
odb_task_roles(Task, Target, Ref) :-
    task_roles_(Task, Target, Ref).

%!  call_classes(+Call, -TaskClass, -ObjectClasses) is det.
%   The odb class IRIs a chain term names.
call_classes(Call, TaskClass, ObjClasses) :-
    must_be(callable, Call),
    Call =.. [Name|Args],
    odb_iri(Name, TaskClass),
    maplist(odb_iri, Args, ObjClasses).
