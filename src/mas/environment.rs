//! Choosing the built-in environment named in a `.mas2g` file.
//!
//! Real GOAL files name the Java jar of their environment: `"bw4t-client-3.8.0.jar"`,
//! `"environments\BW4T2\BW4TClient.jar"`, `"../blocksworld-1.1.0-blocksworld.jar"`. Any
//! reference whose file name contains `bw4t` (any case, `/` or `\` separators) selects the
//! built-in BW4T, any containing `blocksworld` the built-in blocks world; `"bw4t"` and
//! `"blocksworld"` name them directly. [`select_environment`] is the one place that decides.

use super::observer::Observer;
use super::options::RunOptions;
use super::system::Problem;
use crate::agent::{PerceptType, PerceptTypes};
use crate::blocksworld::BlocksWorld;
use crate::bw4t::Bw4t;
use crate::diag::Diagnostic;
use crate::env::thread::EnvInfo;
use crate::env::{Environment, InitParams};
use crate::term::{Style, Term};

/// A built-in environment.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Builtin {
    /// Blocks World for Teams (`bw4t`).
    Bw4t,
    /// GOAL's blocks world with one gripper (`blocksworld`).
    BlocksWorld,
}

/// A created environment with its set-up warnings.
pub type Created = (Box<dyn Environment>, Vec<String>);

/// Every built-in environment, in the order they are listed to users.
pub const BUILTINS: &[Builtin] = &[Builtin::Bw4t, Builtin::BlocksWorld];

impl Builtin {
    /// The short name (`env = "bw4t"`).
    pub fn name(self) -> &'static str {
        match self {
            Builtin::Bw4t => "bw4t",
            Builtin::BlocksWorld => crate::blocksworld::NAME,
        }
    }

    /// The init parameter keys it reads after translation.
    pub fn param_names(self) -> &'static [&'static str] {
        match self {
            Builtin::Bw4t => crate::bw4t::INIT_PARAMS,
            Builtin::BlocksWorld => crate::blocksworld::init::PARAMS,
        }
    }

    /// The actions its entities understand, as `name/arity`.
    pub fn actions(self) -> &'static [&'static str] {
        match self {
            Builtin::Bw4t => crate::bw4t::actions::ACTIONS,
            Builtin::BlocksWorld => crate::blocksworld::ACTIONS,
        }
    }

    /// The percepts its entities can receive, as `(name, arity)`.
    pub fn percepts(self) -> Vec<(String, usize)> {
        match self {
            Builtin::Bw4t => crate::bw4t::percepts::all_declarations()
                .into_iter()
                .map(|d| (d.name, d.arity))
                .chain([("navpoint".to_string(), 5)])
                .collect(),
            Builtin::BlocksWorld => crate::blocksworld::PERCEPTS
                .iter()
                .filter_map(|p| p.split_once('/'))
                .map(|(n, a)| (n.to_string(), a.parse().unwrap_or(0)))
                .collect(),
        }
    }

    /// Creates the environment from (translated) parameters, with its set-up warnings; the
    /// problems of a map file come with its text, so that they show the map line.
    pub fn create(self, params: &InitParams) -> Result<Created, Vec<Problem>> {
        let made: Result<Created, Vec<Diagnostic>> = match self {
            Builtin::Bw4t => Bw4t::from_params(params).map(|world| {
                let warnings = world.warnings().to_vec();
                (Box::new(world) as Box<dyn Environment>, warnings)
            }),
            Builtin::BlocksWorld => BlocksWorld::from_params(params)
                .map(|w| (Box::new(w) as Box<dyn Environment>, Vec::new())),
        };
        made.map_err(|ds| ds.into_iter().map(with_source).collect())
    }
}

