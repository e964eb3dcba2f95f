//! `goal prolog FILE.pl... -q QUERY`: query a knowledge base from the shell.
//!
//! Prints one line per answer: the query's named variables (not starting with `_`) in order of
//! first appearance as `Name = value` joined by `, ` (values as `writeq` writes them, unbound
//! variables as `_`), `true` for an answer of a query without named variables, `false` when there
//! is no answer, and a line starting with `error` when the query raises an error.

use goal::diag::Diagnostic;
use goal::syntax::prolog::{Located, Reader};
use goal::term::print::{Options, MESSAGE_DEPTH};
use goal::term::{Style, Subst, Sym, Term};
use std::io::{self, BufRead, IsTerminal, Write};
use std::path::PathBuf;
use std::process::ExitCode;

/// Arguments of `goal prolog`.
#[derive(clap::Args)]
pub struct Args {
    /// Prolog files to load.
    pub files: Vec<PathBuf>,
    /// The query; without it, queries are read from standard input, one per line.
    #[arg(short, long)]
    pub query: Option<String>,
    /// Seed of the random generator behind `random/1`, `random_between/3`, ... (default 0).
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// The KR engine: native (default) or scryer.
    #[arg(long, default_value = "native", value_parser = super::limits::kr_engine)]
    pub kr: goal::kr::KrKind,
}

/// Runs `goal prolog`.
pub fn main(args: Args) -> ExitCode {
    let kb = match load_files(&args.files, args.seed, args.kr) {
        Ok(kb) => kb,
        Err(()) => return ExitCode::from(1),
    };
    let stdout = io::stdout();
    let mut out = stdout.lock();
    match &args.query {
        Some(q) => match run_query(&kb, q, "<query>", &mut out) {
            Ok(()) => ExitCode::SUCCESS,
            Err(()) => ExitCode::from(1),
        },
        None => repl(&kb, &mut out),
    }
}

/// Reads queries from standard input, one per line; a prompt only when stdin is a terminal.
fn repl(kb: &engine::Kb, out: &mut impl Write) -> ExitCode {
    let stdin = io::stdin();
    let interactive = stdin.is_terminal();
    let mut status = ExitCode::SUCCESS;
    let mut lines = stdin.lock().lines();
    loop {
        if interactive {
            let _ = write!(out, "?- ");
            let _ = out.flush();
        }
        let line = match lines.next() {
            Some(Ok(line)) => line,
            Some(Err(e)) => {
                eprintln!("error: cannot read standard input: {e}");
                return ExitCode::from(1);
            }
            None => break,
        };
        let text = line.trim();
        if text.is_empty() || text.starts_with('%') {
            continue;
        }
        if run_query(kb, text, "<stdin>", out).is_err() {
            status = ExitCode::from(1);
        }
    }
    status
}

/// Loads and compiles the files; prints diagnostics to stderr. `Err` when anything failed.
fn load_files(files: &[PathBuf], seed: u64, kr: goal::kr::KrKind) -> Result<engine::Kb, ()> {
    let mut sources: Vec<(String, String, Vec<Located>)> = Vec::new();
    let mut failed = false;
    for path in files {
        let name = path.display().to_string();
        let text = match std::fs::read_to_string(path) {
            Ok(t) => t,
            Err(e) => {
                eprintln!("error: cannot read {name}: {e}");
                failed = true;
                continue;
            }
        };
        let (clauses, diags) = Reader::new(name.clone()).clauses(&text, 0);
        for d in &diags {
            eprint!("{}", d.render(&text));
            failed |= d.is_error();
        }
        sources.push((name, text, clauses));
    }
    if failed {
        return Err(());
    }
    let clauses: Vec<Term> = sources
        .iter()
        .flat_map(|(_, _, cs)| cs.iter().map(|c| c.term.clone()))
        .collect();
    engine::Kb::load(&clauses, seed, kr).map_err(|errors| {
        for (index, message) in errors {
            // Point at the clause in its file when the loader names one.
            let mut k = index;
            let located = sources.iter().find_map(|(name, text, cs)| {
                if k < cs.len() {
                    Some((name, text, &cs[k]))
                } else {
                    k -= cs.len();
                    None
                }
            });
            match located {
                Some((name, text, c)) => {
                    let d = Diagnostic::error("E0400", message, name.clone(), c.spans.span.clone());
                    eprint!("{}", d.render(text));
                }
                None => eprintln!("error: {message}"),
            }
        }
    })
}

