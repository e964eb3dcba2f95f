//! GOAL's fixed Prolog operator table (no `op/3`), shared by the reader and the printer.

/// How an operator takes its operands (ISO operator types).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OpType {
    Xfx,
    Xfy,
    Yfx,
    Fy,
    Fx,
}

/// One entry of the operator table.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Op {
    pub name: &'static str,
    pub priority: u16,
    pub kind: OpType,
}

const fn op(name: &'static str, priority: u16, kind: OpType) -> Op {
    Op {
        name,
        priority,
        kind,
    }
}

use OpType::*;

/// The whole table (GOAL's fixed operator table).
pub const OPERATORS: &[Op] = &[
    op(":-", 1200, Xfx),
    op("-->", 1200, Xfx),
    op(":-", 1200, Fx),
    op("?-", 1200, Fx),
    op("|", 1105, Xfy),
    op(";", 1100, Xfy),
    op("->", 1050, Xfy),
    op("*->", 1050, Xfy),
    op(",", 1000, Xfy),
    op("\\+", 900, Fy),
    op("=", 700, Xfx),
    op("\\=", 700, Xfx),
    op("==", 700, Xfx),
    op("\\==", 700, Xfx),
    op("@<", 700, Xfx),
    op("@=<", 700, Xfx),
    op("@>", 700, Xfx),
    op("@>=", 700, Xfx),
    op("=@=", 700, Xfx),
    op("=..", 700, Xfx),
    op("is", 700, Xfx),
    op("=:=", 700, Xfx),
    op("=\\=", 700, Xfx),
    op("<", 700, Xfx),
    op("=<", 700, Xfx),
    op(">", 700, Xfx),
    op(">=", 700, Xfx),
    op("+", 500, Yfx),
    op("-", 500, Yfx),
    op("/\\", 500, Yfx),
    op("\\/", 500, Yfx),
    op("xor", 500, Yfx),
    op("><", 500, Yfx),
    op("*", 400, Yfx),
    op("/", 400, Yfx),
    op("//", 400, Yfx),
    op("rem", 400, Yfx),
    op("mod", 400, Yfx),
    op("rdiv", 400, Yfx),
    op("<<", 400, Yfx),
    op(">>", 400, Yfx),
    op("**", 200, Xfx),
    op("^", 200, Xfy),
    op("-", 200, Fy),
    op("\\", 200, Fy),
];

/// The infix operator with this name, if any.
pub fn infix(name: &str) -> Option<Op> {
    OPERATORS
        .iter()
        .copied()
        .find(|o| o.name == name && matches!(o.kind, Xfx | Xfy | Yfx))
}

/// The prefix operator with this name, if any.
pub fn prefix(name: &str) -> Option<Op> {
    OPERATORS
        .iter()
        .copied()
        .find(|o| o.name == name && matches!(o.kind, Fy | Fx))
}

/// True when `name` is an operator of any kind.
pub fn is_operator(name: &str) -> bool {
    OPERATORS.iter().any(|o| o.name == name)
}

impl Op {
    /// Maximum priorities of the (left, right) operands; prefix operators use only `right`.
    pub fn operand_priorities(self) -> (u16, u16) {
        let p = self.priority;
        match self.kind {
            Xfx => (p - 1, p - 1),
            Xfy => (p - 1, p),
            Yfx => (p, p - 1),
            Fy => (0, p),
            Fx => (0, p - 1),
        }
    }
}
