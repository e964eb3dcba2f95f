//! Output built-ins (`write/1`, `format/1..3`, `nl/0`, ...). They write to the query's output
//! buffer; the agent decides where that text goes. `format/3` with `atom(A)`, `string(S)`,
//! `codes(C)` or `chars(C)` writes to a term instead.

use super::budget::new_atom;
use super::builtins::{inst, type_error, Flow, B};
use super::machine::Solver;
use super::store::{Cell, VarNames};
use super::text::text_of;
use crate::kr::error::{KrError, KrResult};
use crate::term::print::format_float;
use crate::term::print::Options;
use crate::term::{well_known as wk, Style, Sym, Term};
use std::sync::Arc;

/// Largest column or repeat count a format directive may use.
const MAX_FORMAT_COUNT: i64 = 100_000;

/// A heap term as text in the given style (the writer is iterative: any depth prints).
pub(crate) fn text(s: &Solver, c: Cell, style: Style) -> KrResult<String> {
    if s.m.st.is_cyclic(c) {
        return Err(super::machine::cyclic());
    }
    Ok(s.m.st.to_term(c, &mut VarNames::new(&[])).to_text(style))
}

fn format_error(msg: &str) -> KrError {
    KrError::iso(
        Term::compound("format", vec![Term::string(msg)]),
        Some((Sym::intern("format"), 2)),
    )
}

