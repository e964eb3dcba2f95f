//! A set of ground facts indexed by predicate and by the first two arguments, iterated in
//! insertion order. Insert and delete are O(1) expected and free their memory (slots are reused,
//! empty index entries are removed), so churn does not grow the base.

use super::fxhash::{FxHashMap, FxHasher};
use super::native::code::Key;
use crate::term::{Sym, Term};
use hashbrown::Equivalent;
use std::hash::{BuildHasherDefault, Hash};

const NONE: u32 = u32::MAX;
/// Link sets of an entry: all facts, its predicate, its first-argument and second-argument keys.
const ALL: usize = 0;
const PRED: usize = 1;
const ARG1: usize = 2;
const ARG2: usize = 3;

#[derive(Clone, Copy, Debug)]
struct Link {
    prev: u32,
    next: u32,
}

const UNLINKED: Link = Link {
    prev: NONE,
    next: NONE,
};

#[derive(Clone, Debug)]
struct Entry {
    term: Option<Term>,
    links: [Link; 4],
}

#[derive(Clone, Copy, Debug)]
struct List {
    first: u32,
    last: u32,
    len: u32,
}

const EMPTY: List = List {
    first: NONE,
    last: NONE,
    len: 0,
};

/// Which list a scan follows (chosen by [`FactBase::scan`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Scan {
    /// The link set to follow.
    pub links: u8,
    /// The next entry to look at (`u32::MAX` at the end).
    pub next: u32,
}

/// An indexed set of ground facts (beliefs, percepts, mailbox, ...).
#[derive(Clone, Debug, Default)]
pub struct FactBase {
    entries: Vec<Entry>,
    free: Vec<u32>,
    /// A hashbrown map, which finds a fact by anything that hashes and compares as it does
    /// (see [`FactBase::contains_instance`]).
    ids: hashbrown::HashMap<Term, u32, BuildHasherDefault<FxHasher>>,
    all: Option<List>,
    preds: FxHashMap<(Sym, u32), List>,
    /// One bit per predicate present ([`pred_bit`]): most asks are for predicates a base
    /// lacks, and a clear bit says so without hashing.
    pred_bits: u64,
    arg1: FxHashMap<(Sym, u32, Key), List>,
    arg2: FxHashMap<(Sym, u32, Key), List>,
    /// Successful inserts and deletes so far (clearing counts as one): lets a reader tell
    /// cheaply whether the base changed since it last looked.
    edits: u64,
}

/// The bit of predicate `name/arity` in [`FactBase::pred_bits`] (symbols are numbered in
/// order, so a program's few predicates rarely share a bit).
#[inline]
fn pred_bit(name: Sym, arity: u32) -> u64 {
    1 << (name.0.wrapping_add(arity.wrapping_mul(13)) & 63)
}

fn pred_of(t: &Term) -> Option<(Sym, u32)> {
    t.functor().map(|(s, n)| (s, n as u32))
}

fn arg_key(t: &Term, i: usize) -> Option<Key> {
    t.args().get(i).and_then(Key::of_term)
}

fn push_back(entries: &mut [Entry], list: &mut List, k: usize, id: u32) {
    entries[id as usize].links[k] = Link {
        prev: list.last,
        next: NONE,
    };
    if list.last != NONE {
        entries[list.last as usize].links[k].next = id;
    } else {
        list.first = id;
    }
    list.last = id;
    list.len += 1;
}

fn unlink(entries: &mut [Entry], list: &mut List, k: usize, id: u32) {
    let Link { prev, next } = entries[id as usize].links[k];
    if prev != NONE {
        entries[prev as usize].links[k].next = next;
    } else {
        list.first = next;
    }
    if next != NONE {
        entries[next as usize].links[k].prev = prev;
    } else {
        list.last = prev;
    }
    list.len -= 1;
    entries[id as usize].links[k] = UNLINKED;
}

impl FactBase {
    /// An empty base.
    pub fn new() -> FactBase {
        FactBase::default()
    }

    /// The number of changes made to the base so far (never decreases, also across
    /// [`FactBase::clear`]): equal counts mean the same facts.
    pub fn edits(&self) -> u64 {
        self.edits
    }

    /// Number of facts.
    pub fn len(&self) -> usize {
        self.ids.len()
    }

