//! The progress bar of batch runs: on stderr, only when stderr is a terminal, not in CI (`CI` set) and
//! only for more than a few files. It is cleared before the reports are printed.

use std::io::IsTerminal;
use std::path::Path;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// Batches of at most this many files get no bar.
const MIN_FILES: usize = 4;

/// A progress bar, or nothing.
pub struct Bar(Option<ProgressBar>);

impl Bar {
    /// A bar for `files` inputs when it should be shown (see the module doc), else a no-op.
    pub fn for_batch(files: usize) -> Bar {
        let ci = std::env::var_os("CI").is_some_and(|v| !v.is_empty());
        Bar(
            should_show(files, std::io::stderr().is_terminal(), ci).then(|| {
                let bar = ProgressBar::with_draw_target(
                    Some(u64::try_from(files).unwrap_or(u64::MAX)),
                    ProgressDrawTarget::stderr(),
                );
                if let Ok(style) = ProgressStyle::with_template(
                    "{bar:30} {pos}/{len} files  {elapsed}  {wide_msg}",
                ) {
                    bar.set_style(style);
                }
                bar
            }),
        )
    }

    /// One more file done.
    pub fn tick(&self, file: &Path) {
        if let Some(bar) = &self.0 {
            bar.set_message(file.display().to_string());
            bar.inc(1);
        }
    }

    /// Remove the bar.
    pub fn finish(&self) {
        if let Some(bar) = &self.0 {
            bar.finish_and_clear();
        }
    }
}

/// Whether to draw: more than a few files, on a terminal, not in CI.
fn should_show(files: usize, stderr_is_terminal: bool, ci: bool) -> bool {
    files >= MIN_FILES && stderr_is_terminal && !ci
}

#[cfg(test)]
mod tests {
    use super::should_show;

    #[test]
    fn only_batches_on_a_terminal_outside_ci() {
        assert!(should_show(10, true, false));
        assert!(!should_show(3, true, false));
        assert!(!should_show(10, false, false));
        assert!(!should_show(10, true, true));
    }
}
