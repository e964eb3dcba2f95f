//! Communicative acts: every message read as `<speech act type> <action/performative>
//! <parameters>`. GOAL's moods give Inform (`:p`), Request (`!p`, an offer when it is about the
//! sender itself) and Query (`?p`); the other acts have content forms of their own (see
//! `docs/communication.md`): `ack(...)`, `offer(A)`, `requestWhen(A, Signal)`, `signal(S)`.

use crate::term::{well_known as wk, Term};
use serde::Serialize;

/// CLAMR speech-act types, with the 3-bit code they have in a frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
pub enum SpeechAct {
    /// Tell something.
    Inform,
    /// Request a performance.
    Request,
    /// Ask for information.
    Query,
    /// Accept a proposal, answer a question, or notify of a status.
    Acknowledge,
    /// Offer to perform in the future.
    Offer,
    /// Request a performance that starts when the requester signals.
    RequestWhen,
}

impl SpeechAct {
    /// Every speech-act type.
    pub const ALL: [SpeechAct; 6] = [
        SpeechAct::Inform,
        SpeechAct::Request,
        SpeechAct::Query,
        SpeechAct::Acknowledge,
        SpeechAct::Offer,
        SpeechAct::RequestWhen,
    ];

    /// The 3-bit code: the seed fixes Acknowledge at 6; the others follow its Table 1 order.
    pub fn code(self) -> u8 {
        match self {
            SpeechAct::Inform => 1,
            SpeechAct::Request => 2,
            SpeechAct::Query => 3,
            SpeechAct::Offer => 4,
            SpeechAct::RequestWhen => 5,
            SpeechAct::Acknowledge => 6,
        }
    }

    /// The type with 3-bit code `c`.
    pub fn from_code(c: u8) -> Option<SpeechAct> {
        SpeechAct::ALL.into_iter().find(|s| s.code() == c)
    }

    /// [`SpeechAct::name`] interned.
    pub fn sym(self) -> crate::term::Sym {
        static SYMS: std::sync::OnceLock<Vec<crate::term::Sym>> = std::sync::OnceLock::new();
        let all = SYMS.get_or_init(|| {
            SpeechAct::ALL
                .iter()
                .map(|a| crate::term::Sym::intern(a.name()))
                .collect()
        });
        all[SpeechAct::ALL.iter().position(|a| *a == self).unwrap_or(0)]
    }

    /// The lower-case name agents see in `session/4` (`request`, `requestWhen`, ...).
    pub fn name(self) -> &'static str {
        match self {
            SpeechAct::Inform => "inform",
            SpeechAct::Request => "request",
            SpeechAct::Query => "query",
            SpeechAct::Acknowledge => "acknowledge",
            SpeechAct::Offer => "offer",
            SpeechAct::RequestWhen => "requestWhen",
        }
    }
}

/// An action or performative, with its 5-bit code: the seed's Table 2 (codes 1-8) and the
/// actions of an environment (BW4T's from 9); 0 is "none" (a plain OK), 31 the extension frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
pub struct Performative {
    /// The 5-bit code.
    pub code: u8,
    /// The name as GOAL programs write it (`sense`, `goTo`, ...).
    pub name: &'static str,
}

/// The performatives: the seed's table, then BW4T's actions (extensible per environment).
pub const PERFORMATIVES: &[Performative] = &[
    Performative {
        code: 1,
        name: "move",
    },
    Performative {
        code: 2,
        name: "stop",
    },
    Performative {
        code: 3,
        name: "pickup",
    },
    Performative {
        code: 4,
        name: "drop",
    },
    Performative {
        code: 5,
        name: "sense",
    },
    Performative {
        code: 6,
        name: "accept",
    },
    Performative {
        code: 7,
        name: "admit",
    },
    Performative {
        code: 8,
        name: "report",
    },
    Performative {
        code: 9,
        name: "goTo",
    },
    Performative {
        code: 10,
        name: "goToBlock",
    },
    Performative {
        code: 11,
        name: "pickUp",
    },
    Performative {
        code: 12,
        name: "putDown",
    },
];

/// The code of the extension frame (content carried as text, see `frame.rs`).
pub const EXTENSION_CODE: u8 = 31;

/// The performative named `name`.
pub fn performative(name: &str) -> Option<Performative> {
    PERFORMATIVES.iter().copied().find(|p| p.name == name)
}

