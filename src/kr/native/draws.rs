//! The engine's random-number generator with a count of its draws, so that the runtime can
//! tell cheaply whether a query drew a random number (reading ChaCha's word position costs
//! about 64 instructions, asked a few times per agent cycle).

use rand::RngCore;
use rand_chacha::rand_core::SeedableRng;
use rand_chacha::ChaCha8Rng;

/// A seeded ChaCha8 generator that counts the calls that drew from it; the numbers drawn are
/// exactly ChaCha8's (every call is passed on unchanged).
#[derive(Clone, Debug)]
pub struct Draws {
    rng: ChaCha8Rng,
    count: u64,
}

impl Draws {
    /// A generator seeded with `seed`, no draws yet.
    pub fn seeded(seed: u64) -> Draws {
        Draws {
            rng: ChaCha8Rng::seed_from_u64(seed),
            count: 0,
        }
    }

    /// The number of calls that drew at least one word: it changes exactly when ChaCha's
    /// word position changes (each such call moves the position forward by one word or more).
    pub fn count(&self) -> u64 {
        self.count
    }
}

impl RngCore for Draws {
    fn next_u32(&mut self) -> u32 {
        self.count += 1;
        self.rng.next_u32()
    }

    fn next_u64(&mut self) -> u64 {
        self.count += 1;
        self.rng.next_u64()
    }

    fn fill_bytes(&mut self, dest: &mut [u8]) {
        // An empty fill draws nothing (the position stays), so it is not counted.
        self.count += u64::from(!dest.is_empty());
        self.rng.fill_bytes(dest)
    }

    fn try_fill_bytes(&mut self, dest: &mut [u8]) -> Result<(), rand::Error> {
        self.count += u64::from(!dest.is_empty());
        self.rng.try_fill_bytes(dest)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::Rng;

    #[test]
    fn draws_are_chachas_and_each_is_counted() {
        let mut plain = ChaCha8Rng::seed_from_u64(7);
        let mut counted = Draws::seeded(7);
        assert_eq!(counted.count(), 0);
        for i in 0..5u64 {
            // One word each (`gen_range` may draw more than once: rejection sampling).
            assert_eq!(counted.gen::<f64>(), plain.gen::<f64>());
            assert_eq!(counted.gen::<u32>(), plain.gen::<u32>());
            let before = counted.count();
            assert_eq!(counted.gen_range(0..10 + i), plain.gen_range(0..10 + i));
            assert!(counted.count() > before);
        }
        assert_eq!(counted.gen::<u64>(), plain.gen::<u64>());
        let n = counted.count();
        assert!(n >= 15);
        counted.fill_bytes(&mut []);
        assert_eq!(counted.count(), n);
    }

    #[test]
    fn chance_changes_exactly_when_a_query_draws_and_output_is_seen() {
        use crate::kr::{Engine, Knowledge, NativeEngine, View};
        use crate::syntax::prolog::Reader;
        let kn = Knowledge::load(&[]).expect("knowledge");
        let view = View::beliefs(&kn, &[]);
        let mut r = Reader::new("t");
        let mut e = NativeEngine::new(3);
        let mut ask = |e: &mut NativeEngine, q: &str| {
            let q = r.term(q, 0).expect("term").term;
            e.query(&view, &q).expect("query").len()
        };
        let start = e.chance();
        ask(&mut e, "X = 1, Y is X + 2");
        assert_eq!(e.chance(), start, "no draw: same chance");
        assert!(!e.has_output());
        ask(&mut e, "X is random(10), X > 100");
        let drawn = e.chance();
        assert_ne!(drawn, start, "a failed query that drew still counts");
        ask(&mut e, "random_between(1, 6, _)");
        assert_ne!(e.chance(), drawn);
        ask(&mut e, "write(hi)");
        assert!(e.has_output());
        assert_eq!(e.take_output(), "hi");
        assert!(!e.has_output());
    }
}
