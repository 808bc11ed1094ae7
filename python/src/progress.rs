//! Long calls: the work runs on its own thread with the GIL released, while
//! the calling thread draws a progress bar (`stickslip._progress.Bar`: tqdm
//! when it is installed, a line on stderr otherwise) from a shared counter.

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{mpsc, Mutex};
use std::time::Duration;

use pyo3::prelude::*;

/// Run `work` (given a counter of the units it has done) with the GIL
/// released; with `show`, a bar of `total` units named `what` follows the
/// counter every 0.1 s (from the first 0.1 s on: a call that ends or fails
/// sooner draws none).
pub fn with_progress<T: Send>(
    py: Python<'_>,
    show: bool,
    total: u64,
    what: &str,
    work: impl FnOnce(&AtomicU64) -> T + Send,
) -> PyResult<T> {
    let done = AtomicU64::new(0);
    if !show {
        return Ok(py.detach(|| work(&done)));
    }
    let mut bar: Option<Bound<'_, PyAny>> = None;
    let result = std::thread::scope(|scope| -> PyResult<T> {
        let (tx, rx) = mpsc::channel();
        // Shared with the detached waits (a receiver alone is not `Sync`).
        let rx = Mutex::new(rx);
        let counter = &done;
        scope.spawn(move || {
            // The receiver outlives the thread: the send cannot fail.
            let _ = tx.send(work(counter));
        });
        loop {
            let got = py.detach(|| match rx.lock() {
                Ok(rx) => rx.recv_timeout(Duration::from_millis(100)),
                Err(_) => Err(mpsc::RecvTimeoutError::Disconnected),
            });
            match got {
                Ok(result) => {
                    if let Some(bar) = &bar {
                        bar.call_method1("update_to", (done.load(Ordering::Relaxed),))?;
                    }
                    return Ok(result);
                }
                Err(mpsc::RecvTimeoutError::Timeout) => {
                    let shown = match &bar {
                        Some(shown) => shown,
                        None => bar.insert(
                            py.import("stickslip._progress")?
                                .getattr("Bar")?
                                .call1((total, what))?,
                        ),
                    };
                    shown.call_method1("update_to", (done.load(Ordering::Relaxed),))?;
                }
                Err(mpsc::RecvTimeoutError::Disconnected) => {
                    return Err(pyo3::exceptions::PyRuntimeError::new_err(
                        "the computation stopped without a result",
                    ))
                }
            }
        }
    });
    if let Some(bar) = bar {
        bar.call_method0("close")?;
    }
    result
}
