//! Knowledge: compiled Prolog clauses (facts and rules), shared read-only by every agent that
//! runs the same program. Loading rejects GOAL's protected predicates and invalid clauses.

use super::error::{KrError, LoadError};
use super::fxhash::FxHashMap;
use super::native::builtins::{self, B};
use super::native::clauses::MAX_REGS;
use super::native::code::{Code, Key};
use super::native::store::Cell;
use crate::term::{well_known as wk, Sym, Term};
use std::sync::Arc;

/// One compiled clause.
#[derive(Clone, Debug)]
pub(crate) struct Clause {
    pub code: Code,
    pub head: Cell,
    pub body: Vec<Cell>,
    /// The predicate each body goal calls, resolved when loading finishes.
    pub preds: Vec<Option<PredRef>>,
    pub nslots: u32,
    /// The cells of the first body goal's arguments when they fit the argument registers and
    /// none is a structure (see `place_args`): fixed by the clause, so found once here.
    pub flat_first: Option<(u32, u32)>,
    pub key: Option<Key>,
    /// The key of the second head argument (for the second-argument index).
    pub key2: Option<Key>,
}

/// The clauses of one predicate, with a first-argument index when there are many.
#[derive(Clone, Debug)]
pub(crate) struct Pred {
    pub name: Sym,
    pub arity: u32,
    pub clauses: Vec<Clause>,
    pub all: Vec<u32>,
    pub by_key: FxHashMap<Key, Vec<u32>>,
    pub var_first: Vec<u32>,
    /// Second-argument index, used when the goal's first argument is unbound (as in
    /// `\+ on(_, X)`).
    pub by_key2: FxHashMap<Key, Vec<u32>>,
    pub var_second: Vec<u32>,
}

/// What a goal `name/arity` refers to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum PredRef {
    /// A built-in implemented in Rust (or a control construct).
    Builtin(B),
    /// Clauses of this knowledge (index into `preds`).
    User(u32),
    /// Clauses of the library prelude.
    Lib(u32),
}

/// Compiled knowledge clauses plus the table resolving every callable name.
#[derive(Debug)]
pub struct Knowledge {
    pub(crate) preds: Vec<Pred>,
    pub(crate) table: FxHashMap<(Sym, u32), PredRef>,
    clause_count: usize,
    /// The clauses as loaded (for engines that load source, such as a scryer engine).
    source: Vec<Term>,
}

/// The reason given for the database updates.
const UPDATES: &str = "updates go through GOAL's insert/delete actions";
/// The reason given for directives.
const DIRECTIVES: &str = "directives are not supported; GOAL declares predicates itself";
/// The reason given for loading files.
const IMPORT: &str = "use `#import` to load Prolog files";
/// The reason given for exceptions.
const EXCEPTIONS: &str = "exceptions run only on the scryer KR engine";
/// The reason given for what the KR layer lacks.
const UNSUPPORTED: &str = "not supported by the KR layer";
/// The reason given for the debugger.
const DEBUGGER: &str = "the debugger is not part of the KR layer";
/// The reason given for global variables and the recorded database.
const GLOBALS: &str = "global variables and the recorded database bypass the mental state";

/// The one table of names GOAL programs may not define or call, with the reason a diagnostic
/// gives (docs/prolog.md). The validator reports them, the engines raise permission errors.
const PROTECTED: &[(&str, &str)] = &[
    ("assert", UPDATES),
    ("asserta", UPDATES),
    ("assertz", UPDATES),
    ("retract", UPDATES),
    ("retractall", UPDATES),
    ("abolish", UPDATES),
    (":", "module qualification is not supported"),
    ("dynamic", DIRECTIVES),
    ("multifile", DIRECTIVES),
    ("discontiguous", DIRECTIVES),
    ("op", "the operator table is fixed"),
    ("char_conversion", DIRECTIVES),
    ("initialization", DIRECTIVES),
    ("ensure_loaded", IMPORT),
    ("module_transparent", DIRECTIVES),
    ("meta_predicate", DIRECTIVES),
    ("thread_local", DIRECTIVES),
    ("volatile", DIRECTIVES),
    ("catch", EXCEPTIONS),
    ("throw", EXCEPTIONS),
    ("numbervars", UNSUPPORTED),
    ("debug", DEBUGGER),
    ("nodebug", DEBUGGER),
    ("subsumes_term", UNSUPPORTED),
    ("tmp_file_stream", "agents do not read or write files"),
    ("consult", IMPORT),
    ("use_module", IMPORT),
    ("module", DIRECTIVES),
    (
        "halt",
        "an agent stops through its program, never by stopping the process",
    ),
    ("set_prolog_flag", "Prolog flags are fixed"),
    ("nb_setval", GLOBALS),
    ("b_setval", GLOBALS),
    ("nb_getval", GLOBALS),
    ("b_getval", GLOBALS),
    ("recorda", GLOBALS),
    ("recordz", GLOBALS),
    ("erase", GLOBALS),
    ("flag", GLOBALS),
    ("predicate_options", UNSUPPORTED),
    ("current_predicate_option", UNSUPPORTED),
    ("check_predicate_option", UNSUPPORTED),
];

