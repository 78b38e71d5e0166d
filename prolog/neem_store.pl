:- module(neem_store, []).
/** <module> NEEM store access: the triple store's facade

The store lives in focused modules under prolog/store/, split as KnowRob 2.x splits its
triple store (a small `tripledb` facade over an interface and its backends). This module has
no predicate of its own: it re-exports the triple store's API (19 predicates), so that a
module or test that reads and writes triples loads one file:

  | store/neem.pl        | store_neem        | which backend (`memory`, `python(NeemId)`) answers; store_reset/0 |
  | store/python.pl      | store_python      | the Python request channel: the only module calling the foreign predicates |
  | store/pattern.pl     | store_pattern     | what a pattern `t(S,P,O)` may say; the taxonomic properties |
  | store/scope.pl       | store_scope       | when (time scopes) and where (named graphs) a fact is visible |
  | store/memory.pl      | store_memory      | the memory backend's triples and their evaluation |
  | store/write.pl       | store_write       | store_insert/1,2,3 and store_retract/1 (kb_project, kb_unproject) |
  | store/read.pl        | store_read        | store_match/2,3 and store_match_scoped/3: one conjunction, one query |

The store's other collections are imported from their own modules, which the facade does not
load: store/graph.pl (store_graph: version markers, store_drop_graph/1),
store/annotations.pl (store_annotations: labels and comments) and store/tf.pl (store_tf:
poses).

Each predicate has one home: json_query and query_policy name the module that defines it,
and the bridge imports the same definition from the facade and from its home.
*/

% The triple store's API; the helpers the store's modules share (checks, scope tests, the
% memory backend's and the channel's primitives) are imported from their home.
:- reexport(store/neem, [store_backend/1, store_use_memory/0, store_use_python/1, store_current_neem/1,
                         store_reset/0]).
:- reexport(store/python, [store_python_request/1, store_set_request/1]).
:- reexport(store/pattern, [store_taxonomic/1]).
:- reexport(store/scope, [store_scope_now/1, store_in_graphs/2]).
:- reexport(store/memory, [store_assert/1, store_assert/3]).
:- reexport(store/write, [store_insert/1, store_insert/2, store_insert/3, store_retract/1]).
:- reexport(store/read, [store_match/2, store_match/3, store_match_scoped/3]).
