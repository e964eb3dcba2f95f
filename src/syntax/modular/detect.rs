//! Telling the generations apart (docs/modular-goal.md): a `.mas2g` file's first item
//! decides; a `.mod2g` checked on its own is (B) when it uses a `.pl` file without `as`.

use super::ast::Generation;
use super::mas::MasTok;
use logos::Logos;
use std::path::Path;

/// The generation of a `.mas2g` text: `environment {`/`agentfiles {`/`do launch` are 2014,
/// `use`/`define` first are modular ((A) or (B) is decided by the modular parser).
pub fn mas_generation(text: &str) -> Generation {
    let mut lx = MasTok::lexer(text);
    let first = loop {
        match lx.next() {
            Some(Ok(t)) => break Some((t, lx.slice())),
            Some(Err(())) => continue,
            None => break None,
        }
    };
    match first {
        Some((MasTok::Use | MasTok::Define, _)) => Generation::Modular,
        Some((MasTok::LaunchPolicy, _)) => {
            // Only a launch policy: 2014 rules read `when [...]@env do launch`.
            let classic = MasTok::lexer(text)
                .spanned()
                .any(|(t, s)| t.is_err() || (t == Ok(MasTok::Ident) && &text[s] == "do"));
            if classic {
                Generation::Classic
            } else {
                Generation::Modular
            }
        }
        _ => Generation::Classic,
    }
}

/// The generation of a `.mod2g` file checked on its own: 2014 when it has 2014 module heads or
/// sections; (B) when a bare `use X.` names only a `.pl` file next to it; else (A).
pub fn module_generation(text: &str, dir: &Path) -> Generation {
    let toks = crate::syntax::lexer::tokens(text, "").0;
    use crate::syntax::lexer::Tok;
    let classic = toks.windows(2).any(|w| {
        matches!(
            (w[0].1, w[1].1),
            (Tok::Program | Tok::Import, _)
                | (Tok::Knowledge | Tok::Beliefs | Tok::Goals, Tok::KrBraces)
                | (Tok::Init | Tok::Main | Tok::Event, Tok::Module)
        )
    });
    if classic {
        return Generation::Classic;
    }
    let mut words = text.split(|c: char| c.is_whitespace());
    while let Some(w) = words.next() {
        if w == "use" {
            if let Some(r) = words.next() {
                if let Some(name) = r.strip_suffix('.') {
                    let name = name.trim_matches('"');
                    let pl = dir.join(format!("{name}.pl"));
                    let other = ["mod2g", "act2g"]
                        .iter()
                        .any(|e| dir.join(format!("{name}.{e}")).is_file());
                    if pl.is_file() && !other {
                        return Generation::Marbel;
                    }
                }
            }
        }
    }
    Generation::Modular
}
