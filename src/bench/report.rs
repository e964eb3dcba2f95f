//! The figures of one benchmark run and their text rendering.

use std::fmt::Write;
use std::time::Duration;

/// A target a figure is compared with.
#[derive(Clone, Debug, PartialEq)]
pub struct Target {
    /// What is compared, e.g. `run time`.
    pub what: &'static str,
    /// The measured value.
    pub value: f64,
    /// The target value.
    pub target: f64,
    /// Unit used when printing both.
    pub unit: &'static str,
    /// True when smaller is better (times, memory).
    pub lower_is_better: bool,
}

impl Target {
    /// True when the measured value meets the target.
    pub fn met(&self) -> bool {
        if self.lower_is_better {
            self.value <= self.target
        } else {
            self.value >= self.target
        }
    }

    /// How far the value is from the target, as a factor > 1 when the target is met.
    pub fn ratio(&self) -> f64 {
        if self.value == 0.0 || self.target == 0.0 {
            return 0.0;
        }
        if self.lower_is_better {
            self.target / self.value
        } else {
            self.value / self.target
        }
    }
}

/// What one benchmark run measured.
#[derive(Clone, Debug, Default)]
pub struct Report {
    /// Benchmark name.
    pub name: String,
    /// The parameters used, as `key=value`.
    pub config: String,
    /// Why the run did not finish correctly; `None` when it did.
    pub failure: Option<String>,
    /// Number of agents.
    pub agents: usize,
    /// Worker threads.
    pub workers: usize,
    /// Loading and compiling the programs, creating the agents and worker threads.
    pub create: Duration,
    /// From "all agents created" to "done".
    pub run: Duration,
    /// What was counted in the run (messages, cycles, goals).
    pub count: u64,
    /// The unit of `count`.
    pub unit: &'static str,
    /// Reasoning cycles run by all agents together.
    pub cycles: u64,
    /// CPU time (user + system, all threads) of creation and run together, when known.
    pub cpu: Option<Duration>,
    /// Peak resident set size of the process (VmHWM), KiB.
    pub peak_rss_kib: Option<u64>,
    /// Further figures: label and value.
    pub extra: Vec<(String, String)>,
    /// The figures compared with the project's targets.
    pub targets: Vec<Target>,
}

impl Report {
    /// True when the run finished correctly.
    pub fn ok(&self) -> bool {
        self.failure.is_none()
    }

    /// `count` per second of run time.
    pub fn rate(&self) -> f64 {
        let s = self.run.as_secs_f64();
        if s > 0.0 {
            self.count as f64 / s
        } else {
            0.0
        }
    }

    /// The report as aligned text lines.
    pub fn render(&self) -> String {
        let mut o = String::new();
        let status = match &self.failure {
            None => "ok".to_string(),
            Some(f) => format!("FAILED: {f}"),
        };
        let _ = writeln!(o, "benchmark   {} ({})", self.name, self.config);
        let _ = writeln!(o, "result      {status}");
        let _ = writeln!(o, "agents      {}", self.agents);
        let _ = writeln!(o, "workers     {}", self.workers);
        let _ = writeln!(o, "creation    {}", secs(self.create));
        let _ = writeln!(o, "run         {}", secs(self.run));
        let wall = self.create + self.run;
        let _ = writeln!(o, "wall        {}", secs(wall));
        if let Some(cpu) = self.cpu {
            let per = cpu.as_secs_f64() * 1e6 / (self.count.max(1) as f64);
            let _ = writeln!(
                o,
                "cpu         {} ({:.2} CPUs; {per:.3} µs per {})",
                secs(cpu),
                cpu.as_secs_f64() / wall.as_secs_f64().max(1e-9),
                self.unit.trim_end_matches('s')
            );
        }
        let _ = writeln!(o, "{:<11} {}", self.unit, self.count);
        let _ = writeln!(o, "{:<11} {}/s", "rate", si(self.rate()));
        if self.cycles > 0 {
            let c = self.cycles as f64 / self.run.as_secs_f64().max(1e-9);
            let _ = writeln!(o, "cycles      {} ({}/s)", self.cycles, si(c));
        }
        match self.peak_rss_kib {
            Some(k) => {
                let _ = writeln!(o, "peak RSS    {:.1} MiB", k as f64 / 1024.0);
            }
            None => {
                let _ = writeln!(o, "peak RSS    unknown");
            }
        }
        for (k, v) in &self.extra {
            let _ = writeln!(o, "{k:<11} {v}");
        }
        for t in &self.targets {
            let cmp = if t.lower_is_better { "<" } else { ">" };
            let _ = writeln!(
                o,
                "target      {} {} {cmp} {} {}: {} (x{:.2})",
                t.what,
                fmt_num(t.value),
                fmt_num(t.target),
                t.unit,
                if t.met() { "met" } else { "missed" },
                t.ratio()
            );
        }
        o
    }
}

fn secs(d: Duration) -> String {
    format!("{:.3} s", d.as_secs_f64())
}

fn fmt_num(v: f64) -> String {
    if v.abs() >= 1000.0 {
        si(v)
    } else {
        format!("{v:.3}")
    }
}

/// A number with a k/M/G suffix.
pub fn si(v: f64) -> String {
    if v >= 1e9 {
        format!("{:.2} G", v / 1e9)
    } else if v >= 1e6 {
        format!("{:.2} M", v / 1e6)
    } else if v >= 1e3 {
        format!("{:.1} k", v / 1e3)
    } else {
        format!("{v:.1}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn targets_and_rendering() {
        let t = Target {
            what: "run time",
            value: 0.5,
            target: 1.0,
            unit: "s",
            lower_is_better: true,
        };
        assert!(t.met());
        assert!((t.ratio() - 2.0).abs() < 1e-9);
        let r = Report {
            name: "ring1".into(),
            count: 1000,
            unit: "messages",
            run: Duration::from_millis(500),
            cpu: Some(Duration::from_millis(250)),
            targets: vec![t],
            ..Report::default()
        };
        assert!((r.rate() - 2000.0).abs() < 1e-6);
        let text = r.render();
        assert!(text.contains("2.0 k/s"), "{text}");
        assert!(text.contains("met (x2.00)"), "{text}");
        assert!(
            text.contains("cpu         0.250 s (0.50 CPUs; 250.000 µs per message)"),
            "{text}"
        );
        assert_eq!(si(5.5e6), "5.50 M");
    }
}
