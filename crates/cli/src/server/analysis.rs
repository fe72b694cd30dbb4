//! Running validations off the main loop: one thread per run, two passes (structure, then physics, whose
//! sampling of arms the document's memo does not hold waits for typing to pause), a newer run of the same
//! document cancelling the older, and a watchdog time limit. The main loop never waits for a run: outcomes come back on a channel it selects
//! on. Each document keeps a memo of its runs' sampled arms, so an edit that leaves an arm's kinematics
//! and geometry as they were (an effort, a mass, a comment) does not sample it again.

use std::collections::HashMap;
use std::io::Write;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::{Duration, Instant};

use crossbeam_channel::Sender;
use lsp_types::Url;

use urdf_validator::analysis::memo::Memo;
use urdf_validator::timings::Progress;
use urdf_validator::{Error, Options, Validation};

/// Which pass of a run an outcome is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Pass {
    /// Parse, tree, meshes and the structural rules: fast, published first.
    Structure,
    /// Everything: statics, stability, workspace.
    Physics,
}

impl Pass {
    /// Its name in log lines.
    pub fn name(self) -> &'static str {
        match self {
            Pass::Structure => "structure",
            Pass::Physics => "physics",
        }
    }
}

/// What a pass of a run gave.
pub struct Outcome {
    /// The document analysed (the root of a xacro tree).
    pub root: Url,
    /// The run (to drop outcomes of runs cancelled since).
    pub run: u64,
    /// The document version analysed (`None`: the file as saved on disk).
    pub version: Option<i32>,
    /// The text analysed (for positions of an error).
    pub text: Arc<String>,
    /// The pass.
    pub pass: Pass,
    /// The validation, or why there is none.
    pub result: Result<Validation, Error>,
    /// How long the pass took.
    pub elapsed: Duration,
    /// Sampled arms the pass took from the document's memo, and arms it sampled.
    pub arms: (usize, usize),
}

/// One validation to run.
pub struct Job {
    /// The document.
    pub root: Url,
    /// Its path.
    pub path: PathBuf,
    /// Its text (saved or not).
    pub text: Arc<String>,
    /// Its version (`None`: read from disk).
    pub version: Option<i32>,
    /// The options its configuration gives.
    pub options: Options,
    /// How long typing must pause before the physics pass samples an arm its memo does not hold (a newer
    /// edit cancels the run first); a pass whose arms are all kept does not wait.
    pub pause: Duration,
    /// Write how long a cancelled pass took to stop to stderr (`URDF_VALIDATOR_LSP_TIMINGS`).
    pub log_timings: bool,
}

/// A run under way.
struct Running {
    id: u64,
    progress: Progress,
    started: Instant,
}

/// The runs under way, one at most per document.
pub struct Analyses {
    running: HashMap<Url, Running>,
    /// Per document, the results its runs keep for the next.
    memos: HashMap<Url, Memo>,
    outcomes: Sender<Outcome>,
    next_id: u64,
    time_limit: Duration,
}

impl Analyses {
    /// Runs that send their outcomes to `outcomes`, each given `time_limit`.
    pub fn new(outcomes: Sender<Outcome>, time_limit: Duration) -> Analyses {
        Analyses {
            running: HashMap::new(),
            memos: HashMap::new(),
            outcomes,
            next_id: 0,
            time_limit,
        }
    }

    /// Start `job`, cancelling the run of the same document still under way.
    pub fn start(&mut self, mut job: Job) {
        self.cancel(&job.root);
        let memo = self.memos.entry(job.root.clone()).or_default();
        job.options.workspace.memo = Some(memo.clone());
        self.next_id += 1;
        let id = self.next_id;
        let progress = Progress::with_time_limit(self.time_limit.as_secs_f64());
        self.running.insert(
            job.root.clone(),
            Running {
                id,
                progress: progress.clone(),
                started: Instant::now(),
            },
        );
        let outcomes = self.outcomes.clone();
        let spawned = std::thread::Builder::new()
            .name(format!("analyse {}", job.path.display()))
            .spawn(move || run(job, id, &progress, &outcomes));
        if let Err(error) = spawned {
            errln!("urdf_validate server: cannot start an analysis thread: {error}");
        }
    }

    /// Cancel the run of `root`, if one is under way.
    pub fn cancel(&mut self, root: &Url) {
        if let Some(running) = self.running.remove(root) {
            running.progress.cancel();
        }
    }

    /// Cancel the run of `root` and drop what its runs kept (the document was closed).
    pub fn forget(&mut self, root: &Url) {
        self.cancel(root);
        self.memos.remove(root);
    }

