//! Operator resolution: turns a flat sequence of items into a term tree using GOAL's fixed
//! operator table. An operator-precedence (shunting-yard) pass with explicit stacks, so even a
//! very long chain of operators cannot overflow the call stack.

use super::item::{Item, ItemError};
use super::Located;
use crate::diag::Span;
use crate::term::ops::{self, Op, OpType};
use crate::term::{well_known as wk, Sym, Term};

/// Longest chain of pending operators accepted; every later pass over the term (printing,
/// validation) walks that deep, and no hand-written program comes near it.
const MAX_PENDING: usize = 1000;

/// An operator waiting for its right operand.
struct Pending {
    name: Sym,
    op: Op,
    /// Start of the operator (prefix) or of its left operand (infix).
    start: usize,
    /// The left operand of an infix operator; `None` for prefix operators.
    left: Option<Located>,
}

/// Resolves `items` (all of one bracketed or top-level term) into one term of priority <= `max`.
pub fn resolve(items: Vec<Item>, max: u16, _span: Span) -> Result<Located, ItemError> {
    let count = items.len();
    let mut items = items.into_iter().peekable();
    let mut stack: Vec<Pending> = Vec::new();
    // The operand just completed, with its priority; `None` while an operand is expected.
    let mut operand: Option<(Located, u16)> = None;
    let mut seen = 0usize;
    while let Some(item) = items.next() {
        seen += 1;
        let ceiling = stack.last().map_or(max, |p| p.op.operand_priorities().1);
        match operand.take() {
            None => match item {
                Item::Operand(o) => operand = Some((o, 0)),
                Item::Call(f, args, whole) => {
                    operand = Some((Located::compound(f, args, whole), 0))
                }
                Item::Comma(s) => {
                    return Err(ItemError::new("unexpected `,`", s)
                        .hint("a term is missing before the comma"))
                }
                Item::Bar(s) => {
                    return Err(ItemError::new("unexpected `|`", s)
                        .hint("a term is missing before the bar"))
                }
                Item::Name(n, span) => {
                    let next = items.peek();
                    if let Some(literal) = negative_number(n, &span, next) {
                        items.next();
                        seen += 1;
                        operand = Some((literal, 0));
                        continue;
                    }
                    let starts_term = match next {
                        Some(Item::Operand(_)) | Some(Item::Call(..)) => true,
                        // An operator name that ends the sequence is an atom operand (`:- ;`).
                        Some(Item::Name(m, _)) => {
                            ops::infix(m.name()).is_none()
                                || ops::prefix(m.name()).is_some()
                                || seen + 1 == count
                        }
                        _ => false,
                    };
                    match ops::prefix(n.name()) {
                        // A prefix operator above the allowed priority reads as an atom (ISO).
                        Some(op) if starts_term && op.priority <= ceiling => {
                            if stack.len() >= MAX_PENDING {
                                return Err(too_deep(span));
                            }
                            stack.push(Pending {
                                name: n,
                                op,
                                start: span.start,
                                left: None,
                            })
                        }
                        _ => operand = Some((Located::leaf(Term::Atom(n), span), 0)),
                    }
                }
            },
            Some((left, left_priority)) => {
                let (op, right) = match item {
                    Item::Comma(_) => (ops::infix(",").unwrap_or(bar_op()), None),
                    Item::Bar(_) => (bar_op(), None),
                    Item::Name(n, s) => match ops::infix(n.name()) {
                        Some(op) => (op, None),
                        None => {
                            return Err(ItemError::new(
                                format!("operator expected, found `{}`", n.name()),
                                s,
                            )
                            .hint("put an operator or a `,` between the two terms"))
                        }
                    },
                    // `a-(b)` reads as `a - (b)`: an infix operator glued to a bracket.
                    Item::Call(f, args, whole) if ops::infix(f.name()).is_some() => (
                        ops::infix(f.name()).unwrap_or(bar_op()),
                        Some(bracket_args(args, whole)),
                    ),
                    other => {
                        return Err(ItemError::new(
                            "operator expected before this term",
                            other.span(),
                        )
                        .hint("put an operator or a `,` between the two terms"))
                    }
                };
                let (left_max, _) = op.operand_priorities();
                let (mut left, mut left_priority) = (left, left_priority);
                // Operators on the stack that cannot take this operator in their right operand
                // are complete now.
                while let Some(top) = stack.last() {
                    if op.priority <= top.op.operand_priorities().1 {
                        break;
                    }
                    let top = stack.pop().unwrap_or_else(|| unreachable!());
                    left_priority = top.op.priority;
                    left = reduce(top, left);
                }
                let ceiling = stack.last().map_or(max, |p| p.op.operand_priorities().1);
                if left_priority > left_max || op.priority > ceiling {
                    return Err(ItemError::new(
                        format!("operator priority clash at `{}`", op.name),
                        left.spans.span.clone(),
                    )
                    .hint("add brackets to say how the operators group"));
                }
                let name = if op.name == "|" {
                    wk::SEMICOLON
                } else {
                    Sym::intern(op.name)
                };
                let start = left.spans.span.start;
                if stack.len() >= MAX_PENDING {
                    return Err(too_deep(left.spans.span.clone()));
                }
                stack.push(Pending {
                    name,
                    op,
                    start,
                    left: Some(left),
                });
                if let Some(r) = right {
                    operand = Some((r, 0));
                }
            }
        }
    }
    let Some((mut result, _)) = operand else {
        let end = stack.last().map_or(0, |p| p.start);
        return Err(
            ItemError::new("unexpected end of term", end..end).hint("a term is missing here")
        );
    };
    while let Some(top) = stack.pop() {
        result = reduce(top, result);
    }
    Ok(result)
}

fn too_deep(span: Span) -> ItemError {
    ItemError::new(
        format!("more than {MAX_PENDING} operators in one chain"),
        span,
    )
    .hint("split the term into smaller parts")
}

/// Applies a pending operator to its right operand.
fn reduce(p: Pending, right: Located) -> Located {
    let span = p.start..right.spans.span.end;
    match p.left {
        Some(left) => Located::compound(p.name, vec![left, right], span),
        None => Located::compound(p.name, vec![right], span),
    }
}

/// `-` glued to a number literal is a negative number.
fn negative_number(n: Sym, span: &Span, next: Option<&Item>) -> Option<Located> {
    if n != wk::MINUS {
        return None;
    }
    let Some(Item::Operand(o)) = next else {
        return None;
    };
    if o.spans.span.start != span.end {
        return None;
    }
    let negated = match &o.term {
        Term::Int(i) => Term::integer(-num_bigint::BigInt::from(*i)),
        Term::BigInt(b) => Term::integer(-(**b).clone()),
        Term::Float(f) => Term::from(-f.0),
        _ => return None,
    };
    Some(Located::leaf(negated, span.start..o.spans.span.end))
}

fn bar_op() -> Op {
    Op {
        name: ";",
        priority: 1100,
        kind: OpType::Xfy,
    }
}

/// The bracketed right operand of `a-(b, c)`: the arguments joined as a conjunction.
fn bracket_args(args: Vec<Located>, whole: Span) -> Located {
    let mut iter = args.into_iter().rev();
    let last = iter
        .next()
        .unwrap_or_else(|| Located::leaf(Term::Atom(wk::TRUE), whole.clone()));
    iter.fold(last, |acc, a| {
        let span = a.spans.span.start..acc.spans.span.end;
        Located::compound(wk::COMMA, vec![a, acc], span)
    })
}
