//! The tools of `urdf_validate mcp`: the table `tools/list` shows (names, descriptions, argument schemas)
//! and the dispatch of a call to its tool, with the answer every tool gives ([`Output`]).

use std::sync::{Arc, LazyLock};

use rmcp::model::{CallToolResult, ContentBlock, JsonObject, Tool, ToolAnnotations};
use serde::Serialize;
use serde_json::Value;
use urdf_validator::report::Report;
use urdf_validator::task_query::TaskQueryRequest;

use super::arguments::{
    check_names, merged, schema, FileInput, FixInput, Flags, NoArguments, RuleName, RunFlags,
    Sweep, TextInput,
};
use super::tools::{
    explain_rule, fix_urdf, list_rules, run_pick_sweep, run_pick_task, validate_urdf,
    validate_urdf_string,
};

/// One tool: what `tools/list` shows of it, and what a call runs.
pub struct ToolDef {
    /// Its name.
    name: &'static str,
    /// What it does, for the agent choosing a tool.
    description: &'static str,
    /// The JSON Schema of its arguments.
    schema: fn() -> JsonObject,
    /// The call, on checked argument names.
    run: fn(JsonObject) -> Result<Output, String>,
}

/// Every tool.
static TOOLS: &[ToolDef] = &[
    ToolDef {
        name: "validate_urdf",
        description: "Validate a robot description with the full physics-aware pipeline (structure, \
            mass and inertia, statics at a pose, stability, workspace reach, self-collision, and the \
            task, orientation and payload checks asked for). Give `path` (a URDF or xacro file) or `xml` \
            (URDF text, with `base_dir` for its relative mesh paths). The text result is the verdict and \
            every finding (severity, rule code, file:line:col, message); the structured result is the \
            complete JSON report `urdf_validate` writes as <name>_validation.json (overall_status PASS, \
            WARN, FAIL or UNKNOWN, confidence_level, the sections, findings[]; rule codes: see \
            explain_rule). The optional arguments are the CLI's flags; a urdf-validate.toml (or \
            pyproject.toml [tool.urdf-validate]) near the file applies, as on the command line. Writes \
            no report file. samples defaults to 30000 per arm (seconds on big robots); a few hundred \
            gives a quick, coarser workspace.",
        schema: || merged(schema::<FileInput>(), schema::<Flags>()),
        run: validate_urdf,
    },
    ToolDef {
        name: "validate_urdf_string",
        description: "validate_urdf with `xml` (the Python tool's server had this tool): URDF XML given \
            as text (not xacro) as `urdf_xml`. The text stands for the file robot.urdf in base_dir (default: the \
            server's working directory): relative mesh paths, package:// look-ups and the \
            configuration file start there. Takes validate_urdf's optional arguments.",
        schema: || merged(schema::<TextInput>(), schema::<Flags>()),
        run: validate_urdf_string,
    },
    ToolDef {
        name: "check_pick_task",
        description: "Can this robot pick an object of this mass at this place, in this orientation? \
            Runs the full pipeline with the target's height as the task, the orientation and the mass \
            as payload, and answers with five sub-checks: reach, reach_orientation, payload_strength, \
            stability_during_reach, self_collision, each PASS, FAIL, N/A (not asked) or UNKNOWN with a \
            reason (numbers), the bottleneck link or joint and a confidence. overall_status is FAIL when \
            a sub-check fails, else UNKNOWN when one could not be assessed, else PASS. A robot that \
            cannot be loaded gives an UNKNOWN urdf_load sub-check, not an error.",
        schema: || merged(schema::<TaskQueryRequest>(), schema::<RunFlags>()),
        run: run_pick_task,
    },
    ToolDef {
        name: "run_pick_task",
        description: "check_pick_task under the name the Python tool's MCP server used.",
        schema: || merged(schema::<TaskQueryRequest>(), schema::<RunFlags>()),
        run: run_pick_task,
    },
    ToolDef {
        name: "run_pick_sweep",
        description: "check_pick_task for every request of `requests`, in parallel: the responses in \
            request order, as {\"responses\": [...]}. A request that cannot run gets its own UNKNOWN \
            response and the others still run.",
        schema: || merged(schema::<Sweep>(), schema::<RunFlags>()),
        run: run_pick_sweep,
    },
    ToolDef {
        name: "fix_urdf",
        description: "The fixes of validate_urdf's findings for a file (`path`), as a unified diff of the \
            files the user edits (the xacro source for xacro input): what `urdf_validate --diff` prints. \
            Safe fixes only (an axis normalised, limits a continuous joint ignores removed, whitespace \
            before <?xml) unless `unsafe_fixes` (effort, limits, mesh scale: the robot changes). Writes \
            nothing; apply the diff, or run `urdf_validate --fix`. The structured result: diff, files, \
            fixes, unsafe_left (fixes left out for want of unsafe_fixes) and skipped (each with why).",
        schema: || merged(schema::<FixInput>(), schema::<Flags>()),
        run: fix_urdf,
    },
    ToolDef {
        name: "list_rules",
        description: "Every rule the validator reports: its code (U205), name, default severity, report \
            section and what it checks, as {\"rules\": [...]}.",
        schema: schema::<NoArguments>,
        run: list_rules,
    },
    ToolDef {
        name: "explain_rule",
        description: "A rule's documentation: what it checks, why it matters (which tool refuses or \
            misbehaves) and how to fix it. `code` is a code such as U205 or a name such as \
            inertia-not-positive-definite.",
        schema: schema::<RuleName>,
        run: explain_rule,
    },
];

