:- module(query_policy,
    [ exposed/3,                  % ?Module, ?Name/Arity, ?Class
      goal_argument/3             % ?Module, ?Name/Arity, ?Index
    ]).
/** <module> Which predicates a service query may call: one table line per predicate

`/api/prolog` (json_query/2) runs a goal only when every predicate in it is on this table as
`read`: a pure reader of the NEEM, the ontology or a term. The table is an allow-list: a
predicate that is not on it is refused, whatever its name. Every predicate exported by a module
under prolog/ has a line here (query_policy.plt fails naming any that has none), so a new
export is exposed only when someone decides it reads.

Classes:
  - `read`: reads only (no store write, no global state, no file, no output);
  - `write`: changes the NEEM or the session's state; refused unless the service runs with
    `--allow-prolog-writes` (which needs a token);
  - `hidden`: never exposed: the store's own access, file loading, test fixtures, the
    service's plumbing, anything that calls a goal it was given as data.

The builtins and library predicates at the end are the pure ones a query needs for terms,
atoms, arithmetic and lists; they are classed by the module that defines them (`system`,
`lists`, `pairs`), as json_query resolves a goal to its defining module before looking it up.
*/

%!  exposed(?Module, ?PI, ?Class) is nondet.
%   The predicate Name/Arity of Module is in Class: `read`, `write` or `hidden`.