/// Why file and operating-system predicates are refused.
const NO_FILES: &str = "agents do not read or write files or run programs";

/// File and operating-system predicates of SWI-Prolog, with their arities: calling one is a
/// permission error, never an undefined predicate that quietly fails (and never a file
/// access). Only arities no agent uses for beliefs (`seen/2`, `read/1` stay free), and a
/// program may define predicates of these names, which then shadow these.
pub(crate) const FILE_IO: &[(&str, &[u32])] = &[
    ("open", &[3, 4]),
    ("read_term", &[2, 3]),
    ("load_files", &[1, 2]),
    ("exists_file", &[1]),
    ("exists_directory", &[1]),
    ("delete_file", &[1]),
    ("shell", &[1, 2]),
    ("getenv", &[2]),
    ("setenv", &[2]),
];

/// The protected names (without the `csv_` family).
pub(crate) fn protected_names() -> impl Iterator<Item = &'static str> {
    PROTECTED.iter().map(|(name, _)| *name)
}

/// True when `name` may not be used as a predicate.
pub fn is_protected(name: &str) -> bool {
    protected_reason(name).is_some()
}

/// Why `name` may not be used as a predicate, or `None` when it may.
pub fn protected_reason(name: &str) -> Option<&'static str> {
    if name.starts_with("csv_") {
        return Some(NO_FILES);
    }
    PROTECTED
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(_, why)| *why)
}

/// Why calling `name/arity` is refused when the program does not define it: a file or
/// operating-system predicate.
pub fn file_io_reason(name: &str, arity: u32) -> Option<&'static str> {
    FILE_IO
        .iter()
        .any(|(n, arities)| *n == name && arities.contains(&arity))
        .then_some(NO_FILES)
}

impl Pred {
    /// The clause indices that can match a goal whose first argument has key `k` (and,
    /// when the first is unbound, whose second argument has key `k2`). Clause order is kept.
    #[inline(always)]
    pub fn candidates(&self, k: Option<Key>, k2: Option<Key>) -> &[u32] {
        match (k, k2) {
            (Some(k), _) if !self.by_key.is_empty() => match self.by_key.get(&k) {
                Some(v) => v,
                None => &self.var_first,
            },
            (None, Some(k2)) if !self.by_key2.is_empty() => match self.by_key2.get(&k2) {
                Some(v) => v,
                None => &self.var_second,
            },
            _ => &self.all,
        }
    }

    /// True when goals may use the second-argument index.
    #[inline]
    pub fn has_second_index(&self) -> bool {
        !self.by_key2.is_empty()
    }

    fn index(&mut self) {
        let n = self.clauses.len();
        self.all = (0..n as u32).collect();
        if n < 4 {
            return;
        }
        let keys1: Vec<Option<Key>> = self.clauses.iter().map(|c| c.key).collect();
        (self.by_key, self.var_first) = Self::index_on(&keys1);
        if self.arity >= 2 {
            let keys2: Vec<Option<Key>> = self.clauses.iter().map(|c| c.key2).collect();
            (self.by_key2, self.var_second) = Self::index_on(&keys2);
        }
    }

    /// For each key, the clauses whose argument has that key or is a variable (in order);
    /// and the clauses whose argument is a variable.
    fn index_on(keys: &[Option<Key>]) -> (FxHashMap<Key, Vec<u32>>, Vec<u32>) {
        let mut by_key: FxHashMap<Key, Vec<u32>> = FxHashMap::default();
        let mut var = Vec::new();
        for k in keys.iter().flatten() {
            by_key.entry(*k).or_default();
        }
        for (i, k) in keys.iter().enumerate() {
            match k {
                Some(k) => {
                    if let Some(v) = by_key.get_mut(k) {
                        v.push(i as u32)
                    }
                }
                None => {
                    var.push(i as u32);
                    for v in by_key.values_mut() {
                        v.push(i as u32)
                    }
                }
            }
        }
        (by_key, var)
    }
}

