% Where the blocks are when the stacker starts.
on(a, b). on(b, table). on(c, table). on(d, c).
