:- module(neem_interface_compat, []).
/** <module> What robot code written for KnowRob 2.x needs around the predicates mirrored here

code-iai/neem-interface (`neem-interface.pl`, used through neem_interface_python by CRAM and
Unreal set-ups) is consulted unchanged into `user`. Beyond the model predicates it needs:

  - `:- use_module(library('db/mongo/client'))` to find a module: this module puts
    `compat/library/` on the `library` search path (mng_client: mng_drop/2);
  - `new_iri(I, Class)` inside kb_project/1 lists, as KnowRob's projection runs it: here a
    kb_projection/2 of `true` after naming I (model/rdfs new_iri/2);
  - an individual left unbound by `has_type(Role, RoleType)` in kb_project/1
    (add_participant_with_role/3): named by new_iri/2 (kb_query:fresh_individual/2), where
    KnowRob 2.x raises an instantiation error (its issue #299).

The other predicates it calls are the model's (docs/prolog.md, "neem-interface").
*/

:- use_module(library(error)).
:- use_module('../model/rdfs', [new_iri/2]).

:- multifile user:file_search_path/2.
:- dynamic user:file_search_path/2.
:- prolog_load_context(directory, Dir),
   atom_concat(Dir, '/library', Lib),
   (   user:file_search_path(library, Lib) -> true ; asserta(user:file_search_path(library, Lib)) ).

:- multifile kb_query:kb_projection/2.
kb_query:kb_projection(new_iri(I, C), true) :-
    (   var(I) -> new_iri(I, C) ; true ).
kb_query:kb_projection(new_iri(I), true) :-
    (   var(I) -> new_iri(I, rdfs:'Resource') ; true ).

:- multifile kb_query:fresh_individual/2.
kb_query:fresh_individual(I, C) :-
    new_iri(I, C).