/// A diagnostic with the text of the map file it points into (built-in maps included).
fn with_source(d: Diagnostic) -> Problem {
    let builtin = d
        .file
        .strip_prefix("maps/")
        .and_then(|f| f.strip_suffix(".toml"))
        .and_then(crate::bw4t::map::builtin_source);
    let text = match builtin {
        Some(t) => Some(t.to_string()),
        None if d.file != "init" => std::fs::read_to_string(&d.file).ok(),
        None => None,
    };
    match text {
        Some(t) => Problem {
            diagnostic: d,
            source: t.into(),
        },
        None => Problem::bare(d),
    }
}

/// The environment a `.mas2g` file runs in.
#[derive(Clone, Debug, PartialEq)]
pub struct EnvSetup {
    pub kind: Builtin,
    /// The reference as written in the file.
    pub reference: String,
    /// The BW4T client version read from the jar name (`3.8.0`, `2`), if any.
    pub client_version: Option<String>,
    /// The init parameters in the built-in environment's terms.
    pub params: InitParams,
    /// Things the user should know about the parameters, as `(key, text)`.
    pub warnings: Vec<(String, String)>,
}

impl EnvSetup {
    /// One line saying which built-in environment runs in place of the reference.
    pub fn describe(&self) -> String {
        let mut s = format!("environment: built-in {}", self.kind.name());
        if self.reference != self.kind.name() {
            s.push_str(&format!(" for `{}`", self.reference));
        }
        if let Some(v) = &self.client_version {
            s.push_str(&format!(" (BW4T client version {v})"));
        }
        s
    }
}

/// The file name of a reference: the part after the last `/` or `\`.
fn file_name(reference: &str) -> &str {
    reference.rsplit(['/', '\\']).next().unwrap_or(reference)
}

/// The BW4T client version in a reference: `bw4t-client-3.8.0.jar` gives `3.8.0`, a directory
/// `BW4T2` gives `2`; `None` when the name carries no version.
pub fn client_version(reference: &str) -> Option<String> {
    let name = file_name(reference);
    let digits = |s: &str| -> Option<String> {
        let v: String = s
            .chars()
            .skip_while(|c| !c.is_ascii_digit())
            .take_while(|c| c.is_ascii_digit() || *c == '.')
            .collect();
        let v = v.trim_end_matches('.').to_string();
        (!v.is_empty()).then_some(v)
    };
    let lower = name.to_ascii_lowercase();
    if let Some(at) = lower.find("bw4t") {
        if let Some(v) = digits(&lower[at + 4..].replace(".jar", "")) {
            return Some(v);
        }
    }
    // `environments\BW4T2\BW4TClient.jar`: the version is in the directory name.
    reference.rsplit(['/', '\\']).skip(1).find_map(|dir| {
        let d = dir.to_ascii_lowercase();
        d.strip_prefix("bw4t").and_then(digits)
    })
}

/// The built-in environment for `reference` (as written after `env =`) and its init
/// parameters, or an error naming the built-in environments.
pub fn select_environment(reference: &str, params: &InitParams) -> Result<EnvSetup, String> {
    let name = file_name(reference).to_ascii_lowercase();
    let kind = if name.contains("bw4t") {
        Builtin::Bw4t
    } else if name.contains("blocksworld") {
        Builtin::BlocksWorld
    } else {
        let names: Vec<&str> = BUILTINS.iter().map(|b| b.name()).collect();
        return Err(format!(
            "environment `{reference}` is not built in; the built-in environments are {} \
             (a jar whose name contains `bw4t` or `blocksworld` selects them)",
            names.join(" and ")
        ));
    };
    let is_jar = reference != kind.name();
    let (params, warnings, version) = match kind {
        Builtin::Bw4t => {
            let t = crate::bw4t::client::translate(params, is_jar);
            let version = client_version(reference).filter(|_| is_jar);
            let mut params = t.params;
            // Programs for the BW4T 2 client (or a client of unknown version) read `navpoint/5`.
            if is_jar && version.as_deref().is_none_or(|v| v.starts_with('2')) {
                params
                    .entry("navpoints".into())
                    .or_insert(crate::term::Term::atom("true"));
            }
            (params, t.warnings, version)
        }
        Builtin::BlocksWorld => (params.clone(), Vec::new(), None),
    };
    Ok(EnvSetup {
        kind,
        reference: reference.to_string(),
        client_version: version,
        params,
        warnings,
    })
}