    /// Whether `outcome` is of the run under way for its document (not of one cancelled since); a
    /// physics outcome ends the run.
    pub fn is_current(&mut self, outcome: &Outcome) -> bool {
        let current = self
            .running
            .get(&outcome.root)
            .is_some_and(|r| r.id == outcome.run);
        if current && (outcome.pass == Pass::Physics || outcome.result.is_err()) {
            self.running.remove(&outcome.root);
        }
        current
    }

    /// Cancel the runs over their time limit; the documents they were for.
    pub fn over_time(&mut self) -> Vec<Url> {
        let late: Vec<Url> = self
            .running
            .iter()
            .filter(|(_, r)| r.started.elapsed() > self.time_limit)
            .map(|(root, _)| root.clone())
            .collect();
        for root in &late {
            self.cancel(root);
        }
        late
    }

    /// The time limit of a run.
    pub fn time_limit(&self) -> Duration {
        self.time_limit
    }
}

/// Run `job`'s two passes, sending each outcome unless the run was cancelled meanwhile (a cancelled
/// pass's report may be partial).
fn run(job: Job, id: u64, progress: &Progress, outcomes: &Sender<Outcome>) {
    let start = Instant::now();
    for pass in [Pass::Structure, Pass::Physics] {
        let mut options = Options {
            structure_only: pass == Pass::Structure,
            progress: Some(progress.clone()),
            ..job.options.clone()
        };
        options.workspace.sample_from = Some(start + job.pause);
        let started = Instant::now();
        let memo = job.options.workspace.memo.as_ref();
        let before = memo.map_or((0, 0), |m| (m.reused(), m.computed()));
        let result = urdf_validator::validate_unsaved(job.text.to_string(), &job.path, &options);
        if let Some(cancelled) = progress.cancelled_at() {
            if job.log_timings {
                errln!(
                    "urdf_validate server: cancelled {} pass of {} stopped {:.1} ms after its cancellation (in {})",
                    pass.name(),
                    job.root,
                    cancelled.elapsed().as_secs_f64() * 1e3,
                    progress.running()
                );
            }
            return;
        }
        let after = memo.map_or((0, 0), |m| (m.reused(), m.computed()));
        let failed = result.is_err();
        let outcome = Outcome {
            root: job.root.clone(),
            run: id,
            version: job.version,
            text: Arc::clone(&job.text),
            pass,
            result,
            elapsed: started.elapsed(),
            arms: (after.0 - before.0, after.1 - before.1),
        };
        if outcomes.send(outcome).is_err() || failed {
            return;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    /// The example robot's physics pass as a run of the server gives it: (arms kept, arms sampled) and
    /// the effort of its shoulder in the report.
    fn physics_pass(
        analyses: &mut Analyses,
        outcomes: &crossbeam_channel::Receiver<Outcome>,
        text: String,
    ) -> ((usize, usize), f64) {
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../examples/robots/mobile_manipulator.urdf");
        let root = Url::from_file_path(&path).expect("absolute");
        analyses.start(Job {
            root: root.clone(),
            path,
            text: Arc::new(text),
            version: Some(1),
            options: Options::default(),
            pause: Duration::ZERO,
            log_timings: false,
        });
        loop {
            let outcome = outcomes
                .recv_timeout(Duration::from_secs(60))
                .expect("an outcome");
            assert!(analyses.is_current(&outcome));
            if outcome.pass == Pass::Physics {
                let report = outcome.result.expect("validates").report;
                let shoulder = report
                    .statics
                    .iter()
                    .flat_map(|statics| &statics.joints)
                    .find(|j| j.name == "shoulder_pan_joint")
                    .and_then(|j| j.declared_effort)
                    .expect("the shoulder's effort");
                return (outcome.arms, shoulder);
            }
        }
    }

    #[test]
    fn an_effort_edit_takes_the_sampled_arm_from_the_documents_memo() {
        let (sender, outcomes) = crossbeam_channel::unbounded();
        let mut analyses = Analyses::new(sender, Duration::from_secs(60));
        let text = std::fs::read_to_string(
            Path::new(env!("CARGO_MANIFEST_DIR"))
                .join("../../examples/robots/mobile_manipulator.urdf"),
        )
        .expect("the example robot");
        let (arms, effort) = physics_pass(&mut analyses, &outcomes, text.clone());
        assert_eq!(
            (arms, effort),
            ((0, 1), 120.0),
            "the first pass samples the arm"
        );
        let edited = text.replacen("effort=\"120.0\"", "effort=\"150.0\"", 1);
        let (arms, effort) = physics_pass(&mut analyses, &outcomes, edited);
        assert_eq!(
            (arms, effort),
            ((1, 0), 150.0),
            "the edit is analysed, the arm kept"
        );
    }
}
