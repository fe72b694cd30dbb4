//! Wall-clock time per pipeline phase (`--timings`): `timings_ms` in the report, one line in the text.

use std::collections::BTreeMap;
use std::time::Instant;

use schemars::JsonSchema;
use serde::{Serialize, Serializer};

/// Milliseconds per phase, in the order the phases ran (serialised as a JSON object in that order).
#[derive(Clone, Debug, Default, PartialEq, JsonSchema)]
#[schemars(with = "BTreeMap<String, f64>")]
pub struct Timings {
    phases: Vec<(&'static str, f64)>,
}

impl Timings {
    /// The phases, in order, with their milliseconds.
    pub fn phases(&self) -> &[(&'static str, f64)] {
        &self.phases
    }

    /// Add `ms` to `phase` (a phase that runs twice adds up).
    pub fn add(&mut self, phase: &'static str, ms: f64) {
        match self.phases.iter_mut().find(|(name, _)| *name == phase) {
            Some((_, total)) => *total += ms,
            None => self.phases.push((phase, ms)),
        }
    }

    /// Every phase of `other` added to this one.
    pub fn extend(&mut self, other: &Timings) {
        for &(phase, ms) in &other.phases {
            self.add(phase, ms);
        }
    }

    /// The sum of all phases.
    pub fn total_ms(&self) -> f64 {
        self.phases.iter().map(|(_, ms)| ms).sum()
    }
}

impl Serialize for Timings {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_map(
            self.phases
                .iter()
                .map(|(phase, ms)| (*phase, (ms * 1000.0).round() / 1000.0)),
        )
    }
}

/// A stopwatch that records the time since its last lap under a phase name.
#[derive(Debug)]
pub struct Stopwatch {
    last: Instant,
    /// What was recorded so far.
    pub timings: Timings,
}

impl Default for Stopwatch {
    fn default() -> Self {
        Stopwatch {
            last: Instant::now(),
            timings: Timings::default(),
        }
    }
}

impl Stopwatch {
    /// Start timing now.
    pub fn start() -> Stopwatch {
        Stopwatch::default()
    }

    /// Record the time since the last lap (or the start) as `phase`.
    pub fn lap(&mut self, phase: &'static str) {
        let now = Instant::now();
        self.timings
            .add(phase, (now - self.last).as_secs_f64() * 1000.0);
        self.last = now;
    }
}