/// The percept types the environment declares, in the agents' form.
pub fn percept_types(info: &EnvInfo) -> PerceptTypes {
    use crate::env::PerceptType as E;
    PerceptTypes::new(info.declarations.iter().map(|d| {
        let k = match d.kind {
            E::Once => PerceptType::Once,
            E::OnChange => PerceptType::OnChange,
            E::OnChangeWithNegation => PerceptType::OnChangeNeg,
            E::Always => PerceptType::Always,
        };
        ((d.name.clone(), d.arity), k)
    }))
}

fn text_of(t: &Term) -> String {
    t.to_text(Style::WRITE)
}

/// The environment's parameters with the run options applied; unknown keys are dropped with
/// a warning (the BW4T of the Java distribution ignores them too).
pub fn env_params(
    setup: &EnvSetup,
    opts: &RunOptions,
    obs: &mut dyn Observer,
) -> (InitParams, u64, String) {
    let mut p = InitParams::new();
    let kind = setup.kind;
    for (k, v) in &setup.params {
        if kind.param_names().contains(&k.as_str()) {
            p.insert(k.clone(), v.clone());
        } else {
            obs.warning(&format!(
                "init parameter `{k}` is not used by {}; ignored",
                kind.name()
            ));
        }
    }
    if kind != Builtin::Bw4t {
        if opts.map.is_some() || opts.robots.is_some() || opts.humans.is_some() {
            obs.warning(&format!(
                "--map, --robots and --humans are for bw4t, not {}; ignored",
                kind.name()
            ));
        }
        let seed = opts.seed.unwrap_or(0);
        return (p, seed, String::new());
    }
    if let Some(s) = opts.seed {
        p.insert("seed".into(), Term::Int(s as i64));
    }
    let seed = match p.get("seed") {
        Some(Term::Int(i)) => *i as u64,
        _ => 0,
    };
    p.insert("seed".into(), Term::Int(seed as i64));
    if let Some(m) = &opts.map {
        p.insert("map".into(), Term::string(m));
    }
    if let Some(r) = opts.robots {
        p.insert("robots".into(), Term::Int(r as i64));
    }
    if let Some(h) = opts.humans {
        p.insert("humans".into(), Term::Int(h as i64));
    }
    let map = p
        .get("map")
        .map(text_of)
        .unwrap_or_else(|| crate::bw4t::map::DEFAULT_MAP.to_string());
    (p, seed, map)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn jar_names_select_built_ins() {
        let p = InitParams::new();
        for (r, k) in [
            ("bw4t-client-3.8.0.jar", Builtin::Bw4t),
            ("BW4TClient.jar", Builtin::Bw4t),
            ("environments\\BW4T2\\BW4TClient.jar", Builtin::Bw4t),
            ("../blocksworld-1.1.0-blocksworld.jar", Builtin::BlocksWorld),
            ("bw4t", Builtin::Bw4t),
        ] {
            assert_eq!(select_environment(r, &p).unwrap().kind, k, "{r}");
        }
        let e = select_environment("tictactoe.jar", &p).unwrap_err();
        assert!(e.contains("bw4t and blocksworld"), "{e}");
    }

    #[test]
    fn client_versions_from_names() {
        assert_eq!(
            client_version("bw4t-client-3.8.0.jar").as_deref(),
            Some("3.8.0")
        );
        assert_eq!(
            client_version("environments\\BW4T2\\BW4TClient.jar").as_deref(),
            Some("2")
        );
        assert_eq!(client_version("BW4TClient.jar"), None);
    }
}
