//! `urdf_validate mcp`: the validator as a Model Context Protocol server on stdin/stdout, for AI agents.
//!
//! The tools (`tools`) keep the names and arguments of the Python tool's MCP server where the feature
//! exists here. Each call runs off the async executor, so the server keeps answering while it works.
//! A failure (a missing file, a bad argument, an unknown rule) is a tool result with `isError` and a
//! one-line message; the server goes on. stdout carries the protocol only; messages go to stderr.

mod arguments;
mod policy;
mod table;
mod tools;

use std::ffi::OsString;
use std::io::{IsTerminal, Write};

use rmcp::model::{
    CallToolRequestParams, CallToolResponse, CallToolResult, ContentBlock, Implementation,
    ListToolsResult, PaginatedRequestParams, ServerCapabilities, ServerConfig,
};
use rmcp::service::{NotificationContext, Peer, RequestContext, ServerInitializeError};
use rmcp::{ErrorData, RoleServer, ServerHandler, ServiceExt};

/// `urdf_validate mcp --help`.
pub(crate) const HELP: &str = "\
Serve the validator to AI agents over the Model Context Protocol (MCP), on stdin/stdout.

Usage: urdf_validate mcp [--root DIR]... [--allow-env NAME]... [--trusted]

An MCP client (Claude Desktop, an agent framework) starts this command and speaks JSON-RPC to it, one
message a line; messages for people go to stderr. Tools: validate_urdf, validate_urdf_string,
run_pick_task, run_pick_sweep, list_rules, explain_rule. Client set-up and every tool's arguments:
https://urdf-validator.github.io/urdf-validator/integrations/mcp.html. Relative paths in tool arguments start from this command's working directory.

Untrusted by default: an agent passes on files and text from anywhere, so every validation runs as
`urdf_validate --untrusted` (see SECURITY.md). Path arguments must be inside the --root folders
(repeatable) or the roots the client declares (MCP roots/list; with neither, the working directory),
files are read only from there, no environment variable is read unless --allow-env NAME names it, `xml`
is at most 4 MiB and every call has a time limit (timeout 0 is refused). --trusted turns this off.

A file named `mcp` is validated as `urdf_validate ./mcp`.
";

/// What the server tells clients on `initialize`.
const INSTRUCTIONS: &str = "Physics-aware validation of robot descriptions (URDF and xacro). \
validate_urdf returns the full JSON report (overall_status PASS, WARN, FAIL or UNKNOWN; findings with \
rule codes and file:line:col; statics, stability and workspace sections); explain_rule explains a rule \
code; run_pick_task answers whether the robot can pick an object at a place. Paths are files on the \
machine that runs the server; relative ones start from its working directory, so prefer absolute \
paths. Each call is independent and writes no report file.";

/// Run `urdf_validate mcp ARGS`: serve until stdin closes. Exit status 0, or 2 when the server cannot run.
pub(crate) fn main(args: &[OsString]) -> u8 {
    if args.iter().any(|arg| arg == "-h" || arg == "--help") {
        out!("{HELP}");
        return 0;
    }
    match policy::Policy::parse(args) {
        Ok(policy) => policy.install(),
        Err(message) => {
            errln!("error: urdf_validate mcp: {message}");
            return 2;
        }
    }
    if std::io::stdin().is_terminal() {
        errln!(
            "urdf_validate mcp: an MCP server, waiting for JSON-RPC on stdin (one message a line); \
             Ctrl-D ends it. An MCP client starts it: see https://urdf-validator.github.io/urdf-validator/integrations/mcp.html."
        );
    }
    let runtime = match tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .build()
    {
        Ok(runtime) => runtime,
        Err(error) => {
            errln!("error: urdf_validate mcp: cannot start: {error}");
            return 2;
        }
    };
    let status = runtime.block_on(serve());
    // Do not wait for a validation still running for a client that has gone, nor for the blocked read
    // of stdin.
    runtime.shutdown_background();
    status
}

