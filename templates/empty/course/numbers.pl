% The counter's database: the count (a fact the program changes) and where it stops.
:- dynamic count/1.
count(0).
target(100).