/// Expands a format string with its arguments.
pub(crate) fn format(s: &mut Solver, fmt: &str, args: &[Cell]) -> KrResult<String> {
    let mut out = String::new();
    let mut args = args.iter().copied();
    let mut next_arg = |what: &str| {
        args.next()
            .ok_or_else(|| format_error(&format!("not enough arguments for ~{what}")))
    };
    let mut line_start = 0usize;
    let mut seg_start = 0usize;
    let mut fills: Vec<(usize, char)> = Vec::new();
    let chars: Vec<char> = fmt.chars().collect();
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        i += 1;
        if c != '~' {
            out.push(c);
            if c == '\n' {
                line_start = out.len();
                seg_start = out.len();
                fills.clear();
            }
            continue;
        }
        // Numeric argument: digits, `*` (from the arguments) or a backquoted fill character.
        let mut num: Option<i64> = None;
        let mut fill = ' ';
        if i < chars.len() && chars[i] == '*' {
            i += 1;
            match s.m.st.deref(next_arg("*")?) {
                Cell::Int(n) => num = Some(n.min(MAX_FORMAT_COUNT)),
                _ => return Err(format_error("~* needs an integer argument")),
            }
        } else if i + 1 < chars.len() && chars[i] == '`' {
            fill = chars[i + 1];
            i += 2;
        } else {
            let st = i;
            while i < chars.len() && chars[i].is_ascii_digit() {
                i += 1;
            }
            if i > st {
                // Column and repeat counts are capped so a format string cannot exhaust memory.
                num = chars[st..i]
                    .iter()
                    .collect::<String>()
                    .parse::<i64>()
                    .ok()
                    .map(|n| n.min(MAX_FORMAT_COUNT));
            }
        }
        let Some(&d) = chars.get(i) else {
            return Err(format_error("truncated format directive"));
        };
        i += 1;
        match d {
            '~' => out.push('~'),
            'n' => {
                for _ in 0..num.unwrap_or(1) {
                    out.push('\n');
                }
                line_start = out.len();
                seg_start = out.len();
                fills.clear();
            }
            'w' => {
                let a = next_arg("w")?;
                out.push_str(&text(s, a, Style::WRITE)?)
            }
            'p' | 'q' => {
                let a = next_arg("q")?;
                out.push_str(&text(s, a, Style::WRITEQ)?)
            }
            'a' => {
                let a = next_arg("a")?;
                match text_of(s, a) {
                    Some(t) if !matches!(s.m.st.deref(a), Cell::Ptr(_)) => out.push_str(&t),
                    _ => return Err(format_error("~a expects an atomic argument")),
                }
            }
            's' => {
                let a = next_arg("s")?;
                match text_of(s, a) {
                    Some(t) => out.push_str(&t),
                    None => return Err(format_error("~s expects a string or a list of codes")),
                }
            }
            'd' | 'D' => {
                let a = next_arg("d")?;
                let (negative, mut digits) = match s.m.st.deref(a) {
                    Cell::Int(v) => (v < 0, v.unsigned_abs().to_string()),
                    Cell::Big(i) => {
                        let text = &s.m.st.strs[i as usize];
                        (
                            text.starts_with('-'),
                            text.trim_start_matches('-').to_string(),
                        )
                    }
                    _ => return Err(format_error("~d expects an integer argument")),
                };
                let group = d == 'D';
                let dec = num.unwrap_or(0).max(0) as usize;
                let mut frac = String::new();
                if dec > 0 {
                    while digits.len() <= dec {
                        digits.insert(0, '0');
                    }
                    frac = digits.split_off(digits.len() - dec);
                }
                if group {
                    let mut g = String::new();
                    for (k, ch) in digits.chars().enumerate() {
                        if k > 0 && (digits.len() - k) % 3 == 0 {
                            g.push(',');
                        }
                        g.push(ch);
                    }
                    digits = g;
                }
                if negative {
                    out.push('-');
                }
                out.push_str(&digits);
                if dec > 0 {
                    out.push('.');
                    out.push_str(&frac);
                }
            }
            'f' | 'e' | 'g' => {
                let a = next_arg("f")?;
                let v = match s.m.st.deref(a) {
                    Cell::Int(v) => v as f64,
                    Cell::Flt(v) => v,
                    _ => s.eval(a).map(|n| match n {
                        super::arith::Num::I(v) => v as f64,
                        super::arith::Num::F(v) => v,
                        n @ super::arith::Num::B(_) => n.f(),
                    })?,
                };
                let prec = num.unwrap_or(6).clamp(0, 60) as usize;
                match d {
                    'f' => out.push_str(&format!("{v:.prec$}")),
                    'e' => {
                        let t = format!("{v:.prec$e}");
                        // Rust writes 1.5e3; C writes 1.500000e+03.
                        let (m, e) = t.split_once('e').unwrap_or((&t, "0"));
                        let ev: i32 = e.parse().unwrap_or(0);
                        out.push_str(&format!(
                            "{m}e{}{:02}",
                            if ev < 0 { '-' } else { '+' },
                            ev.abs()
                        ));
                    }
                    _ => out.push_str(&format_float(v)),
                }
            }
            'c' => {
                let a = next_arg("c")?;
                let Cell::Int(code) = s.m.st.deref(a) else {
                    return Err(format_error("~c expects a character code"));
                };
                let ch = u32::try_from(code)
                    .ok()
                    .and_then(char::from_u32)
                    .unwrap_or('?');
                for _ in 0..num.unwrap_or(1) {
                    out.push(ch);
                }
            }
            'r' | 'R' => {
                let a = next_arg("r")?;
                let Cell::Int(v) = s.m.st.deref(a) else {
                    return Err(format_error("~r expects an integer"));
                };
                let radix = num.unwrap_or(8).clamp(2, 36) as u32;
                let mut digits = Vec::new();
                let mut n = v.unsigned_abs();
                loop {
                    let dgt =
                        std::char::from_digit((n % radix as u64) as u32, radix).unwrap_or('?');
                    digits.push(if d == 'R' {
                        dgt.to_ascii_uppercase()
                    } else {
                        dgt
                    });
                    n /= radix as u64;
                    if n == 0 {
                        break;
                    }
                }
                if v < 0 {
                    out.push('-');
                }
                out.extend(digits.iter().rev());
            }
            'i' => {
                next_arg("i")?;
            }
            't' => fills.push((out.len(), fill)),
            '|' | '+' => {
                let col = out[line_start..].chars().count();
                let seg_col = out[line_start..seg_start].chars().count();
                let target = match (d, num) {
                    ('|', Some(n)) => n as usize,
                    ('|', None) => col,
                    (_, n) => seg_col + n.unwrap_or(8) as usize,
                };
                if target > col {
                    if fills.is_empty() {
                        fills.push((out.len(), fill));
                    }
                    distribute_pad(&mut out, &fills, target - col);
                }
                seg_start = out.len();
                fills.clear();
            }
            other => return Err(format_error(&format!("unknown directive ~{other}"))),
        }
    }
    if args.next().is_some() {
        return Err(format_error("too many arguments"));
    }
    Ok(out)
}

/// Spreads `pad` fill characters over the fill points of a column (`~t`), as SWI does: evenly,
/// the remainder going to the leftmost points.
fn distribute_pad(out: &mut String, fills: &[(usize, char)], pad: usize) {
    let (each, extra) = (pad / fills.len(), pad % fills.len());
    // Right to left, so earlier positions stay valid.
    for (i, (pos, ch)) in fills.iter().enumerate().rev() {
        let n = each + usize::from(i < extra);
        let padding: String = std::iter::repeat_n(*ch, n).collect();
        out.insert_str(*pos, &padding);
    }
}

