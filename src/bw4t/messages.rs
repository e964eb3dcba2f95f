//! The BW4T message vocabulary as data: each message's logical form, its CLAMR
//! speech-act type and its English sentence, with [`describe`] to put a message into words.
//!
//! Patterns use slots: `Me` (the sender, or the atom `me`), `Player`, `Place`, `Room` (atoms),
//! `Color` (a colour name), `Block` and `N` (integers); `_` stands for an unbound variable in
//! the message (the thing asked about). Imperatives about the sender are offers, about others
//! requests (CLAMR's Offer/Request); declaratives inform, `int(...)` queries, answers acknowledge.

use super::color::Color;
use crate::term::{Style, Term};
use serde::Serialize;

/// CLAMR speech-act types (defined with the communicative acts).
pub use crate::clamr::act::SpeechAct;

/// One message of the vocabulary.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct Message {
    /// The logical form with slots, e.g. `imp(in(Me,Place))`.
    pub pattern: &'static str,
    pub act: SpeechAct,
    /// The English sentence with `{Slot}` placeholders.
    pub sentence: &'static str,
}

const fn m(pattern: &'static str, act: SpeechAct, sentence: &'static str) -> Message {
    Message {
        pattern,
        act,
        sentence,
    }
}

use SpeechAct::*;

/// The message list, in the order patterns are tried.
pub const MESSAGES: &[Message] = &[
    m("imp(in(Me,Place))", Offer, "I am going to {Place}"),
    m(
        "imp(found(Me,Color))",
        Offer,
        "I am looking for a {Color} block",
    ),
    m(
        "imp(pickedUpFrom(Me,Color,Room))",
        Offer,
        "I am getting a {Color} block from room {Room}",
    ),
    m(
        "imp(holding(Me,Color))",
        Offer,
        "I will get a {Color} block",
    ),
    m("imp(putDown(Me))", Offer, "I am going to put down a block"),
    m("imp(in(Player,Room))", Request, "{Player} go to {Room}"),
    m(
        "imp(found(Player,Color))",
        Request,
        "{Player} find a {Color} block",
    ),
    m(
        "imp(pickedUpFrom(Player,Color,Room))",
        Request,
        "{Player} get the {Color} block from room {Room}",
    ),
    m(
        "imp(putDown(Player))",
        Request,
        "{Player} put down the block you're holding",
    ),
    m(
        "at(Color,Room)",
        Inform,
        "room {Room} contains a {Color} block",
    ),
    m(
        "at(N,Color,Room)",
        Inform,
        "room {Room} contains {N} {Color} blocks",
    ),
    m("empty(Room)", Inform, "room {Room} is empty"),
    m("in(Me,Room)", Inform, "I am in room {Room}"),
    m("at(Block)", Inform, "I am at a {Block} box"),
    m("holding(Me,Color)", Inform, "I have a {Color} block"),
    m(
        "pickedUpFrom(Me,Color,Room)",
        Inform,
        "I have a {Color} block from room {Room}",
    ),
    m("putDown(Me)", Inform, "I just dropped off a block"),
    m(
        "putDown(Me,Color)",
        Inform,
        "I just dropped off a {Color} block",
    ),
    m(
        "waitingOutside(Me,Room)",
        Inform,
        "I am waiting outside room {Room}",
    ),
    m("need(Color)", Inform, "We need a {Color} block"),
    m("checked(Room)", Inform, "room {Room} has been checked"),
    m(
        "checked(Player,Room)",
        Inform,
        "room {Room} has been checked by {Player}",
    ),
    m("int(at(_,Room))", Query, "What is in room {Room}?"),
    m("int(at(Color,_))", Query, "Where is a {Color} block?"),
    m("int(in(_,Room))", Query, "Who is in room {Room}?"),
    m("int(imp(in(Me,_)))", Query, "Where should I go?"),
    m("int(imp(holding(Me,_)))", Query, "What color should I get?"),
    m(
        "int(imp(in(_,Room)))",
        Query,
        "Is anybody going to room {Room}?",
    ),
    m(
        "int(willBeLong(Player))",
        Query,
        "{Player}, will you be long?",
    ),
    m(
        "int(checked(_,Room))",
        Query,
        "Has anybody checked room {Room}?",
    ),
    m("int(areClose(Player))", Query, "{Player}, are you close?"),
    m("int(holding(_,Color))", Query, "Who has a {Color} block?"),
    m("yes", Acknowledge, "yes"),
    m("no", Acknowledge, "no"),
    m("dontknow", Acknowledge, "I don't know"),
    m("wait", Acknowledge, "wait"),
    m("ok", Acknowledge, "OK"),
    m("idont", Acknowledge, "I don't"),
    m("ido", Acknowledge, "I do"),
    m("ontheway", Acknowledge, "I am on the way"),
    m("faraway", Acknowledge, "I am far away"),
    m("delayed", Acknowledge, "I am delayed"),
    m("almostthere", Acknowledge, "I am almost there"),
    m("couldnot", Acknowledge, "I could not"),
    m("ok(Room)", Acknowledge, "OK, room {Room}"),
];

/// A parsed pattern: a functor with sub-patterns, a slot, or `_`.
enum Pat<'a> {
    Functor(&'a str, Vec<Pat<'a>>),
    Slot(&'a str),
    Unbound,
}

