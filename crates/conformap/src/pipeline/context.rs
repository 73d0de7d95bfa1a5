//! The context a run happens in: who watches its progress (the CLI's spinner, or nobody)
//! and the memory budget it shares with other runs (`batch --jobs N`).
//!
//! The context is per thread and scoped ([`RunContext::scope`]): [`crate::pipeline::run_map`]
//! reports its stages with [`stage`] and reserves its memory estimate with [`reserve`], and
//! both do nothing outside a scope (library callers, the Python package, tests). So every
//! job gets progress and the budget without passing them down.

use std::cell::RefCell;
use std::sync::{Arc, Condvar, Mutex};

/// Who is told what a run is doing: a front end's progress display. Library code never
/// prints; it tells the watcher of its thread, if there is one.
pub trait Watcher: Send + Sync {
    /// The run is now doing `message` (`"reading m.obj"`).
    fn stage(&self, message: &str);
    /// A batch starts on `total` inputs.
    fn started(&self, total: usize) {
        let _ = total;
    }
    /// A batch finished `done` of its inputs, the last one named `name`.
    fn advanced(&self, done: usize, name: &str) {
        let _ = (done, name);
    }
    /// Something the user should know that is neither progress nor the result (stale
    /// staging files removed); a front end prints it on stderr.
    fn notice(&self, message: &str) {
        let _ = message;
    }
    /// Runs `print` (a batch line going to stdout) so that it does not tear the display.
    fn suspend(&self, print: &mut dyn FnMut()) {
        print();
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
#[derive(Clone, Default)]
pub struct RunContext {
    /// Who [`stage`] messages go to.
    pub watcher: Option<Arc<dyn Watcher>>,
    /// Where [`reserve`] reserves.
    pub budget: Option<Arc<MemoryBudget>>,
}

thread_local! {
    static CURRENT: RefCell<RunContext> = RefCell::new(RunContext::default());
}

impl std::fmt::Debug for RunContext {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("RunContext")
            .field("watcher", &self.watcher.is_some())
            .field("budget", &self.budget)
            .finish()
    }
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
        if let Some(watcher) = &c.borrow().watcher {
            watcher.stage(&message.into());
        }
    });
}

/// Tells the thread's watcher something the user should know (no-op without one).
pub fn notice(message: impl Into<String>) {
    if let Some(watcher) = watcher() {
        watcher.notice(&message.into());
    }
}

/// The watcher of this thread's runs, if any.
pub fn watcher() -> Option<Arc<dyn Watcher>> {
    CURRENT.with(|c| c.borrow().watcher.clone())
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
    use std::time::Duration;

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
