//! The context a run happens in: where its progress goes (an `indicatif` spinner on stderr,
//! or nowhere) and the memory budget it shares with other runs (`batch --jobs N`).
//!
//! The context is per thread and scoped ([`RunContext::scope`]): [`crate::pipeline::run_map`]
//! reports its stages with [`stage`] and reserves its memory estimate with [`reserve`], and
//! both do nothing outside a scope (library callers, the Python package, tests). So the
//! command dispatch stays as it is, and every map command gets progress and the budget.

use std::cell::RefCell;
use std::io::IsTerminal;
use std::sync::mpsc;
use std::sync::{Arc, Condvar, Mutex};
use std::time::Duration;

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

/// A memory budget shared by concurrent runs: a run waits until its estimate fits beside
/// the estimates of the runs going on (a run alone always starts: whether it fits at all is
/// its own memory check's business, as in a single run).
#[derive(Debug)]
pub struct MemoryBudget {
    total: u64,
    used: Mutex<u64>,
    freed: Condvar,
}

impl MemoryBudget {
    /// A budget of `total` bytes.
    pub fn new(total: u64) -> Arc<Self> {
        Arc::new(Self {
            total,
            used: Mutex::new(0),
            freed: Condvar::new(),
        })
    }

    /// The bytes reserved now.
    pub fn used(&self) -> u64 {
        *self.used.lock().unwrap_or_else(|p| p.into_inner())
    }

    /// Waits until `bytes` fit (or nothing else is reserved) and reserves them. Whoever
    /// waits holds nothing, so runs cannot wait on each other in a cycle.
    pub fn reserve(self: &Arc<Self>, bytes: u64) -> Reservation {
        let mut used = self.used.lock().unwrap_or_else(|p| p.into_inner());
        while *used > 0 && used.saturating_add(bytes) > self.total {
            used = self.freed.wait(used).unwrap_or_else(|p| p.into_inner());
        }
        *used += bytes;
        Reservation {
            budget: Some(Arc::clone(self)),
            bytes,
        }
    }
}

/// Bytes reserved in a [`MemoryBudget`], given back when dropped.
#[derive(Debug)]
pub struct Reservation {
    budget: Option<Arc<MemoryBudget>>,
    bytes: u64,
}

impl Drop for Reservation {
    fn drop(&mut self) {
        if let Some(b) = self.budget.take() {
            let mut used = b.used.lock().unwrap_or_else(|p| p.into_inner());
            *used = used.saturating_sub(self.bytes);
            b.freed.notify_all();
        }
    }
}

/// What the runs on this thread report to and reserve from.
#[derive(Debug, Clone, Default)]
pub struct RunContext {
    /// Where [`stage`] messages go.
    pub progress: Option<ProgressBar>,
    /// Where [`reserve`] reserves.
    pub budget: Option<Arc<MemoryBudget>>,
}

thread_local! {
    static CURRENT: RefCell<RunContext> = RefCell::new(RunContext::default());
}

impl RunContext {
    /// Runs `f` with this context as the thread's, then restores the previous one.
    pub fn scope<T>(&self, f: impl FnOnce() -> T) -> T {
        let previous = CURRENT.with(|c| c.replace(self.clone()));
        struct Restore(Option<RunContext>);
        impl Drop for Restore {
            fn drop(&mut self) {
                if let Some(p) = self.0.take() {
                    CURRENT.with(|c| *c.borrow_mut() = p);
                }
            }
        }
        let _restore = Restore(Some(previous));
        f()
    }
}

/// Tells the thread's progress display what the run is doing now (no-op without one).
pub fn stage(message: impl Into<String>) {
    CURRENT.with(|c| {
        if let Some(bar) = &c.borrow().progress {
            bar.set_message(message.into());
        }
    });
}

/// Reserves `bytes` in the thread's memory budget, waiting until they fit (no-op without
/// one).
pub fn reserve(bytes: u64) -> Reservation {
    let budget = CURRENT.with(|c| c.borrow().budget.clone());
    match budget {
        Some(b) => b.reserve(bytes),
        None => Reservation {
            budget: None,
            bytes: 0,
        },
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

    #[test]
    fn budget_waits_until_a_reservation_is_freed() {
        let budget = MemoryBudget::new(100);
        let a = budget.reserve(70);
        // alone, a run always starts, even above the budget
        assert_eq!(budget.used(), 70);
        let b2 = Arc::clone(&budget);
        let waiter = std::thread::spawn(move || {
            let _r = b2.reserve(50);
            b2.used()
        });
        std::thread::sleep(Duration::from_millis(50));
        assert_eq!(budget.used(), 70, "50 more must wait beside 70 of 100");
        drop(a);
        assert_eq!(waiter.join().ok(), Some(50));
        assert_eq!(budget.used(), 0);
    }
}