% -- the robot's answers (prolog/answers.pl)
exposed(answers, why_not/2, read).
exposed(answers, why_not/3, read).
exposed(answers, what_next/1, read).
exposed(answers, something_else/2, read).
exposed(answers, something_else/3, read).
exposed(answers, chosen_after/3, read).
exposed(answers, call_text/2, read).
exposed(answers, reason_dict/2, read).
exposed(answers, answer_json/1, hidden).       % answers the bridge's pending request
% -- service and tool plumbing
exposed(batch_toplevel, batch_queries/3, hidden).
exposed(batch_toplevel, batch_goal/2, hidden).
exposed(json_query, json_query/2, hidden).
exposed(json_query, safe_query/1, hidden).
exposed(json_query, safe_query/2, hidden).
% rosprolog_solution/2 runs the text it is given, checked first with this table's `read` lines
% (the _writing one with `read` and `write`), as json_query/2 checks /api/prolog's text
exposed(rosprolog_json, rosprolog_solution/2, read).
exposed(rosprolog_json, rosprolog_solution_writing/2, write).
exposed(rosprolog_json, rosprolog_encode/2, read).
exposed(json_text, json_text/2, hidden).
exposed(json_text, json_data_text/2, hidden).
exposed(query_policy, exposed/3, hidden).
exposed(query_policy, goal_argument/3, hidden).
% -- KnowRob 2.x conformance harness and test fixtures
exposed(knowrob_2x, knowrob_suite_setup/2, hidden).
exposed(knowrob_2x, knowrob_2x_units/1, hidden).
exposed(knowrob_2x, knowrob_2x_score/3, hidden).
exposed(knowrob_2x, knowrob_fixture/2, hidden).
exposed(knowrob_2x, assert_true/1, hidden).
exposed(knowrob_2x, assert_false/1, hidden).
exposed(knowrob_2x, assert_equals/2, hidden).
exposed(knowrob_2x, assert_unifies/2, hidden).
exposed(knowrob_2x, test_call/3, hidden).
exposed(history_reference, situation_history_reference/1, hidden).
exposed(history_reference, load_generated_episode/2, hidden).
exposed(test_episode, load_test_episode/0, hidden).
exposed(fixture_triples, fixture_assert/4, hidden).
% -- the store itself (prolog/store/, its public predicates re-exported by the facade
%    prolog/neem_store.pl): reached only through the language
exposed(store_neem, store_backend/1, hidden).
exposed(store_neem, store_use_memory/0, hidden).
exposed(store_neem, store_use_python/1, hidden).
exposed(store_neem, store_current_neem/1, hidden).
exposed(store_neem, store_reset/0, hidden).
exposed(store_python, store_python_ready/0, hidden).
exposed(store_python, store_python_call/3, hidden).
exposed(store_python, store_python_rows/2, hidden).
exposed(store_python, store_python_request/1, hidden).
exposed(store_python, store_set_request/1, hidden).
exposed(store_pattern, store_taxonomic/1, hidden).
exposed(store_pattern, store_closure_edge/1, hidden).
exposed(store_pattern, store_check_pattern/1, hidden).
exposed(store_pattern, store_check_term/1, hidden).
exposed(store_pattern, store_compare/3, hidden).
exposed(store_scope, store_scope_now/1, hidden).
exposed(store_scope, store_check_scope/1, hidden).
exposed(store_scope, store_in_scope/3, hidden).
exposed(store_scope, store_scope_intersection/4, hidden).
exposed(store_scope, store_in_graphs/2, hidden).
exposed(store_scope, store_query_graphs/1, hidden).
exposed(store_memory, store_assert/1, hidden).
exposed(store_memory, store_assert/3, hidden).
exposed(store_memory, store_memory_insert/3, hidden).
exposed(store_memory, store_memory_retract/1, hidden).
exposed(store_memory, store_memory_drop_graph/1, hidden).
exposed(store_memory, store_memory_match/3, hidden).
exposed(store_write, store_insert/1, hidden).
exposed(store_write, store_insert/2, hidden).
exposed(store_write, store_insert/3, hidden).
exposed(store_write, store_retract/1, hidden).
exposed(store_read, store_match/2, hidden).
exposed(store_read, store_match/3, hidden).
exposed(store_read, store_match_scoped/3, hidden).
exposed(store_graph, store_graph_version/2, hidden).
exposed(store_graph, store_set_graph_version/3, hidden).
exposed(store_graph, store_drop_graph/1, hidden).
exposed(store_annotations, store_annotation/3, hidden).
exposed(store_annotations, store_insert_annotations/1, hidden).
exposed(store_tf, store_pose/4, hidden).
exposed(store_tf, store_assert_pose/3, hidden).
exposed(store_tf, store_poses/4, hidden).
% -- the query language (prolog/lang/)
exposed(kb_owl_guard, owl_file_safe/1, hidden). % reads a file's head (load_owl's check)
exposed(kb_db, load_owl/1, hidden).             % reads a file, replaces a graph
exposed(kb_db, load_owl/2, hidden).
exposed(kb_db, annotation/3, read).
exposed(kb_db, has_label/2, read).
exposed(kb_db, has_comment/2, read).
exposed(kb_aggregate, aggregate/1, read).
exposed(kb_holds, holds/1, read).
exposed(kb_holds, holds/3, read).
exposed(kb_query, kb_call/1, read).
exposed(kb_query, kb_call/2, read).
exposed(kb_query, kb_call/3, read).
exposed(kb_query, kb_call/4, read).
exposed(kb_query, kb_call_stepwise/1, read).
exposed(kb_query, kb_call_stepwise/2, read).
exposed(kb_query, kb_compile/3, hidden).
exposed(kb_query, kb_findall/4, read).
exposed(kb_query, kb_findall/5, read).
exposed(kb_query, kb_group/5, read).
exposed(kb_query, kb_project/1, write).
exposed(kb_query, kb_project/2, write).
exposed(kb_query, kb_project/3, write).
exposed(kb_query, kb_unproject/1, write).
exposed(kb_scope, universal_scope/1, read).
exposed(kb_scope, current_scope/1, read).
exposed(kb_scope, scope_check/1, read).
exposed(kb_scope, scope_overlaps/3, read).
exposed(kb_scope, runtime_scope/3, read).
exposed(kb_scope, scope_term/2, read).
exposed(kb_scope, scope_dict/2, read).
exposed(kb_scope, wildcard_scope/1, read).
exposed(kb_scope, time_scope/3, read).
exposed(kb_scope, time_scope_data/2, read).
exposed(kb_scope, subscope_of/2, read).
exposed(kb_scope, scope_intersect/3, read).
exposed(kb_subgraph, add_subgraph/2, write).
exposed(kb_subgraph, get_supgraphs/2, read).
exposed(kb_subgraph, graph_filter/2, read).
exposed(kb_subgraph, subgraph_reset/0, write).
exposed(kb_temporal, during/2, read).
exposed(kb_temporal, since/2, read).
exposed(kb_temporal, until/2, read).
exposed(kb_temporal, occurs/1, read).
exposed(kb_triple, triple/3, read).
exposed(kb_triple, kb_iri/2, read).
exposed(kb_triple, iri_term/1, read).
exposed(kb_triple, triple_steps/6, hidden).     % the compiler's internals
exposed(kb_triple, value_test/3, read).
exposed(kb_triple, modified_triple/4, hidden).
exposed(kb_triple, unit_factor/2, read).
% -- the model (prolog/model/)
exposed(soma_action, action_status/2, read).
exposed(soma_action, action_succeeded/1, read).
exposed(soma_action, action_failed/1, read).
exposed(soma_action, action_active/1, read).
exposed(soma_action, action_paused/1, read).
exposed(dul_event, is_event/1, read).
exposed(dul_event, is_action/1, read).
exposed(dul_event, is_mental_action/1, read).
exposed(dul_event, executes_task/2, read).
exposed(dul_event, is_performed_by/2, read).
exposed(dul_event, has_participant/2, read).
exposed(dul_event, has_participant/3, read).
exposed(dul_event, has_subevent/2, read).
exposed(dul_event, has_time_interval/2, read).
exposed(dul_event, has_interval_begin/2, read).
exposed(dul_event, has_interval_end/2, read).
exposed(dul_event, event_interval/3, read).
exposed(allen_interval, interval/2, read).
exposed(allen_interval, interval_before/2, read).
exposed(allen_interval, interval_after/2, read).
exposed(allen_interval, interval_meets/2, read).
exposed(allen_interval, interval_met_by/2, read).
exposed(allen_interval, interval_overlaps/2, read).
exposed(allen_interval, interval_overlapped_by/2, read).
exposed(allen_interval, interval_starts/2, read).
exposed(allen_interval, interval_started_by/2, read).
exposed(allen_interval, interval_during/2, read).
exposed(allen_interval, interval_contains/2, read).
exposed(allen_interval, interval_finishes/2, read).
exposed(allen_interval, interval_finished_by/2, read).
exposed(allen_interval, interval_equals/2, read).
exposed(dul_object, is_object/1, read).
exposed(dul_object, is_physical_object/1, read).
exposed(dul_object, is_agent/1, read).
exposed(dul_object, is_role/1, read).
exposed(dul_object, has_role/2, read).
exposed(dul_object, is_classified_by/2, read).
exposed(dul_object, has_region/2, read).
exposed(model_rdfs, instance_of/2, read).
exposed(model_rdfs, subclass_of/2, read).
exposed(model_rdfs, subproperty_of/2, read).
exposed(model_rdfs, has_type/2, read).
exposed(model_rdfs, is_resource/1, read).
exposed(model_rdfs, is_property/1, read).
exposed(model_rdfs, has_range/2, read).
exposed(model_rdfs, has_domain/2, read).
exposed(model_rdfs, rdf_list/2, read).
exposed(model_rdfs, rdf_list_head/2, read).
exposed(model_rdfs, new_iri/1, hidden).         % mints IRIs for writers
exposed(model_rdfs, new_iri/2, hidden).
exposed(dul_situation, is_task/1, read).
exposed(dul_situation, is_physical_task/1, read).
exposed(dul_situation, is_episode/1, read).
exposed(dul_situation, task_role/2, read).
exposed(dul_situation, plan_defines_task/2, read).
exposed(dul_situation, is_setting_for/2, read).
exposed(dul_situation, satisfies/2, read).
exposed(dul_situation, is_diagnosis/1, read).
exposed(kb_tf, is_at/2, read).
exposed(kb_tf, tf_get_pose/3, read).
exposed(kb_tf, object_frame_name/2, read).
% -- the odb model (prolog/odb/)
exposed(odb_calls, task_class/2, read).
exposed(odb_calls, task_call/2, read).
exposed(odb_calls, task_calls/2, read).
exposed(odb_calls, task_calls_reached/3, hidden).   % calls the goal it is given
exposed(odb_calls, task_calls_reached/4, hidden).   % calls the goal it is given
exposed(odb_calls, task_calls/3, hidden).   % calls the goals it is given
exposed(odb_calls, call_tasks/2, read).
exposed(odb_calls, call_task_times/3, read).
exposed(odb_calls, call_time/4, read).
exposed(odb_calls, call_time/5, read).
exposed(odb_calls, action_call/4, read).
exposed(odb_calls, times_done/2, read).
exposed(odb_calls, chain_before/3, read).
exposed(odb_decisions, decision/3, read).
exposed(odb_decisions, decision_at/3, read).
exposed(odb_decisions, latest_decision/4, read).
exposed(odb_decisions, latest_first/4, read).
exposed(odb_decisions, imagined_available/2, read).
exposed(odb_decisions, available_tasks_at/2, read).
exposed(odb_decisions, imagined_preference/2, read).
exposed(odb_decisions, preference_at/3, read).
exposed(odb_decisions, latest_preference/3, read).
exposed(odb_decisions, times_available/2, read).
exposed(odb_decisions, action_time/5, read).
exposed(odb_events, event_time_of_day/2, read).
exposed(odb_events, is_idle_action/1, read).
exposed(odb_events, idle_action/3, read).
exposed(odb_events, perceived_at/2, read).
exposed(odb_history, situation_history/1, read).
exposed(odb_history, situation_history_after/2, read).
exposed(odb_history, situation_history_json/1, read).
exposed(odb_history, situation_history_json/2, read).
exposed(odb_history, situation_history_json/3, read).
exposed(odb_history, history_slice_bounds/2, read).
exposed(odb_history, history_slice_bounds_json/2, read).
exposed(odb_history, latest_situation/2, read).
exposed(odb_history, latest_situation/3, read).
exposed(odb_history, history_view_json/2, read).
exposed(odb_history, latest_situation_json/1, read).
exposed(odb_history, action_modes/2, read).
exposed(odb_history, typed_modes/2, read).
exposed(odb_names, odb_iri/2, read).
exposed(odb_names, odb_set_namespace/1, write).
exposed(odb_names, odb_set_task_roles/3, write).
exposed(odb_names, odb_task_roles/3, read).
exposed(odb_names, call_classes/3, read).
exposed(odb_past, latest_time/1, read).
exposed(odb_past, done_between/3, read).
exposed(odb_past, last_done/3, read).
exposed(odb_past, done_times/4, read).
exposed(odb_past, usual_after/3, read).
exposed(odb_past, suggestion/3, read).
exposed(odb_past, object_place/3, read).
exposed(odb_past, last_before/2, read).
exposed(odb_past, latest_before/3, read).
exposed(odb_past, performers/2, read).
exposed(odb_past, past_answer_json/1, hidden).   % answers the bridge's pending request
% -- model_owl_description
exposed(model_owl_description, is_owl_term/1, read).
exposed(model_owl_description, is_restriction_term/1, read).
exposed(model_owl_description, is_restriction/2, read).
exposed(model_owl_description, is_union_of/2, read).
exposed(model_owl_description, is_intersection_of/2, read).
exposed(model_owl_description, is_complement_of/2, read).
exposed(model_owl_description, has_description/2, read).
exposed(model_owl_description, instance_of_description/2, read).
% -- soma_shape
exposed(soma_shape, object_localization/2, read).
exposed(soma_shape, object_shape_type/2, read).
exposed(soma_shape, object_mesh_path/2, read).
exposed(soma_shape, object_color_rgb/4, read).
exposed(soma_shape, object_dimensions/4, read).
exposed(soma_shape, object_shape/5, read).
% -- dul_description
exposed(dul_description, is_event_type/1, read).
exposed(dul_description, is_process/1, read).
exposed(dul_description, is_description/1, read).
exposed(dul_description, is_situation/1, read).
exposed(dul_description, is_goal/1, read).
exposed(dul_description, is_design/1, read).
exposed(dul_description, is_plan/1, read).
exposed(dul_description, is_plan_execution/1, read).
exposed(dul_description, is_norm/1, read).
exposed(dul_description, is_transition/1, read).
exposed(dul_description, has_task_role/2, read).
exposed(dul_description, task_role_type/3, read).
exposed(dul_description, task_role_range/3, read).
exposed(dul_description, has_parameter/2, read).
exposed(dul_description, has_parameter/3, read).
exposed(dul_description, has_parameter_range/3, read).
exposed(dul_description, has_assignment/2, read).
exposed(dul_description, plan_has_goal/2, read).
% -- allen_interval
exposed(allen_interval, interval_constraint/2, read).
exposed(allen_interval, interval_constraint/3, read).
exposed(allen_interval, interval_query/1, read).
exposed(allen_interval, interval_order/2, read).
% -- soma_workflow
exposed(soma_workflow, workflow_step/2, read).
exposed(soma_workflow, workflow_first_step/2, read).
exposed(soma_workflow, workflow_constituent/2, read).
exposed(soma_workflow, workflow_role_range/3, read).
exposed(soma_workflow, has_process_role/2, read).
exposed(soma_workflow, task_effect/2, read).
exposed(soma_workflow, has_kinematics_file/3, read).
exposed(soma_workflow, has_interval_duration/2, read).
exposed(soma_workflow, is_interval_equal/2, read).
exposed(soma_workflow, workflow_sequence/2, read).
% -- soma_types
exposed(soma_types, is_manipulation_action/1, read).
exposed(soma_types, is_mental_task/1, read).
exposed(soma_types, is_computational_agent/1, read).
exposed(soma_types, is_digital_object/1, read).
exposed(soma_types, is_kino_dynamic_data/1, read).
exposed(soma_types, is_chemical_process/1, read).
exposed(soma_types, is_physical_process/1, read).
exposed(soma_types, is_process_flow/1, read).
exposed(soma_types, is_process_type/1, read).
exposed(soma_types, is_motion/1, read).
exposed(soma_types, is_force_interaction/1, read).
exposed(soma_types, is_progression/1, read).
exposed(soma_types, is_state/1, read).
exposed(soma_types, is_physical_state/1, read).
exposed(soma_types, is_social_state/1, read).
exposed(soma_types, is_configuration/1, read).
exposed(soma_types, is_state_type/1, read).
exposed(soma_types, is_binding/1, read).
exposed(soma_types, is_succeedence/1, read).
% -- model_rdfs
exposed(model_rdfs, is_literal/1, read).
exposed(model_rdfs, is_datatype/1, read).
exposed(model_rdfs, is_a/2, read).
exposed(model_rdfs, get_unique_name/2, read).
exposed(model_rdfs, is_unique_name/1, read).
% -- model_owl
exposed(model_owl, is_class/1, read).
exposed(model_owl, is_restriction/1, read).
exposed(model_owl, is_individual/1, read).
exposed(model_owl, is_all_disjoint_classes/1, read).
exposed(model_owl, is_object_property/1, read).
exposed(model_owl, is_data_property/1, read).
exposed(model_owl, is_functional_property/1, read).
exposed(model_owl, is_transitive_property/1, read).
exposed(model_owl, is_symmetric_property/1, read).
exposed(model_owl, has_inverse_property/2, read).
exposed(model_owl, has_property_chain/2, read).
exposed(model_owl, has_equivalent_class/2, read).
exposed(model_owl, same_as/2, read).
exposed(model_owl, disjoint_with/2, read).
exposed(model_owl, disjoint_with_direct/2, read).
% -- dul_object_types
exposed(dul_object_types, is_quality/1, read).
exposed(dul_object_types, is_concept/1, read).
exposed(dul_object_types, is_physical_artifact/1, read).
exposed(dul_object_types, is_social_object/1, read).
exposed(dul_object_types, is_region/1, read).
exposed(dul_object_types, is_parameter/1, read).
exposed(dul_object_types, is_time_interval/1, read).
exposed(dul_object_types, is_space_region/1, read).
exposed(dul_object_types, is_amount/1, read).
exposed(dul_object_types, is_physical_attribute/1, read).
exposed(dul_object_types, is_social_attribute/1, read).
exposed(dul_object_types, has_object_type/2, read).
exposed(dul_object_types, has_quality_type/2, read).
exposed(dul_object_types, has_location/2, read).
exposed(dul_object_types, has_part/2, read).
exposed(dul_object_types, has_data_value/2, read).
% -- model_qudt
exposed(model_qudt, qudt_unit/4, read).
exposed(model_qudt, qudt_conv/4, read).
% -- soma_object
exposed(soma_object, is_feature/1, read).
exposed(soma_object, is_affordance/1, read).
exposed(soma_object, is_disposition/1, read).
exposed(soma_object, is_physical_quality/1, read).
exposed(soma_object, is_social_quality/1, read).
exposed(soma_object, is_intrinsic/1, read).
exposed(soma_object, is_extrinsic/1, read).
exposed(soma_object, object_feature/2, read).
exposed(soma_object, object_feature_type/3, read).
exposed(soma_object, has_disposition/2, read).
exposed(soma_object, has_disposition_type/3, read).
exposed(soma_object, disposition_trigger_type/2, read).
exposed(soma_object, is_patient/1, read).
exposed(soma_object, is_instrument/1, read).
exposed(soma_object, is_location/1, read).
exposed(soma_object, is_destination/1, read).
exposed(soma_object, is_origin/1, read).
% -- plowl
exposed(plowl, owl_subclass_of/2, read).
exposed(plowl, owl_subproperty_of/2, read).
exposed(plowl, owl_property_range/3, read).
exposed(plowl, owl_property_cardinality/5, read).
exposed(plowl, owl_individual_of/3, read).
exposed(plowl, owl_satisfied_by/3, read).
exposed(plowl, owl_has/4, read).
exposed(plowl, owl_cardinality/5, read).
% -- fixture_owl_world
exposed(fixture_owl_world, load_owl_world/0, hidden).
exposed(fixture_owl_world, ow/2, hidden).
% -- knowrob_tests
exposed(knowrob_tests, begin_rdf_tests/2, hidden).
exposed(knowrob_tests, begin_rdf_tests/3, hidden).
exposed(knowrob_tests, end_rdf_tests/1, hidden).
exposed(knowrob_tests, knowrob_units_score/2, hidden).
exposed(knowrob_tests, assert_true/1, hidden).
exposed(knowrob_tests, assert_false/1, hidden).
exposed(knowrob_tests, assert_equals/2, hidden).
exposed(knowrob_tests, assert_unifies/2, hidden).
exposed(knowrob_tests, test_call/3, hidden).
% -- knowrob_2x
exposed(knowrob_2x, knowrob_marked/2, hidden).
% -- kb_subgraph
exposed(kb_subgraph, get_subgraphs/2, read).
exposed(kb_subgraph, load_graph_structure/0, hidden).
% -- kb_db
exposed(kb_db, load_owl/3, hidden).
% -- kb_query
exposed(kb_query, kb_unproject/2, write).
exposed(kb_query, kb_unproject/3, write).
exposed(kb_query, ask/1, read).
exposed(kb_query, ask/2, read).
exposed(kb_query, is_callable_with/2, hidden).
exposed(kb_query, call_with/3, hidden).
% -- kb_rules
exposed(kb_rules, kb_add_rule/2, write).
exposed(kb_rules, kb_drop_rule/1, write).
exposed(kb_rules, kb_expand/2, read).
% -- kb_mongolog
exposed(kb_mongolog, mongolog_call/1, read).
exposed(kb_mongolog, mongolog_call/2, read).
exposed(kb_mongolog, is_mongolog_predicate/1, read).
% -- kb_computable
exposed(kb_computable, computables/1, read).
exposed(kb_computable, add_computable_predicate/2, write).
exposed(kb_computable, add_computable_property/2, write).
exposed(kb_computable, drop_computable_predicate/1, write).
exposed(kb_computable, drop_computable_predicate/2, write).
exposed(kb_computable, drop_computable_property/1, write).
exposed(kb_computable, drop_computable_property/2, write).
exposed(odb_routines, routine_workflow/1, read).
exposed(odb_routines, workflow_calls/2, read).
exposed(odb_routines, stored_routines_json/1, read).
% -- neem-interface's needs: tf, urdf, mng_client, memorize/remember, execution states
exposed(soma_action, action_pending/1, read).
exposed(soma_action, action_cancelled/1, read).
exposed(kb_tf, tf_get_pose/4, read).
exposed(kb_tf, tf_set_pose/3, write).
exposed(kb_tf, tf_mng_trajectory/4, read).
exposed(kb_tf, pose_compose/3, read).
exposed(kb_tf, tf_logger_enable/0, write).
exposed(kb_tf, tf_logger_disable/0, write).
exposed(kb_tf, tf_mem_clear/0, write).
exposed(mng_client, mng_db_name/1, read).
exposed(mng_client, mng_drop/2, write).
exposed(kb_urdf, urdf_load/2, hidden).   % reads a file
exposed(kb_urdf, urdf_load/3, hidden).   % reads a file
exposed(kb_urdf, is_urdf_link/1, read).
exposed(kb_urdf, is_urdf_joint/1, read).
exposed(kb_urdf, has_base_link_name/2, read).
exposed(kb_urdf, has_urdf_prefix/2, read).
exposed(kb_urdf, has_base_link/2, read).
exposed(kb_urdf, has_child_link/2, read).
exposed(kb_urdf, has_parent_link/2, read).
exposed(kb_db, drop_graph/1, write).
exposed(kb_db, memorize/1, hidden).   % writes a dump folder
exposed(kb_db, remember/1, hidden).   % reads a dump folder
% -- pure builtins and library predicates: terms, comparison, arithmetic, atoms, lists
exposed(system, Name/Arity, read) :- pure_builtin(Name/Arity).
exposed(lists, member/2, read).
exposed(lists, nth0/3, read).
exposed(lists, nth1/3, read).
exposed(lists, last/2, read).
exposed(lists, append/3, read).
exposed(lists, reverse/2, read).
exposed(lists, list_to_set/2, read).
exposed(lists, sum_list/2, read).
exposed(lists, max_list/2, read).
exposed(lists, min_list/2, read).
exposed(pairs, pairs_keys_values/3, read).

