% Knowledge of the reference BW4T team (shared by every module of the robot).
% The map, the task and the team; README.md says how the team splits the work.

% ---- The map ----
% A room (where blocks are) is a zone whose name starts with Room: the interface does not
% say which places are rooms, but BW4T maps name them so (RoomA1, ..., RoomC3).
room(R) :- zone(_, R, _, _, _), atom_concat('Room', _, R).
% The corridor in front of a room or the drop zone (its first neighbour; rooms on the
% standard maps have only one).
front(R, F) :- zone(_, R, _, _, [F|_]).
% Length of the straight line between the centres of two neighbouring zones.
step(P, Q, D) :- zone(_, P, X1, Y1, Nbrs), member(Q, Nbrs), zone(_, Q, X2, Y2, _),
	D is sqrt((X1 - X2) * (X1 - X2) + (Y1 - Y2) * (Y1 - Y2)).
% routes(From, Routes): Routes lists To-Distance for every place reachable from From,
% along the zone graph as robots walk it (Dijkstra over a sorted queue).
routes(From, Routes) :- dijkstra([0-From], [], Routes).
dijkstra([], Done, Done).
dijkstra([_-P|Queue], Done, Routes) :- memberchk(P-_, Done), !, dijkstra(Queue, Done, Routes).
dijkstra([D-P|Queue], Done, Routes) :-
	findall(D1-Q, (step(P, Q, S), \+ memberchk(Q-_, Done), D1 is D + S), Next),
	append(Queue, Next, Queue1), keysort(Queue1, Queue2),
	dijkstra(Queue2, [P-D|Done], Routes).

% ---- The task ----
nextColor(C) :- sequence(S), sequenceIndex(I), nth0(I, S, C).
% The colours still to be delivered, in order.
remaining(L) :- sequence(S), sequenceIndex(I), skip(I, S, L).
skip(0, L, L) :- !.
skip(N, [_|T], L) :- N1 is N - 1, skip(N1, T, L).
% How often colour C occurs in list L.
occurrences(C, L, K) :- findall(C, member(C, L), Cs), length(Cs, K).

% ---- The team ----
% A claim on colour C: robot X is fetching or carrying a block of that colour.
claim(X, C) :- fetching(X, C, _).
claim(X, C) :- holding(X, C).
busy(X) :- fetching(X, _, _).
busy(X) :- holding(X, _).
busy(X) :- going(X, _).
% The first colour of the rest of the sequence that the claims do not cover; each claim
% covers one occurrence of its colour.
uncovered(C) :- remaining(L), findall(C1, claim(_, C1), Cs), firstUncovered(L, Cs, C).
firstUncovered([C|T], Cs, U) :-
	( selectchk(C, Cs, Rest) -> firstUncovered(T, Rest, U) ; U = C ).
% Claims on colour C that go before the claim of robot Me: carrying first, then by name.
before(X, Me, C) :- holding(X, C), X \= Me.
before(X, Me, C) :- fetching(X, C, _), X @< Me.
% Me's claim on C is not needed: the claims before it cover every C still to deliver.
surplus(Me, C) :- remaining(L), occurrences(C, L, K),
	findall(X, before(X, Me, C), Xs), length(Xs, M), M >= K.
% Room R has no C block left for Me: robots before Me take all of them.
overbooked(Me, C, R) :- knownCount(R, C, N),
	findall(X, (fetching(X, C, R), X @< Me), Xs), length(Xs, K), K >= N.
% Room R has a C block that no other robot is fetching.
available(Me, C, R) :- count(R, C, N), N > 0,
	findall(X, (fetching(X, C, R), X \= Me), Xs), length(Xs, K), N > K.
% The colour of the block the robot is walking up to.
targetColor(C) :- target(block(B)), percept(color(B, C)).
knownCount(R, C, N) :- count(R, C, N), !.
knownCount(_, _, 0).
% The nearest room (by route from where the robot is) with a C block for Me.
fetchRoom(Me, C, R) :- at(P),
	findall(D-R1, (available(Me, C, R1), route(P, R1, D)), L), keysort(L, [_-R|_]).
% The nearest room that nobody has checked or is going to check.
exploreRoom(R) :- at(P),
	findall(D-R1, (room(R1), \+ checked(R1), \+ going(_, R1), route(P, R1, D)), L),
	keysort(L, [_-R|_]).
% The colours seen in this room, each once.
seenColor(C) :- findall(C1, percept(color(_, C1)), L), sort(L, S), member(C, S).
seen(C, N) :- findall(B, percept(color(B, C)), L), length(L, N).
