//! Interned atoms: every atom name is stored once and named by a small integer.

use std::collections::HashMap;
use std::fmt;
use std::sync::atomic::{AtomicPtr, Ordering};
use std::sync::{OnceLock, RwLock};

/// An interned atom (or functor, or variable) name.
#[derive(Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Sym(pub u32);

struct Interner {
    ids: HashMap<&'static str, Sym>,
    names: Vec<&'static str>,
}

/// Names interned at start-up, in this order, so that the constants below are fixed.
const PREDEFINED: &[&str] = &[
    "[]",
    ".",
    "{}",
    ",",
    ";",
    "->",
    "*->",
    "|",
    ":-",
    "-->",
    "?-",
    "\\+",
    "not",
    "true",
    "false",
    "fail",
    "!",
    "-",
    "+",
    "*",
    "/",
    "=",
    "call",
    "is",
    "^",
    "end_of_file",
    "error",
    "[|]",
    "imp",
    "int",
    "percept",
    "received",
    "sent",
    "agent",
    "me",
    "_",
];

/// Well-known symbols, interned at fixed positions of [`PREDEFINED`].
pub mod well_known {
    use super::Sym;
    pub const NIL: Sym = Sym(0);
    pub const DOT: Sym = Sym(1);
    pub const CURLY: Sym = Sym(2);
    pub const COMMA: Sym = Sym(3);
    pub const SEMICOLON: Sym = Sym(4);
    pub const ARROW: Sym = Sym(5);
    pub const SOFT_ARROW: Sym = Sym(6);
    pub const BAR: Sym = Sym(7);
    pub const NECK: Sym = Sym(8);
    pub const DCG_ARROW: Sym = Sym(9);
    pub const QUERY: Sym = Sym(10);
    pub const NAF: Sym = Sym(11);
    pub const NOT: Sym = Sym(12);
    pub const TRUE: Sym = Sym(13);
    pub const FALSE: Sym = Sym(14);
    pub const FAIL: Sym = Sym(15);
    pub const CUT: Sym = Sym(16);
    pub const MINUS: Sym = Sym(17);
    pub const PLUS: Sym = Sym(18);
    pub const STAR: Sym = Sym(19);
    pub const SLASH: Sym = Sym(20);
    pub const EQUALS: Sym = Sym(21);
    pub const CALL: Sym = Sym(22);
    pub const IS: Sym = Sym(23);
    pub const CARET: Sym = Sym(24);
    pub const END_OF_FILE: Sym = Sym(25);
    pub const ERROR: Sym = Sym(26);
    pub const SWI_CONS: Sym = Sym(27);
    pub const IMP: Sym = Sym(28);
    pub const INT: Sym = Sym(29);
    pub const PERCEPT: Sym = Sym(30);
    pub const RECEIVED: Sym = Sym(31);
    pub const SENT: Sym = Sym(32);
    pub const AGENT: Sym = Sym(33);
    pub const ME: Sym = Sym(34);
    pub const UNDERSCORE: Sym = Sym(35);
}

fn interner() -> &'static RwLock<Interner> {
    static INTERNER: OnceLock<RwLock<Interner>> = OnceLock::new();
    INTERNER.get_or_init(|| {
        let mut interner = Interner {
            ids: HashMap::new(),
            names: Vec::new(),
        };
        for name in PREDEFINED {
            let sym = Sym(interner.names.len() as u32);
            interner.names.push(name);
            interner.ids.insert(name, sym);
            publish(sym.0 as usize, name);
        }
        RwLock::new(interner)
    })
}

/// The most names the table holds before [`Sym::try_intern_new`] refuses new ones (a
/// backstop over the per-agent budgets: about 90 bytes each, so some 700 MB at most).
pub const MAX_SYMS: usize = 8_000_000;

/// Names per chunk of the lock-free name table.
const CHUNK: usize = 1 << 12;
/// Chunks of the lock-free name table: room for [`MAX_SYMS`] names and the predefined ones
/// (names interned from program text beyond that are read under the lock).
const CHUNKS: usize = MAX_SYMS / CHUNK + 2;

/// One chunk of the name table: each slot points at a leaked name, or is null.
type Chunk = [AtomicPtr<&'static str>; CHUNK];

/// The names by symbol number, readable without the interner's lock: [`Sym::name`] runs on
/// every term written, compared or hashed by name, from every worker thread at once. Slots are
/// written once, under the interner's write lock, before the symbol is handed out.
static NAMES: [AtomicPtr<Chunk>; CHUNKS] = [const { AtomicPtr::new(std::ptr::null_mut()) }; CHUNKS];

/// Publishes `name` as the text of symbol number `i` in [`NAMES`] (caller holds the write lock).
fn publish(i: usize, name: &'static str) {
    let Some(chunk_slot) = NAMES.get(i / CHUNK) else {
        return;
    };
    let mut chunk = chunk_slot.load(Ordering::Acquire);
    if chunk.is_null() {
        let fresh: Box<Chunk> =
            Box::new(std::array::from_fn(
                |_| AtomicPtr::new(std::ptr::null_mut()),
            ));
        chunk = Box::into_raw(fresh);
        chunk_slot.store(chunk, Ordering::Release);
    }
    let text: &'static mut &'static str = Box::leak(Box::new(name));
    // SAFETY: chunks are never freed once published.
    unsafe { (*chunk)[i % CHUNK].store(text, Ordering::Release) };
}

/// The text of symbol number `i` from [`NAMES`], when published there.
fn published(i: usize) -> Option<&'static str> {
    let chunk = NAMES.get(i / CHUNK)?.load(Ordering::Acquire);
    if chunk.is_null() {
        return None;
    }
    // SAFETY: chunks and the names they point at are leaked, never freed or rewritten.
    let text = unsafe { (*chunk)[i % CHUNK].load(Ordering::Acquire) };
    if text.is_null() {
        return None;
    }
    Some(unsafe { *text })
}

