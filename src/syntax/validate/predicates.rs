//! KR predicates: queried but never defined, knowledge/beliefs name clashes, protected names in
//! KR content, and knowledge, beliefs or goals that are never queried.

use super::builtins::{file_io_reason, is_builtin, is_reserved, protected_reason};
use super::terms::{calls, conjuncts, Sub};
use super::{Ctx, Key};
use crate::diag::Span;
use crate::syntax::ast::{ActionKind, LiteralKind, SelectorKind};
use crate::syntax::prolog::Located;
use crate::term::Term;
use std::collections::BTreeMap;

const SCRYER_HINT: &str = "give the agent `language = scryer` in its .mas2g entry or run with `--kr scryer`; on the native engine the agent does not start";

/// What only the scryer engine runs: exceptions, DCG rules and `phrase/2,3`.
fn scryer_only(name: &str, arity: usize) -> Option<String> {
    match (name, arity) {
        ("catch", 3) | ("throw", 1) | ("phrase", 2) | ("phrase", 3) => {
            Some(format!("`{name}/{arity}`"))
        }
        ("-->", 2) => Some("a DCG rule (`-->`)".into()),
        _ => None,
    }
}

/// Where predicates are defined and queried.
#[derive(Default)]
struct Uses {
    knowledge: BTreeMap<Key, Span>,
    beliefs: BTreeMap<Key, Span>,
    goals: BTreeMap<Key, Span>,
    /// Defined by updates (post, insert, adopt) or imported knowledge: no span needed.
    other: BTreeMap<Key, ()>,
    /// Predicates that can become believed: knowledge, beliefs, post and insert updates.
    believable: BTreeMap<Key, ()>,
    /// Predicates adopted as goals by `adopt` actions (first place).
    adopted: BTreeMap<Key, Span>,
    /// Queries in this file, in order.
    queries: Vec<(Key, Span)>,
    /// Predicates queried somewhere (this file or imported knowledge).
    queried: BTreeMap<Key, ()>,
}

fn key(t: &Term) -> Option<Key> {
    t.functor().map(|(n, a)| (n.name().to_string(), a))
}

/// The head and body of a clause (`None` body for facts and directives).
fn clause_parts(c: &Located) -> (Option<Sub<'_>>, Option<Sub<'_>>) {
    let s = Sub::of(c);
    match c.term.functor() {
        Some((n, 2)) if n.name() == ":-" => (s.arg(0), s.arg(1)),
        Some((n, 1)) if n.name() == ":-" || n.name() == "?-" => (None, s.arg(0)),
        _ => (Some(s), None),
    }
}

