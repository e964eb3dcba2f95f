//! Launch rules: which agents to create, with which names, connected to
//! which entity. Pure bookkeeping: no programs, no threads.

use crate::env::EntityInfo;
use crate::syntax::mas2g::ast::{AgentName, EntitySpec, LaunchInstruction, LaunchRule};
use std::collections::BTreeSet;

/// One agent to create.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Launch {
    /// The agent's (unique) name.
    pub name: String,
    /// The reference name of its agent file.
    pub reference: String,
    /// The entity it controls, if any.
    pub entity: Option<String>,
}

/// Applies launch rules, keeping agent names unique and counting rule applications for `max`.
#[derive(Clone, Debug)]
pub struct Launcher {
    rules: Vec<LaunchRule>,
    counts: Vec<u64>,
    taken: BTreeSet<String>,
}

impl Launcher {
    /// A launcher for `rules` (in file order).
    pub fn new(rules: &[LaunchRule]) -> Launcher {
        Launcher {
            rules: rules.to_vec(),
            counts: vec![0; rules.len()],
            taken: BTreeSet::new(),
        }
    }

    /// The agents of the unconditional rules (run once, when the system starts).
    pub fn unconditional(&mut self) -> Vec<Launch> {
        let mut out = Vec::new();
        for i in 0..self.rules.len() {
            if self.rules[i].condition.is_none() {
                let insts = self.rules[i].instructions.clone();
                for inst in &insts {
                    self.instantiate(inst, None, &mut out);
                }
            }
        }
        out
    }

    /// The agents launched for a new (or freed) entity: the first conditional rule in file
    /// order whose constraints match and whose count is below `max`. `None` when no rule
    /// matches (the caller warns).
    pub fn entity(&mut self, entity: &EntityInfo) -> Option<Vec<Launch>> {
        let i = (0..self.rules.len()).find(|&i| self.matches(i, entity))?;
        self.counts[i] += 1;
        let insts = self.rules[i].instructions.clone();
        let mut out = Vec::new();
        for inst in &insts {
            self.instantiate(inst, Some(entity), &mut out);
        }
        Some(out)
    }

    fn matches(&self, i: usize, e: &EntityInfo) -> bool {
        match &self.rules[i].condition {
            None => false,
            Some(EntitySpec::Any(_)) => true,
            Some(EntitySpec::Constraints {
                name,
                entity_type,
                max,
                ..
            }) => {
                name.as_ref().is_none_or(|n| n.value == e.name)
                    && entity_type.as_ref().is_none_or(|t| t.value == e.kind)
                    && max.as_ref().is_none_or(|m| self.counts[i] < m.value)
            }
        }
    }

    fn instantiate(
        &mut self,
        inst: &LaunchInstruction,
        entity: Option<&EntityInfo>,
        out: &mut Vec<Launch>,
    ) {
        let base = match &inst.name {
            None => inst.reference.value.clone(),
            Some(AgentName::Given(g)) => g.value.clone(),
            // `*` outside a conditional rule is a checked error; fall back to the reference.
            Some(AgentName::Entity(_)) => entity
                .map(|e| e.name.clone())
                .unwrap_or_else(|| inst.reference.value.clone()),
        };
        let n = inst.count();
        for k in 1..=n {
            // Decision 4: `name1 .. nameN` when N > 1, `name` when N = 1.
            let wanted = if n > 1 {
                format!("{base}{k}")
            } else {
                base.clone()
            };
            let name = self.unique(&wanted);
            out.push(Launch {
                name,
                reference: inst.reference.value.clone(),
                entity: entity.map(|e| e.name.clone()),
            });
        }
    }

    /// `wanted` if free, else `wanted1`, `wanted2`, ... (the first free one).
    fn unique(&mut self, wanted: &str) -> String {
        let mut name = wanted.to_string();
        let mut k = 1u64;
        while self.taken.contains(&name) {
            name = format!("{wanted}{k}");
            k += 1;
        }
        self.taken.insert(name.clone());
        name
    }
}

/// A per-agent seed from the run seed and the agent's name (FNV-1a, then splitmix64).
pub fn agent_seed(seed: u64, name: &str) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in name.bytes() {
        h ^= u64::from(b);
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
    let mut z = seed ^ h;
    z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}
