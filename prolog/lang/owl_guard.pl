:- module(kb_owl_guard,
    [ owl_file_safe/1           % +File
    ]).
/** <module> An OWL file checked before rdf_load/2 reads it

load_owl/1,2 hands a file to SWI-Prolog's RDF/XML parser, which expands XML entities without
a bound: a 1 KB file of nested entities crashed `swipl` (signal 11) after growing for a
second. The Python side has the same rule (python/oracle/xmlguard.py) in a richer form; here:

- the file is a regular file (exists_file/1 is false for a FIFO, a device or a folder) of at
  most 64 MiB;
- a document type may declare internal entities only: no `SYSTEM`/`PUBLIC` (another file or a
  URL), no parameter entity, no entity whose value refers to another entity (`&name;`), none
  longer than 4096 characters (Protégé declares IRI prefixes, under 100);
- all references to the declared entities together may add at most max(1 MiB, the file's
  size) characters.

A file without a document type costs one look at its first 64 KB. Each refusal is a
permission_error(load, owl_file, File) whose context says why, in one line.
*/

:- use_module(library(readutil), [read_file_to_string/3]).

%!  owl_file_safe(+File) is det.
%   True when File may be parsed (see the module's doc); a permission_error naming the file
%   and the reason otherwise. Turtle and N-Triples files (by extension) have no entities: only
%   the file and size rules apply.
owl_file_safe(File) :-
    (   exists_file(File)
    ->  true
    ;   refuse(File, 'not a regular file (a FIFO, a device or a folder is not read)')
    ),
    size_file(File, Size),
    MaxSize is 64 * 1024 * 1024,
    (   Size =< MaxSize
    ->  true
    ;   format(atom(Why), '~d bytes, larger than the limit of ~d bytes', [Size, MaxSize]),
        refuse(File, Why)
    ),
    file_name_extension(_, Ext, File),
    (   memberchk(Ext, [ttl, nt, turtle])
    ->  true
    ;   entities_bounded(File, Size)
    ).

refuse(File, Why) :-
    throw(error(permission_error(load, owl_file, File), context(_, Why))).

entities_bounded(File, Size) :-
    setup_call_cleanup(open(File, read, In, [type(binary)]),
                       read_string(In, 65536, Head),
                       close(In)),
    (   sub_string(Head, _, _, _, "<!DOCTYPE")
    ->  read_file_to_string(File, Text, [encoding(octet)]),
        declared_entities(File, Text, Entities),
        Budget is max(1048576, Size),
        references_bounded(File, Text, Entities, Budget)
    ;   true
    ).

%   The entities of the internal subset, as Name-Length pairs.
declared_entities(File, Text, Entities) :-
    findall(Decl, entity_declaration(Text, Decl), Decls),
    maplist(checked_entity(File), Decls, Entities).

entity_declaration(Text, Decl) :-
    sub_string(Text, Before, _, _, "<!ENTITY"),
    Start is Before + 8,
    sub_string(Text, Start, _, 0, Rest),
    (   sub_string(Rest, End, _, _, ">")
    ->  sub_string(Rest, 0, End, _, Decl)
    ;   Decl = Rest
    ).

checked_entity(File, Decl0, Name-Length) :-
    normalize_space(string(Decl), Decl0),
    (   sub_string(Decl, 0, 1, _, "%")
    ->  refuse(File, 'declares a parameter entity')
    ;   sub_string(Decl, B, 1, _, " ")
    ->  sub_string(Decl, 0, B, _, NameS), atom_string(Name, NameS),
        Q is B + 1,
        sub_string(Decl, Q, 1, _, Quote),
        (   memberchk(Quote, ["\"", "'"])
        ->  entity_value(Decl0, Quote, Value)
        ;   format(atom(Why), 'declares the external entity &~w; (it would read another file or URL)', [Name]),
            refuse(File, Why)
        ),
        string_length(Value, Length),
        (   sub_string(Value, At, 1, _, "&"), \+ sub_string(Value, At, 2, _, "&#")
        ->  format(atom(Why), 'entity &~w; refers to another entity (nested entities are refused)', [Name]),
            refuse(File, Why)
        ;   Length > 4096
        ->  format(atom(Why), 'entity &~w; is ~d characters, more than 4096', [Name, Length]),
            refuse(File, Why)
        ;   true
        )
    ;   refuse(File, 'holds an entity declaration it cannot read')
    ).

%   The quoted value of a declaration as written (white space kept).
entity_value(Decl, Quote, Value) :-
    sub_string(Decl, Open, 1, _, Quote), !,
    Start is Open + 1,
    sub_string(Decl, Start, _, 0, Rest),
    (   sub_string(Rest, Len, 1, _, Quote)
    ->  sub_string(Rest, 0, Len, _, Value)
    ;   Value = Rest
    ).

references_bounded(File, Text, Entities, Budget) :-
    foldl(added(Text), Entities, 0, Added),
    (   Added =< Budget
    ->  true
    ;   format(atom(Why), 'its entity references expand by ~d characters, more than ~d', [Added, Budget]),
        refuse(File, Why)
    ).

added(Text, Name-Length, Sum0, Sum) :-
    format(string(Token), "&~w;", [Name]),
    string_length(Token, TokenLength),
    aggregate_all(count, sub_string(Text, _, TokenLength, _, Token), Uses),
    Sum is Sum0 + Uses * max(0, Length - TokenLength).
