//! The flags as a [`Request`] of the session crate, and the command-line checks that come before any file
//! is read.

use std::path::PathBuf;

use clap::parser::ValueSource;
use clap::{ArgMatches, CommandFactory, FromArgMatches};
use urdf_validate_session::discovery::{parse_xacro_arg_flag, split_xacro_args};
use urdf_validate_session::Request;

use crate::args::Args;

/// The paths to validate and the request of the flags. A value with a default (`--samples`, `--seed`)
/// is in the request only when the command line gives it, so that a configuration file can set it.
pub(crate) fn request_of(
    args: &Args,
    matches: &ArgMatches,
) -> Result<(Vec<PathBuf>, Request), String> {
    let overriding = !args.overrides.is_empty() || args.override_file.is_some();
    if args.from_overrides && !(args.fix || args.diff) {
        return Err(
            "--from-overrides writes the overrides as fixes: give it with --fix or --diff".into(),
        );
    }
    if args.from_overrides && !overriding {
        return Err("--from-overrides: no --override or --override-file to write".into());
    }
    if overriding && (args.fix || args.diff) && !args.from_overrides {
        return Err(
            "--override with --fix or --diff: the fixes would be computed for values the file does not hold; \
             add --from-overrides to write the overrides into the file"
                .into(),
        );
    }
    let (paths, mut xacro_args) = split_xacro_args(&args.inputs);
    for arg in &args.xacro_arg {
        xacro_args.push(parse_xacro_arg_flag(arg)?);
    }
    let given = |id: &str| matches.value_source(id) == Some(ValueSource::CommandLine);
    let request = Request {
        xacro_args,
        model: args.model.clone(),
        package_path: args.package_path.clone(),
        untrusted: args.untrusted,
        // Set by the caller when an HTML report is among the outputs.
        view: false,
        root: args.root.clone(),
        allow_env: args.allow_env.clone(),
        pose: Some(args.pose.clone()),
        joint_angles: args.joint_angles.clone(),
        srdf: args.srdf.clone(),
        state: Some(args.state.clone()),
        samples: given("samples").then_some(args.samples),
        seed: given("seed").then_some(args.seed),
        payload_mass: args.payload_mass,
        payload_link: args.payload_link.clone(),
        robot_type: args.robot_type,
        up_axis: args.up_axis,
        contact_links: args.contact_links.clone(),
        arm_root: args.arm_root.clone(),
        arm_tip: args.arm_tip.clone(),
        task: args.task.clone(),
        height: args.height,
        orientation: args.orientation.clone(),
        orientation_tolerance: Some(args.orientation_tolerance),
        approach_axis: args.approach_axis.clone(),
        timings: args.timings,
        no_cache: args.no_cache,
        deep: args.deep,
        simulator: args.simulator.clone(),
        timeout: Some(args.timeout),
        select: args.select.clone(),
        ignore: args.ignore.clone(),
        show_suppressed: args.show_suppressed,
        config: args.config.clone(),
        no_config: args.no_config,
        overrides: args.overrides.clone(),
        override_file: args.override_file.clone(),
        baseline: args.baseline.clone(),
    };
    request.check()?;
    Ok((paths, request))
}

/// The request of option flags alone (`urdf_validate server FLAGS`): an unknown or malformed flag, an input
/// path or a flag of a whole run (`--write-baseline`) is an error naming it.
pub(crate) fn request_from_flags(flags: &[String]) -> Result<Request, String> {
    let argv = std::iter::once("urdf_validate".to_string()).chain(flags.iter().cloned());
    let matches = Args::command()
        .try_get_matches_from(argv)
        .map_err(|e| first_line(&e.to_string()))?;
    let args = Args::from_arg_matches(&matches).map_err(|e| first_line(&e.to_string()))?;
    if args.write_baseline.is_some() {
        return Err(
            "--write-baseline writes a file for a whole run of the command: run `urdf_validate ... \
             --write-baseline FILE`"
                .to_string(),
        );
    }
    let (inputs, request) = request_of(&args, &matches)?;
    if let Some(input) = inputs.first() {
        return Err(format!(
            "unexpected input {} among the options (give paths separately)",
            input.display()
        ));
    }
    Ok(request)
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

/// For a subcommand's own option `name` (`--port`, `--format`): its value when `word` is `NAME VALUE`
/// (the value taken from `words`; empty when nothing follows) or `NAME=VALUE`, else `None`.
pub fn option_value<'a>(
    word: &str,
    name: &str,
    words: &mut impl Iterator<Item = &'a std::ffi::OsString>,
) -> Option<String> {
    if word == name {
        return Some(
            words
                .next()
                .map(|v| v.to_string_lossy().into_owned())
                .unwrap_or_default(),
        );
    }
    word.strip_prefix(name)?
        .strip_prefix('=')
        .map(str::to_string)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn flags(words: &[&str]) -> Result<Request, String> {
        request_from_flags(&words.iter().map(|w| w.to_string()).collect::<Vec<_>>())
    }

    #[test]
    fn flags_become_the_request() {
        let request = flags(&[
            "--samples",
            "1234",
            "--payload-mass",
            "2",
            "--xacro-arg=arm:=ur5",
        ])
        .expect("request");
        assert_eq!(request.samples, Some(1234));
        assert_eq!(request.payload_mass, Some(2.0));
        assert_eq!(request.xacro_args, [("arm".to_string(), "ur5".to_string())]);
        // A default is not a value given: the configuration file may set it.
        assert_eq!(flags(&[]).expect("request").seed, None);
    }

    #[test]
    fn a_bad_flag_is_named() {
        let error = |words: &[&str]| flags(words).expect_err("bad flags");
        assert!(error(&["--sampels", "3"]).contains("--sampels"));
        assert!(error(&["--samples", "0"]).contains("--samples"));
        assert!(error(&["--robot-type", "boat"]).contains("possible values: wheeled"));
        assert!(error(&["--write-baseline=b.json"]).starts_with("--write-baseline"));
        assert!(error(&["robot.urdf"]).contains("unexpected input robot.urdf"));
    }
}
