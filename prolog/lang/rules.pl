:- module(kb_rules,
    [ kb_add_rule/2,            % +Head, +Body
      kb_drop_rule/1,           % +Head
      kb_expand/2,              % +Goal, -Expanded
      op(1100, xfx, ?>),
      op(1100, xfx, +>),
      op(1100, xfx, ?+>)
    ]).
/** <module> KnowRob's rule declarations: `?>`, `+>`, `?+>` (KnowRob 2.x src/lang/query.pl)

A file written for KnowRob declares model predicates as rules:

    is_kitchen_tool(X) ?> has_type(X, soma:'Cutlery').
    has_colour(O, C) ?+> holds(O, soma:hasColor, C).

`Head ?> Body` is a query rule: Body answers Head inside kb_call/1, unfolded into the
compiled store query like the project's own rules (a kb_query:kb_rule/2 clause); `Head +>
Body` a projection rule: kb_project(Head) asserts Body (a kb_query:kb_projection/2
clause); `Head ?+> Body` both. The first rule of a predicate also defines Head in the
file's module as `Head :- kb_call(Head)`, so it can be called from Prolog (unless the module
defines or imports that predicate already). Several query rules of one predicate are
alternatives; `pragma(Goal)` in a body runs when the query is compiled.

The operators are declared in module `user` (as KnowRob does), so any file can use them once
this module is loaded. kb_add_rule/2 and kb_drop_rule/1 add and remove query rules at run
time; kb_expand/2 shows what a goal unfolds to.
*/

:- use_module(library(error)).
:- use_module(library(lists)).
:- use_module(query, [kb_call/1]).

:- op(1100, xfx, user:(?>)).
:- op(1100, xfx, user:(+>)).
:- op(1100, xfx, user:(?+>)).

%   rule_clauses(+Term, +Module, -Clauses): the clauses a rule declaration stands for.
rule_clauses((Head ?> Body), M, Clauses) :- !,
    query_clauses(Head, Body, M, Clauses).
rule_clauses((Head +> Body), _, [kb_query:kb_projection(Head, Body)]) :- !,
    must_be(callable, Head).
rule_clauses((Head ?+> Body), M, [kb_query:kb_projection(Head, Body)|Clauses]) :-
    query_clauses(Head, Body, M, Clauses).

query_clauses(Head0, Body, M, [kb_query:kb_rule(Head, Body)|Wrapper]) :-
    strip_module(Head0, _, Head),
    must_be(callable, Head),
    (   Head0 \= _:_, functor(Head, F, N), \+ known(M, F, N)
    ->  Wrapper = [(Head1 :- kb_rules:rule_call(Head1))],
        functor(Head1, F, N)
    ;   Wrapper = []
    ).

known(M, F, N) :-
    functor(H, F, N),
    (   predicate_property(M:H, defined) ; predicate_property(M:H, imported_from(_)) ), !.

%!  rule_call(+Goal) is nondet.
%   The Prolog definition a rule file's first rule of a predicate gets: kb_call/1 of it
%   (no solution once its rules are dropped).
rule_call(Goal) :-
    functor(Goal, F, N), functor(G0, F, N),
    (   clause(kb_query:kb_rule(G0, _), true) -> kb_call(Goal) ; fail ).

:- multifile user:term_expansion/2.
:- dynamic user:term_expansion/2.
user:term_expansion(Rule, Clauses) :-
    compound(Rule), functor(Rule, Op, 2), memberchk(Op, [?>, +>, ?+>]),
    prolog_load_context(module, M),
    rule_clauses(Rule, M, Clauses).

%!  kb_add_rule(+Head, +Body) is det.
%   Add the query rule `Head ?> Body` (kb_call/1 unfolds Head into Body).
kb_add_rule(Head, Body) :-
    must_be(callable, Head), must_be(callable, Body),
    assertz(kb_query:kb_rule(Head, Body)).

%!  kb_drop_rule(+Head) is det.
%   Remove the query rules whose head unifies with Head (those kb_add_rule/2 or a rule file
%   added; the project's own model rules are part of its modules and stay).
kb_drop_rule(Head) :-
    must_be(callable, Head),
    forall(( clause(kb_query:kb_rule(H, B), true, Ref), \+ H \= Head, \+ own_rule(Ref) ),
           ( _ = B, erase(Ref) )).

own_rule(Ref) :-
    clause_property(Ref, file(File)),
    module_property(kb_query, file(QF)),
    file_directory_name(QF, LangDir), file_directory_name(LangDir, PrologDir),
    sub_atom(File, 0, _, _, PrologDir).

%!  kb_expand(+Goal, -Expanded) is det.
%   Goal with every model predicate replaced by the bodies of its query rules (several as a
%   disjunction), down to triple/3 and Prolog goals; a recursive rule is left as its call.
kb_expand(Goal, Expanded) :-
    must_be(callable, Goal),
    expand(Goal, [], Expanded).

expand(G, _, G) :- var(G), !.
expand(M:G, Stack, M:E) :- atom(M), !, expand(G, Stack, E).
expand((A, B), S, (EA, EB)) :- !, expand(A, S, EA), expand(B, S, EB).
expand((A ; B), S, (EA ; EB)) :- !, expand(A, S, EA), expand(B, S, EB).
expand((A -> B), S, (EA -> EB)) :- !, expand(A, S, EA), expand(B, S, EB).
expand(\+ A, S, \+ EA) :- !, expand(A, S, EA).
expand(G, Stack, E) :-
    functor(G, F, N),
    \+ memberchk(F/N, Stack),
    findall(G-B, kb_query:kb_rule(G, B), Rules0),
    Rules0 \== [], !,
    findall(EB, ( member(G-B, Rules0), expand(B, [F/N|Stack], EB) ), Bodies),
    disjunction(Bodies, E).
expand(G, _, G).

disjunction([B], B) :- !.
disjunction([B|Bs], (B ; R)) :- disjunction(Bs, R).
