//! The command's options for programs: the Python package and the MCP server validate with exactly the
//! options `urdf_validate` would use for the same flags (configuration files included), without a
//! process per file.

use std::path::{Path, PathBuf};
use std::time::Duration;

use clap::{CommandFactory, FromArgMatches};
use urdf_validator::input::LoadError;
use urdf_validator::{Options, Validation};

use crate::args::Args;

/// Validation options built from command-line flags.
#[derive(Clone, Debug)]
pub struct Session {
    options: Options,
    timeout: Option<Duration>,
}

impl Session {
    /// The options `urdf_validate FLAGS...` would use for files near `anchor` (its configuration file
    /// is the nearest `urdf-validate.toml` or `pyproject.toml` from there, unless the flags name one or
    /// say `--no-config`). `flags` hold options only, no input paths; an unknown or malformed flag is an
    /// error naming it.
    pub fn from_flags(flags: &[String], anchor: Option<&Path>) -> Result<Session, String> {
        let argv = std::iter::once("urdf_validate".to_string()).chain(flags.iter().cloned());
        let matches = Args::command()
            .try_get_matches_from(argv)
            .map_err(|e| first_line(&e.to_string()))?;
        let args = Args::from_arg_matches(&matches).map_err(|e| first_line(&e.to_string()))?;
        if args.write_baseline.is_some() {
            return Err(
                "--write-baseline writes a file for a whole run of the command: run `urdf_validate ... \
                 --write-baseline FILE` (`--baseline FILE` is taken here)"
                    .to_string(),
            );
        }
        let (inputs, xacro_args) = crate::checked_inputs(&args)?;
        if let Some(input) = inputs.first() {
            return Err(format!(
                "unexpected input {} among the options (give paths separately)",
                input.display()
            ));
        }
        let timeout = crate::timeout_of(&args)?;
        let config = if args.no_config {
            None
        } else {
            args.config
                .clone()
                .or_else(|| crate::config::discover(anchor.unwrap_or(Path::new("."))))
        };
        let meshes = crate::mesh_cache(args.no_cache);
        let options =
            crate::configured_options(&args, &matches, config.as_deref(), &xacro_args, &meshes)?;
        Ok(Session { options, timeout })
    }

    /// How long one validation may take (`--timeout`; `None`: no limit).
    pub fn timeout(&self) -> Option<Duration> {
        self.timeout
    }

    /// The library options.
    pub fn options(&self) -> &Options {
        &self.options
    }

    /// Validate one file (within `--timeout`).
    pub fn validate(&self, path: &Path) -> Result<Validation, LoadError> {
        crate::outputs::validate_within(path, &self.options, self.timeout, urdf_validator::validate)
    }

    /// Validate every file in parallel (on threads of their own: [`crate::batch`]); one result per path, in
    /// order.
    pub fn validate_many(&self, paths: &[PathBuf]) -> Vec<Result<Validation, LoadError>> {
        crate::batch::map_files(paths, |path| self.validate(path))
    }

    /// Validate URDF `text`, as if read from `path` (relative meshes and the report's name use it), within
    /// `--timeout`.
    pub fn validate_text(&self, text: String, path: &Path) -> Result<Validation, LoadError> {
        crate::outputs::validate_within(path, &self.options, self.timeout, move |path, options| {
            urdf_validator::validate_text(text, path, options)
        })
    }
}

/// A clap error in one line, without its `error: ` prefix, with the allowed values when clap lists them
/// (`invalid value 'foo' for '--robot-type <TYPE>' [possible values: wheeled, ...]`).
pub(crate) fn first_line(message: &str) -> String {
    let mut lines = message.lines();
    let first = lines.next().unwrap_or_default();
    let first = first.strip_prefix("error: ").unwrap_or(first);
    match lines
        .map(str::trim)
        .find(|l| l.starts_with("[possible values"))
    {
        Some(values) => format!("{first} {values}"),
        None => first.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flags_become_the_options_the_command_uses() {
        let session = Session::from_flags(
            &[
                "--samples".into(),
                "1234".into(),
                "--payload-mass".into(),
                "2".into(),
            ],
            None,
        )
        .expect("session");
        assert_eq!(session.options().workspace.samples, 1234);
        assert_eq!(session.options().statics.payload_mass, Some(2.0));
    }

    #[test]
    fn xacro_arguments_reach_the_options() {
        let session = Session::from_flags(&["--xacro-arg=arm:=ur5".into()], None).expect("session");
        assert_eq!(
            session.options().xacro_args,
            [("arm".to_string(), "ur5".to_string())]
        );
    }

    #[test]
    fn an_unknown_flag_is_named() {
        let error =
            Session::from_flags(&["--sampels".into(), "3".into()], None).expect_err("unknown flag");
        assert!(error.contains("--sampels"), "{error}");
        let error =
            Session::from_flags(&["--samples".into(), "0".into()], None).expect_err("no samples");
        assert!(error.contains("--samples"), "{error}");
        let error = Session::from_flags(&["--robot-type".into(), "boat".into()], None)
            .expect_err("unknown robot type");
        assert!(error.contains("possible values: wheeled"), "{error}");
        let error =
            Session::from_flags(&["--payload-mass=-3".into()], None).expect_err("negative payload");
        assert!(error.contains("--payload-mass -3"), "{error}");
        let error = Session::from_flags(&["--write-baseline=b.json".into()], None)
            .expect_err("a command-level flag");
        assert!(error.starts_with("--write-baseline"), "{error}");
        let error = Session::from_flags(&["--baseline=missing.json".into()], None)
            .expect_err("an absent baseline");
        assert!(error.contains("baseline missing.json"), "{error}");
    }
}
