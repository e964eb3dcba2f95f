//! Binary frames (the seed's packet): 30 bytes, fixed. Byte 0 the sender's address, 1 the
//! receiver's, 2-3 the token type (`1 0` general, `0 1` session), 4 the CL byte (complex-act type
//! in the high nibble, constraint bits in the low), 5 the CA byte (3 bits speech-act type, 5 bits
//! action/performative), 6 the parameter bits, 7-29 data. Acts of the seed's vocabulary take one
//! frame; any other GOAL content travels as its text in extension frames (action code 31, data:
//! fragment index and count as big-endian u16, payload length, up to 18 payload bytes).

use super::act::{bits, classify, performative, performative_code, SpeechAct, EXTENSION_CODE};
use super::content;
use crate::term::{well_known as wk, Term};
use std::collections::BTreeMap;

/// The size of every frame.
pub const FRAME_LEN: usize = 30;
/// Bytes before the data.
pub const HEADER_LEN: usize = 7;
/// Payload bytes in one extension frame.
pub const EXT_PAYLOAD: usize = 18;
/// Most extension frames of one message.
pub const MAX_FRAGMENTS: usize = u16::MAX as usize;

/// The token a frame travels with.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Token {
    /// `1 0`: the general token, passed round the ring.
    General,
    /// `0 1`: a session token, kept for the conversation with one partner.
    Session,
}

/// One frame, decoded.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Frame {
    pub sender: u8,
    pub receiver: u8,
    pub token: Token,
    /// Complex-act type (high nibble) and constraint bits (low nibble).
    pub cl: u8,
    pub sat: SpeechAct,
    /// The 5-bit action/performative code (0: none, 31: extension).
    pub action: u8,
    pub param: u8,
    pub data: [u8; FRAME_LEN - HEADER_LEN],
}

/// Why bytes are not a frame, or frames not a message.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FrameError(pub String);

impl std::fmt::Display for FrameError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

fn err<T>(m: impl Into<String>) -> Result<T, FrameError> {
    Err(FrameError(m.into()))
}

impl Frame {
    /// The 30 bytes of the frame.
    pub fn encode(&self) -> [u8; FRAME_LEN] {
        let mut b = [0u8; FRAME_LEN];
        b[0] = self.sender;
        b[1] = self.receiver;
        (b[2], b[3]) = match self.token {
            Token::General => (1, 0),
            Token::Session => (0, 1),
        };
        b[4] = self.cl;
        b[5] = (self.sat.code() << 5) | (self.action & 0x1F);
        b[6] = self.param;
        b[HEADER_LEN..].copy_from_slice(&self.data);
        b
    }

    /// Reads a frame from `b` (exactly 30 bytes); never panics.
    pub fn decode(b: &[u8]) -> Result<Frame, FrameError> {
        if b.len() != FRAME_LEN {
            return err(format!("a frame has {FRAME_LEN} bytes, not {}", b.len()));
        }
        let token = match (b[2], b[3]) {
            (1, 0) => Token::General,
            (0, 1) => Token::Session,
            (x, y) => return err(format!("token bytes {x} {y} are neither 1 0 nor 0 1")),
        };
        let Some(sat) = SpeechAct::from_code(b[5] >> 5) else {
            return err(format!("speech-act code {} is not defined", b[5] >> 5));
        };
        let action = b[5] & 0x1F;
        if action != 0 && action != EXTENSION_CODE && performative_code(action).is_none() {
            return err(format!("action code {action} is not defined"));
        }
        let mut data = [0u8; FRAME_LEN - HEADER_LEN];
        data.copy_from_slice(&b[HEADER_LEN..]);
        Ok(Frame {
            sender: b[0],
            receiver: b[1],
            token,
            cl: b[4],
            sat,
            action,
            param: b[6],
            data,
        })
    }
}

/// Parameter bits of `sense` (the seed's Table 3: temperature first, the high bit).
const SENSE: &[(&str, u8)] = &[("temperature", 0x80), ("pressure", 0x40), ("light", 0x20)];