/// Parses the restricted pattern syntax above (identifiers, parentheses, commas).
fn parse(text: &str) -> Option<Pat<'_>> {
    fn go<'a>(s: &'a str, i: &mut usize) -> Option<Pat<'a>> {
        let start = *i;
        let b = s.as_bytes();
        while *i < b.len() && (b[*i].is_ascii_alphanumeric() || b[*i] == b'_') {
            *i += 1;
        }
        let name = &s[start..*i];
        if name.is_empty() {
            return None;
        }
        if *i < b.len() && b[*i] == b'(' {
            *i += 1;
            let mut args = vec![go(s, i)?];
            while *i < b.len() && b[*i] == b',' {
                *i += 1;
                args.push(go(s, i)?);
            }
            if *i >= b.len() || b[*i] != b')' {
                return None;
            }
            *i += 1;
            return Some(Pat::Functor(name, args));
        }
        Some(match name {
            "_" => Pat::Unbound,
            n if n.starts_with(|c: char| c.is_ascii_uppercase()) => Pat::Slot(n),
            n => Pat::Functor(n, Vec::new()),
        })
    }
    let mut i = 0;
    let p = go(text, &mut i)?;
    (i == text.len()).then_some(p)
}

fn matches<'a>(p: &Pat<'a>, t: &Term, me: Option<&str>, out: &mut Vec<(&'a str, String)>) -> bool {
    match p {
        Pat::Unbound => t.is_var(),
        Pat::Functor(name, args) => {
            t.functor()
                .is_some_and(|(f, a)| f.name() == *name && a == args.len())
                && args
                    .iter()
                    .zip(t.args())
                    .all(|(pa, ta)| matches(pa, ta, me, out))
        }
        Pat::Slot(slot) => {
            let text = t.to_text(Style::WRITE);
            let ok = match *slot {
                "Me" => matches!(t, Term::Atom(s) if s.name() == "me" || Some(s.name()) == me),
                "Player" => {
                    matches!(t, Term::Atom(s) if s.name() != "me" && Some(s.name()) != me)
                }
                "Place" | "Room" => matches!(t, Term::Atom(_)),
                "Color" => matches!(t, Term::Atom(s) if Color::parse(s.name()).is_some()),
                "Block" | "N" => matches!(t, Term::Int(_)),
                _ => false,
            };
            if ok {
                out.push((slot, text));
            }
            ok
        }
    }
}

/// The vocabulary entry matching `content` as sent by `sender` (whose name counts as `Me`),
/// with the values of its slots.
pub fn lookup(
    sender: Option<&str>,
    content: &Term,
) -> Option<(&'static Message, Vec<(&'static str, String)>)> {
    MESSAGES.iter().find_map(|msg| {
        let pat = parse(msg.pattern)?;
        let mut slots = Vec::new();
        matches(&pat, content, sender, &mut slots).then_some((msg, slots))
    })
}

/// The speech act and English sentence of a message sent by `sender`.
pub fn describe_from(sender: Option<&str>, content: &Term) -> Option<(SpeechAct, String)> {
    let (msg, slots) = lookup(sender, content)?;
    let mut text = msg.sentence.to_string();
    for (slot, value) in slots {
        text = text.replace(&format!("{{{slot}}}"), &value);
    }
    Some((msg.act, text))
}

/// The speech act and English sentence of a message (`me` stands for the sender).
pub fn describe(content: &Term) -> Option<(SpeechAct, String)> {
    describe_from(None, content)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn a(s: &str) -> Term {
        Term::atom(s)
    }

    fn c(f: &str, args: Vec<Term>) -> Term {
        Term::compound(f, args)
    }

    #[test]
    fn every_pattern_parses() {
        for msg in MESSAGES {
            assert!(parse(msg.pattern).is_some(), "{}", msg.pattern);
        }
    }

    #[test]
    fn messages_are_described_with_their_arguments() {
        let going = c("imp", vec![c("in", vec![a("Bot1"), a("RoomA1")])]);
        assert_eq!(
            describe_from(Some("Bot1"), &going),
            Some((SpeechAct::Offer, "I am going to RoomA1".into()))
        );
        assert_eq!(
            describe_from(Some("Bot2"), &going),
            Some((SpeechAct::Request, "Bot1 go to RoomA1".into()))
        );
        let at = c("at", vec![a("Red"), a("RoomB2")]);
        assert_eq!(
            describe(&at),
            Some((SpeechAct::Inform, "room RoomB2 contains a Red block".into()))
        );
        let what = c("int", vec![c("at", vec![Term::var("_G1"), a("RoomC1")])]);
        assert_eq!(
            describe(&what),
            Some((SpeechAct::Query, "What is in room RoomC1?".into()))
        );
        let where_ = c("int", vec![c("at", vec![a("Blue"), Term::var("_G2")])]);
        assert_eq!(describe(&where_).unwrap().1, "Where is a Blue block?");
        assert_eq!(
            describe(&a("dontknow")),
            Some((SpeechAct::Acknowledge, "I don't know".into()))
        );
        let n = c("at", vec![Term::Int(2), a("Red"), a("RoomA1")]);
        assert_eq!(describe(&n).unwrap().1, "room RoomA1 contains 2 Red blocks");
        assert_eq!(describe(&c("at", vec![a("Purple"), a("RoomA1")])), None);
        assert_eq!(describe(&a("hello")), None);
    }
}
