//! The table of diagnostic codes, one line each. Ranges: `E00xx`/`W00xx` lexing and parsing of
//! `.goal`/`.mod2g`/`.pl` files and file access, `E01xx`/`W01xx` the validator, `E02xx`/`W02xx`
//! `.mas2g` files, `E03xx`/`W03xx` `.test2g` files, `E04xx`/`W04xx` compiling a program to run it,
//! `E06xx`/`W06xx` modular GOAL and MARBEL (`.mod2g` modules, `.act2g` files and the modular
//! `.mas2g` forms), `M000x`/`M001x` BW4T maps, `M002x`/`M004x` environment init parameters,
//! `M003x` starting a run. Each code has a page, `docs/diagnostics/CODE.md`, embedded here for
//! `goal explain`.

/// Defines [`CODES`] and, from the same list, the embedded pages (so neither can miss a code).
macro_rules! table {
    ($(($code:literal, $meaning:literal),)*) => {
        /// `(code, meaning)` for every diagnostic code, sorted by code.
        pub const CODES: &[(&str, &str)] = &[$(($code, $meaning)),*];
        /// The page of every code, in the order of [`CODES`].
        const PAGES: &[&str] = &[$(
            include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/diagnostics/", $code, ".md"))
        ),*];
    };
}

#[rustfmt::skip]
table! {
    ("E0009", "unexpected character at GOAL level"),
    ("E0010", "Prolog syntax error in KR content or a .pl file (the Prolog reader)"),
    ("E0011", "unterminated quoted atom, string or back-quoted string"),
    ("E0012", "unterminated block comment `/*` without `*/`"),
    ("E0013", "unclosed `(` or `{` around KR content"),
    ("E0014", "unexpected token: the grammar expected something else here"),
    ("E0015", "unexpected end of file: a module, section or rule is not finished"),
    ("E0016", "blocks nested too deeply"),
    ("E0017", "the file cannot be read (missing, a directory, no permission)"),
    ("E0018", "the file is not valid UTF-8"),
    ("E0019", "the file is larger than the 10 MB limit"),
    ("E0020", "unknown module option value, program option or rule order"),
    ("E0021", "`send`/`sendonce` without a receiver"),
    ("E0022", "`listall` needs a variable"),
    ("E0024", "unknown file extension (not .goal, .mod2g, .pl, .mas2g or .test2g)"),
    ("E0030", "empty KR content or empty argument list"),
    ("E0031", "`#import` of the wrong kind of file at this place"),
    ("E0032", "a `.mod2g` file must hold exactly one module"),
    ("E0033", "too many problems in one file: the rest are not reported"),
    ("E0101", "the program has neither a `main` nor an `event` module"),
    ("E0102", "a module other than `init` has no `program` section"),
    ("E0103", "duplicate module or action name/arity, or an action and a module with one name/arity"),
    ("E0104", "an action or module is called but never specified"),
    ("E0105", "an action or module is called with the wrong number of arguments"),
    ("E0106", "a parameter occurs twice in an action spec"),
    ("E0107", "a variable in `post` is bound by neither the parameters nor `pre`"),
    ("E0108", "a module or action-spec parameter is not a variable"),
    ("E0109", "a variable in `beliefs` or `goals` is not a module parameter"),
    ("E0110", "a `goals` entry is not a positive conjunction of facts"),
    ("E0111", "an empty update (`insert(true)`, ...)"),
    ("E0112", "`not(...)` inside `adopt`, `drop` or `delete`"),
    ("E0113", "a variable in an action is not bound by the rule condition, listall or module parameters"),
    ("E0114", "a variable in a selector is not bound"),
    ("E0115", "`_` as an argument of a user action or module call"),
    ("E0116", "a message sent to `this`, `some` or `someother`"),
    ("E0117", "a macro is defined twice"),
    ("E0118", "an undefined macro is used"),
    ("E0119", "an ill-formed macro: a parameter that is not a variable or not in the body"),
    ("E0120", "`#import` of a file that does not exist"),
    ("E0121", "a predicate is queried but never defined (knowledge, beliefs, goals, updates)"),
    ("E0122", "a predicate is defined both in knowledge and in beliefs"),
    ("E0123", "a protected predicate (assert, retract, catch, directives, ...) in KR content"),
    ("E0124", "an update is not a conjunction of facts and `not(fact)`s"),
    ("E0200", "lexical error in a .mas2g file"),
    ("E0201", "brackets nested too deeply in a .mas2g file"),
    ("E0202", "syntax error in a .mas2g file"),
    ("E0203", "unknown agent file option or entity constraint"),
    ("E0204", "invalid option value (a name, count or max of the wrong kind)"),
    ("E0205", "an agent file is missing or not a .goal file"),
    ("E0206", "a launch rule refers to an unknown agent file"),
    ("E0207", "`*` as agent name in an unconditional launch rule"),
    ("E0208", "the environment is not built in (neither bw4t nor blocksworld)"),
    ("E0209", "the KR engine an agent file chooses is not in this build"),
    ("E0301", "`do(...)`/`reactTo(...)` nested too deeply in a .test2g file"),
    ("E0302", "number out of range in a .test2g file"),
    ("E0303", "more than one `do(...)` test in one test condition"),
    ("E0304", "syntax error in a .test2g file"),
    ("E0305", "the MAS file of a test is missing or not a .mas2g file"),
    ("E0306", "a tested agent is not launched by the MAS file"),
    ("E0307", "agents of one test file have different numbers of named tests"),
    ("E0308", "the MAS file of a test has errors"),
    ("E0309", "a test calls an action or module the tested agent does not have"),
    ("E0310", "a test uses a macro the tested agent does not define"),
    ("E0311", "a variable in an action that a test runs (never bound)"),
    ("E0400", "the knowledge cannot be loaded into the Prolog engine"),
    ("E0401", "two modules or action specs with one name/arity (found while compiling)"),
    ("E0403", "the program has neither a `main` nor an `event` module (found while compiling)"),
    ("E0406", "`listall` needs a variable (found while compiling)"),
    ("E0408", "a macro is used but not defined (found while compiling)"),
    ("E0409", "macros nest more than 32 deep"),
    ("E0410", "the arguments of a macro use do not match its parameters"),
    ("E0411", "a selector on `drop`, `insert` or `delete`, or one other than this/self on `adopt`"),
    ("E0412", "`send` without a receiver: all, allother, self or agent names"),
    ("E0413", "an action or module that does not exist (found while compiling)"),
    ("E0601", "`sendonce` in a modular module (removed after 2014)"),
    ("E0602", "`send` without receivers or to `this` in a modular module"),
    ("E0603", "`sleep`, `starttimer`, `canceltimer`, `subscribe` or `unsubscribe` with the wrong number of arguments"),
    ("E0604", "`not(...)` inside `post-` of an `.act2g` spec"),
    ("E0605", "a `.mas2g` file mixes modular GOAL (A) and MARBEL (B) forms"),
    ("E0606", "an unknown module role, a role given twice, or an agent without main and event module"),
    ("E0607", "a file named by a use clause is not found"),
    ("E0608", "an `.act2g` file uses something other than knowledge files"),
    ("E0609", "a rule in a file used as beliefs or goals"),
    ("E0610", "a MARBEL percept declared twice in one agent"),
    ("E0611", "a module file of another generation than its MAS file"),
    ("E0612", "one file named twice by the use clauses of one file"),
    ("M0000", "a map cannot be read: no built-in map and no map file has that name"),
    ("M0001", "a map file is not valid TOML or BW4T XML, or has an unknown, missing or mistyped field"),
    ("M0002", "a zone names a neighbour that is not a zone of the map"),
    ("M0003", "the map has no drop zone (a room named `DropZone`)"),
    ("M0004", "blocks listed in a zone that is not a blocks room"),
    ("M0005", "doors on a zone that is not a room, or a door off its room's wall"),
    ("M0006", "an unknown colour in a room's blocks or in the sequence"),
    ("M0007", "two spawn points overlap"),
    ("M0008", "a spawn point inside a room"),
    ("M0009", "more random blocks than the rooms can take"),
    ("M0010", "a map or zone size that is not positive, or a position that is not a number"),
    ("M0011", "two zones with one name"),
    ("M0012", "an unknown zone type or door orientation in a BW4T XML map"),
    ("M0013", "rooms that overlap, or a room that overlaps the drop zone"),
    ("M0014", "a room or the drop zone without a door"),
    ("M0015", "a spawn point outside the map"),
    ("M0016", "a room the game needs that no robot can reach from a spawn point"),
    ("M0017", "a colour sequence longer than 1000"),
    ("M0020", "a BW4T init parameter with a value of the wrong kind or out of range"),
    ("M0021", "an init parameter the BW4T world does not know"),
    ("M0030", "the environment stopped while the run was starting"),
    ("M0031", "no agent was launched"),
    ("M0032", "a launch names an agent file the run did not load"),
    ("M0033", "a worker thread for the agents cannot be started"),
    ("M0034", "an agent's KR engine or the run's message layer cannot be set up"),
    ("M0040", "blocks-world towers that cannot be built"),
    ("W0001", "duplicate section: only the first one is used"),
    ("W0002", "legacy send form (`bob.send(p)` or `send(bob, p)`)"),
    ("W0003", "unknown module option (ignored)"),
    ("W0004", "duplicate module option: the first one is used"),
    ("W0006", "empty nested rule block"),
    ("W0010", "a space between a name and `(` in KR text: read as GOAL did, as a compound term"),
    ("W0011", "an unmatched closing bracket after a complete KR term: it and the rest are ignored, as GOAL did"),
    ("W0101", "an action spec is never used"),
    ("W0102", "a user module is never called"),
    ("W0103", "a macro is never used"),
    ("W0104", "an empty `program` section"),
    ("W0105", "an empty `pre` or `post`"),
    ("W0106", "an action parameter used in neither `pre` nor `post`"),
    ("W0107", "an action after `exit-module` is never executed"),
    ("W0108", "an `exit` option on `init` or `event` (ignored)"),
    ("W0109", "a `focus` option on a built-in module (ignored)"),
    ("W0110", "a knowledge or belief predicate is never queried"),
    ("W0111", "a goal predicate is never queried"),
    ("W0112", "a goal can never be achieved: nothing makes its predicate believed"),
    ("W0113", "a parameter occurs twice in a module head (calls need equal arguments there)"),
    ("W0125", "catch/throw, phrase or a DCG rule: runs only on the scryer KR engine"),
    ("W0201", "duplicate .mas2g section: only the first one is used"),
    ("W0202", "duplicate `env`, `init` or init parameter: the first one is used"),
    ("W0203", "`environment` section without `env` (ignored)"),
    ("W0204", "duplicate agent file option or entity constraint"),
    ("W0205", "unknown KR language (the run's engine is used)"),
    ("W0206", "duplicate agent file reference name"),
    ("W0207", "an environment init parameter without effect here (human bots, agent class, config file)"),
    ("W0208", "an agent file is never launched"),
    ("W0209", "an agent name is launched by more than one instruction"),
    ("W0210", "an `@env` action the built-in environment does not have"),
    ("W0211", "a `percept(...)` query of a percept the built-in environment never sends"),
    ("W0301", "duplicate named test in one agent block"),
    ("W0302", "an agent is tested in more than one block"),
    ("W0402", "`order=adaptive` runs as `order=random`"),
    ("W0601", "an adaptive learning clause (ignored)"),
    ("W0602", "a MARBEL role alias (`for decision`, `for events`, ...) read as the canonical word"),
    ("W0603", "a called module's declared name differs from its file name"),
    ("W0605", "a Prolog directive other than `:- dynamic` in a `.pl` file (ignored)"),
    ("W0607", "a launch rule for an entity type BW4T never has"),
    ("W0609", "a `.pl` line `p/1.` that looks like a declaration cut off by `.`"),
    ("W0610", "a MARBEL `goal(..)` literal reads the database's goal/1 predicate"),
    ("W0611", "a MARBEL percept declaration whose predicate nothing reads"),
}

/// The meaning of a code, if it is known.
pub fn describe(code: &str) -> Option<&'static str> {
    CODES.iter().find(|(c, _)| *c == code).map(|(_, d)| *d)
}

/// The page of a code (Markdown: what it means, a wrong and a fixed example), if it is known.
pub fn page(code: &str) -> Option<&'static str> {
    CODES.iter().position(|(c, _)| *c == code).map(|i| PAGES[i])
}

#[cfg(test)]
mod tests {
    #[test]
    fn codes_are_sorted_and_unique() {
        let codes: Vec<&str> = super::CODES.iter().map(|(c, _)| *c).collect();
        let mut sorted = codes.clone();
        sorted.sort();
        sorted.dedup();
        assert_eq!(codes, sorted);
    }
}