/// The (action code, parameter bits) of an action the seed's vocabulary can carry in one frame.
fn seed_action(t: &Term) -> Option<(u8, u8)> {
    match t.functor()? {
        (f, 1) if f.name() == "sense" => {
            let Term::Atom(what) = &t.args()[0] else {
                return None;
            };
            let bit = SENSE.iter().find(|(n, _)| *n == what.name())?.1;
            Some((performative("sense")?.code, bit))
        }
        (f, 0) if f.name() == "stop" => Some((performative("stop")?.code, 0)),
        _ => None,
    }
}

/// The action term of (action code, parameter bits), inverse of [`seed_action`].
fn seed_action_term(code: u8, param: u8) -> Option<Term> {
    let p = performative_code(code)?;
    match p.name {
        "sense" => {
            let what = SENSE.iter().find(|(_, b)| *b == param)?.0;
            Some(Term::compound("sense", vec![Term::atom(what)]))
        }
        "stop" if param == 0 => Some(Term::atom("stop")),
        _ => None,
    }
}

/// The seed frame of `content` (CL, SAT, action, param, data) when it has one.
fn seed_frame(content: &Term) -> Option<(SpeechAct, u8, u8, Vec<u8>)> {
    let a = content.args();
    let (f, n) = content.functor()?;
    let with = |sat, inner: &Term| seed_action(inner).map(|(c, p)| (sat, c, p, Vec::new()));
    match (f.name(), n) {
        _ if f == wk::IMP && n == 1 => with(SpeechAct::Request, &a[0]),
        _ if f == wk::INT && n == 1 => with(SpeechAct::Query, &a[0]),
        ("offer", 1) => with(SpeechAct::Offer, &a[0]),
        ("ack", 1) if a[0] == Term::atom("ok") => Some((SpeechAct::Acknowledge, 0, 0, Vec::new())),
        ("ack", 2) => {
            let ack = |name: &str, param, data| {
                Some((
                    SpeechAct::Acknowledge,
                    performative(name)?.code,
                    param,
                    data,
                ))
            };
            match &a[0] {
                Term::Atom(x) if x.name() == "accept" || x.name() == "refuse" => {
                    let (c, p) = seed_action(&a[1])?;
                    let bit = if x.name() == "accept" {
                        bits::ACCEPT
                    } else {
                        0
                    };
                    ack("accept", bit, vec![c, p])
                }
                Term::Atom(x) if matches!(x.name(), "done" | "failed" | "status") => {
                    let Term::Int(v) = &a[1] else { return None };
                    let v = i32::try_from(*v).ok()?;
                    let param = match x.name() {
                        "done" => bits::DONE,
                        "failed" => bits::FAILED,
                        _ => 0,
                    };
                    ack("report", param, v.to_be_bytes().to_vec())
                }
                _ => None,
            }
        }
        _ => None,
    }
}

/// The content of a seed frame, inverse of [`seed_frame`].
fn seed_content(f: &Frame) -> Option<Term> {
    let act_term = || seed_action_term(f.action, f.param);
    match f.sat {
        SpeechAct::Request => Some(Term::compound(wk::IMP, vec![act_term()?])),
        SpeechAct::Query => Some(Term::compound(wk::INT, vec![act_term()?])),
        SpeechAct::Offer => Some(Term::compound("offer", vec![act_term()?])),
        SpeechAct::Acknowledge => match performative_code(f.action).map(|p| p.name) {
            None if f.action == 0 => Some(Term::compound("ack", vec![Term::atom("ok")])),
            Some("accept") => {
                let what = if f.param & bits::ACCEPT != 0 {
                    "accept"
                } else {
                    "refuse"
                };
                let inner = seed_action_term(f.data[0], f.data[1])?;
                Some(Term::compound("ack", vec![Term::atom(what), inner]))
            }
            Some("report") => {
                let what = match f.param {
                    bits::DONE => "done",
                    bits::FAILED => "failed",
                    _ => "status",
                };
                let v = i32::from_be_bytes([f.data[0], f.data[1], f.data[2], f.data[3]]);
                Some(Term::compound(
                    "ack",
                    vec![Term::atom(what), Term::Int(v.into())],
                ))
            }
            _ => None,
        },
        _ => None,
    }
}

