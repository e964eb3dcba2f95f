% What the robot believes when it starts: where its last movement action was going
% (a place or block(Id)); none yet.
target(none).