/// Reads, runs and prints one query. `Err` when the query text could not be read or the
/// query raised an error.
fn run_query(kb: &engine::Kb, text: &str, file: &str, out: &mut impl Write) -> Result<(), ()> {
    let text = text.trim();
    let text = text.strip_suffix('.').unwrap_or(text);
    let query = match Reader::new(file).term(text, 0) {
        Ok(located) => located.term,
        Err(d) => {
            eprint!("{}", d.render(text));
            return Err(());
        }
    };
    for warning in kb.undefined_goals(&query) {
        eprintln!("warning: {warning}");
    }
    let vars = named_vars(&query);
    let (answers, error, output) = kb.solve(&query);
    if !output.is_empty() {
        let _ = write!(out, "{output}");
        if !output.ends_with('\n') {
            let _ = writeln!(out);
        }
    }
    for a in &answers {
        let _ = writeln!(out, "{}", answer_line(&vars, a));
    }
    match error {
        Some(e) => {
            let _ = writeln!(out, "{}", error_line(&e));
            // An error answer is a failure of the query: the exit code says so.
            return Err(());
        }
        None if answers.is_empty() => {
            let _ = writeln!(out, "false");
        }
        None => {}
    }
    Ok(())
}

/// The query's variables that are printed: not starting with `_`, in order of first appearance.
pub fn named_vars(query: &Term) -> Vec<Sym> {
    query
        .vars()
        .into_iter()
        .filter(|v| !v.name().starts_with('_'))
        .collect()
}

