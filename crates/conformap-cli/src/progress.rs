//! Progress on stderr: an `indicatif` spinner (a batch's bar) that appears only on a
//! terminal and only when the work takes over a second, told what the job is doing through
//! [`conformap::pipeline::context::Watcher`].

use std::io::IsTerminal;
use std::sync::mpsc;
use std::time::Duration;

use conformap::pipeline::context::Watcher;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// Work shorter than this shows no progress at all: 1 s (the spinner appears after it).
pub const SHOW_AFTER: Duration = Duration::from_secs(1);
/// Redraw interval of a visible spinner or bar: 100 ms.
pub const TICK: Duration = Duration::from_millis(100);

/// How progress is shown.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ProgressMode {
    /// Not at all: `--quiet`, or stderr is not a terminal (a pipe, a file, CI).
    Hidden,
    /// On the terminal without colours (`NO_COLOR` is set).
    Plain,
    /// On the terminal with colours.
    Colored,
}

impl ProgressMode {
    /// The mode for `quiet`, whether stderr is a terminal and whether `NO_COLOR` is set
    /// (to anything but the empty string, as no-color.org says).
    pub fn decide(quiet: bool, stderr_is_terminal: bool, no_color: bool) -> Self {
        match (quiet, stderr_is_terminal, no_color) {
            (true, _, _) | (_, false, _) => Self::Hidden,
            (false, true, true) => Self::Plain,
            (false, true, false) => Self::Colored,
        }
    }

    /// The mode of this process: [`Self::decide`] on the real stderr and environment.
    pub fn detect(quiet: bool) -> Self {
        let no_color = std::env::var_os("NO_COLOR").is_some_and(|v| !v.is_empty());
        Self::decide(quiet, std::io::stderr().is_terminal(), no_color)
    }

    /// The spinner's style (`{spinner} {msg}`, coloured or not).
    pub fn spinner_style(self) -> ProgressStyle {
        let template = match self {
            Self::Colored => "{spinner:.cyan} {msg} {elapsed:.dim}",
            _ => "{spinner} {msg} {elapsed}",
        };
        ProgressStyle::with_template(template).unwrap_or_else(|_| ProgressStyle::default_spinner())
    }

    /// A counting bar's style (`[=====>   ] 3/10 msg`).
    pub fn bar_style(self) -> ProgressStyle {
        let template = match self {
            Self::Colored => "{bar:30.cyan/blue} {pos}/{len} {msg} {elapsed:.dim}",
            _ => "{bar:30} {pos}/{len} {msg} {elapsed}",
        };
        ProgressStyle::with_template(template)
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .progress_chars("=> ")
    }
}

/// A progress display that stays hidden for [`SHOW_AFTER`] and then draws on stderr until
/// it is dropped (cleared then, leaving no trace).
#[derive(Debug)]
pub struct Progress {
    bar: ProgressBar,
    stop: Option<mpsc::Sender<()>>,
    watcher: Option<std::thread::JoinHandle<()>>,
}

impl Progress {
    /// A spinner (`mode` [`ProgressMode::Hidden`]: never drawn).
    pub fn spinner(mode: ProgressMode) -> Self {
        let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::hidden());
        bar.set_style(mode.spinner_style());
        Self::watched(bar, mode)
    }

    /// A bar counting to `len` (batch files).
    pub fn bar(mode: ProgressMode, len: u64) -> Self {
        let bar = ProgressBar::with_draw_target(Some(len), ProgressDrawTarget::hidden());
        bar.set_style(mode.bar_style());
        Self::watched(bar, mode)
    }

    fn watched(bar: ProgressBar, mode: ProgressMode) -> Self {
        if mode == ProgressMode::Hidden {
            return Self {
                bar,
                stop: None,
                watcher: None,
            };
        }
        let (stop, stopped) = mpsc::channel::<()>();
        let shown = bar.clone();
        let watcher = std::thread::spawn(move || {
            if let Err(mpsc::RecvTimeoutError::Timeout) = stopped.recv_timeout(SHOW_AFTER) {
                shown.set_draw_target(ProgressDrawTarget::stderr());
                shown.enable_steady_tick(TICK);
            }
        });
        Self {
            bar,
            stop: Some(stop),
            watcher: Some(watcher),
        }
    }

    /// The underlying bar (message, position; `suspend` to print around it).
    pub fn bar_handle(&self) -> &ProgressBar {
        &self.bar
    }
}

impl Drop for Progress {
    fn drop(&mut self) {
        // dropping the sender ends the watcher's wait at once
        drop(self.stop.take());
        if let Some(w) = self.watcher.take() {
            let _ = w.join();
        }
        self.bar.finish_and_clear();
    }
}

/// A job's watcher drawing on a progress bar: stages as its message, a batch's inputs as
/// its position.
#[derive(Debug, Clone)]
pub struct BarWatcher(pub ProgressBar);

impl Watcher for BarWatcher {
    fn started(&self, total: usize) {
        self.0.set_length(total as u64);
    }

    fn stage(&self, message: &str) {
        self.0.set_message(message.to_string());
    }

    fn advanced(&self, done: usize, name: &str) {
        self.0.set_position(done as u64);
        self.0.set_message(name.to_string());
    }

    fn notice(&self, message: &str) {
        self.0.suspend(|| eprintln!("{message}"));
    }

    fn suspend(&self, print: &mut dyn FnMut()) {
        self.0.suspend(print);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn progress_is_hidden_off_terminals_and_when_quiet() {
        assert_eq!(
            ProgressMode::decide(false, false, false),
            ProgressMode::Hidden
        );
        assert_eq!(
            ProgressMode::decide(true, true, false),
            ProgressMode::Hidden
        );
        assert_eq!(ProgressMode::decide(false, true, true), ProgressMode::Plain);
        assert_eq!(
            ProgressMode::decide(false, true, false),
            ProgressMode::Colored
        );
    }
}
