//! Starting a run: launching the system's agents on the environment's entities, and naming
//! them in the trace header.

use super::*;

fn problem(code: &str, msg: String) -> Vec<Problem> {
    vec![Problem::bare(Diagnostic::error(code, msg, "run", 0..0))]
}

impl<'a> Setup<'a> {
    pub(super) fn new(
        system: &'a MasSystem,
        opts: &'a RunOptions,
        level: TraceLevel,
        obs: &mut dyn Observer,
    ) -> Result<Setup<'a>, Vec<Problem>> {
        let mut launcher = Launcher::new(&system.rules);
        let mut launches: Vec<Launch> = launcher.unconditional();
        let (env, info, seed, map) = match &system.env {
            Some(setup) => {
                let (p, seed, map) = env_params(setup, opts, obs);
                let (world, warnings) = setup.kind.create(&p)?;
                for w in &warnings {
                    obs.warning(w);
                }
                let map = Some(map).filter(|m| !m.is_empty());
                let handle = EnvHandle::spawn(world, Mode::LockStep);
                let info = handle
                    .info()
                    .map_err(|e| problem("M0030", format!("environment: {e}")))?;
                (Some(handle), Some(info), seed, map)
            }
            None => (None, None, opts.seed.unwrap_or(0), None),
        };
        if let Some(info) = &info {
            obs.entities(&info.entities);
            for e in &info.entities {
                match launcher.entity(e) {
                    Some(l) => launches.extend(l),
                    None => obs.warning(&format!(
                        "no launch rule for entity {} (type {}); it stays without an agent",
                        e.name, e.kind
                    )),
                }
            }
        }
        launches.sort_by(|a, b| a.name.cmp(&b.name));
        if launches.is_empty() {
            return Err(problem("M0031", "no agent was launched".into()));
        }
        let names: Vec<String> = launches.iter().map(|l| l.name.clone()).collect();
        let types = Arc::new(info.as_ref().map(percept_types).unwrap_or_default());
        let directory = Directory::new(&names);
        let mut agents = Vec::new();
        let mut slots = Vec::new();
        let mut by_entity: BTreeMap<String, Vec<usize>> = BTreeMap::new();
        for (i, l) in launches.iter().enumerate() {
            let prog = system.programs.get(&l.reference).ok_or_else(|| {
                problem(
                    "M0032",
                    format!("launch of {}: no agent file `{}`", l.name, l.reference),
                )
            })?;
            let kr = system.engines.get(&l.reference).copied().unwrap_or(opts.kr);
            if let Err(why) = crate::kr::AgentEngine::new(kr, &prog.knowledge, 0, Limits::default())
            {
                return Err(problem("M0034", format!("agent {}: {why}", l.name)));
            }
            let config = AgentConfig {
                seed: agent_seed(seed, &l.name),
                directory: Some(directory.clone()),
                percept_types: types.clone(),
                trace: level,
                cycle_time: opts.cycle_time,
                limits: Limits {
                    deadline: opts.time_limit.and_then(|t| Instant::now().checked_add(t)),
                    ..Limits::default()
                },
                max_beliefs: opts.max_beliefs,
                max_sent: opts.max_sent,
                kr,
                ..AgentConfig::default()
            };
            let agent = obs.agent(i, &l.name, prog, &config);
            agents.push(agent.unwrap_or_else(|| Agent::new(prog.clone(), &l.name, config)));
            if let Some(e) = &l.entity {
                by_entity.entry(e.clone()).or_default().push(i);
            }
            slots.push(Slot {
                name: l.name.clone(),
                reference: l.reference.clone(),
                entity: l.entity.clone(),
                stats: AgentStats {
                    entity: l.entity.clone(),
                    ..AgentStats::default()
                },
                waiting: false,
                percepts: Vec::new(),
                inbox: Vec::new(),
                queued: true,
                counted: 0,
            });
        }
        let initial = match &env {
            Some(h) => h
                .perceive(&[])
                .map_err(|e| problem("M0030", format!("environment: {e}")))?,
            None => Vec::new(),
        };
        let slots_len = slots.len();
        let pool = Pool::new(agents, opts.workers).map_err(|e| problem("M0033", e.0))?;
        let comm =
            crate::clamr::Comm::new(&names, &opts.comm, seed).map_err(|e| problem("M0034", e))?;
        Ok(Setup {
            system,
            opts,
            seed,
            map,
            env,
            pool,
            router: Router::new(&names),
            comm,
            slots,
            ready: (0..slots_len).collect(),
            by_entity,
            initial,
        })
    }

    pub(super) fn agent_infos(&self) -> Vec<AgentInfo> {
        self.slots
            .iter()
            .map(|s| AgentInfo {
                name: s.name.clone(),
                file: self
                    .system
                    .files
                    .get(&s.reference)
                    .cloned()
                    .unwrap_or_default(),
                entity: s.entity.clone(),
            })
            .collect()
    }
}
