//! BW4T's built-in message vocabulary (the seed's message list): for a mood-wrapped message, its
//! logical form, CLAMR speech-act type and English sentence. `src/bw4t/messages.rs` is still
//! empty, so the table lives here.

use crate::term::{Style, Term};
use serde::Serialize;

/// CLAMR speech-act types (seed: clamr-communication-language.md, Table I).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum SpeechAct {
    /// Declarative content: the sender informs.
    Inform,
    /// An imperative aimed at another agent.
    Request,
    /// An interrogative.
    Query,
    /// An answer (`ok`, `yes`, `no`, `dontknow`, ...).
    Acknowledge,
    /// An imperative about the sender itself: a commitment to do something.
    Offer,
}

/// How a message reads: its logical form, speech act and (when in the vocabulary) sentence.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct Reading {
    /// The mood-wrapped content as Prolog text.
    pub logical_form: String,
    /// The speech-act type.
    pub act: SpeechAct,
    /// The English sentence, when the message is in BW4T's vocabulary.
    pub english: Option<String>,
}

const ANSWERS: &[(&str, &str)] = &[
    ("yes", "yes"),
    ("no", "no"),
    ("dontknow", "I don't know"),
    ("wait", "wait"),
    ("ok", "OK"),
    ("idont", "I don't"),
    ("ido", "I do"),
    ("ontheway", "I am on the way"),
    ("faraway", "I am far away"),
    ("delayed", "I am delayed"),
    ("almostthere", "I am almost there"),
    ("couldnot", "I could not"),
];

/// Reads `content` (mood-wrapped: `p`, `imp(p)` or `int(p)`) sent by `sender`.
pub fn read(sender: &str, content: &Term) -> Reading {
    let logical_form = content.to_string();
    let (act, english) = match unwrap(content, "imp") {
        Some(p) => {
            let mine = first_arg_is(p, sender);
            let act = if mine {
                SpeechAct::Offer
            } else {
                SpeechAct::Request
            };
            (act, imperative(p, mine))
        }
        None => match unwrap(content, "int") {
            Some(q) => (SpeechAct::Query, question(q, sender)),
            None => match answer(content) {
                Some(s) => (SpeechAct::Acknowledge, Some(s)),
                None => (SpeechAct::Inform, declarative(content, sender)),
            },
        },
    };
    Reading {
        logical_form,
        act,
        english,
    }
}

fn unwrap<'a>(t: &'a Term, wrapper: &str) -> Option<&'a Term> {
    match t.functor() {
        Some((s, 1)) if s.name() == wrapper => t.args().first(),
        _ => None,
    }
}

fn name_of(t: &Term) -> Option<&'static str> {
    t.functor().map(|(s, _)| s.name())
}

/// Prints an argument as `write` does (no quotes); `_` for variables.
fn w(t: &Term) -> String {
    if t.is_var() {
        "_".into()
    } else {
        t.to_text(Style::WRITE)
    }
}

fn first_arg_is(t: &Term, sender: &str) -> bool {
    t.args().first().is_some_and(|a| w(a) == sender)
}

fn answer(t: &Term) -> Option<String> {
    if let Some(("ok", 1)) = name_of(t).map(|n| (n, t.args().len())) {
        return Some(format!("OK, room {}", w(&t.args()[0])));
    }
    if !t.args().is_empty() {
        return None;
    }
    let n = name_of(t)?;
    ANSWERS
        .iter()
        .find(|(k, _)| *k == n)
        .map(|(_, s)| s.to_string())
}

fn imperative(p: &Term, mine: bool) -> Option<String> {
    let a = p.args();
    let s = match (name_of(p)?, a.len(), mine) {
        ("in", 2, true) => format!("I am going to {}", w(&a[1])),
        ("found", 2, true) => format!("I am looking for a {} block", w(&a[1])),
        ("pickedUpFrom", 3, true) => {
            format!("I am getting a {} block from room {}", w(&a[1]), w(&a[2]))
        }
        ("holding", 2, true) => format!("I will get a {} block", w(&a[1])),
        ("putDown", 1, true) => "I am going to put down a block".into(),
        ("in", 2, false) => format!("{} go to {}", w(&a[0]), w(&a[1])),
        ("found", 2, false) => format!("{} find a {} block", w(&a[0]), w(&a[1])),
        ("pickedUpFrom", 3, false) => format!(
            "{} get the {} block from room {}",
            w(&a[0]),
            w(&a[1]),
            w(&a[2])
        ),
        ("putDown", 1, false) => format!("{} put down the block you're holding", w(&a[0])),
        _ => return None,
    };
    Some(s)
}