/// The tools as `tools/list` gives them (schemas built once).
pub fn listed() -> &'static [Tool] {
    static LISTED: LazyLock<Vec<Tool>> = LazyLock::new(|| {
        TOOLS
            .iter()
            .map(|tool| {
                Tool::new(tool.name, tool.description, Arc::new((tool.schema)()))
                    .with_annotations(ToolAnnotations::new().read_only(true).open_world(false))
            })
            .collect()
    });
    &LISTED
}

/// The tool called `name`.
pub fn find(name: &str) -> Option<&'static ToolDef> {
    TOOLS.iter().find(|tool| tool.name == name)
}

/// The names of the tools.
pub fn names() -> Vec<&'static str> {
    TOOLS.iter().map(|tool| tool.name).collect()
}

/// Run `tool` on `arguments` (blocking): its output, or the one-line message of an error result.
pub fn call(tool: &ToolDef, arguments: JsonObject) -> Result<Output, String> {
    let schema = listed()
        .iter()
        .find(|listed| listed.name == tool.name)
        .map(|listed| listed.input_schema.clone())
        .unwrap_or_default();
    check_names(&arguments, &schema, tool.name)?;
    (tool.run)(arguments)
}

/// A tool's answer: JSON for programs (`structuredContent`) and text for the model.
pub struct Output {
    /// The JSON result.
    pub(super) structured: Value,
    /// The text shown for it.
    pub(super) text: String,
}

impl Output {
    /// `value`, shown as indented JSON.
    pub(super) fn json(value: &impl Serialize) -> Result<Output, String> {
        let structured = serde_json::to_value(value)
            .map_err(|error| format!("cannot serialise the result: {error}"))?;
        let text = serde_json::to_string_pretty(&structured).unwrap_or_default();
        Ok(Output { structured, text })
    }

    /// A validation report: the whole report as JSON, the verdict and the findings as text.
    pub(super) fn report(report: &Report) -> Result<Output, String> {
        let mut text = format!(
            "{}: {} (confidence {}), {} finding(s)\n",
            report.robot_name,
            report.overall_status.label(),
            report.confidence_level.label(),
            report.findings.len()
        );
        for finding in &report.findings {
            let at = match (&finding.file, finding.line, finding.column) {
                (Some(file), Some(line), Some(column)) => format!("{file}:{line}:{column}: "),
                (Some(file), _, _) => format!("{file}: "),
                _ => String::new(),
            };
            text.push_str(&format!(
                "{} {} {}: {at}{}\n",
                finding.severity.label(),
                finding.rule,
                finding.name,
                finding.message
            ));
        }
        Ok(Output {
            text,
            ..Output::json(report)?
        })
    }

    /// The successful tool result.
    pub fn into_result(self) -> CallToolResult {
        let mut result = CallToolResult::success(vec![ContentBlock::text(self.text)]);
        result.structured_content = Some(self.structured);
        result
    }
}