/// The performative with code `code`.
pub fn performative_code(code: u8) -> Option<Performative> {
    PERFORMATIVES.iter().copied().find(|p| p.code == code)
}

/// BW4T's message vocabulary states wishes as facts about a robot (`imp(in(Bot, Room))`: "Bot,
/// go to Room"); these are the actions such facts ask for.
const BW4T_FORMS: &[(&str, &str)] = &[
    ("in", "goTo"),
    ("found", "sense"),
    ("holding", "pickUp"),
    ("pickedUpFrom", "pickUp"),
    ("putDown", "putDown"),
];

/// The parameter bits of Accept (accept/refuse) and Report (done/failed); the seed sets the
/// last bit for "done".
pub mod bits {
    /// Accept: the proposal is accepted (clear: refused).
    pub const ACCEPT: u8 = 0x01;
    /// Report: the task is done.
    pub const DONE: u8 = 0x01;
    /// Report: the task failed.
    pub const FAILED: u8 = 0x02;
}

/// What an acknowledgement says.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Answer {
    /// A plain OK (no performative).
    Ok,
    /// Accept a request or offer.
    Accept,
    /// Refuse a request or offer.
    Refuse,
    /// Answer a question.
    Admit,
    /// Report the task done.
    Done,
    /// Report the task failed.
    Failed,
    /// Report progress (the task goes on).
    Status,
}

impl Answer {
    /// The performative of the answer (none for a plain OK).
    pub fn performative(self) -> Option<Performative> {
        match self {
            Answer::Ok => None,
            Answer::Accept | Answer::Refuse => performative("accept"),
            Answer::Admit => performative("admit"),
            Answer::Done | Answer::Failed | Answer::Status => performative("report"),
        }
    }
}

/// A message read as a communicative act.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Act {
    /// The speech-act type.
    pub sat: SpeechAct,
    /// The action asked for, offered or answered, if the content names one.
    pub action: Option<Performative>,
    /// What an Acknowledge says.
    pub answer: Option<Answer>,
    /// True for the start signal of a RequestWhen (`signal(S)`).
    pub signal: bool,
    /// The parameters: the arguments of the action term (or of the answer).
    pub params: Vec<Term>,
}

/// Acknowledgements of everyday English (the BW4T vocabulary's answers) and what they say.
const PLAIN_ANSWERS: &[(&str, Answer)] = &[
    ("ok", Answer::Ok),
    ("yes", Answer::Admit),
    ("no", Answer::Admit),
    ("dontknow", Answer::Admit),
    ("ido", Answer::Admit),
    ("idont", Answer::Admit),
    ("ontheway", Answer::Accept),
    ("wait", Answer::Status),
    ("delayed", Answer::Status),
    ("faraway", Answer::Status),
    ("almostthere", Answer::Status),
    // "I could not": the team answers offers and requests with it.
    ("couldnot", Answer::Refuse),
];

/// The answer named by the first argument of `ack/1,2`.
pub fn answer_named(name: &str) -> Option<Answer> {
    Some(match name {
        "ok" => Answer::Ok,
        "accept" => Answer::Accept,
        "refuse" => Answer::Refuse,
        "admit" => Answer::Admit,
        "done" => Answer::Done,
        "failed" => Answer::Failed,
        "status" => Answer::Status,
        _ => return None,
    })
}

fn name_of(t: &Term) -> Option<&'static str> {
    t.functor().map(|(f, _)| f.name())
}

/// The performative an action term asks for: its own name, or BW4T's fact form.
fn action_of(t: &Term) -> (Option<Performative>, Vec<Term>) {
    let Some(name) = name_of(t) else {
        return (None, Vec::new());
    };
    let p = performative(name).or_else(|| {
        BW4T_FORMS
            .iter()
            .find(|(f, _)| *f == name)
            .and_then(|(_, p)| performative(p))
    });
    (p, t.args().to_vec())
}

fn act(sat: SpeechAct, inner: &Term) -> Act {
    let (action, params) = action_of(inner);
    Act {
        sat,
        action,
        answer: None,
        signal: false,
        params,
    }
}

fn ack(answer: Answer, params: Vec<Term>) -> Act {
    Act {
        sat: SpeechAct::Acknowledge,
        action: answer.performative(),
        answer: Some(answer),
        signal: false,
        params,
    }
}

