//! A runtime for GOAL agent programs: parser and validator (`syntax`), the shared term type
//! (`term`), the knowledge-representation layer (`kr`), the agent interpreter (`agent`),
//! multi-agent systems (`mas`), the environment interface (`env`) and the built-in Blocks World
//! for Teams (`bw4t`) and blocks world (`blocksworld`) environments. See ARCHITECTURE.md for a map.

pub mod agent;
pub mod alloc;
pub mod bench;
pub mod blocksworld;
pub mod bw4t;
pub mod clamr;
pub mod diag;
pub mod env;
pub mod grade;
pub mod kr;
pub mod mas;
pub mod suggest;
pub mod syntax;
pub mod term;
pub mod testing;
pub mod view;
pub mod why;

/// Small blocks from mimalloc, large ones from the system allocator (see [`alloc`]).
#[global_allocator]
static GLOBAL: alloc::Hybrid = alloc::Hybrid;
