//! Wall-clock time per pipeline phase (`--timings`: `timings_ms` in the report, one line in the text), and
//! where a run stands for a watchdog (`--timeout`): shared by every stage, it imports none of them.

use std::collections::BTreeMap;
use std::sync::{Arc, Mutex, OnceLock, PoisonError};
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

/// The phases of the pipeline, in the order they run.
pub const PHASES: [&str; 13] = [
    "load",
    "parse",
    "model",
    "assets",
    "checks",
    "statics",
    "classify",
    "stability",
    "collision_setup",
    "workspace",
    "start_contacts",
    "deep",
    "report",
];

/// Where a validation running elsewhere has got to, and a request to stop it (for a watchdog:
/// `--timeout`). Clones share it.
#[derive(Clone, Debug, Default)]
pub struct Progress {
    finished: Arc<Mutex<Option<&'static str>>>,
    /// When [`Progress::cancel`] was first called.
    cancelled: Arc<OnceLock<Instant>>,
    time_limit_seconds: f64,
}

impl Progress {
    /// Progress of a run its watchdog gives `seconds` (named when the run is given up on).
    pub fn with_time_limit(seconds: f64) -> Progress {
        Progress {
            time_limit_seconds: seconds,
            ..Progress::default()
        }
    }

    /// The time the watchdog gives the run, in seconds (0 when not told).
    pub fn time_limit_seconds(&self) -> f64 {
        self.time_limit_seconds
    }

    /// Ask the run to stop: the pipeline gives up before its next stage, and sampling stages end at
    /// their next batch of samples (their results are then partial and the report is not to be used).
    pub fn cancel(&self) {
        self.cancelled.get_or_init(Instant::now);
    }

    /// Whether [`cancel`](Self::cancel) was called.
    pub fn is_cancelled(&self) -> bool {
        self.cancelled.get().is_some()
    }

    /// When [`cancel`](Self::cancel) was first called (how long a cancelled run took to stop is measured
    /// from it).
    pub fn cancelled_at(&self) -> Option<Instant> {
        self.cancelled.get().copied()
    }

    /// The phase running now: the one after the last finished phase ([`PHASES`] order).
    pub fn running(&self) -> &'static str {
        let finished = *self.finished.lock().unwrap_or_else(PoisonError::into_inner);
        match finished.and_then(|last| PHASES.iter().position(|p| *p == last)) {
            Some(index) => PHASES.get(index + 1).copied().unwrap_or("report"),
            None => PHASES[0],
        }
    }

    fn finish(&self, phase: &'static str) {
        *self.finished.lock().unwrap_or_else(PoisonError::into_inner) = Some(phase);
    }
}

/// A stopwatch that records the time since its last lap under a phase name.
#[derive(Debug)]
pub struct Stopwatch {
    last: Instant,
    /// What was recorded so far.
    pub timings: Timings,
    progress: Option<Progress>,
}

impl Default for Stopwatch {
    fn default() -> Self {
        Stopwatch {
            last: Instant::now(),
            timings: Timings::default(),
            progress: None,
        }
    }
}

impl Stopwatch {
    /// Start timing now.
    pub fn start() -> Stopwatch {
        Stopwatch::default()
    }

    /// Start timing now, telling `progress` each phase that finishes.
    pub fn reporting_to(progress: Option<Progress>) -> Stopwatch {
        Stopwatch {
            progress,
            ..Stopwatch::default()
        }
    }

    /// Record the time since the last lap (or the start) as `phase`.
    pub fn lap(&mut self, phase: &'static str) {
        let now = Instant::now();
        self.timings
            .add(phase, (now - self.last).as_secs_f64() * 1000.0);
        self.last = now;
        if let Some(progress) = &self.progress {
            progress.finish(phase);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn progress_names_the_phase_after_the_last_finished_one() {
        let progress = Progress::default();
        assert_eq!(progress.running(), "load");
        let mut clock = Stopwatch::reporting_to(Some(progress.clone()));
        clock.lap("load");
        clock.lap("parse");
        assert_eq!(progress.running(), "model");
        clock.lap("collision_setup");
        assert_eq!(progress.running(), "workspace");
        // Every phase a run laps is one of them (a lap outside the list named the first phase instead).
        clock.lap("start_contacts");
        assert_eq!(progress.running(), "deep");
    }
}
