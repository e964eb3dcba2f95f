//! The init parameters of the Java BW4T client (`bw4t-client-3.8.0.jar`, `BW4TClient.jar`),
//! translated to the built-in environment's: `agentcount` becomes `robots`, BW4T server map
//! names (`Random`, `SuperRandom`, any case) become built-in map names, values written as
//! strings (`"3"`, `"true"`) become numbers and booleans, and the connection and GUI settings,
//! which have no meaning for a built-in world, are dropped.

use crate::env::InitParams;
use crate::term::Term;

/// Client keys that are accepted and have no effect here (the world is built in, headless and
/// runs in lock-step, so addresses, GUIs and the simulation rate mean nothing).
pub const IGNORED: &[&str] = &[
    "clientip",
    "clientport",
    "serverip",
    "serverport",
    "launchgui",
    "goal",
    "goalhuman",
    "kill",
    "log",
    "speed",
];

/// The translated parameters and one line per thing the user should know.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Translated {
    pub params: InitParams,
    /// Warnings as `(key, text)`.
    pub warnings: Vec<(String, String)>,
}

/// A string value as the number or boolean it spells, else unchanged.
fn plain_value(v: &Term) -> Term {
    let text = match v {
        Term::Str(s) => s.to_string(),
        _ => return v.clone(),
    };
    let t = text.trim();
    if let Ok(i) = t.parse::<i64>() {
        return Term::Int(i);
    }
    match t {
        "true" | "false" => Term::atom(t),
        _ => v.clone(),
    }
}

/// The canonical spelling of `key` among the built-in's parameters (keys may be in any case).
fn canonical(key: &str) -> Option<&'static str> {
    super::INIT_PARAMS
        .iter()
        .find(|k| k.eq_ignore_ascii_case(key))
        .copied()
}

/// `Random`, `SuperRandom`, `super_random`, `DUTCH-FLAG`, ... as a built-in map name, when
/// one matches ignoring case and separators.
pub fn builtin_map_name(name: &str) -> Option<&'static str> {
    let squash = |s: &str| -> String {
        s.chars()
            .filter(|c| c.is_ascii_alphanumeric())
            .map(|c| c.to_ascii_lowercase())
            .collect()
    };
    let wanted = squash(name.strip_suffix(".xml").unwrap_or(name));
    super::map::builtin_names()
        .into_iter()
        .find(|n| squash(n) == wanted)
}

/// Translates the parameters of a BW4T client (`from_client` true) or of `env = "bw4t"`.
pub fn translate(params: &InitParams, from_client: bool) -> Translated {
    let mut out = Translated::default();
    for (key, value) in params {
        let lower = key.to_ascii_lowercase();
        let value = plain_value(value);
        if from_client && IGNORED.contains(&lower.as_str()) {
            continue;
        }
        match lower.as_str() {
            "agentcount" => {
                out.params.insert("robots".into(), value);
            }
            "humancount" => {
                out.params.insert("humans".into(), value);
            }
            "agentclass" => out.warnings.push((
                key.clone(),
                format!(
                    "`{key}` names a Java agent class; ignored (agents are GOAL programs here)"
                ),
            )),
            "configfile" => out.warnings.push((
                key.clone(),
                format!(
                    "`{key}`: BW4T client configuration files are not supported; \
                     every robot gets the default settings"
                ),
            )),
            "map" => {
                let text = match &value {
                    Term::Atom(a) => Some(a.name().to_string()),
                    Term::Str(s) => Some(s.to_string()),
                    _ => None,
                };
                let v = match text.as_deref().and_then(builtin_map_name) {
                    Some(n) => Term::atom(n),
                    None => match text {
                        Some(t) => Term::string(&t.replace('\\', "/")),
                        None => value,
                    },
                };
                out.params.insert("map".into(), v);
            }
            _ => {
                let k = canonical(key).map_or_else(|| key.clone(), str::to_string);
                out.params.insert(k, value);
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(pairs: &[(&str, Term)]) -> InitParams {
        pairs
            .iter()
            .map(|(k, v)| (k.to_string(), v.clone()))
            .collect()
    }

    #[test]
    fn client_parameters_become_built_in_ones() {
        let t = translate(
            &p(&[
                ("agentcount", Term::string("3")),
                ("map", Term::string("SuperRandom")),
                ("clientip", Term::string("localhost")),
                ("LAUNCHGUI", Term::string("false")),
                ("humancount", Term::string("0")),
            ]),
            true,
        );
        assert_eq!(t.params.get("robots"), Some(&Term::Int(3)));
        assert_eq!(t.params.get("map"), Some(&Term::atom("super-random")));
        assert_eq!(t.params.get("humans"), Some(&Term::Int(0)));
        assert_eq!(t.params.len(), 3);
        assert!(t.warnings.is_empty());
    }

    #[test]
    fn humancount_asks_for_human_controlled_robots() {
        let t = translate(&p(&[("humancount", Term::string("2"))]), true);
        assert!(t.warnings.is_empty());
        assert_eq!(t.params.get("humans"), Some(&Term::Int(2)));
    }

    #[test]
    fn map_names_in_any_case() {
        assert_eq!(builtin_map_name("Banana"), Some("banana"));
        assert_eq!(builtin_map_name("DUTCH_FLAG"), Some("dutch-flag"));
        assert_eq!(builtin_map_name("Cooperation"), None);
    }
}