/// The frames of message `content` from address `from` to `to`, sent by agent `sender`.
pub fn encode_message(
    from: u8,
    to: u8,
    sender: &str,
    content: &Term,
) -> Result<Vec<[u8; FRAME_LEN]>, FrameError> {
    let act = classify(sender, content);
    let token = if act.sat == SpeechAct::Inform && !act.signal {
        Token::General
    } else {
        Token::Session
    };
    let frame = |sat, action, param, data: &[u8]| {
        let mut d = [0u8; FRAME_LEN - HEADER_LEN];
        d[..data.len()].copy_from_slice(data);
        Frame {
            sender: from,
            receiver: to,
            token,
            cl: 0,
            sat,
            action,
            param,
            data: d,
        }
    };
    if let Some((sat, action, param, data)) = seed_frame(content) {
        let f = frame(sat, action, param, &data);
        // Only when the frame reads back as the same content (the seed form is exact).
        if seed_content(&f).as_ref() == Some(content) {
            return Ok(vec![f.encode()]);
        }
    }
    let text = content.to_string();
    let chunks: Vec<&[u8]> = text.as_bytes().chunks(EXT_PAYLOAD).collect();
    if chunks.len() > MAX_FRAGMENTS {
        return err(format!(
            "the message takes {} bytes, more than {} extension frames can carry",
            text.len(),
            MAX_FRAGMENTS
        ));
    }
    let count = chunks.len() as u16;
    let cl = content::cl_byte(inner(content));
    Ok(chunks
        .iter()
        .enumerate()
        .map(|(i, c)| {
            let mut data = Vec::with_capacity(5 + c.len());
            data.extend_from_slice(&(i as u16).to_be_bytes());
            data.extend_from_slice(&count.to_be_bytes());
            data.push(c.len() as u8);
            data.extend_from_slice(c);
            let mut f = frame(act.sat, EXTENSION_CODE, 0, &data);
            f.cl = cl;
            f.encode()
        })
        .collect())
}

/// The act term under the mood wrapper or act form.
fn inner(content: &Term) -> &Term {
    match content.functor() {
        Some((f, 1)) if f == wk::IMP || f == wk::INT || f.name() == "offer" => &content.args()[0],
        Some((f, 2)) if f.name() == "requestWhen" => &content.args()[0],
        _ => content,
    }
}

/// Reassembles messages from frames, per (sender, receiver) address pair.
#[derive(Debug, Default)]
pub struct Assembler {
    partial: BTreeMap<(u8, u8), (u16, Vec<u8>)>,
}

impl Assembler {
    /// Takes one frame's bytes; returns the message content when the frame completes one.
    pub fn push(&mut self, bytes: &[u8]) -> Result<Option<Term>, FrameError> {
        let f = Frame::decode(bytes)?;
        if f.action != EXTENSION_CODE {
            return match seed_content(&f) {
                Some(t) => Ok(Some(t)),
                None => err(format!(
                    "a {:?} frame with action code {} and parameter bits {:#04x} has no meaning",
                    f.sat, f.action, f.param
                )),
            };
        }
        let index = u16::from_be_bytes([f.data[0], f.data[1]]);
        let count = u16::from_be_bytes([f.data[2], f.data[3]]);
        let len = f.data[4] as usize;
        if len > EXT_PAYLOAD || count == 0 || index >= count {
            return err(format!(
                "extension frame {index} of {count} with {len} payload bytes is malformed"
            ));
        }
        let key = (f.sender, f.receiver);
        let (next, mut buf) = self.partial.remove(&key).unwrap_or((0, Vec::new()));
        if index != next {
            return err(format!(
                "extension frame {index} arrived where {next} was due"
            ));
        }
        buf.extend_from_slice(&f.data[5..5 + len]);
        if index + 1 < count {
            self.partial.insert(key, (index + 1, buf));
            return Ok(None);
        }
        let text =
            String::from_utf8(buf).map_err(|_| FrameError("the text is not UTF-8".into()))?;
        match crate::syntax::prolog::Reader::new("frame").term(&text, 0) {
            Ok(t) => Ok(Some(t.term)),
            Err(d) => err(format!("the text {text:?} is not a term: {}", d.message)),
        }
    }
}

/// Frames a message and reads it back (what a transport leaving the process does).
pub fn round_trip(from: u8, to: u8, sender: &str, content: &Term) -> Result<Term, FrameError> {
    let mut a = Assembler::default();
    let mut out = None;
    for f in encode_message(from, to, sender, content)? {
        out = a.push(&f)?;
    }
    out.ok_or_else(|| FrameError("the frames ended before the message".into()))
}