/// Adds `name`, not yet interned, to the table.
fn add(guard: &mut Interner, name: &str) -> Sym {
    let leaked: &'static str = Box::leak(name.to_owned().into_boxed_str());
    let sym = Sym(guard.names.len() as u32);
    guard.names.push(leaked);
    guard.ids.insert(leaked, sym);
    publish(sym.0 as usize, leaked);
    sym
}

impl Sym {
    /// Interns `name`, returning the existing symbol when it is already known.
    ///
    /// Interned names live for the whole process (like atoms in Prolog systems without atom
    /// garbage collection): names from program text use this; names made by running queries
    /// go through [`Sym::try_intern_new`], which is bounded.
    pub fn intern(name: &str) -> Sym {
        if let Some(sym) = interner()
            .read()
            .unwrap_or_else(|e| e.into_inner())
            .ids
            .get(name)
        {
            return *sym;
        }
        let mut guard = interner().write().unwrap_or_else(|e| e.into_inner());
        if let Some(sym) = guard.ids.get(name) {
            return *sym;
        }
        add(&mut guard, name)
    }

    /// The symbol named `name` when it is already interned.
    pub fn lookup(name: &str) -> Option<Sym> {
        interner()
            .read()
            .unwrap_or_else(|e| e.into_inner())
            .ids
            .get(name)
            .copied()
    }

    /// Interns `name` for a name made at run time: the symbol and whether it was new, or
    /// `None` when the name is new and the table already holds [`MAX_SYMS`] names (interned
    /// names are never freed, so the table is bounded for names made by running programs).
    pub fn try_intern_new(name: &str) -> Option<(Sym, bool)> {
        if let Some(sym) = Sym::lookup(name) {
            return Some((sym, false));
        }
        let mut guard = interner().write().unwrap_or_else(|e| e.into_inner());
        if let Some(sym) = guard.ids.get(name) {
            return Some((*sym, false));
        }
        if guard.names.len() >= MAX_SYMS {
            return None;
        }
        Some((add(&mut guard, name), true))
    }

    /// The text of this symbol (without taking the interner's lock).
    pub fn name(self) -> &'static str {
        if let Some(name) = published(self.0 as usize) {
            return name;
        }
        interner().read().unwrap_or_else(|e| e.into_inner()).names[self.0 as usize]
    }
}

impl fmt::Debug for Sym {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.name())
    }
}

impl fmt::Display for Sym {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl From<&str> for Sym {
    fn from(name: &str) -> Sym {
        Sym::intern(name)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn predefined_symbols_have_fixed_ids() {
        assert_eq!(Sym::intern("[]"), well_known::NIL);
        assert_eq!(Sym::intern("not"), well_known::NOT);
        assert_eq!(Sym::intern("_"), well_known::UNDERSCORE);
        assert_eq!(well_known::SENT.name(), "sent");
        for (i, name) in PREDEFINED.iter().enumerate() {
            assert_eq!(Sym::intern(name).0 as usize, i, "{name}");
        }
    }

    #[test]
    fn interning_is_idempotent() {
        let a = Sym::intern("RoomA1");
        assert_eq!(a, Sym::intern("RoomA1"));
        assert_eq!(a.name(), "RoomA1");
        assert_ne!(a, Sym::intern("RoomA2"));
    }

    #[test]
    fn names_are_read_from_other_threads() {
        let syms: Vec<Sym> = (0..3 * CHUNK / 2)
            .map(|i| Sym::intern(&format!("sym_test_thread_{i}")))
            .collect();
        let names = std::thread::spawn(move || {
            syms.iter()
                .map(|s| s.name().to_string())
                .collect::<Vec<_>>()
        })
        .join()
        .expect("reader thread");
        for (i, n) in names.iter().enumerate() {
            assert_eq!(n, &format!("sym_test_thread_{i}"));
        }
        assert_eq!(well_known::UNDERSCORE.name(), "_");
    }

    #[test]
    fn run_time_interning_says_whether_the_name_is_new() {
        assert_eq!(Sym::lookup("sym_test_fresh_name"), None);
        let (a, new) = Sym::try_intern_new("sym_test_fresh_name").unwrap();
        assert!(new);
        assert_eq!(Sym::try_intern_new("sym_test_fresh_name"), Some((a, false)));
        assert_eq!(Sym::lookup("sym_test_fresh_name"), Some(a));
        assert_eq!(Sym::try_intern_new("[]"), Some((well_known::NIL, false)));
    }
}