/// Splits a clause into head and body.
fn split_clause(t: &Term) -> (&Term, Option<&Term>) {
    if t.is_functor(wk::NECK, 2) {
        (&t.args()[0], Some(&t.args()[1]))
    } else {
        (t, None)
    }
}

fn pi(name: Sym, arity: usize) -> String {
    format!("{}/{}", Term::Atom(name), arity)
}

/// Checks one body goal (and the goals inside control constructs) for protected predicates.
fn check_body(goal: &Term, errors: &mut Vec<String>) {
    let mut stack = vec![(goal, false)];
    while let Some((g, in_bagof)) = stack.pop() {
        let Some((name, arity)) = g.functor() else {
            if let Term::Var(_) = g {
                continue;
            }
            errors.push(format!("{g} is not a callable goal"));
            continue;
        };
        let text = name.name();
        if text == "^" && arity == 2 {
            if !in_bagof {
                errors.push(
                    "the goal form of ^/2 is protected (use it only inside bagof/setof)".into(),
                );
                continue;
            }
            stack.push((&g.args()[1], true));
            continue;
        }
        if is_protected(text) {
            errors.push(format!("{} is a protected predicate", pi(name, arity)));
            continue;
        }
        let args = g.args();
        match (text, arity) {
            (",", 2) | (";", 2) | ("->", 2) | ("*->", 2) | ("forall", 2) => {
                stack.push((&args[1], false));
                stack.push((&args[0], false));
            }
            ("\\+", 1) | ("not", 1) | ("once", 1) | ("ignore", 1) => stack.push((&args[0], false)),
            // The atom `call` (arity 0) has no goal to check: calling it is an existence error.
            ("call", n) if n >= 1 => stack.push((&args[0], false)),
            ("findall", 3) | ("findall", 4) | ("aggregate_all", 3) => stack.push((&args[1], false)),
            ("bagof", 3) | ("setof", 3) | ("aggregate", 3) => stack.push((&args[1], true)),
            ("aggregate_all", 4) | ("aggregate", 4) => stack.push((&args[2], true)),
            _ => {}
        }
    }
}

impl Knowledge {
    /// Compiles knowledge clauses (facts and `Head :- Body` rules). Rejects protected
    /// predicates, directives and clauses whose head is not an atom or compound term.
    pub fn load(clauses: &[Term]) -> Result<Arc<Knowledge>, KrError> {
        let lib = builtins::library();
        let mut k = Knowledge::blank();
        k.table = lib.table.clone();
        k.source = clauses.to_vec();
        let mut errors = Vec::new();
        for (i, t) in clauses.iter().enumerate() {
            if let Err(e) = k.add_checked(t, i) {
                errors.push(e);
            }
        }
        if !errors.is_empty() {
            return Err(KrError::Load(errors));
        }
        k.finish();
        Ok(Arc::new(k))
    }

    /// Compiles `stand_ins` (see [`crate::kr::choice::native_stand_ins`]) but keeps `source`
    /// as [`Knowledge::source`], for knowledge only the scryer engine runs as written.
    pub fn load_as(source: &[Term], stand_ins: &[Term]) -> Result<Arc<Knowledge>, KrError> {
        let mut k = Knowledge::load(stand_ins)?;
        if let Some(k) = Arc::get_mut(&mut k) {
            k.source = source.to_vec();
        }
        Ok(k)
    }

    /// A knowledge base with no clauses and no names at all (the library starts from it).
    pub(crate) fn blank() -> Knowledge {
        Knowledge {
            preds: Vec::new(),
            table: FxHashMap::default(),
            clause_count: 0,
            source: Vec::new(),
        }
    }

    /// Knowledge without clauses (the built-ins and the library only).
    pub fn empty() -> Arc<Knowledge> {
        let mut k = Knowledge::blank();
        k.table = builtins::library().table.clone();
        Arc::new(k)
    }

    /// The clauses as given to [`Knowledge::load`].
    pub fn source(&self) -> &[Term] {
        &self.source
    }

    /// Number of clauses loaded.
    pub fn len(&self) -> usize {
        self.clause_count
    }

    /// True when no clauses were loaded.
    pub fn is_empty(&self) -> bool {
        self.clause_count == 0
    }

    /// Checks a query or condition for protected predicates (as loading does for clause
    /// bodies); the error lists every problem found.
    pub fn check_query(goal: &Term) -> Result<(), KrError> {
        let mut problems = Vec::new();
        check_body(goal, &mut problems);
        if problems.is_empty() {
            return Ok(());
        }
        Err(KrError::Load(
            problems
                .into_iter()
                .map(|message| LoadError {
                    clause: 0,
                    predicate: None,
                    message,
                })
                .collect(),
        ))
    }

