//! What every front end of urdf-validator shares: the command line, the MCP server, the language server
//! and the Python module each map their own input onto a [`Request`], and validate through a
//! [`Session`] (the library options for the files one configuration file governs) or a [`Batch`] (one
//! session per configuration file, the files on threads of their own).
//!
//! No command-line parser, no async runtime, no protocol crate lives here: only what the front ends
//! must agree on, so that a report is the same whichever of them asked for it.

pub mod batch;
pub mod config;
pub mod discovery;
pub mod options;
pub mod request;
mod session;
pub mod tasks;
pub mod watchdog;

pub use request::Request;
pub use session::{config_file, Batch, Session};