/// One answer line: `X = a, Y = [b,c]`, or `true` when there are no named variables. Values are
/// written as SWI-Prolog's top level writes them: `writeq` text at priority 699, so operators
/// are bracketed (`X = (a:-b)`, `O = (>)`); unbound variables are written `_`.
pub fn answer_line(vars: &[Sym], answer: &Subst) -> String {
    if vars.is_empty() {
        return "true".into();
    }
    let options = Options {
        priority: 699,
        anonymous_vars: true,
        ..Options::new(Style::WRITEQ)
    };
    vars.iter()
        .map(|v| {
            // The native engine's answers are fully resolved: one walk finds the value.
            let var = Term::Var(*v);
            let value = answer.walk(&var);
            format!("{} = {}", v.name(), value.to_text_with(options))
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// The line for an error: the error term when it is `error(...)`, else `error: Term`. The term
/// is cut off at depth [`MESSAGE_DEPTH`] (`...`), so a huge culprit cannot flood the output.
pub fn error_line(error: &Term) -> String {
    let text = error.to_text_limited(MESSAGE_DEPTH);
    if text.starts_with("error") {
        text
    } else {
        format!("error: {text}")
    }
}

/// The knowledge base behind the command: the native engine with the agents' default limits.
mod engine {
    use goal::kr::native::library;
    use goal::kr::{AgentEngine, Engine, FactBase, Knowledge, KrError, KrKind, Limits, View};
    use goal::term::{Subst, Term};
    use std::cell::RefCell;
    use std::sync::Arc;

    /// Loaded knowledge and the engine that queries it.
    pub struct Kb {
        knowledge: Arc<Knowledge>,
        engine: RefCell<AgentEngine>,
    }

    impl Kb {
        /// Compiles clauses; on failure, (clause index, message) for every rejected clause.
        pub fn load(clauses: &[Term], seed: u64, kr: KrKind) -> Result<Kb, Vec<(usize, String)>> {
            let loaded = match kr {
                KrKind::Native => Knowledge::load(clauses),
                KrKind::Scryer => goal::agent::kr_bridge::load_knowledge(clauses),
            };
            match loaded {
                Ok(knowledge) => {
                    let engine = AgentEngine::new(kr, &knowledge, seed, Limits::default())
                        .map_err(|e| vec![(usize::MAX, e)])?;
                    Ok(Kb {
                        knowledge,
                        engine: RefCell::new(engine),
                    })
                }
                Err(KrError::Load(errors)) => {
                    Err(errors.into_iter().map(|e| (e.clause, e.message)).collect())
                }
                Err(e) => Err(vec![(usize::MAX, e.to_string())]),
            }
        }

        /// A warning for each goal of `query` that nothing defines (it fails, as GOAL's
        /// undefined predicates do), with a "did you mean" for a near name.
        pub fn undefined_goals(&self, query: &Term) -> Vec<String> {
            let mut out = Vec::new();
            let mut stack = vec![query];
            while let Some(g) = stack.pop() {
                let Some((name, arity)) = g.functor() else {
                    continue;
                };
                let args = g.args();
                match (name.name(), arity) {
                    ("," | ";" | "->" | "*->" | "|", 2) => stack.extend(args.iter().rev()),
                    ("\\+" | "not" | "once" | "ignore" | "call", 1) => stack.push(&args[0]),
                    ("findall" | "forall" | "aggregate_all" | "bagof" | "setof", _)
                        if arity >= 2 =>
                    {
                        stack.push(&args[1])
                    }
                    _ if self.knowledge.resolves(name, arity)
                        || library::is_known(name.name(), arity) => {}
                    _ => {
                        let own = self.knowledge.predicates();
                        let own = own.iter().map(|(n, a)| (n.name(), *a));
                        let hint = match library::suggest(name.name(), arity, own) {
                            Some(s) => format!(" (did you mean `{s}`?)"),
                            None => String::new(),
                        };
                        out.push(format!(
                            "`{}/{arity}` is not defined, so it fails{hint}",
                            name.name()
                        ));
                    }
                }
            }
            out
        }

        /// All answers of `query`, the error that stopped it (if any), and the text written by
        /// output built-ins.
        pub fn solve(&self, query: &Term) -> (Vec<Subst>, Option<Term>, String) {
            let empty = FactBase::new();
            let bases = [&empty];
            let view = View::beliefs(&self.knowledge, &bases);
            let mut engine = self.engine.borrow_mut();
            let (answers, error) = match &mut *engine {
                // The native engine streams: answers found before an error are kept.
                AgentEngine::Native(e) => {
                    let mut answers = Vec::new();
                    let result = e.solve(&view, query, &mut |s| {
                        answers.push(s);
                        true
                    });
                    (answers, result.err().map(|e| e.to_term()))
                }
                // Only reachable when the scryer engine is compiled in.
                #[allow(unreachable_patterns)]
                other => match other.query(&view, query) {
                    Ok(answers) => (answers, None),
                    Err(e) => (Vec::new(), Some(e.to_term())),
                },
            };
            let output = engine.take_output();
            (answers, error, output)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn answer_lines_name_variables_in_order() {
        let q = Term::compound(
            Sym::intern("f"),
            vec![Term::var("X"), Term::var("_Y"), Term::var("Z")],
        );
        let vars = named_vars(&q);
        let mut s = Subst::new();
        s.bind(
            Sym::intern("X"),
            Term::list(vec![Term::atom("a"), Term::atom("B c")]),
        );
        s.bind(
            Sym::intern("Z"),
            Term::compound(Sym::intern("g"), vec![Term::var("W")]),
        );
        assert_eq!(answer_line(&vars, &s), "X = [a,'B c'], Z = g(_)");
        assert_eq!(answer_line(&[], &s), "true");
    }

    #[test]
    fn error_lines_start_with_error() {
        let e = Term::compound(
            Sym::intern("error"),
            vec![Term::atom("instantiation_error"), Term::var("_")],
        );
        assert!(error_line(&e).starts_with("error(instantiation_error"));
        assert_eq!(error_line(&Term::atom("oops")), "error: oops");
    }
}