    /// The predicates defined by knowledge clauses, in order of first definition.
    pub fn predicates(&self) -> Vec<(Sym, usize)> {
        self.preds
            .iter()
            .map(|p| (p.name, p.arity as usize))
            .collect()
    }

    /// True when calling `name/arity` runs a built-in, a control construct or knowledge
    /// clauses; false when it can only match facts of the fact bases.
    pub fn resolves(&self, name: Sym, arity: usize) -> bool {
        self.table.contains_key(&(name, arity as u32))
    }

    /// True when knowledge clauses define `name/arity`.
    pub fn defines(&self, name: Sym, arity: usize) -> bool {
        matches!(
            self.table.get(&(name, arity as u32)),
            Some(PredRef::User(_))
        )
    }

    fn add_checked(&mut self, t: &Term, i: usize) -> Result<(), LoadError> {
        let err = |predicate: Option<String>, message: String| LoadError {
            clause: i,
            predicate,
            message,
        };
        if t.is_functor(wk::NECK, 1) {
            return Err(err(
                Some(":-/1".into()),
                format!("directives are not allowed in knowledge: {t}"),
            ));
        }
        let (head, body) = split_clause(t);
        let Some((name, arity)) = head.functor() else {
            return Err(err(
                None,
                format!("{head} cannot be the head of a clause (not an atom or compound term)"),
            ));
        };
        if is_protected(name.name()) || (name == wk::CARET && arity == 2) {
            return Err(err(
                Some(pi(name, arity)),
                format!(
                    "{} is a protected predicate and cannot be defined",
                    pi(name, arity)
                ),
            ));
        }
        if let Some(PredRef::Builtin(b)) = self.table.get(&(name, arity as u32)) {
            // Names that are only refused at run time (file predicates) may be defined.
            if !builtins::is_library(*b) && *b != B::Protected {
                return Err(err(
                    Some(pi(name, arity)),
                    format!(
                        "{} is a built-in predicate and cannot be redefined",
                        pi(name, arity)
                    ),
                ));
            }
        }
        if let Some(b) = body {
            let mut problems = Vec::new();
            check_body(b, &mut problems);
            if let Some(p) = problems.into_iter().next() {
                return Err(err(
                    Some(pi(name, arity)),
                    format!("in a clause of {}: {p}", pi(name, arity)),
                ));
            }
        }
        self.add(t);
        Ok(())
    }

    /// Adds a clause without checks (used for the library prelude).
    pub(crate) fn add(&mut self, t: &Term) {
        let (head, body) = split_clause(t);
        let Some((name, arity)) = head.functor() else {
            return;
        };
        let arity = arity as u32;
        let idx = match self.table.get(&(name, arity)) {
            Some(PredRef::User(i)) => *i,
            _ => {
                self.preds.push(Pred {
                    name,
                    arity,
                    clauses: Vec::new(),
                    all: Vec::new(),
                    by_key: FxHashMap::default(),
                    var_first: Vec::new(),
                    by_key2: FxHashMap::default(),
                    var_second: Vec::new(),
                });
                let i = self.preds.len() as u32 - 1;
                self.table.insert((name, arity), PredRef::User(i));
                i
            }
        };
        let mut code = Code::default();
        let mut vars = Vec::new();
        let head_cell = code.add(head, &mut vars);
        let mut body_cells = Vec::new();
        if let Some(b) = body {
            for g in b.conjuncts() {
                if g.is_functor(wk::TRUE, 0) {
                    continue;
                }
                let g = if let Term::Var(_) = g {
                    Term::compound(wk::CALL, vec![g.clone()])
                } else {
                    g.clone()
                };
                body_cells.push(code.add(&g, &mut vars));
            }
        }
        let flat_first = body_cells
            .first()
            .and_then(|&g| code.flat_args(g))
            .filter(|&(from, end)| (end - from) as usize <= MAX_REGS);
        let key = head.args().first().and_then(Key::of_term);
        let key2 = head.args().get(1).and_then(Key::of_term);
        self.preds[idx as usize].clauses.push(Clause {
            code,
            head: head_cell,
            preds: Vec::new(),
            body: body_cells,
            nslots: vars.len() as u32,
            flat_first,
            key,
            key2,
        });
        self.clause_count += 1;
    }