/// Runs the predicate checks.
pub fn check(ctx: &mut Ctx<'_>) {
    let mut u = Uses::default();
    let mut kr_goals: Vec<Sub<'_>> = Vec::new(); // positions checked for protected names
    let modules = ctx.modules.clone();
    for m in &modules {
        for c in &m.knowledge {
            let (head, body) = clause_parts(c);
            if head.is_none() {
                ctx.error(
                    "E0123",
                    format!("directive `{}` in knowledge", c.term),
                    c.spans.span.clone(),
                    "directives are not supported; GOAL declares predicates itself",
                );
                continue;
            }
            if let Some(h) = head {
                if let Some(k) = key(h.term) {
                    u.knowledge.entry(k).or_insert(h.span.clone());
                }
                kr_goals.push(h);
            }
            if let Some(b) = body {
                query(&mut u, &mut kr_goals, b, true);
            }
        }
        for b in &m.beliefs {
            let (head, body) = clause_parts(b);
            if let Some(h) = head {
                if let Some(k) = key(h.term) {
                    u.beliefs.entry(k).or_insert(h.span.clone());
                }
                kr_goals.push(h);
            }
            if let Some(body) = body {
                query(&mut u, &mut kr_goals, body, true);
            }
        }
        for g in &m.goals {
            for c in conjuncts(Sub::of(g)) {
                // Negated or built-in conjuncts are reported by the variables checks (E0110).
                if let Some(k) = key(c.term).filter(|k| !is_builtin(&k.0, k.1)) {
                    u.goals.entry(k).or_insert(c.span.clone());
                }
                kr_goals.push(c);
            }
        }
        for s in &m.action_specs {
            query(&mut u, &mut kr_goals, Sub::of(&s.pre.term), true);
            update(&mut u, &mut kr_goals, &s.post.term, Defines::Belief);
        }
    }
    for c in &ctx.imported_knowledge {
        let (head, body) = clause_parts(c);
        if let Some(k) = head.and_then(|h| key(h.term)) {
            u.other.insert(k.clone(), ());
            u.believable.insert(k, ());
        }
        if let Some(b) = body {
            for (call, _) in calls(b) {
                if let Some(k) = key(call.term) {
                    u.queried.insert(k, ());
                }
            }
        }
    }
    for l in ctx.literals() {
        if let LiteralKind::Mental {
            query: q, selector, ..
        } = &l.kind
        {
            // Other agents' mental models hold their own predicates.
            let own = matches!(selector.kind, SelectorKind::This | SelectorKind::SelfAgent);
            query(&mut u, &mut kr_goals, Sub::of(q), own);
        }
    }
    for (_, a) in ctx.actions() {
        match &a.kind {
            ActionKind::Insert { content, .. } => {
                update(&mut u, &mut kr_goals, content, Defines::Belief)
            }
            ActionKind::Adopt { content, .. } => {
                update(&mut u, &mut kr_goals, content, Defines::Goal)
            }
            ActionKind::Delete { content, .. } => {
                update(&mut u, &mut kr_goals, content, Defines::Nothing)
            }
            // drop removes the goals that entail its content: a goal query.
            ActionKind::Drop { content, .. } => {
                query(&mut u, &mut kr_goals, Sub::of(content), false)
            }
            _ => {}
        }
    }
    for g in kr_goals {
        if let Some((n, a)) = g.term.functor() {
            if let Some(what) = scryer_only(n.name(), a) {
                ctx.warning(
                    "W0125",
                    format!("{what} runs only on the scryer KR engine"),
                    g.span.clone(),
                    SCRYER_HINT,
                );
            } else if let Some(why) = protected_reason(n.name()) {
                ctx.error(
                    "E0123",
                    format!("`{}/{a}` may not be used in KR content", n.name()),
                    g.span.clone(),
                    why,
                );
            } else if let Some(why) = refused_file_call(&u, ctx.module_file, n.name(), a) {
                ctx.error(
                    "E0123",
                    format!("`{}/{a}` is a file or system predicate", n.name()),
                    g.span.clone(),
                    why,
                );
            }
        }
    }
    let defined = |k: &Key| {
        u.knowledge.contains_key(k)
            || u.beliefs.contains_key(k)
            || u.goals.contains_key(k)
            || u.other.contains_key(k)
            || is_builtin(&k.0, k.1)
            || is_reserved(&k.0, k.1)
            || protected_reason(&k.0).is_some()
            || scryer_only(&k.0, k.1).is_some()
            || crate::kr::native::library::is_known(&k.0, k.1)
    };
    let mut reported: std::collections::BTreeSet<&Key> = Default::default();
    for (k, span) in &u.queries {
        // In a module file, definitions may be in the importing program.
        if !ctx.module_file && !defined(k) && reported.insert(k) {
            ctx.error(
                "E0121",
                format!(
                    "`{}/{}` is queried but not defined as knowledge, belief or goal",
                    k.0, k.1
                ),
                span.clone(),
                undefined_hint(&k.0, k.1, &u),
            );
        }
    }
    for (k, span) in &u.beliefs {
        if u.knowledge.contains_key(k) {
            ctx.error(
                "E0122",
                format!(
                    "`{}/{}` is defined both in knowledge and in beliefs",
                    k.0, k.1
                ),
                span.clone(),
                "knowledge is static and beliefs change: keep each predicate in one of them",
            );
        }
    }
    if ctx.module_file {
        return; // queries may be in the importing program
    }
    let queried = |k: &Key| u.queried.contains_key(k);
    // Blind commitment queries every goal with `bel(...)`, so a predicate used in a goal is
    // queried (`goals { done. }` with `done :- ...` in knowledge).
    let in_goal = |k: &Key| u.goals.contains_key(k) || u.adopted.contains_key(k);
    for (k, span) in u.knowledge.iter().chain(u.beliefs.iter()) {
        if !queried(k) && !in_goal(k) {
            ctx.warning(
                "W0110",
                format!("`{}/{}` is defined but never queried", k.0, k.1),
                span.clone(),
                "query it in a condition or precondition, or remove it",
            );
        }
    }
    for (k, span) in &u.goals {
        if !queried(k) && !u.knowledge.contains_key(k) && !u.beliefs.contains_key(k) {
            ctx.warning(
                "W0111",
                format!("goal predicate `{}/{}` is never queried", k.0, k.1),
                span.clone(),
                "test the goal with `goal(...)` or `a-goal(...)` in a rule condition",
            );
        }
    }
    unachievable(ctx, &u);
}

