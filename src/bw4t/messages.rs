//! The BW4T message vocabulary of the seed: logical forms, speech acts and English sentences.
