//! CLAMR, the seed's communication language for robot teams, layer by layer: communicative
//! acts (`act`), the content language (`content`), sessions (`session`), binary frames
//! (`frame`), the simulated token ring (`ring`) and the run's communication layer over a
//! transport (`transport`). See `docs/communication.md`.

pub mod act;
pub mod content;
pub mod frame;
pub mod ring;
pub mod session;
pub mod transport;

pub use act::{classify, Act, SpeechAct};
pub use transport::{Comm, CommOptions};
