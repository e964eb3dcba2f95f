//! An insertion-ordered set of a condition's answers without repetitions.

use super::Found;
use crate::kr::fxhash::{FxHashMap, FxHasher};
use crate::term::Subst;
use smallvec::SmallVec;
use std::hash::{Hash, Hasher};

/// An insertion-ordered set of answers: while small, each answer is compared with the others
/// directly; beyond that its hash is compared first (a linear scan of hashes, then a hash
/// index), the bindings only when hashes are equal.
#[derive(Default)]
pub(super) struct AnswerSet {
    pub(super) items: Found,
    /// The hashes of the items, made once the set outgrows direct comparison.
    hashed: Option<Box<Hashed>>,
}

/// The hashes of an [`AnswerSet`]'s items, and an index of them once the set is large.
#[derive(Default)]
struct Hashed {
    /// The hashes of the first items (computed when a membership test needs them).
    hashes: Vec<u64>,
    index: FxHashMap<u64, SmallVec<[usize; 1]>>,
    /// How many of `items` the index covers.
    indexed: usize,
}

/// Up to this many answers a new one is compared with each directly (no hashing).
const COMPARE_UPTO: usize = 8;
const HASH_FROM: usize = 32;

/// A hash of the bindings of `s` that does not depend on their order.
fn hash_of(s: &Subst) -> u64 {
    s.iter().fold(0u64, |acc, binding| {
        let mut h = FxHasher::default();
        binding.hash(&mut h);
        acc.wrapping_add(h.finish())
    })
}

/// True when `a` and `b` bind the same variables to the same terms, in whatever order: the
/// same answer reached through literals that bound its variables in another order.
fn same_answer(a: &Subst, b: &Subst) -> bool {
    a.len() == b.len() && a.iter().all(|(v, t)| b.get(v) == Some(t))
}

impl AnswerSet {
    /// Adds `s` unless present.
    pub(super) fn push(&mut self, s: Subst) {
        let items = &mut self.items;
        if items.len() < COMPARE_UPTO {
            if !items.iter().any(|i| same_answer(i, &s)) {
                items.push(s);
            }
            return;
        }
        let hs = self.hashed.get_or_insert_with(Box::default);
        while hs.hashes.len() < items.len() {
            hs.hashes.push(hash_of(&items[hs.hashes.len()]));
        }
        let h = hash_of(&s);
        if items.len() < HASH_FROM {
            let mut same = hs.hashes.iter().zip(items.iter());
            if !same.any(|(&hi, i)| hi == h && same_answer(i, &s)) {
                hs.hashes.push(h);
                items.push(s);
            }
            return;
        }
        while hs.indexed < items.len() {
            let hi = hs.hashes[hs.indexed];
            hs.index.entry(hi).or_default().push(hs.indexed);
            hs.indexed += 1;
        }
        let slot = hs.index.entry(h).or_default();
        if slot.iter().any(|&i| same_answer(&items[i], &s)) {
            return;
        }
        slot.push(items.len());
        hs.indexed += 1;
        hs.hashes.push(h);
        items.push(s);
    }

    /// Adds `s`, known to differ from every answer present.
    pub(super) fn push_new(&mut self, s: Subst) {
        self.items.push(s);
    }
}
