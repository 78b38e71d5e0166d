:- module(neem_store, []).
/** <module> NEEM store access: the facade over the store's modules

The store's predicates live in the focused modules under prolog/store/, as KnowRob 2.x puts
a small `tripledb` facade over its backends. This module re-exports their public predicates (the
27 that callers use), so that a module or test that reaches the store loads one file:

  | store/neem.pl        | store_neem        | which backend (`memory`, `python(NeemId)`) answers; store_reset/0 |
  | store/python.pl      | store_python      | the Python request channel: the only module calling the foreign predicates |
  | store/pattern.pl     | store_pattern     | what a pattern `t(S,P,O)` may say; the taxonomic properties |
  | store/scope.pl       | store_scope       | when (time scopes) and where (named graphs) a fact is visible |
  | store/memory.pl      | store_memory      | the memory backend's triples and their evaluation |
  | store/write.pl       | store_write       | store_insert/1,2,3 and store_retract/1 (kb_project, kb_unproject) |
  | store/read.pl        | store_read        | store_match/2,3 and store_match_scoped/3: one conjunction, one query |
  | store/graph.pl       | store_graph       | named graphs: version markers, drop |
  | store/annotations.pl | store_annotations | labels, comments and other annotation values |
  | store/tf.pl          | store_tf          | poses of the NEEM's tf collection |

Each predicate has one home: json_query and query_policy name the module that defines it,
and the bridge imports the same definition from the facade and from its home.
*/

% The store's public predicates, as callers have always imported them from here; the
% helpers the store's modules share (checks, scope tests, the memory backend's and the
% channel's primitives) are imported from their home.
:- reexport(store/neem, [store_backend/1, store_use_memory/0, store_use_python/1, store_current_neem/1,
                         store_reset/0]).
:- reexport(store/python, [store_python_request/1, store_set_request/1]).
:- reexport(store/pattern, [store_taxonomic/1]).
:- reexport(store/scope, [store_scope_now/1, store_in_graphs/2]).
:- reexport(store/memory, [store_assert/1, store_assert/3]).
:- reexport(store/write, [store_insert/1, store_insert/2, store_insert/3, store_retract/1]).
:- reexport(store/read, [store_match/2, store_match/3, store_match_scoped/3]).
:- reexport(store/graph, [store_graph_version/2, store_set_graph_version/3, store_drop_graph/1]).
:- reexport(store/annotations, [store_annotation/3, store_insert_annotations/1]).
:- reexport(store/tf, [store_pose/4, store_assert_pose/3, store_poses/4]).
