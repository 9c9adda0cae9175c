//! A spinner on standard error for work that takes more than a second; it never shows when
//! standard error is not a terminal, so scripts and `--json` output stay clean.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::time::Duration;

/// Delay before the spinner appears.
const SHOW_AFTER: Duration = Duration::from_secs(1);

/// A named-stage spinner.
pub struct Progress {
    bar: ProgressBar,
}

impl Progress {
    /// Starts a spinner with `message`; it appears only if the work is still running after a
    /// second.
    pub fn start(message: &str) -> Progress {
        let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::hidden());
        if let Ok(style) = ProgressStyle::with_template("{spinner} {elapsed:>3} {msg}") {
            bar.set_style(style);
        }
        bar.set_message(message.to_string());
        let shown = bar.clone();
        std::thread::spawn(move || {
            std::thread::sleep(SHOW_AFTER);
            if !shown.is_finished() {
                shown.set_draw_target(ProgressDrawTarget::stderr());
                shown.enable_steady_tick(Duration::from_millis(120));
            }
        });
        Progress { bar }
    }

    /// Names the stage now running.
    pub fn stage(&self, message: &str) {
        self.bar.set_message(message.to_string());
    }

    /// Removes the spinner.
    pub fn finish(&self) {
        self.bar.finish_and_clear();
    }
}

impl Drop for Progress {
    fn drop(&mut self) {
        self.bar.finish_and_clear();
    }
}
