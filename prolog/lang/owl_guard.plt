:- begin_tests(kb_owl_guard).

:- use_module(library(process)).
:- use_module(library(uuid)).

:- use_module(owl_guard).
:- use_module(db).
:- use_module('../neem_store').

%   A file of Text in a fresh temporary folder, removed when the suite's swipl halts. The uuid:
%   tmp_file/2's name repeats when a later process gets the same pid.
owl(Name, Text, File) :-
    tmp_file(owlguard, Base), uuid(Id), atomic_list_concat([Base, '_', Id], Dir),
    make_directory(Dir), at_halt(catch(delete_directory_and_contents(Dir), _, true)),
    atomic_list_concat([Dir, '/', Name], File),
    setup_call_cleanup(open(File, write, Out), write(Out, Text), close(Out)).

refused_because(File, Fragment) :-
    catch(owl_file_safe(File), error(permission_error(load, owl_file, File), context(_, Why)), true),
    nonvar(Why), sub_atom(Why, _, _, _, Fragment).

rdf(Doctype, Body, Text) :-
    format(atom(Text), '<?xml version="1.0"?>~n~w<rdf:RDF xmlns:rdf="http://www.w3.org/1999/02/22-rdf-syntax-ns#" xmlns:owl="http://www.w3.org/2002/07/owl#"><owl:Ontology rdf:about="http://x/o"/>~w</rdf:RDF>~n', [Doctype, Body]).

test(nested_entities_refused_before_rdf_load) :-
    rdf('<!DOCTYPE rdf:RDF [<!ENTITY a "aaaaaaaaaa"><!ENTITY b "&a;&a;&a;&a;&a;&a;&a;&a;&a;&a;">]>', '<owl:Thing rdf:about="http://x/&b;"/>', T),
    owl('nested.owl', T, F),
    refused_because(F, 'nested entities'),
    catch(load_owl(F), error(permission_error(load, owl_file, _), _), true).

test(external_and_parameter_entities_refused) :-
    rdf('<!DOCTYPE rdf:RDF [<!ENTITY x SYSTEM "file:///etc/passwd">]>', '', T1), owl('ext.owl', T1, F1),
    refused_because(F1, 'external entity'),
    rdf('<!DOCTYPE rdf:RDF [<!ENTITY % p "x">]>', '', T2), owl('par.owl', T2, F2),
    refused_because(F2, 'parameter entity').

test(many_references_refused) :-
    length(L, 4000), maplist(=(x), L), atomic_list_concat(L, Long),
    length(R, 400), maplist(=('&e;'), R), atomic_list_concat(R, Refs),
    format(atom(D), '<!DOCTYPE rdf:RDF [<!ENTITY e "~w">]>', [Long]),
    format(atom(B), '<owl:Thing rdf:about="http://x/t"><owl:versionInfo>~w</owl:versionInfo></owl:Thing>', [Refs]),
    rdf(D, B, T), owl('many.owl', T, F),
    refused_because(F, 'expand by').

test(a_fifo_is_not_opened) :-
    tmp_file(owlfifo, F),
    process_create(path(mkfifo), [F], []), at_halt(catch(delete_file(F), _, true)),
    refused_because(F, 'not a regular file').

test(iri_prefix_entities_load, [setup(store_reset), cleanup(store_reset)]) :-
    rdf('<!DOCTYPE rdf:RDF [<!ENTITY owl "http://www.w3.org/2002/07/owl#">]>', '<rdf:Description rdf:about="http://x/t"><rdf:type rdf:resource="&owl;Class"/></rdf:Description>', T),
    owl('prefix.owl', T, F),
    owl_file_safe(F),
    load_owl(F, [graph(test)]).

:- end_tests(kb_owl_guard).