fn declarative(p: &Term, sender: &str) -> Option<String> {
    let a = p.args();
    let me = |t: &Term| w(t) == sender;
    let s = match (name_of(p)?, a.len()) {
        ("at", 2) => format!("room {} contains a {} block", w(&a[1]), w(&a[0])),
        ("at", 3) => format!(
            "room {} contains {} {} blocks",
            w(&a[2]),
            w(&a[0]),
            w(&a[1])
        ),
        ("empty", 1) => format!("room {} is empty", w(&a[0])),
        ("in", 2) if me(&a[0]) => format!("I am in room {}", w(&a[1])),
        ("in", 2) => format!("{} is in room {}", w(&a[0]), w(&a[1])),
        ("at", 1) => format!("I am at a {} box", w(&a[0])),
        ("holding", 2) if me(&a[0]) => format!("I have a {} block", w(&a[1])),
        ("pickedUpFrom", 3) if me(&a[0]) => {
            format!("I have a {} block from room {}", w(&a[1]), w(&a[2]))
        }
        ("putDown", 1) if me(&a[0]) => "I just dropped off a block".into(),
        ("putDown", 2) if me(&a[0]) => format!("I just dropped off a {} block", w(&a[1])),
        ("waitingOutside", 2) if me(&a[0]) => {
            format!("I am waiting outside room {}", w(&a[1]))
        }
        ("need", 1) => format!("We need a {} block", w(&a[0])),
        ("checked", 1) => format!("room {} has been checked", w(&a[0])),
        ("checked", 2) => format!("room {} has been checked by {}", w(&a[1]), w(&a[0])),
        _ => return None,
    };
    Some(s)
}

fn question(q: &Term, sender: &str) -> Option<String> {
    let a = q.args();
    if let Some(inner) = unwrap(q, "imp") {
        let b = inner.args();
        return match (name_of(inner)?, b.len()) {
            ("in", 2) if w(&b[0]) == sender && b[1].is_var() => Some("Where should I go?".into()),
            ("holding", 2) if w(&b[0]) == sender && b[1].is_var() => {
                Some("What color should I get?".into())
            }
            ("in", 2) if b[0].is_var() => Some(format!("Is anybody going to room {}?", w(&b[1]))),
            _ => None,
        };
    }
    let s = match (name_of(q)?, a.len()) {
        ("at", 2) if a[0].is_var() && !a[1].is_var() => {
            format!("What is in room {}?", w(&a[1]))
        }
        ("at", 2) if a[1].is_var() && !a[0].is_var() => {
            format!("Where is a {} block?", w(&a[0]))
        }
        ("in", 2) if a[0].is_var() => format!("Who is in room {}?", w(&a[1])),
        ("willBeLong", 1) => format!("{}, will you be long?", w(&a[0])),
        ("checked", 2) if a[0].is_var() => format!("Has anybody checked room {}?", w(&a[1])),
        ("areClose", 1) => format!("{}, are you close?", w(&a[0])),
        ("holding", 2) if a[0].is_var() => format!("Who has a {} block?", w(&a[1])),
        _ => return None,
    };
    Some(s)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn t(name: &str, args: Vec<Term>) -> Term {
        Term::compound(name, args)
    }

    #[test]
    fn offer_request_inform_query_acknowledge() {
        let me = Term::atom("Bot1");
        let offer = t("imp", vec![t("in", vec![me.clone(), Term::atom("RoomA1")])]);
        let r = read("Bot1", &offer);
        assert_eq!(r.act, SpeechAct::Offer);
        assert_eq!(r.english.as_deref(), Some("I am going to RoomA1"));
        let r = read("Bot2", &offer);
        assert_eq!(r.act, SpeechAct::Request);
        assert_eq!(r.english.as_deref(), Some("Bot1 go to RoomA1"));
        let inform = t("at", vec![Term::atom("Red"), Term::atom("RoomB2")]);
        let r = read("Bot1", &inform);
        assert_eq!(r.act, SpeechAct::Inform);
        assert_eq!(
            r.english.as_deref(),
            Some("room RoomB2 contains a Red block")
        );
        let q = t(
            "int",
            vec![t("at", vec![Term::var("_"), Term::atom("RoomC1")])],
        );
        let r = read("Bot1", &q);
        assert_eq!(r.act, SpeechAct::Query);
        assert_eq!(r.english.as_deref(), Some("What is in room RoomC1?"));
        let r = read("Bot1", &Term::atom("dontknow"));
        assert_eq!(r.act, SpeechAct::Acknowledge);
        assert_eq!(r.english.as_deref(), Some("I don't know"));
        let r = read("Bot1", &t("foo", vec![Term::Int(1)]));
        assert_eq!(r.act, SpeechAct::Inform);
        assert_eq!(r.english, None);
        assert_eq!(r.logical_form, "foo(1)");
    }
}