pure_builtin(true/0). pure_builtin(fail/0). pure_builtin(false/0).
pure_builtin((=)/2). pure_builtin((\=)/2). pure_builtin((==)/2). pure_builtin((\==)/2).
pure_builtin((@<)/2). pure_builtin((@>)/2). pure_builtin((@=<)/2). pure_builtin((@>=)/2).
pure_builtin(compare/3).
pure_builtin((is)/2). pure_builtin((<)/2). pure_builtin((>)/2). pure_builtin((=<)/2).
pure_builtin((>=)/2). pure_builtin((=:=)/2). pure_builtin((=\=)/2).
pure_builtin(var/1). pure_builtin(nonvar/1). pure_builtin(atom/1). pure_builtin(number/1).
pure_builtin(integer/1). pure_builtin(float/1). pure_builtin(string/1). pure_builtin(is_list/1).
pure_builtin(compound/1). pure_builtin(ground/1). pure_builtin(atomic/1). pure_builtin(callable/1).
pure_builtin(functor/3). pure_builtin(arg/3). pure_builtin((=..)/2).
pure_builtin(atom_concat/3). pure_builtin(sub_atom/5). pure_builtin(atom_string/2).
pure_builtin(atom_length/2). pure_builtin(atom_number/2). pure_builtin(term_to_atom/2).
pure_builtin(atomic_list_concat/2). pure_builtin(atomic_list_concat/3).
pure_builtin(split_string/4). pure_builtin(string_concat/3). pure_builtin(sub_string/5).
pure_builtin(string_length/2). pure_builtin(number_codes/2). pure_builtin(atom_codes/2).
pure_builtin(memberchk/2). pure_builtin(length/2). pure_builtin(msort/2). pure_builtin(sort/2).
pure_builtin(sort/4).
pure_builtin(between/3). pure_builtin(succ/2). pure_builtin(plus/3).

%!  goal_argument(?Module, ?PI, ?Index) is nondet.
%   Argument Index of the `read` predicate Module:PI is a goal (KnowRob's query language or a
%   scope modifier): json_query checks it with the same table before anything runs.
goal_argument(kb_query, ask/1, 1).
goal_argument(kb_query, ask/2, 1).
goal_argument(kb_mongolog, mongolog_call/1, 1).
goal_argument(kb_mongolog, mongolog_call/2, 1).
goal_argument(kb_query, kb_call/1, 1).
goal_argument(kb_query, kb_call/2, 1).
goal_argument(kb_query, kb_call/3, 1).
goal_argument(kb_query, kb_call/4, 1).
goal_argument(kb_query, kb_call_stepwise/1, 1).
goal_argument(kb_query, kb_call_stepwise/2, 1).
goal_argument(kb_query, kb_findall/4, 2).
goal_argument(kb_query, kb_findall/5, 2).
goal_argument(kb_query, kb_group/5, 3).
goal_argument(kb_temporal, during/2, 1).
goal_argument(kb_temporal, since/2, 1).
goal_argument(kb_temporal, until/2, 1).