    /// True when the base holds no facts.
    pub fn is_empty(&self) -> bool {
        self.ids.is_empty()
    }

    /// True when exactly this fact is present.
    pub fn contains(&self, fact: &Term) -> bool {
        // Empty bases (often the mailbox) are common: skip hashing the term.
        !self.ids.is_empty() && self.ids.contains_key(fact)
    }

    /// True when the fact `q` stands for is present, found without building it (e.g. a
    /// [`crate::term::instance::Instance`]).
    pub fn contains_instance<Q: Hash + Equivalent<Term>>(&self, q: &Q) -> bool {
        !self.ids.is_empty() && self.ids.contains_key(q)
    }

    /// True when some fact of predicate `name/arity` is present (cheaper than hashing a
    /// whole fact: lets lookups skip bases that cannot hold it).
    #[inline]
    pub fn has_pred(&self, name: Sym, arity: usize) -> bool {
        self.pred_bits & pred_bit(name, arity as u32) != 0
            && self.preds.contains_key(&(name, arity as u32))
    }

    /// False when no fact of predicate `name/arity` is present, by the quick filter alone (true
    /// may still be wrong): for a reader about to [`FactBase::scan`], which finds nothing for an
    /// absent predicate anyway, so the exact test's hashing would be paid twice.
    #[inline]
    pub fn may_have_pred(&self, name: Sym, arity: usize) -> bool {
        self.pred_bits & pred_bit(name, arity as u32) != 0
    }

    /// Adds a fact (an atom or compound term, normally ground); returns false when it was
    /// already present or is not a callable term.
    pub fn insert(&mut self, fact: Term) -> bool {
        let Some((name, arity)) = pred_of(&fact) else {
            return false;
        };
        // One hash of the whole fact: the entry API both checks and inserts.
        let slot = match self.ids.entry(fact) {
            hashbrown::hash_map::Entry::Occupied(_) => return false,
            hashbrown::hash_map::Entry::Vacant(v) => v,
        };
        let id = match self.free.pop() {
            Some(id) => id,
            None => {
                self.entries.push(Entry {
                    term: None,
                    links: [UNLINKED; 4],
                });
                self.entries.len() as u32 - 1
            }
        };
        let fact = slot.key().clone();
        slot.insert(id);
        self.edits += 1;
        let (k1, k2) = (arg_key(&fact, 0), arg_key(&fact, 1));
        self.entries[id as usize].term = Some(fact);
        let entries = &mut self.entries;
        push_back(entries, self.all.get_or_insert(EMPTY), ALL, id);
        self.pred_bits |= pred_bit(name, arity);
        push_back(
            entries,
            self.preds.entry((name, arity)).or_insert(EMPTY),
            PRED,
            id,
        );
        if let Some(k) = k1 {
            push_back(
                entries,
                self.arg1.entry((name, arity, k)).or_insert(EMPTY),
                ARG1,
                id,
            );
        }
        if let Some(k) = k2 {
            push_back(
                entries,
                self.arg2.entry((name, arity, k)).or_insert(EMPTY),
                ARG2,
                id,
            );
        }
        true
    }

    /// Removes a fact; returns false when it was not present.
    pub fn delete(&mut self, fact: &Term) -> bool {
        let Some(id) = self.ids.remove(fact) else {
            return false;
        };
        self.unlink_fact(fact, id)
    }

    /// Removes the fact `q` stands for, found without building it (see
    /// [`FactBase::contains_instance`]), and hands it back; `None` when it was not present.
    pub fn take_instance<Q: Hash + Equivalent<Term>>(&mut self, q: &Q) -> Option<Term> {
        if self.ids.is_empty() {
            return None;
        }
        let (fact, id) = self.ids.remove_entry(q)?;
        self.unlink_fact(&fact, id);
        Some(fact)
    }