    /// Builds the indexes; call after the last `add`.
    pub(crate) fn finish(&mut self) {
        let table = &self.table;
        for p in &mut self.preds {
            p.index();
            for c in &mut p.clauses {
                c.preds = c
                    .body
                    .iter()
                    .map(|g| {
                        let f = match *g {
                            Cell::Atom(s) => Some((s, 0)),
                            Cell::Ptr(off) => c.code.cells[off as usize].fun(),
                            _ => None,
                        };
                        f.and_then(|f| table.get(&f).copied())
                    })
                    .collect();
            }
        }
    }

    /// Turns every user predicate into a library predicate (for the prelude).
    pub(crate) fn into_library(mut self) -> Knowledge {
        for v in self.table.values_mut() {
            if let PredRef::User(i) = *v {
                *v = PredRef::Lib(i);
            }
        }
        self
    }
}

#[cfg(test)]
mod tests {
    use crate::kr::{Engine, Knowledge, NativeEngine, View};
    use crate::syntax::prolog::Reader;

    /// The knowledge of the Prolog text `src`, and the reader that read it (for queries).
    fn load(src: &str) -> (Reader, std::sync::Arc<Knowledge>) {
        let mut r = Reader::new("t");
        let (clauses, _) = r.clauses(src, 0);
        let kn = Knowledge::load(&clauses.into_iter().map(|c| c.term).collect::<Vec<_>>()).unwrap();
        (r, kn)
    }

    #[test]
    fn second_argument_index_keeps_answers_and_order() {
        let (mut r, kn) = load("on(a, b). on(b, c). on(X, d). on(c, d). on(e, b). on(f, Y).");
        let mut e = NativeEngine::new(0);
        let mut answers = |q: &str| -> Vec<String> {
            let q = r.term(q, 0).unwrap().term;
            let view = View::beliefs(&kn, &[]);
            e.query(&view, &q)
                .unwrap()
                .iter()
                .map(|s| s.iter().map(|(_, t)| t.to_string()).collect::<String>())
                .collect()
        };
        assert_eq!(answers("on(W, b)"), ["a", "e", "f"]);
        assert_eq!(answers("on(W, d)"), ["", "c", "f"]);
        assert_eq!(answers("on(W, z)"), ["f"]);
        assert_eq!(answers("on(c, W)"), ["d", "d"]);
        // on(f, Y) matches any second argument.
        assert!(answers("\\+ on(_, a)").is_empty());
        assert_eq!(answers("\\+ on(b, b)"), [""]);
    }

    #[test]
    fn a_body_calling_the_atom_call_loads_and_answers_like_an_unknown_predicate() {
        let (mut r, kn) =
            load("t :- call. u(X) :- call(call, p, X). v :- call(call, true). w :- foo.");
        let mut e = NativeEngine::new(0);
        let view = View::beliefs(&kn, &[]);
        let mut count = |q: &str| e.query(&view, &r.term(q, 0).unwrap().term).map(|a| a.len());
        assert_eq!(count("t"), count("w"));
        assert_eq!(count("u(_)"), count("w"));
        assert_eq!(count("v"), Ok(1));
    }

    #[test]
    fn a_first_body_goal_of_slots_and_constants_that_fit_the_registers_is_marked_flat() {
        let (mut r, kn) = load(
            "f(X, Z) :- q(X, a, 1, Y, Z, Y). s(X, Z) :- q(g(X), a, 1, Y, Z, Y). \
             n(X) :- r(X, 1, 2, 3, 4, 5, 6, 7, 8). \
             q(A, B, C, D, E, F) :- D = E, F = k(A, B, C). r(A, _, _, _, _, _, _, _, B) :- A = B.",
        );
        let flat = |name: &str| {
            let p = kn
                .preds
                .iter()
                .find(|p| crate::term::Term::Atom(p.name).to_string() == name);
            p.unwrap().clauses[0]
                .flat_first
                .map(|(from, end)| end - from)
        };
        assert_eq!(flat("f"), Some(6));
        assert_eq!(flat("s"), None, "a structure is built on the heap");
        assert_eq!(flat("n"), None, "nine arguments do not fit the registers");
        let mut e = NativeEngine::new(0);
        let view = View::beliefs(&kn, &[]);
        let mut answers = |q: &str| -> Vec<String> {
            let q = r.term(q, 0).unwrap().term;
            e.query(&view, &q)
                .unwrap()
                .iter()
                .map(|s| s.iter().map(|(_, t)| t.to_string()).collect::<String>())
                .collect()
        };
        assert_eq!(answers("f(b, Z)"), ["k(b,a,1)"]);
        assert_eq!(answers("s(b, Z)"), ["k(g(b),a,1)"]);
        assert_eq!(answers("n(W)"), ["8"]);
    }
}