/// Serve on stdin/stdout until the client closes stdin.
async fn serve() -> u8 {
    let service = match Server.serve(rmcp::transport::stdio()).await {
        Ok(service) => service,
        // stdin closed before `initialize`: nothing was asked.
        Err(ServerInitializeError::ConnectionClosed(_)) => return 0,
        Err(error) => {
            errln!("error: urdf_validate mcp: {error}");
            return 2;
        }
    };
    match service.waiting().await {
        Ok(_) => 0,
        Err(error) => {
            errln!("error: urdf_validate mcp: {error}");
            2
        }
    }
}

/// The server: stateless, every call stands alone.
struct Server;

impl ServerHandler for Server {
    fn get_info(&self) -> ServerConfig {
        ServerConfig::new(ServerCapabilities::builder().enable_tools().build())
            .with_server_info(Implementation::new(
                "urdf_validator",
                env!("CARGO_PKG_VERSION"),
            ))
            .with_instructions(INSTRUCTIONS)
    }

    async fn list_tools(
        &self,
        _request: Option<PaginatedRequestParams>,
        _context: RequestContext<RoleServer>,
    ) -> Result<ListToolsResult, ErrorData> {
        Ok(ListToolsResult::with_all_items(table::listed().to_vec()))
    }

    async fn on_initialized(&self, context: NotificationContext<RoleServer>) {
        let peer = context.peer;
        tokio::spawn(async move { refresh_roots(&peer).await });
    }

    async fn on_roots_list_changed(&self, context: NotificationContext<RoleServer>) {
        refresh_roots(&context.peer).await;
    }

    async fn call_tool(
        &self,
        request: CallToolRequestParams,
        context: RequestContext<RoleServer>,
    ) -> Result<CallToolResponse, ErrorData> {
        // A call that comes before the answer to the first `roots/list`: ask now, so the client's roots
        // bound this call too.
        if offers_roots(&context.peer) && !policy::Policy::current().has_client_roots() {
            refresh_roots(&context.peer).await;
        }
        let Some(tool) = table::find(&request.name) else {
            // The one protocol error: the spec's answer to a tool that does not exist.
            return Err(ErrorData::invalid_params(
                format!(
                    "no tool '{}' (tools: {})",
                    request.name,
                    table::names().join(", ")
                ),
                None,
            ));
        };
        let arguments = request.arguments.unwrap_or_default();
        let result = match tokio::task::spawn_blocking(move || table::call(tool, arguments)).await {
            Ok(Ok(output)) => output.into_result(),
            Ok(Err(message)) => CallToolResult::error(vec![ContentBlock::text(message)]),
            Err(error) => CallToolResult::error(vec![ContentBlock::text(format!(
                "internal error in {}: {error}",
                request.name
            ))]),
        };
        Ok(result.into())
    }
}

/// True when the client declared the `roots` capability on `initialize`.
fn offers_roots(peer: &Peer<RoleServer>) -> bool {
    peer.peer_info()
        .is_some_and(|info| info.capabilities.roots.is_some())
}

/// Ask a client that offers roots for them (`roots/list`): with the `--root` folders they bound what the
/// tools may read (the MCP spec's roots). A root that is not a folder here is left out, said on stderr.
/// rmcp marks roots deprecated (SEP-2577 replaces them in a later protocol revision); the clients of the
/// revisions this server speaks still declare them, and `--root` stays for those that do not.
#[allow(deprecated)]
async fn refresh_roots(peer: &Peer<RoleServer>) {
    if !offers_roots(peer) {
        return;
    }
    match peer.list_roots().await {
        Ok(listed) => {
            let uris: Vec<String> = listed.roots.into_iter().map(|root| root.uri).collect();
            for uri in policy::Policy::set_client_roots(&uris) {
                errln!("urdf_validate mcp: client root {uri} left out: not a file:// folder on this machine");
            }
        }
        Err(error) => errln!("urdf_validate mcp: roots/list failed: {error}"),
    }
}
