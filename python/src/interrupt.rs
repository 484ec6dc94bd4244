//! Long computations on a thread of their own, so that Ctrl-C stops them: the calling thread
//! waits without the GIL and checks for signals every [`POLL`], and raises the signal's
//! exception (KeyboardInterrupt) at once, telling the computation to stop.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{sync_channel, RecvTimeoutError, SyncSender};
use std::sync::{Arc, Mutex};
use std::time::Duration;

use pyo3::exceptions::{PyMemoryError, PyRuntimeError};
use pyo3::prelude::*;

/// How often the waiting thread checks for signals.
const POLL: Duration = Duration::from_millis(50);

/// Stack of a computation's thread: what the main thread of a program gets.
const STACK_BYTES: usize = 8 * 1024 * 1024;

/// Parts a computation may have sent and the caller not yet taken: the memory a sweep holds
/// beyond its table is this many chunks of rows.
const PARTS_IN_FLIGHT: usize = 2;

/// Set once the caller has stopped waiting: the computation starts no further work.
#[derive(Clone, Default)]
pub(crate) struct Cancel(Arc<AtomicBool>);

impl Cancel {
    pub(crate) fn is_set(&self) -> bool {
        self.0.load(Ordering::Relaxed)
    }

    fn set(&self) {
        self.0.store(true, Ordering::Relaxed);
    }
}

/// Hands a part of the result to the caller; false once the caller has stopped waiting.
pub(crate) struct Parts<P>(SyncSender<Message<P>>);

impl<P> Parts<P> {
    pub(crate) fn send(&self, part: P) -> bool {
        self.0.send(Message::Part(part)).is_ok()
    }
}

enum Message<P> {
    Part(P),
    /// The computation has ended (its result is in its thread's join handle).
    Done,
}

/// `work()` on a thread of its own, this thread waiting without the GIL and checking for
/// signals. The signal's exception (KeyboardInterrupt for Ctrl-C) is raised within [`POLL`];
/// the computation runs on until it ends, its result thrown away: use [`run_in_parts`] for
/// work that can stop early.
pub(crate) fn run<R: Send + 'static>(
    py: Python<'_>,
    work: impl FnOnce() -> R + Send + 'static,
) -> PyResult<R> {
    run_in_parts(py, move |_, _: &Parts<()>| work(), |_| Ok(()))
}

/// `work(cancel, parts)` on a thread of its own. This thread waits without the GIL, hands each
/// part `work` sends to `take` (with the GIL) and checks for signals every [`POLL`]. The
/// signal's exception, or an error of `take`, is raised at once: `cancel` is set, and `work`
/// is left to finish what it has under way on its own thread (it should look at `cancel`
/// before starting anything long, and stop when a part cannot be sent).
pub(crate) fn run_in_parts<P: Send + 'static, R: Send + 'static>(
    py: Python<'_>,
    work: impl FnOnce(&Cancel, &Parts<P>) -> R + Send + 'static,
    mut take: impl FnMut(P) -> PyResult<()>,
) -> PyResult<R> {
    let cancel = Cancel::default();
    let (sender, receiver) = sync_channel(PARTS_IN_FLIGHT);
    // Locked by this thread alone: the lock lets it wait without the GIL.
    let receiver = Mutex::new(receiver);
    let handle = {
        let cancel = cancel.clone();
        std::thread::Builder::new()
            .name("flexrock".into())
            .stack_size(STACK_BYTES)
            .spawn(move || {
                let parts = Parts(sender);
                let result = work(&cancel, &parts);
                let _ = parts.0.send(Message::Done);
                result
            })
            .map_err(|e| {
                PyMemoryError::new_err(format!("cannot start the computation's thread: {e}"))
            })?
    };
    let stop = |e: PyErr| {
        cancel.set();
        e
    };
    loop {
        let received = py.detach(|| {
            let receiver = receiver.lock().unwrap_or_else(|e| e.into_inner());
            receiver.recv_timeout(POLL)
        });
        match received {
            Ok(Message::Part(part)) => take(part).map_err(stop)?,
            Ok(Message::Done) => break,
            Err(RecvTimeoutError::Timeout) => {}
            // The thread ended without saying so: it panicked.
            Err(RecvTimeoutError::Disconnected) => break,
        }
        py.check_signals().map_err(stop)?;
    }
    py.detach(|| handle.join()).map_err(|panic| {
        let message = panic
            .downcast_ref::<String>()
            .map(String::as_str)
            .or_else(|| panic.downcast_ref::<&str>().copied())
            .unwrap_or("(no message)");
        PyRuntimeError::new_err(format!(
            "the computation stopped on an internal error (a bug of flexrock): {message}"
        ))
    })
}
