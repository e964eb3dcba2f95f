% What the stacker knows about every blocks world.
:- dynamic on/2.

% A block is anything that is on something.
block(X) :- on(X, _).
% The table is always clear; a block is clear when nothing is on it.
clear(table).
clear(X) :- block(X), \+ on(_, X).
% tower([X|T]): X sits on top of a tower T that reaches the table.
tower([X]) :- on(X, table).
tower([X, Y|T]) :- on(X, Y), tower([Y|T]).
