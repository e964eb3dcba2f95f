//! Trace events of a reasoning cycle (serializable; they become JSON lines).

use serde::Serialize;

/// How much the agent records in its trace.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Serialize)]
pub enum TraceLevel {
    /// Nothing but errors and warnings.
    Off,
    /// State changes, actions, messages, prints, module entry/exit.
    Changes,
    /// Everything, including every rule evaluation.
    Rules,
}

/// One thing that happened in a cycle. Terms are printed as Prolog text. `attention` numbers an
/// attention set by its place on the agent's attention stack: 0 is the top-level goal base, 1 the
/// set pushed by the first module with a focus, and so on.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "event", rename_all = "snake_case")]
pub enum Event {
    /// A cycle began.
    CycleStart { cycle: u64 },
    /// A module was entered (`init`, `main`, `event`, a user module or `{block}`).
    ModuleEntered { module: String },
    /// A module exited.
    ModuleExited { module: String },
    /// A rule's condition was evaluated.
    RuleEvaluated { rule: String, answers: usize },
    /// A rule's body ran for an answer.
    RuleFired { rule: String, bindings: String },
    /// An action was performed.
    ActionPerformed { action: String },
    /// An action was tried but did not run.
    ActionFailed { action: String, reason: String },
    /// An environment action was handed to the caller.
    EnvAction { action: String },
    /// A belief was added.
    BeliefInserted { fact: String },
    /// A belief was removed.
    BeliefDeleted { fact: String },
    /// A percept appeared in the percept base.
    PerceptAdded { percept: String },
    /// A percept left the percept base.
    PerceptRemoved { percept: String },
    /// A goal was adopted.
    GoalAdopted {
        goal: String,
        #[serde(skip_serializing_if = "is_top_level")]
        attention: usize,
    },
    /// A goal was dropped by `drop`.
    GoalDropped {
        goal: String,
        #[serde(skip_serializing_if = "is_top_level")]
        attention: usize,
    },
    /// A goal was achieved (blind commitment removed it).
    GoalAchieved {
        goal: String,
        #[serde(skip_serializing_if = "is_top_level")]
        attention: usize,
    },
    /// Entering a module with a focus pushed attention set number `attention` holding `goals`.
    AttentionPushed {
        module: String,
        focus: String,
        attention: usize,
        goals: Vec<String>,
    },
    /// Leaving a module with a focus popped its attention set, number `attention`.
    AttentionPopped { module: String, attention: usize },
    /// A mailbox fact was added.
    MailAdded { fact: String },
    /// A mailbox fact was removed.
    MailDeleted { fact: String },
    /// A message was sent.
    MessageSent { to: String, content: String },
    /// `print/1` output.
    Print { text: String },
    /// `log/1` output.
    Log { text: String },
    /// A non-fatal problem.
    Warning { message: String },
    /// A fatal runtime error (the agent stops).
    Error { message: String },
    /// The agent stopped.
    Stopped { reason: String },
}

/// True for the top-level goal base (attention set 0), whose number goal events leave out:
/// traces of programs without focus read as they did before attention sets were recorded.
fn is_top_level(attention: &usize) -> bool {
    *attention == 0
}
