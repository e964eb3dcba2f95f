//! How the runtime reads a message for traces and `--verbose` output: its logical form, its
//! CLAMR speech-act type and, for BW4T's built-in vocabulary (`bw4t::messages`), its English
//! sentence.

use crate::bw4t::messages::describe_from;
pub use crate::bw4t::messages::SpeechAct;
use crate::term::Term;
use serde::Serialize;

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

/// Reads `content` (mood-wrapped: `p`, `imp(p)` or `int(p)`) sent by `sender`.
pub fn read(sender: &str, content: &Term) -> Reading {
    let logical_form = content.to_string();
    match describe_from(Some(sender), content) {
        Some((act, sentence)) => Reading {
            logical_form,
            act,
            english: Some(sentence),
        },
        None => Reading {
            logical_form,
            act: crate::clamr::classify(sender, content).sat,
            english: crate::clamr::content::english_message(content),
        },
    }
}

/// The communicative act of a message (speech act, action, parameters): BW4T's vocabulary
/// gives the speech act of its messages, CLAMR's reading the rest.
pub fn act(sender: &str, content: &Term) -> crate::clamr::Act {
    let mut act = crate::clamr::classify(sender, content);
    if let Some((sat, _)) = describe_from(Some(sender), content) {
        act.sat = sat;
    }
    act
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
