//! `urdf_validate server`: the validator as a Language Server Protocol server on stdin/stdout, for
//! editors. Synchronous (`lsp-server`, as rust-analyzer and ruff use it): the main loop owns the state and
//! answers every request from it at once; validations run on threads of their own ([`analysis`]) and
//! come back on a channel, so no request ever waits for one, and a newer edit cancels the run under way.
//!
//! One job per module: the open documents ([`documents`]), positions ([`positions`]), a tolerant XML scan
//! of the text as typed ([`xml`]) and what the cursor is on ([`here`]); the features: diagnostics,
//! hover, navigation, completion, code actions.

mod analysis;
mod code_actions;
mod completion;
mod diagnostics;
mod documents;
#[doc(hidden)]
pub mod fuzzing;
mod here;
mod hover;
mod lifecycle;
mod navigation;
mod positions;
mod transport;
mod xacro_names;
mod xml;

use std::collections::HashMap;
use std::ffi::OsString;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Duration;

use crossbeam_channel::{select, Receiver};
use lsp_server::{Connection, Message, Notification, Request, Response};
use lsp_types::notification::{
    DidChangeTextDocument, DidCloseTextDocument, DidOpenTextDocument, DidSaveTextDocument,
    Notification as _, PublishDiagnostics,
};
use lsp_types::request::{
    CodeActionRequest, Completion, DocumentSymbolRequest, GotoDefinition, HoverRequest, References,
    Request as _,
};
use lsp_types::{
    CodeActionKind, CodeActionOptions, CodeActionProviderCapability, CompletionOptions, Diagnostic,
    GotoDefinitionResponse, Hover, HoverContents, HoverProviderCapability, MarkupContent,
    MarkupKind, OneOf, PublishDiagnosticsParams, SaveOptions, ServerCapabilities, ServerInfo,
    TextDocumentSyncCapability, TextDocumentSyncKind, TextDocumentSyncOptions,
    TextDocumentSyncSaveOptions, Url,
};
use urdf_validate_session::options::mesh_cache;
use urdf_validate_session::{config_file, Request as Settings, Session};
use urdf_validator::diagnostics::Section;
use urdf_validator::input::mesh::MeshCache;
use urdf_validator::report::FindingReport;
use urdf_validator::Validation;

use crate::request;
use analysis::{Analyses, Job, Outcome, Pass};
use documents::Documents;
use navigation::File;

/// `urdf_validate server --help`.
pub(crate) const HELP: &str = "\
Serve the validator to editors over the Language Server Protocol (LSP), on stdin/stdout.

Usage: urdf_validate server [FLAGS]...

An editor starts this command and speaks LSP to it. For .urdf, .xacro, .urdf.xacro, .sdf and .world files
it publishes the findings as diagnostics (structural ones as you type, physics when the analysis
finishes), offers each finding's fix, \"fix all safe\" and \"suppress this finding\" as code actions, and
answers hover (mass properties of links, gravity torque and effort margin of joints, resolved mesh paths),
go to definition, references, document symbols (the kinematic tree) and completion. Set-up per editor:
https://urdf-validator.github.io/urdf-validator/integrations/editors.html.

