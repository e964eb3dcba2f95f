% What the counter knows: the last number it counts to.
:- dynamic count/1.
target(100).