/// The `write_term/2,3` options that change the text: `quoted(Bool)`, `ignore_ops(Bool)`,
/// `max_depth(N)`; others are accepted and ignored.
fn write_options(s: &Solver, list: Cell) -> Options {
    let mut o = Options::new(Style::WRITE);
    let (items, _) = s.m.st.list_items(list);
    for it in items {
        let Cell::Ptr(q) = s.m.st.deref(it) else {
            continue;
        };
        let Some((name, 1)) = s.m.st.heap[q as usize].fun() else {
            continue;
        };
        let on = matches!(s.ad(q, 0), Cell::Atom(a) if a == wk::TRUE);
        match (name.name(), s.ad(q, 0)) {
            ("quoted", _) => o.style.quoted = on,
            ("ignore_ops", _) => o.style.operators = !on,
            ("max_depth", Cell::Int(n)) => o.max_depth = n.clamp(0, 1 << 20) as usize,
            _ => {}
        }
    }
    o
}

fn format_args(s: &Solver, c: Cell) -> Vec<Cell> {
    let (items, end) = s.m.st.list_items(c);
    if matches!(end, Cell::Atom(n) if n == wk::NIL) {
        items
    } else {
        vec![c]
    }
}

/// Output built-ins; `None` when `b` is not one of them.
pub(crate) fn det(s: &mut Solver, b: B, p: u32, arity: u32) -> KrResult<Option<Flow>> {
    // The stream argument of write/2, nl/1, ... is ignored: all output goes to the buffer.
    let last = arity.saturating_sub(1);
    let emit = |s: &mut Solver, t: &str| s.cx.out.push_str(t);
    match b {
        B::Write | B::Print | B::Writeln | B::Writeq | B::WriteCanonical => {
            let style = match b {
                B::Write | B::Writeln => Style::WRITE,
                B::WriteCanonical => Style::CANONICAL,
                _ => Style::WRITEQ,
            };
            let mut t = text(s, s.a(p, last), style)?;
            if b == B::Writeln {
                t.push('\n');
            }
            emit(s, &t);
        }
        B::WriteTerm => {
            let (ti, oi) = if arity == 3 { (1, 2) } else { (0, 1) };
            let options = write_options(s, s.a(p, oi));
            let c = s.a(p, ti);
            if s.m.st.is_cyclic(c) {
                return Err(super::machine::cyclic());
            }
            let t = s.m.st.to_term(c, &mut VarNames::new(&[]));
            emit(s, &t.to_text_with(options));
        }
        B::Nl => emit(s, "\n"),
        B::Tab => {
            let n = s.eval(s.a(p, last))?;
            let n = match n {
                super::arith::Num::I(n) => n.clamp(0, 1_000_000) as usize,
                _ => 0,
            };
            emit(s, &" ".repeat(n));
        }
        B::PrintMessage | B::GetTime if b == B::PrintMessage => {}
        B::GetTime => {
            s.cx.clock.reads += 1;
            let now = s.cx.clock.now.unwrap_or_else(|| {
                std::time::SystemTime::now()
                    .duration_since(std::time::UNIX_EPOCH)
                    .map_or(0.0, |d| d.as_secs_f64())
            });
            let x = s.a(p, 0);
            return Ok(Some(if s.unify(x, Cell::Flt(now)) {
                Flow::True
            } else {
                Flow::Fail
            }));
        }
        B::Format => {
            let (fi, ai) = match arity {
                1 => (0, None),
                2 => (0, Some(1)),
                _ => (1, Some(2)),
            };
            let f = s.ad(p, fi);
            let Some(fmt) = text_of(s, f) else {
                return Err(match f {
                    Cell::Ref(_) => inst("format", arity as usize),
                    _ => type_error(s, "text", f, "format", arity as usize),
                });
            };
            let args = match ai {
                Some(i) => format_args(s, s.a(p, i)),
                None => Vec::new(),
            };
            let out = format(s, &fmt, &args)?;
            if arity == 3 {
                if let Cell::Ptr(q) = s.ad(p, 0) {
                    if let Some((k, 1)) = s.m.st.heap[q as usize].fun() {
                        let v = match k.name() {
                            "atom" => Some(new_atom(s, &out, "format", 3)?),
                            "string" => Some(s.m.st.new_str(Arc::from(out.as_str()))),
                            "codes" => {
                                let cs: Vec<Cell> =
                                    out.chars().map(|c| Cell::Int(c as i64)).collect();
                                Some(s.m.st.new_list(&cs, Cell::Atom(wk::NIL)))
                            }
                            "chars" => {
                                let cs = out
                                    .chars()
                                    .map(|c| new_atom(s, &c.to_string(), "format", 3))
                                    .collect::<KrResult<Vec<Cell>>>()?;
                                Some(s.m.st.new_list(&cs, Cell::Atom(wk::NIL)))
                            }
                            _ => None,
                        };
                        if let Some(v) = v {
                            let x = s.a(q, 0);
                            return Ok(Some(if s.unify(x, v) {
                                Flow::True
                            } else {
                                Flow::Fail
                            }));
                        }
                    }
                }
            }
            emit(s, &out);
        }
        _ => return Ok(None),
    }
    Ok(Some(Flow::True))
}