FLAGS are the command's own (`--package-path DIR`, `--samples N`, `--select`, ...: see `urdf_validate
--help`), applied to every file; each file's urdf-validate.toml or pyproject.toml applies too, as on the
command line. Messages for people go to stderr.
";

/// How long typing must pause before the physics of a changed document is analysed again (its
/// structural pass runs at once: a few milliseconds, cancelled by the next keystroke).
const DEBOUNCE: Duration = Duration::from_millis(30);

/// How often the main loop looks at the runs' time limits when nothing else wakes it.
const WATCH: Duration = Duration::from_secs(1);

/// Run `urdf_validate server FLAGS`: serve until the client says exit. Exit status 0, or 2 when the server
/// cannot run (a bad flag, a broken connection).
pub(crate) fn main(args: &[OsString]) -> u8 {
    if args.iter().any(|arg| arg == "-h" || arg == "--help") {
        out!("{HELP}");
        return 0;
    }
    let flags: Vec<String> = args
        .iter()
        .map(|a| a.to_string_lossy().into_owned())
        .collect();
    // The flags are checked once here, so a typo stops the server with a message rather than failing
    // every file.
    let checked = request::request_from_flags(&flags)
        .and_then(|request| Session::new(&request, None).map(|session| (request, session)));
    let (settings, timeout) = match checked {
        Ok((settings, session)) => (settings, session.timeout()),
        Err(message) => {
            errln!("error: urdf_validate server: {message}");
            return 2;
        }
    };
    let (connection, io_threads) = transport::stdio();
    let status = match serve(&connection, settings, timeout) {
        Ok(()) => 0,
        Err(message) => {
            errln!("error: urdf_validate server: {message}");
            2
        }
    };
    // Closing the connection ends the writer thread; the reader ends with stdin.
    drop(connection);
    if status == 0 {
        io_threads.join();
    }
    status
}

/// `changes` with a range each where it can be told: a whole new text (the one change) becomes the edit
/// of the part of `before` it changes, so what is shown can follow it.
fn located_changes(
    before: Option<&str>,
    changes: &[lsp_types::TextDocumentContentChangeEvent],
) -> Vec<lsp_types::TextDocumentContentChangeEvent> {
    match (before, changes) {
        (Some(before), [whole]) if whole.range.is_none() => {
            let (start, end, text) = positions::changed_part(before, &whole.text);
            let index = positions::LineIndex::new(before);
            vec![lsp_types::TextDocumentContentChangeEvent {
                range: Some(index.range(before, start, end)),
                range_length: None,
                text: text.to_string(),
            }]
        }
        _ => changes.to_vec(),
    }
}

/// What the server can do.
fn capabilities() -> ServerCapabilities {
    ServerCapabilities {
        text_document_sync: Some(TextDocumentSyncCapability::Options(
            TextDocumentSyncOptions {
                open_close: Some(true),
                change: Some(TextDocumentSyncKind::INCREMENTAL),
                save: Some(TextDocumentSyncSaveOptions::SaveOptions(SaveOptions {
                    include_text: Some(false),
                })),
                ..TextDocumentSyncOptions::default()
            },
        )),
        hover_provider: Some(HoverProviderCapability::Simple(true)),
        definition_provider: Some(OneOf::Left(true)),
        references_provider: Some(OneOf::Left(true)),
        document_symbol_provider: Some(OneOf::Left(true)),
        completion_provider: Some(CompletionOptions {
            trigger_characters: Some(vec!["\"".into(), "'".into(), " ".into()]),
            ..CompletionOptions::default()
        }),
        code_action_provider: Some(CodeActionProviderCapability::Options(CodeActionOptions {
            code_action_kinds: Some(vec![
                CodeActionKind::QUICKFIX,
                CodeActionKind::SOURCE_FIX_ALL,
            ]),
            ..CodeActionOptions::default()
        })),
        ..ServerCapabilities::default()
    }
}

/// Initialise, then run the main loop until `exit`.
fn serve(
    connection: &Connection,
    settings: Settings,
    timeout: Option<Duration>,
) -> Result<(), String> {
    // stdin closed (or `exit`) before `initialize`: nothing was asked.
    let Some((id, _params)) = lifecycle::initialize(connection) else {
        return Ok(());
    };
    let result = lsp_types::InitializeResult {
        capabilities: capabilities(),
        server_info: Some(ServerInfo {
            name: "urdf_validate".into(),
            version: Some(env!("CARGO_PKG_VERSION").into()),
        }),
    };
    let result = serde_json::to_value(result).map_err(|e| e.to_string())?;
    (connection.sender.send(Response::new_ok(id, result).into()))
        .map_err(|_| "initialize: the client is gone".to_string())?;
    let (sender, outcomes) = crossbeam_channel::unbounded();
    // A run never ends by itself past the time limit: the watchdog cancels it (none: an hour).
    let time_limit = timeout.unwrap_or(Duration::from_secs(3600));
    let mut server = Server {
        connection,
        meshes: mesh_cache(settings.no_cache),
        settings,
        sessions: HashMap::new(),
        documents: Documents::default(),
        analyses: Analyses::new(sender, time_limit),
        analysed: HashMap::new(),
        published: HashMap::new(),
        log_timings: std::env::var_os("URDF_VALIDATOR_LSP_TIMINGS").is_some(),
    };
    server.run(&outcomes)
}

/// The last analyses of a document that gave a validation.
struct Analysed {
    /// The latest (the text fixes are offered for).
    validation: Arc<Validation>,
    /// The latest physics pass (hover's statics, and the physics findings shown until the next one).
    physics: Option<Arc<Validation>>,
}

/// The server's state; the main loop owns it.
struct Server<'c> {
    connection: &'c Connection,
    /// The settings of the server's flags.
    settings: Settings,
    /// The meshes loaded so far, shared by every session.
    meshes: MeshCache,
    /// Options per configuration file (`None`: no file), built on first use.
    sessions: HashMap<Option<PathBuf>, Result<Session, String>>,
    documents: Documents,
    analyses: Analyses,
    /// The last validation of each analysed document (kept while a newer text does not parse).
    analysed: HashMap<Url, Analysed>,
    /// What each analysed document published, by file (a xacro tree's findings go to its includes).
    published: HashMap<Url, HashMap<Url, Vec<Diagnostic>>>,
    /// Write each pass's time to stderr (`URDF_VALIDATOR_LSP_TIMINGS`: the latency bench reads it).
    log_timings: bool,
}

impl Server<'_> {
    fn run(&mut self, outcomes: &Receiver<Outcome>) -> Result<(), String> {
        loop {
            select! {
                recv(self.connection.receiver) -> message => {
                    let Ok(message) = message else { return Ok(()) };
                    match message {
                        Message::Request(request) => {
                            if lifecycle::shut_down(self.connection, &request) {
                                return Ok(());
                            }
                            self.request(request);
                        }
                        Message::Notification(notification) => self.notification(notification),
                        Message::Response(_) => {}
                    }
                }
                recv(outcomes) -> outcome => {
                    if let Ok(outcome) = outcome {
                        self.outcome(outcome);
                    }
                }
                default(WATCH) => {}
            }
            for root in self.analyses.over_time() {
                let seconds = self.analyses.time_limit().as_secs_f64();
                let diagnostic = Diagnostic {
                    severity: Some(lsp_types::DiagnosticSeverity::ERROR),
                    source: Some(diagnostics::SOURCE.into()),
                    message: format!(
                        "the analysis did not finish within {seconds} s and was stopped (--timeout)"
                    ),
                    ..Diagnostic::default()
                };
                self.publish_for(
                    &root,
                    None,
                    HashMap::from([(root.clone(), vec![diagnostic])]),
                );
            }
        }
    }

    fn notification(&mut self, notification: Notification) {
        match notification.method.as_str() {
            DidOpenTextDocument::METHOD => {
                if let Ok(params) = notification
                    .extract::<lsp_types::DidOpenTextDocumentParams>(DidOpenTextDocument::METHOD)
                {
                    let document = params.text_document;
                    self.documents
                        .open(document.uri.clone(), document.text, document.version);
                    self.analyse(&document.uri, Duration::ZERO);
                }
            }
            DidChangeTextDocument::METHOD => {
                if let Ok(params) = notification.extract::<lsp_types::DidChangeTextDocumentParams>(
                    DidChangeTextDocument::METHOD,
                ) {
                    let uri = params.text_document.uri;
                    let version = params.text_document.version;
                    let changes = params.content_changes;
                    let before = self.documents.get(&uri).map(|d| d.text.as_str());
                    let located = located_changes(before, &changes);
                    match self.documents.change(&uri, version, changes) {
                        Ok(()) => {
                            self.follow_edit(&uri, version, &located);
                            // The run under way is for an older text: this one replaces it.
                            self.analyse(&uri, DEBOUNCE);
                        }
                        Err(message) => errln!("urdf_validate server: {message}"),
                    }
                }
            }
            DidSaveTextDocument::METHOD => {
                if let Ok(params) = notification
                    .extract::<lsp_types::DidSaveTextDocumentParams>(DidSaveTextDocument::METHOD)
                {
                    self.saved(&params.text_document.uri);
                }
            }
            DidCloseTextDocument::METHOD => {
                if let Ok(params) = notification
                    .extract::<lsp_types::DidCloseTextDocumentParams>(DidCloseTextDocument::METHOD)
                {
                    let uri = params.text_document.uri;
                    self.documents.close(&uri);
                    self.analyses.forget(&uri);
                    self.analysed.remove(&uri);
                    self.publish_for(&uri, None, HashMap::new());
                }
            }
            _ => {}
        }
    }

    /// A document was saved: analyse it, and every open robot whose analysis read it (a xacro tree
    /// including it: the expansion reads includes from disk).
    fn saved(&mut self, uri: &Url) {
        self.analyse(uri, Duration::ZERO);
        let Some(path) = documents::path_of(uri) else {
            return;
        };
        let readers: Vec<Url> = self
            .analysed
            .iter()
            .filter(|(root, a)| {
                *root != uri && a.validation.sources.iter().any(|s| s.path() == path)
            })
            .map(|(root, _)| root.clone())
            .collect();
        for root in readers {
            self.analyse(&root, Duration::ZERO);
        }
    }

    /// Analyse the open document at `uri` (a robot file; a xacro macro library alone is only checked to
    /// be well-formed XML: its robots analyse it), its physics once typing has paused for `pause`.
    fn analyse(&mut self, uri: &Url, pause: Duration) {
        let Some(path) = documents::path_of(uri).filter(|p| documents::is_robot_file(p)) else {
            return;
        };
        let Some(document) = self.documents.get(uri) else {
            return;
        };
        let (text, version) = (Arc::new(document.text.clone()), document.version);
        if urdf_validator::input::xacro::is_xacro(&path)
            && !urdf_validate_session::discovery::is_robot_xacro_text(&text)
        {
            let diagnostics = match roxmltree::Document::parse(&text) {
                Ok(_) => Vec::new(),
                Err(error) => {
                    let at = document.index.position_of_line_column(
                        &text,
                        error.pos().row,
                        error.pos().col,
                    );
                    vec![Diagnostic {
                        range: lsp_types::Range::new(at, at),
                        severity: Some(lsp_types::DiagnosticSeverity::ERROR),
                        source: Some(diagnostics::SOURCE.into()),
                        message: format!("not well-formed XML: {error}"),
                        ..Diagnostic::default()
                    }]
                }
            };
            self.publish_for(
                uri,
                Some(version),
                HashMap::from([(uri.clone(), diagnostics)]),
            );
            return;
        }
        match self.session(&path) {
            Ok(session) => {
                let options = session.options().clone();
                self.analyses.start(Job {
                    root: uri.clone(),
                    path,
                    text,
                    version: Some(version),
                    options,
                    pause,
                    log_timings: self.log_timings,
                });
            }
            Err(message) => {
                let diagnostic = Diagnostic {
                    severity: Some(lsp_types::DiagnosticSeverity::ERROR),
                    source: Some(diagnostics::SOURCE.into()),
                    message,
                    ..Diagnostic::default()
                };
                self.publish_for(
                    uri,
                    Some(version),
                    HashMap::from([(uri.clone(), vec![diagnostic])]),
                );
            }
        }
    }

    /// The options for the file at `path`: the flags with its configuration file.
    fn session(&mut self, path: &Path) -> Result<&Session, String> {
        let config = config_file(&self.settings, path);
        let (settings, meshes) = (&self.settings, &self.meshes);
        self.sessions
            .entry(config)
            .or_insert_with_key(|config| Session::with_config(settings, config.as_deref(), meshes))
            .as_ref()
            .map_err(Clone::clone)
    }

    /// A pass finished: publish it (unless a newer edit cancelled its run) and keep its validation.
    fn outcome(&mut self, outcome: Outcome) {
        if !self.analyses.is_current(&outcome) {
            return;
        }
        if self.log_timings {
            errln!(
                "urdf_validate server: {} pass of {} (version {:?}) in {:.1} ms (arms kept {}, sampled {})",
                outcome.pass.name(),
                outcome.root,
                outcome.version,
                outcome.elapsed.as_secs_f64() * 1e3,
                outcome.arms.0,
                outcome.arms.1
            );
        }
        let root = outcome.root;
        match outcome.result {
            Ok(validation) => {
                let validation = Arc::new(validation);
                let mut by_file = diagnostics::of_validation(&root, &validation, |_| true);
                let previous = self.analysed.remove(&root);
                let physics = match outcome.pass {
                    Pass::Physics => Some(Arc::clone(&validation)),
                    // Until the physics pass of this text is in, the last one's findings stay shown.
                    Pass::Structure => previous.and_then(|p| p.physics),
                };
                if let (Pass::Structure, Some(physics)) = (outcome.pass, &physics) {
                    let physical = |f: &FindingReport| f.section != Section::Schema;
                    for (file, shown) in diagnostics::of_validation(&root, physics, physical) {
                        by_file.entry(file).or_default().extend(shown);
                    }
                }
                self.analysed.insert(
                    root.clone(),
                    Analysed {
                        validation,
                        physics,
                    },
                );
                self.publish_for(&root, outcome.version, by_file);
            }
            Err(error) => {
                // The last good analysis stays for hover and navigation, and its findings stay shown
                // (as they moved with the edits since), marked stale, beside the error: a half-typed
                // tag does not wipe the file's findings.
                let (file, diagnostic) = diagnostics::of_error(&root, &error, &outcome.text);
                let mut by_file: HashMap<Url, Vec<Diagnostic>> = self
                    .published
                    .get(&root)
                    .map(|old| {
                        old.iter()
                            .map(|(file, shown)| {
                                let kept = shown
                                    .iter()
                                    .filter(|d| !diagnostics::is_load_error(d))
                                    .map(diagnostics::stale)
                                    .collect();
                                (file.clone(), kept)
                            })
                            .collect()
                    })
                    .unwrap_or_default();
                by_file.entry(file).or_default().push(diagnostic);
                self.publish_for(&root, outcome.version, by_file);
            }
        }
    }

    /// Replace what `root`'s analysis (of `root`'s text at `version`) shows with `by_file`, and publish
    /// every file whose diagnostics change (each file shows what every analysis reading it found, once).
    fn publish_for(
        &mut self,
        root: &Url,
        version: Option<i32>,
        by_file: HashMap<Url, Vec<Diagnostic>>,
    ) {
        let old = self.published.remove(root).unwrap_or_default();
        let mut files: Vec<Url> = old.keys().chain(by_file.keys()).cloned().collect();
        files.sort();
        files.dedup();
        self.published.insert(root.clone(), by_file);
        for file in files {
            // The version analysed, for the document analysed (another file's text was read from disk).
            let version = version.filter(|_| file == *root);
            self.publish_file(file, version);
        }
    }

    /// Publish what every analysis reading `file` shows of it, once each.
    fn publish_file(&self, file: Url, version: Option<i32>) {
        let mut diagnostics: Vec<Diagnostic> = Vec::new();
        for shown in self.published.values() {
            for diagnostic in shown.get(&file).into_iter().flatten() {
                if !diagnostics.contains(diagnostic) {
                    diagnostics.push(diagnostic.clone());
                }
            }
        }
        let params = PublishDiagnosticsParams::new(file, diagnostics, version);
        self.send(Message::Notification(Notification::new(
            PublishDiagnostics::METHOD.into(),
            params,
        )));
    }

    /// An edit of `uri` (`changes`, as applied): what is shown of it moves with the text until the next
    /// analysis (a diagnostic below an inserted line goes down with it), and what an edit touched is
    /// withdrawn; published again at once, for the edited `version`.
    fn follow_edit(
        &mut self,
        uri: &Url,
        version: i32,
        changes: &[lsp_types::TextDocumentContentChangeEvent],
    ) {
        let mut moved = false;
        for shown in self.published.values_mut() {
            let Some(diagnostics) = shown.get_mut(uri) else {
                continue;
            };
            if diagnostics.is_empty() {
                continue;
            }
            diagnostics.retain_mut(|diagnostic| {
                changes.iter().all(|change| {
                    match positions::through_edit(diagnostic.range, change.range, &change.text) {
                        Some(range) => {
                            diagnostic.range = range;
                            true
                        }
                        None => false,
                    }
                })
            });
            moved = true;
        }
        if moved {
            self.publish_file(uri.clone(), Some(version));
        }
    }

    fn send(&self, message: Message) {
        if self.connection.sender.send(message).is_err() {
            errln!("urdf_validate server: the client is gone");
        }
    }

    fn request(&mut self, request: Request) {
        let id = request.id.clone();
        let result = match request.method.as_str() {
            HoverRequest::METHOD => self.answer(request, Self::hover),
            GotoDefinition::METHOD => self.answer(request, Self::definition),
            References::METHOD => self.answer(request, Self::references),
            DocumentSymbolRequest::METHOD => self.answer(request, Self::symbols),
            Completion::METHOD => self.answer(request, Self::completion),
            CodeActionRequest::METHOD => self.answer(request, Self::code_actions),
            _ => Err((
                lsp_server::ErrorCode::MethodNotFound,
                format!("no method {}", request.method),
            )),
        };
        let response = match result {
            Ok(value) => Response::new_ok(id, value),
            Err((code, message)) => Response::new_err(id, code as i32, message),
        };
        self.send(Message::Response(response));
    }

    /// Parse `request`'s parameters and answer with `handler`.
    fn answer<P, R>(
        &self,
        request: Request,
        handler: fn(&Self, P) -> R,
    ) -> Result<serde_json::Value, (lsp_server::ErrorCode, String)>
    where
        P: serde::de::DeserializeOwned,
        R: serde::Serialize,
    {
        let params: P = serde_json::from_value(request.params).map_err(|e| {
            (
                lsp_server::ErrorCode::InvalidParams,
                format!("{}: {e}", request.method),
            )
        })?;
        serde_json::to_value(handler(self, params))
            .map_err(|e| (lsp_server::ErrorCode::InternalError, e.to_string()))
    }

    /// The last analysis of the robot `uri` belongs to: its own, else one whose files include it.
    fn analysis_of(&self, uri: &Url) -> Option<&Analysed> {
        self.analysed.get(uri).or_else(|| {
            let path = documents::path_of(uri)?;
            self.analysed
                .values()
                .find(|a| a.validation.sources.iter().any(|s| s.path() == path))
        })
    }

    /// The robot's files around `uri`, as the editor has them: `uri` first, then the other files its
    /// analysis read (open documents' text when open, else as read).
    fn files_of(&self, uri: &Url) -> Vec<File> {
        let mut files: Vec<File> = self
            .documents
            .get(uri)
            .map(|d| File::new(uri.clone(), d.text.clone()))
            .into_iter()
            .collect();
        if let Some(analysis) = self.analysis_of(uri) {
            for source in &analysis.validation.sources {
                let Ok(other) = Url::from_file_path(source.path()) else {
                    continue;
                };
                if other == *uri {
                    continue;
                }
                let text = self
                    .documents
                    .get(&other)
                    .map_or_else(|| source.text().to_string(), |d| d.text.clone());
                files.push(File::new(other, text));
            }
        }
        files.extend(self.srdf_of(uri));
        files
    }

    /// The SRDF of the robot at `uri` (the one `--srdf` names, else the one beside it that the analyses
    /// read: [`urdf_validator::input::srdf::find`]), as the editor has it when open.
    fn srdf_of(&self, uri: &Url) -> Option<File> {
        let path = documents::path_of(uri)?;
        let config = config_file(&self.settings, &path);
        let session = self.sessions.get(&config)?.as_ref().ok()?;
        let robot = self
            .analysis_of(uri)
            .map(|a| a.validation.report.robot_name.clone());
        let explicit = session.options().statics.pose.srdf.clone();
        let srdf = urdf_validator::input::srdf::find(&path, robot.as_deref(), explicit.as_deref())?;
        let srdf_uri = Url::from_file_path(&srdf).ok()?;
        let text = match self.documents.get(&srdf_uri) {
            Some(document) => document.text.clone(),
            None => urdf_validator::input::srdf::Srdf::read(srdf).text.ok()?,
        };
        Some(File::new(srdf_uri, text))
    }

    /// The byte offset of `position` in the open document `uri`.
    fn offset(&self, uri: &Url, position: lsp_types::Position) -> Option<usize> {
        let document = self.documents.get(uri)?;
        Some(document.index.offset(&document.text, position))
    }

    /// The files of the document at `at` (the document first, then what it includes) and what its cursor is
    /// on.
    fn cursor(
        &self,
        at: &lsp_types::TextDocumentPositionParams,
    ) -> Option<(Vec<File>, here::Target)> {
        let offset = self.offset(&at.text_document.uri, at.position)?;
        let files = self.files_of(&at.text_document.uri);
        let file = files.first()?;
        let target = here::target(&file.text, &file.scan, offset)?;
        Some((files, target))
    }

    fn folder_and_resolver(
        &self,
        uri: &Url,
    ) -> Option<(PathBuf, urdf_validator::input::resolve::PackageResolver)> {
        let path = documents::path_of(uri)?;
        let dir = path.parent()?.to_path_buf();
        let config = config_file(&self.settings, &path);
        let session = self.sessions.get(&config)?.as_ref().ok()?;
        Some((dir, session.options().resolver.clone()))
    }

    fn hover(&self, params: lsp_types::HoverParams) -> Option<Hover> {
        let at = params.text_document_position_params;
        let uri = &at.text_document.uri;
        let (files, target) = self.cursor(&at)?;
        let file = files.first()?;
        let (dir, resolver) = self.folder_and_resolver(uri)?;
        let analysis = self.analysis_of(uri);
        let report = analysis.map(|a| &a.physics.as_ref().unwrap_or(&a.validation).report);
        let mut text = hover::text(&target, report, &files, &dir, &resolver)?;
        let physics_behind = analysis
            .and_then(|a| a.physics.as_ref().map(|p| !Arc::ptr_eq(p, &a.validation)))
            .unwrap_or(false);
        if matches!(target, here::Target::Name { .. }) && physics_behind {
            text.push_str(
                "  \n_(physics of the text before the last edit: its analysis is running)_",
            );
        }
        let span = match &target {
            here::Target::Name { span, .. }
            | here::Target::Xacro { span, .. }
            | here::Target::Path { span, .. }
            | here::Target::Rule { span, .. } => span.clone(),
        };
        Some(Hover {
            contents: HoverContents::Markup(MarkupContent {
                kind: MarkupKind::Markdown,
                value: text,
            }),
            range: Some(file.index.range(&file.text, span.start, span.end)),
        })
    }

    fn definition(
        &self,
        params: lsp_types::GotoDefinitionParams,
    ) -> Option<GotoDefinitionResponse> {
        let at = params.text_document_position_params;
        let (files, target) = self.cursor(&at)?;
        let (dir, resolver) = self.folder_and_resolver(&at.text_document.uri)?;
        let locations = navigation::definition(&target, &files, &dir, &resolver);
        (!locations.is_empty()).then_some(GotoDefinitionResponse::Array(locations))
    }

    fn references(&self, params: lsp_types::ReferenceParams) -> Option<Vec<lsp_types::Location>> {
        let (files, target) = self.cursor(&params.text_document_position)?;
        Some(navigation::references(
            &target,
            &files,
            params.context.include_declaration,
        ))
    }

    fn symbols(
        &self,
        params: lsp_types::DocumentSymbolParams,
    ) -> Option<lsp_types::DocumentSymbolResponse> {
        let uri = params.text_document.uri;
        let document = self.documents.get(&uri)?;
        let file = File::new(uri, document.text.clone());
        Some(lsp_types::DocumentSymbolResponse::Nested(
            navigation::symbols(&file),
        ))
    }

    fn completion(
        &self,
        params: lsp_types::CompletionParams,
    ) -> Option<lsp_types::CompletionResponse> {
        let at = params.text_document_position;
        let uri = &at.text_document.uri;
        let offset = self.offset(uri, at.position)?;
        let files = self.files_of(uri);
        let file = files.first()?;
        Some(lsp_types::CompletionResponse::Array(completion::items(
            file, offset, &files,
        )))
    }

    fn code_actions(
        &self,
        params: lsp_types::CodeActionParams,
    ) -> Option<lsp_types::CodeActionResponse> {
        let uri = &params.text_document.uri;
        let analysis = self.analysis_of(uri)?;
        Some(code_actions::actions(
            uri,
            params.range,
            params.context.only.as_deref(),
            &analysis.validation,
            &self.documents,
        ))
    }
}
