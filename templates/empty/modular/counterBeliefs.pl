% The counter starts at 0.
count(0).