/// Reads `content` (mood-wrapped) sent by `sender` as a communicative act.
pub fn classify(sender: &str, content: &Term) -> Act {
    let args = content.args();
    match content.functor() {
        Some((f, 1)) if f == wk::IMP => {
            let about_sender =
                matches!(args[0].args().first(), Some(Term::Atom(a)) if a.name() == sender);
            let sat = if about_sender {
                SpeechAct::Offer
            } else {
                SpeechAct::Request
            };
            act(sat, &args[0])
        }
        Some((f, 1)) if f == wk::INT => act(SpeechAct::Query, &args[0]),
        Some((f, 1)) if f.name() == "offer" => act(SpeechAct::Offer, &args[0]),
        Some((f, 2)) if f.name() == "requestWhen" => act(SpeechAct::RequestWhen, &args[0]),
        Some((f, 1)) if f.name() == "signal" => Act {
            signal: true,
            ..act(SpeechAct::Inform, &Term::atom("signal"))
        },
        Some((f, n @ (1 | 2))) if f.name() == "ack" => {
            match name_of(&args[0]).and_then(answer_named) {
                Some(a) if n == 2 => ack(a, vec![args[1].clone()]),
                Some(a) => ack(a, Vec::new()),
                None => act(SpeechAct::Inform, content),
            }
        }
        Some((f, arity)) => match PLAIN_ANSWERS.iter().find(|(n, _)| *n == f.name()) {
            // `ok(Room)` of the BW4T vocabulary is an OK too.
            Some((_, a)) if arity == 0 || f.name() == "ok" => ack(*a, args.to_vec()),
            _ => Act {
                action: None,
                params: Vec::new(),
                ..act(SpeechAct::Inform, content)
            },
        },
        None => Act {
            action: None,
            params: Vec::new(),
            ..act(SpeechAct::Inform, content)
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(sender: &str, text: &str) -> Act {
        let t = crate::syntax::prolog::Reader::new("t")
            .term(text, 0)
            .expect("term")
            .term;
        classify(sender, &t)
    }

    #[test]
    fn moods_and_forms_give_their_acts() {
        let r = read("r2", "imp(sense(temperature))");
        assert_eq!(r.sat, SpeechAct::Request);
        assert_eq!(r.action.map(|p| p.name), Some("sense"));
        assert_eq!(r.params, vec![Term::atom("temperature")]);
        assert_eq!(read("r2", "imp(in(r2, room))").sat, SpeechAct::Offer);
        assert_eq!(
            read("r2", "imp(in(r3, room))").action.map(|p| p.name),
            Some("goTo")
        );
        assert_eq!(read("r2", "int(at(X, room))").sat, SpeechAct::Query);
        assert_eq!(read("r2", "at(red, room)").sat, SpeechAct::Inform);
        assert_eq!(read("r2", "offer(stop)").sat, SpeechAct::Offer);
        let rw = read("r2", "requestWhen(move(north), go)");
        assert_eq!(rw.sat, SpeechAct::RequestWhen);
        assert_eq!(rw.action.map(|p| p.code), Some(1));
        assert!(read("r2", "signal(go)").signal);
        let a = read("r3", "ack(done, 25)");
        assert_eq!(
            (a.sat, a.answer),
            (SpeechAct::Acknowledge, Some(Answer::Done))
        );
        assert_eq!(a.action.map(|p| p.name), Some("report"));
        assert_eq!(read("r3", "ack(refuse, x)").answer, Some(Answer::Refuse));
        assert_eq!(read("r3", "ack(ok)").answer, Some(Answer::Ok));
        assert_eq!(read("r3", "yes").answer, Some(Answer::Admit));
        assert_eq!(read("r3", "couldnot").answer, Some(Answer::Refuse));
        assert_eq!(read("r3", "ack(maybe, x)").sat, SpeechAct::Inform);
    }

    #[test]
    fn codes_round_trip() {
        for s in SpeechAct::ALL {
            assert_eq!(SpeechAct::from_code(s.code()), Some(s));
        }
        assert_eq!(SpeechAct::Acknowledge.code(), 6);
        for p in PERFORMATIVES {
            assert!(p.code < 32 && p.code != EXTENSION_CODE);
            assert_eq!(performative_code(p.code), Some(*p));
        }
    }
}