/// Warns about goals whose predicate nothing can make believed (they are never achieved).
fn unachievable(ctx: &mut Ctx<'_>, u: &Uses) {
    let goals = u
        .goals
        .iter()
        .chain(u.adopted.iter().filter(|(k, _)| !u.goals.contains_key(*k)));
    for (k, span) in goals {
        let believable = u.believable.contains_key(k)
            || u.knowledge.contains_key(k)
            || u.beliefs.contains_key(k)
            || is_reserved(&k.0, k.1)
            || is_builtin(&k.0, k.1);
        if !believable {
            ctx.warning(
                "W0112",
                format!(
                    "goal `{}/{}` can never be achieved: nothing makes it believed",
                    k.0, k.1
                ),
                span.clone(),
                "insert it (or derive it in knowledge) when it holds, so the goal is dropped",
            );
        }
    }
}

/// Records the predicate calls of query `q` (reported if undefined when `report`).
fn query<'a>(u: &mut Uses, kr_goals: &mut Vec<Sub<'a>>, q: Sub<'a>, report: bool) {
    for (c, _) in calls(q) {
        if let Some(k) = key(c.term) {
            u.queried.insert(k.clone(), ());
            if report {
                u.queries.push((k, c.span.clone()));
            }
        }
        kr_goals.push(c);
    }
}

/// What the positive literals of an update define.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Defines {
    Nothing,
    Belief,
    Goal,
}

/// Records the literals of update `t` and what its positive literals define.
fn update<'a>(u: &mut Uses, kr_goals: &mut Vec<Sub<'a>>, t: &'a Located, defines: Defines) {
    for c in conjuncts(Sub::of(t)) {
        let lit = if c
            .term
            .functor()
            .is_some_and(|(n, a)| n.name() == "not" && a == 1)
        {
            c.arg(0)
        } else {
            if let Some(k) = key(c.term).filter(|_| defines != Defines::Nothing) {
                u.other.insert(k.clone(), ());
                if defines == Defines::Belief {
                    u.believable.insert(k, ());
                } else {
                    u.adopted.entry(k).or_insert(c.span.clone());
                }
            }
            Some(c)
        };
        if let Some(l) = lit {
            kr_goals.push(l);
        }
    }
}

/// Why a call of `name/arity` is refused: a file or operating-system predicate the program does
/// not define itself (in a module file, the importing program may define it).
fn refused_file_call(
    u: &Uses,
    module_file: bool,
    name: &str,
    arity: usize,
) -> Option<&'static str> {
    let key = (name.to_string(), arity);
    let defined = u.knowledge.contains_key(&key) || u.beliefs.contains_key(&key);
    if module_file || defined {
        return None;
    }
    file_io_reason(name, u32::try_from(arity).ok()?)
}

/// Protected names and directives in the clauses of a standalone `.pl` file.
pub fn check_prolog_clauses(clauses: &[Located], file: &str) -> Vec<crate::diag::Diagnostic> {
    use crate::diag::Diagnostic;
    let mut diags = Vec::new();
    for c in clauses {
        let (head, body) = clause_parts(c);
        if head.is_none() {
            diags.push(
                Diagnostic::error(
                    "E0123",
                    format!("directive `{}` in a Prolog file", c.term),
                    file,
                    c.spans.span.clone(),
                )
                .with_hint("directives are not supported; GOAL declares predicates itself"),
            );
            continue;
        }
        let mut goals: Vec<Sub<'_>> = head.into_iter().collect();
        if let Some(b) = body {
            goals.extend(calls(b).into_iter().map(|(g, _)| g));
        }
        for g in goals {
            if let Some((n, a)) = g.term.functor() {
                if let Some(what) = scryer_only(n.name(), a) {
                    diags.push(
                        Diagnostic::warning(
                            "W0125",
                            format!("{what} runs only on the scryer KR engine"),
                            file,
                            g.span.clone(),
                        )
                        .with_hint(SCRYER_HINT),
                    );
                } else if let Some(why) = protected_reason(n.name()) {
                    diags.push(
                        Diagnostic::error(
                            "E0123",
                            format!("`{}/{a}` may not be used in KR content", n.name()),
                            file,
                            g.span.clone(),
                        )
                        .with_hint(why),
                    );
                }
            }
        }
    }
    diags
}

/// The hint for an undefined predicate: "did you mean" the closest defined or built-in name.
fn undefined_hint(name: &str, arity: usize, u: &Uses) -> String {
    let own = u
        .knowledge
        .keys()
        .chain(u.beliefs.keys())
        .chain(u.goals.keys())
        .chain(u.other.keys())
        .map(|(n, a)| (n.as_str(), *a));
    match crate::kr::native::library::suggest(name, arity, own) {
        Some(s) => format!(
            "did you mean `{s}`? Otherwise define it in `knowledge` or `beliefs`, or insert it"
        ),
        None => "define it in `knowledge` or `beliefs`, insert it, or check the spelling and arity"
            .into(),
    }
}
