:- module(soma_workflow,
    [ workflow_step/2,          % ?Workflow, ?Step
      workflow_first_step/2,    % ?Workflow, ?Step
      workflow_constituent/2,   % ?Workflow, ?Constituent
      workflow_role_range/3,    % ?Workflow, ?Role, ?ObjectType
      has_process_role/2,       % ?ProcessType, ?Role
      task_effect/2,            % ?Task, ?Effect
      has_kinematics_file/3,    % ?Object, ?Identifier, ?Format
      has_interval_duration/2,  % ?Interval, ?Duration
      is_interval_equal/2,      % ?Interval1, ?Interval2
      workflow_sequence/2       % +WorkflowOrSteps, -Sequence
    ]).
/** <module> Workflows, task effects, kinematics files and interval arithmetic (KnowRob 2.x src/model/SOMA.pl)

A workflow (a plan) has steps (soma:hasStep, soma:hasFirstStep) and defines tasks and
processes (its constituents); task_effect/2 reads what a task creates, destroys, alters, ...
from the `only` restrictions on the classes of its roles. Each relation is a kb_rule/2 and,
called from Prolog, kb_call/1 of itself; has_kinematics_file/3 also projects.
*/

:- use_module(library(lists)).
:- use_module('../lang/query', [kb_call/1]).
:- use_module(interval, [interval_order/2]).
:- use_module(library(semweb/rdf_prefixes), [rdf_global_term/2]).

:- multifile kb_query:kb_rule/2.
kb_query:kb_rule(workflow_step(W, S), holds(W, soma:hasStep, S)).
kb_query:kb_rule(workflow_first_step(W, S), holds(W, soma:hasFirstStep, S)).
kb_query:kb_rule(workflow_constituent(W, X),
                 ( triple(W, dul:describes, X) ; triple(W, dul:definesTask, X) ; triple(W, soma:definesProcess, X) )).
kb_query:kb_rule(workflow_role_range(W, R, T), ( workflow_constituent(W, Tsk), task_role_range(Tsk, R, T) )).
kb_query:kb_rule(has_process_role(P, R), holds(P, soma:isProcessTypeOf, R)).
kb_query:kb_rule(has_kinematics_file(O, Id, Format),
                 ( triple(IO, dul:isAbout, O), has_type(IO, soma:'KinoDynamicData'),
                   triple(IR, dul:realizes, IO), triple(IR, soma:hasPersistentIdentifier, Id),
                   triple(IR, soma:hasDataFormat, Format) )).
kb_query:kb_rule(has_interval_duration(I, D),
                 ( has_interval_begin(I, B), has_interval_end(I, E), D is E - B )).
kb_query:kb_rule(is_interval_equal(I1, I2),
                 ( has_interval_begin(I1, B), has_interval_begin(I2, B),
                   has_interval_end(I1, E), has_interval_end(I2, E) )).

:- multifile kb_query:kb_projection/2.
kb_query:kb_projection(has_kinematics_file(O, Id, Format),
                       [ has_type(IO, soma:'KinoDynamicData'), has_type(IR, soma:'DigitalResource'),
                         triple(IO, dul:isAbout, O), triple(IR, dul:realizes, IO),
                         triple(IR, soma:hasPersistentIdentifier, Id), triple(IR, soma:hasDataFormat, Format) ]) :-
    must_be(ground, O-Id-Format),
    model_rdfs:new_iri(IO, soma:'KinoDynamicData'),
    model_rdfs:new_iri(IR, soma:'DigitalResource').

%!  workflow_step(?Workflow, ?Step) is nondet.
workflow_step(W, S) :- kb_call(workflow_step(W, S)).
%!  workflow_first_step(?Workflow, ?Step) is nondet.
workflow_first_step(W, S) :- kb_call(workflow_first_step(W, S)).
%!  workflow_constituent(?Workflow, ?Constituent) is nondet.
%   What the workflow describes, the tasks and processes it defines.
workflow_constituent(W, X) :- kb_call(workflow_constituent(W, X)).
%!  workflow_role_range(?Workflow, ?Role, ?ObjectType) is nondet.
%   A role of a task of the workflow, restricted to classify ObjectType.
workflow_role_range(W, R, T) :- kb_call(workflow_role_range(W, R, T)).
%!  has_process_role(?ProcessType, ?Role) is nondet.
has_process_role(P, R) :- kb_call(has_process_role(P, R)).
%!  has_kinematics_file(?Object, ?Identifier, ?Format) is nondet.
%   A digital resource (its persistent identifier and data format) realizes kino-dynamic data
%   about Object.
has_kinematics_file(O, Id, F) :- kb_call(has_kinematics_file(O, Id, F)).
%!  has_interval_duration(?Interval, ?Duration) is nondet.
%   End minus begin of a time interval (seconds).
has_interval_duration(I, D) :- kb_call(has_interval_duration(I, D)).
%!  is_interval_equal(?Interval1, ?Interval2) is nondet.
%   Both intervals begin and end at the same times.
is_interval_equal(I1, I2) :- kb_call(is_interval_equal(I1, I2)).

%!  task_effect(?Task, ?Effect) is nondet.
%   What performing Task does to objects: `created(Type)`, `destroyed(Type)`, `linked(Type)`,
%   `commited(Type)`, `deposited(Type)`, `extracted(Type)`, `included(Type)` (the range of
%   the task's role of that kind) or `altered(Type, QualityType)` (the altered object's type
%   and the quality its setpoint region is a region for). Once when Effect is ground.
task_effect(T, Effect) :-
    (   ground(Effect) -> once(task_effect_(T, Effect)) ; task_effect_(T, Effect) ).

task_effect_(T, Effect) :-
    member(Effect-Role, [created(X)-'CreatedObject', destroyed(X)-'DestroyedObject', linked(X)-'LinkedObject',
                         commited(X)-'CommitedObject', deposited(X)-'DepositedObject',
                         extracted(X)-'ExtractedObject', included(X)-'IncludedObject']),
    atom_concat('http://www.ease-crc.org/ont/SOMA.owl#', Role, RoleType),
    kb_call(( task_role_range(T, R, X), has_type(R, RoleType) )).
task_effect_(T, altered(X, Q)) :-
    kb_call(( task_role_range(T, R, X), has_type(R, soma:'AlteredObject'),
              has_parameter_range(T, P, Region), has_type(P, soma:'Setpoint') )),
    once(( kb_call(holds(Region, dul:isRegionFor, only(Q))),
           Q \== 'http://www.ontologydesignpatterns.org/ont/dul/DUL.owl#Quality' )).

%!  workflow_sequence(+WorkflowOrSteps, -Sequence) is det.
%   The steps of a workflow (or a list of steps) in the order their times or the Allen
%   relations SOMA states among them (soma:before, soma:meets, ...) give them (KnowRob's
%   src/reasoning/temporal/workflow.pl).
workflow_sequence(WF0, Seq) :-
    rdf_global_term(WF0, WF),
    (   is_list(WF) -> Steps = WF
    ;   findall(S, workflow_step(WF, S), Steps0), sort(Steps0, Steps)
    ),
    interval_order(Steps, Seq0),
    rdf_global_term(Seq, Seq1),
    Seq1 = Seq0.
