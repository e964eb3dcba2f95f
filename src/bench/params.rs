//! Benchmark parameters given as `--param key=value`.

use std::collections::BTreeMap;
use std::collections::BTreeSet;
use std::sync::Mutex;

/// `key=value` parameters; every key must be read by the benchmark (see [`Params::unused`]).
#[derive(Debug, Default)]
pub struct Params {
    values: BTreeMap<String, String>,
    read: Mutex<BTreeSet<String>>,
}

impl Params {
    /// Parses `key=value` items.
    pub fn parse<S: AsRef<str>>(items: &[S]) -> Result<Params, String> {
        let mut values = BTreeMap::new();
        for it in items {
            let it = it.as_ref();
            let (k, v) = it
                .split_once('=')
                .ok_or_else(|| format!("parameter `{it}`: expected key=value"))?;
            values.insert(k.trim().to_string(), v.trim().to_string());
        }
        Ok(Params {
            values,
            read: Mutex::new(BTreeSet::new()),
        })
    }

    /// Parameters from `(key, value)` pairs.
    pub fn of(pairs: &[(&str, u64)]) -> Params {
        let items: Vec<String> = pairs.iter().map(|(k, v)| format!("{k}={v}")).collect();
        Params::parse(&items).unwrap_or_default()
    }

    /// The positive integer `key`, or `default` when absent.
    pub fn get(&self, key: &str, default: u64) -> Result<u64, String> {
        if let Ok(mut r) = self.read.lock() {
            r.insert(key.to_string());
        }
        match self.values.get(key) {
            None => Ok(default),
            Some(v) => {
                let n: u64 = v
                    .replace('_', "")
                    .parse()
                    .map_err(|_| format!("parameter {key}={v}: expected a positive integer"))?;
                if n == 0 {
                    return Err(format!("parameter {key}={v}: must be at least 1"));
                }
                Ok(n)
            }
        }
    }

    /// The switch `key` (`0` or `1`), or `default` when absent.
    pub fn flag(&self, key: &str, default: bool) -> Result<bool, String> {
        if let Ok(mut r) = self.read.lock() {
            r.insert(key.to_string());
        }
        match self.values.get(key).map(String::as_str) {
            None => Ok(default),
            Some("0") => Ok(false),
            Some("1") => Ok(true),
            Some(v) => Err(format!("parameter {key}={v}: expected 0 or 1")),
        }
    }

    /// Keys given but never read (misspelt parameters).
    pub fn unused(&self) -> Vec<String> {
        let read = self.read.lock().map(|r| r.clone()).unwrap_or_default();
        self.values
            .keys()
            .filter(|k| !read.contains(*k))
            .cloned()
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_defaults_errors_and_unused_keys() {
        let p = Params::parse(&["hops=1_000", "agents = 5", "typo=3"]).unwrap();
        assert_eq!(p.get("hops", 7), Ok(1000));
        assert_eq!(p.get("agents", 7), Ok(5));
        assert_eq!(p.get("tokens", 7), Ok(7));
        assert_eq!(p.unused(), vec!["typo".to_string()]);
        assert!(Params::parse(&["novalue"]).is_err());
        let bad = Params::parse(&["hops=x", "agents=0"]).unwrap();
        assert!(bad.get("hops", 1).is_err());
        assert!(bad.get("agents", 1).is_err());
        let f = Params::parse(&["compare=0", "trace=1", "bad=2"]).unwrap();
        assert_eq!(f.flag("compare", true), Ok(false));
        assert_eq!(f.flag("trace", false), Ok(true));
        assert_eq!(f.flag("absent", true), Ok(true));
        assert!(f.flag("bad", true).is_err());
    }
}
