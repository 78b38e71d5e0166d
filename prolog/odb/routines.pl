:- module(odb_routines,
    [ routine_workflow/1,         % ?Workflow
      workflow_calls/2,           % +Workflow, -Calls
      stored_routines_json/1      % -JSONString
    ]).
/** <module> The user's routines stored as SOMA/DUL workflows (oracle.past.workflows)

A routine is a dul:Workflow whose steps (soma:hasStep) are odb task individuals, the first
named by soma:hasFirstStep and each next one by soma:before, as KnowRob's workflow_step/2 and
workflow_first_step/2 read them; its name is its rdfs:label.
*/

:- use_module(library(error)).
:- use_module(library(lists)).
:- use_module('../json_text', [json_text/2]).
:- use_module('../lang/query', [kb_call/2]).
:- use_module('../model/rdfs', []).
:- use_module(names, [odb_iri/2]).
:- use_module(calls, [task_call/2]).
:- use_module('../answers', [call_text/2]).

%!  routine_workflow(?Workflow) is nondet.
%   Workflow is a dul:Workflow of the NEEM.
routine_workflow(WF) :-
    kb_call(instance_of(WF, dul:'Workflow'), any).

%!  workflow_calls(+Workflow, -Calls) is det.
%   The calls of the workflow's steps in order: from its first step along soma:before.
workflow_calls(WF, Calls) :-
    must_be(atom, WF),
    (   kb_call(triple(WF, soma:hasFirstStep, First), any)
    ->  steps_from(First, [First], Steps)
    ;   Steps = []
    ),
    findall(C, ( member(S, Steps), task_call(S, C) ), Calls).

steps_from(Step, Seen, [Step|Rest]) :-
    (   kb_call(triple(Step, soma:before, Next), any), \+ memberchk(Next, Seen)
    ->  steps_from(Next, [Next|Seen], Rest)
    ;   Rest = []
    ).

%!  stored_routines_json(-JSON) is det.
%   Every stored routine as `{iri, name, steps, days, hour, by_user}`, as a JSON string.
stored_routines_json(JSON) :-
    findall(WF, routine_workflow(WF), WFs0),
    sort(WFs0, WFs),
    findall(_{iri: WF, name: Name, steps: Texts, days: Days, hour: Hour, by_user: ByUser},
            ( member(WF, WFs),
              value(WF, rdfs:label, '', Name),
              odb_iri(routineDays, DP), value(WF, DP, 0, Days),
              odb_iri(routineUsualHour, HP), value(WF, HP, 0, Hour),
              odb_iri(routineNamedByUser, UP), value(WF, UP, false, ByUser0), truth(ByUser0, ByUser),
              workflow_calls(WF, Calls), findall(T, ( member(C, Calls), call_text(C, T) ), Texts) ),
            Dicts),
    json_text(Dicts, JSON).

value(S, P, Default, V) :-
    (   kb_call(triple(S, P, V0), any) -> V = V0 ; V = Default ).

truth(V, true) :- ( V == true ; V == 1 ; V == 'true' ), !.
truth(_, false).
