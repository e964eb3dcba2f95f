//! One file per subcommand: its arguments and what it does.

pub mod bench;
pub mod check;
pub mod exit;
pub mod explain;
pub mod grade;
pub mod limits;
pub mod new;
pub mod prolog;
pub mod run;
pub mod test;
pub mod view;
pub mod why;
