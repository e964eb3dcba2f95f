% The towers the stacker wants (one goal): c on b on a, d on the table.
on(a, table), on(b, a), on(c, b), on(d, table).