    /// Takes the entry `id` of `fact` (already out of `ids`) off every list.
    fn unlink_fact(&mut self, fact: &Term, id: u32) -> bool {
        self.edits += 1;
        let Some((name, arity)) = pred_of(fact) else {
            return false;
        };
        let entries = &mut self.entries;
        if let Some(all) = self.all.as_mut() {
            unlink(entries, all, ALL, id);
        }
        if let Some(l) = self.preds.get_mut(&(name, arity)) {
            unlink(entries, l, PRED, id);
            if l.len == 0 {
                self.preds.remove(&(name, arity));
                self.pred_bits = self.preds.keys().fold(0, |b, (s, n)| b | pred_bit(*s, *n));
            }
        }
        for (i, (k, map)) in [(ARG1, &mut self.arg1), (ARG2, &mut self.arg2)]
            .into_iter()
            .enumerate()
        {
            if let Some(key) = arg_key(fact, i) {
                if let Some(l) = map.get_mut(&(name, arity, key)) {
                    unlink(entries, l, k, id);
                    if l.len == 0 {
                        map.remove(&(name, arity, key));
                    }
                }
            }
        }
        entries[id as usize].term = None;
        self.free.push(id);
        if self.ids.is_empty() {
            self.reset();
        }
        true
    }

    /// Empties the base after its last fact went. A small base keeps its allocations (a
    /// mailbox that empties after every message would otherwise rebuild its maps each time);
    /// a large one frees them, so memory follows the current size.
    fn reset(&mut self) {
        if self.entries.capacity() > 256 {
            let edits = self.edits;
            *self = FactBase::default();
            self.edits = edits;
            return;
        }
        self.entries.clear();
        self.free.clear();
        self.ids.clear();
        self.all = None;
        self.preds.clear();
        self.pred_bits = 0;
        self.arg1.clear();
        self.arg2.clear();
    }

    /// Removes every fact, as deleting them one by one would (same edit count, allocations of
    /// a small base kept): cheaper when a whole base is replaced.
    pub fn delete_all(&mut self) {
        self.edits += self.len() as u64;
        self.reset();
    }

    /// Removes every fact and frees the memory.
    pub fn clear(&mut self) {
        let edits = self.edits + 1;
        *self = FactBase::default();
        self.edits = edits;
    }

