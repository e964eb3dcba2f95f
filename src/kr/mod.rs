//! The knowledge-representation boundary (a trait) and its engines.
