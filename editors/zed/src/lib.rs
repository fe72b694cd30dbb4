//! The Zed extension of urdf-validator: starts the installed `urdf_validate server` (found on the PATH of the
//! worktree's shell) as the language server of XML files, which `.urdf`, `.xacro`, `.sdf` and `.world`
//! files are once associated with XML in Zed's settings.

use zed_extension_api as zed;

/// The extension: it keeps no state.
struct UrdfValidate;

impl zed::Extension for UrdfValidate {
    fn new() -> Self {
        UrdfValidate
    }

    fn language_server_command(
        &mut self,
        _language_server_id: &zed::LanguageServerId,
        worktree: &zed::Worktree,
    ) -> zed::Result<zed::Command> {
        let command = worktree.which("urdf_validate").ok_or_else(|| {
            "urdf_validate is not on the PATH: install it (pip install urdf-validator, or cargo install \
             --path crates/cli in the urdf-validator repository)"
                .to_string()
        })?;
        Ok(zed::Command {
            command,
            args: vec!["server".into()],
            env: Vec::new(),
        })
    }
}

zed::register_extension!(UrdfValidate);