    /// All facts in insertion order.
    pub fn iter(&self) -> impl Iterator<Item = &Term> + '_ {
        let mut id = self.all.map_or(NONE, |l| l.first);
        std::iter::from_fn(move || {
            if id == NONE {
                return None;
            }
            let e = &self.entries[id as usize];
            id = e.links[ALL].next;
            e.term.as_ref()
        })
    }

    /// The facts of predicate `name/arity` in insertion order.
    pub fn facts_of(&self, name: Sym, arity: usize) -> impl Iterator<Item = &Term> + '_ {
        let start = self
            .preds
            .get(&(name, arity as u32))
            .map_or(NONE, |l| l.first);
        let mut scan = Scan {
            links: PRED as u8,
            next: start,
        };
        std::iter::from_fn(move || self.advance(&mut scan))
    }

    /// Starts a scan over the facts that can match `name/arity` with the given argument keys,
    /// following the shortest applicable list.
    pub(crate) fn scan(&self, name: Sym, arity: u32, k1: Option<Key>, k2: Option<Key>) -> Scan {
        // Most queries look at several bases, some of them empty: no key to hash then.
        if self.ids.is_empty() {
            return Scan {
                links: 0,
                next: NONE,
            };
        }
        let mut best: Option<(usize, List)> = None;
        if let Some(k) = k1 {
            match self.arg1.get(&(name, arity, k)) {
                Some(l) => best = Some((ARG1, *l)),
                None => {
                    return Scan {
                        links: 0,
                        next: NONE,
                    }
                }
            }
        }
        if let Some(k) = k2 {
            match self.arg2.get(&(name, arity, k)) {
                Some(l) => {
                    if best.is_none_or(|(_, b)| l.len < b.len) {
                        best = Some((ARG2, *l))
                    }
                }
                None => {
                    return Scan {
                        links: 0,
                        next: NONE,
                    }
                }
            }
        }
        if best.is_none() {
            best = self.preds.get(&(name, arity)).map(|l| (PRED, *l));
        }
        match best {
            Some((k, l)) => Scan {
                links: k as u8,
                next: l.first,
            },
            None => Scan {
                links: 0,
                next: NONE,
            },
        }
    }

    /// The next fact of a scan.
    #[inline]
    pub(crate) fn advance(&self, scan: &mut Scan) -> Option<&Term> {
        if scan.next == NONE {
            return None;
        }
        let e = &self.entries[scan.next as usize];
        scan.next = e.links[scan.links as usize].next;
        e.term.as_ref()
    }

    /// Approximate heap bytes held (for memory tests and budgets).
    pub fn allocated_entries(&self) -> usize {
        self.entries.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn on(a: &str, b: &str) -> Term {
        Term::compound("on", vec![Term::atom(a), Term::atom(b)])
    }

    #[test]
    fn insert_delete_report_changes_and_keep_order() {
        let mut fb = FactBase::new();
        assert!(fb.insert(on("a", "b")));
        assert!(fb.insert(on("c", "d")));
        assert!(!fb.insert(on("a", "b")));
        assert!(fb.insert(on("b", "c")));
        let all: Vec<String> = fb.iter().map(|t| t.to_string()).collect();
        assert_eq!(all, ["on(a,b)", "on(c,d)", "on(b,c)"]);
        assert!(fb.delete(&on("c", "d")));
        assert!(!fb.delete(&on("c", "d")));
        let all: Vec<String> = fb
            .facts_of(Sym::intern("on"), 2)
            .map(|t| t.to_string())
            .collect();
        assert_eq!(all, ["on(a,b)", "on(b,c)"]);
        assert!(!fb.insert(Term::Int(3)));
        // Three inserts and one delete changed the base; the refused ones did not.
        assert_eq!(fb.edits(), 4);
        fb.clear();
        assert!(fb.is_empty() && fb.edits() == 5);
        assert!(fb.insert(on("a", "b")) && fb.delete(&on("a", "b")));
        assert_eq!(fb.edits(), 7, "emptying the base keeps the count");
    }

    #[test]
    fn scans_use_the_argument_indexes() {
        let mut fb = FactBase::new();
        for i in 0..10 {
            fb.insert(Term::compound("p", vec![Term::Int(i % 3), Term::Int(i)]));
        }
        let p = Sym::intern("p");
        let mut s = fb.scan(p, 2, Some(Key::Int(1)), None);
        let mut got = vec![];
        while let Some(t) = fb.advance(&mut s) {
            got.push(t.to_string());
        }
        assert_eq!(got, ["p(1,1)", "p(1,4)", "p(1,7)"]);
        let mut s = fb.scan(p, 2, None, Some(Key::Int(5)));
        assert_eq!(
            fb.advance(&mut s).map(|t| t.to_string()),
            Some("p(2,5)".into())
        );
        assert!(fb.advance(&mut s).is_none());
        let mut s = fb.scan(p, 2, Some(Key::Int(7)), None);
        assert!(fb.advance(&mut s).is_none());
    }

    #[test]
    fn has_pred_follows_inserts_and_deletes_of_many_predicates() {
        // More predicates than bits in the quick filter: answers must stay exact.
        let mut fb = FactBase::new();
        let fact = |i: usize| Term::compound(format!("hp{i}").as_str(), vec![Term::Int(i as i64)]);
        for i in 0..100 {
            fb.insert(fact(i));
        }
        for i in (0..100).step_by(2) {
            assert!(fb.delete(&fact(i)));
        }
        for i in 0..100 {
            let name = Sym::intern(&format!("hp{i}"));
            assert_eq!(fb.has_pred(name, 1), i % 2 == 1, "hp{i}/1");
            assert!(!fb.has_pred(name, 2), "hp{i}/2");
        }
        for i in (1..100).step_by(2) {
            assert!(fb.delete(&fact(i)));
        }
        assert!(!fb.has_pred(Sym::intern("hp1"), 1));
        fb.insert(fact(7));
        assert!(fb.has_pred(Sym::intern("hp7"), 1));
        assert!(!fb.has_pred(Sym::intern("hp9"), 1));
    }

    #[test]
    fn churn_does_not_grow_the_base() {
        let mut fb = FactBase::new();
        fb.insert(on("x", "y"));
        for i in 0..100_000 {
            let f = Term::compound("at", vec![Term::Int(i)]);
            assert!(fb.insert(f.clone()));
            assert!(fb.delete(&f));
        }
        assert_eq!(fb.len(), 1);
        assert!(fb.allocated_entries() <= 2);
        assert!(fb.arg1.len() <= 1 && fb.preds.len() == 1);
    }
}
