//! The progress of a long study ([`map`](super::map), [`basins`](super::basins)):
//! the bar the command-line tool draws on a terminal, and a counter of the
//! finished points that another thread reads while the run goes on (the
//! Python package draws its own bar from it).

use std::sync::atomic::{AtomicU64, Ordering};

use indicatif::ProgressBar;

/// Where a run reports each finished point: its bar (hidden unless asked
/// for) and, when given, a shared counter.
pub(crate) struct Progress<'a> {
    bar: ProgressBar,
    counter: Option<&'a AtomicU64>,
}

impl<'a> Progress<'a> {
    /// Report to `bar` and `counter`, `done` points being finished already
    /// (the counter is set to it; the bar is positioned by its maker).
    pub(crate) fn new(bar: ProgressBar, counter: Option<&'a AtomicU64>, done: u64) -> Self {
        if let Some(c) = counter {
            c.store(done, Ordering::Relaxed);
        }
        Self { bar, counter }
    }

    /// One more point finished.
    pub(crate) fn inc(&self) {
        self.bar.inc(1);
        if let Some(c) = self.counter {
            c.fetch_add(1, Ordering::Relaxed);
        }
    }

    /// The run is over: clear the bar.
    pub(crate) fn finish(&self) {
        self.bar.finish_and_clear();
    }
}
