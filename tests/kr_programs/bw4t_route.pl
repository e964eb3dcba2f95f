% BW4T-like route finding: rooms off a corridor of drop zones and hall nodes.
zone('DropZone', 0, 0).
zone('FrontDropZone', 0, 1).
zone(hall1, 1, 1). zone(hall2, 2, 1). zone(hall3, 3, 1).
zone('RoomA1', 1, 2). zone('RoomA2', 2, 2). zone('RoomA3', 3, 2).
zone('RoomB1', 1, 0). zone('RoomB2', 2, 0).
door('RoomA1', hall1). door('RoomA2', hall2). door('RoomA3', hall3).
door('RoomB1', hall1). door('RoomB2', hall2).
link('DropZone', 'FrontDropZone').
link('FrontDropZone', hall1).
link(hall1, hall2). link(hall2, hall3).

room(R) :- door(R, _).
adjacent(X, Y) :- link(X, Y).
adjacent(X, Y) :- link(Y, X).
adjacent(X, Y) :- door(X, Y).
adjacent(X, Y) :- door(Y, X).

distance(X, Y, D) :-
    zone(X, X1, Y1), zone(Y, X2, Y2),
    D is sqrt((X1 - X2) ** 2 + (Y1 - Y2) ** 2).

route(From, To, Route) :- route(From, To, [From], Rev), reverse(Rev, Route).
route(To, To, Visited, Visited).
route(From, To, Visited, Route) :-
    adjacent(From, Next), \+ member(Next, Visited),
    route(Next, To, [Next|Visited], Route).

route_length([_], 0).
route_length([A, B|T], L) :- distance(A, B, D), route_length([B|T], L0), L is L0 + D.

best_route(From, To, Best) :-
    findall(L-R, (route(From, To, R), route_length(R, L)), Rs),
    msort(Rs, [_-Best|_]).

color(block1, red). color(block2, blue). color(block3, red). color(block4, white).
in(block1, 'RoomA1'). in(block2, 'RoomA3'). in(block3, 'RoomB2'). in(block4, 'RoomA1').
sequence([red, white, blue]).

needed(C) :- sequence(S), member(C, S).
candidate(B, R) :- needed(C), color(B, C), in(B, R).
next_color(Delivered, C) :- sequence(S), length(Delivered, N), nth0(N, S, C).
