% The stacker's database: what it knows about every blocks world, and the tower it wants.
:- dynamic on/2, done/0.

% on(X, Y) facts come from the percepts (`replace on/2` in stacker.mas2g).
% A block is anything that is on something.
block(X) :- on(X, _).
% The table is always clear; a block is clear when nothing is on it.
clear(table).
clear(X) :- block(X), \+ on(_, X).
% tower([X|T]): X sits on top of a tower T that reaches the table.
tower([X]) :- on(X, table).
tower([X, Y|T]) :- on(X, Y), tower([Y|T]).

% The tower to build, top first.
wanted([c, b, a]).
% X belongs on Y in the wanted tower (the bottom block belongs on the table).
belongs(X, Y) :- wanted(T), append(_, [X, Y|_], T).
belongs(X, table) :- wanted(T), last(T, X).
% X is in place: it is on what it belongs on, and so is everything below it.
inPlace(X) :- belongs(X, table), on(X, table).
inPlace(X) :- belongs(X, Y), Y \= table, on(X, Y), inPlace(Y).
