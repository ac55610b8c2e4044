//! Worker threads kept for the process, for the deforming mesh's per-frame phases
//! ([`super::gather`]). Starting threads for each phase costs more than the phase on a virtual
//! machine (`rouge bench deform` on the lent H200's 16 vCPUs: about 0.1 ms a thread, so
//! 16 threads made a 2.2 ms update 5 ms); these start once and wait for work.
//!
//! A job is a borrowed closure run for chunk indices `0..chunks`, on the workers and on the
//! calling thread together; [`Pool::run`] returns once every chunk is done, so the borrow
//! outlives every call of it (the one `unsafe` below rests on that).

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::{Arc, Condvar, Mutex, MutexGuard, OnceLock, PoisonError};

/// The job in flight: the closure with its lifetime erased, and its chunk count.
#[derive(Clone, Copy)]
struct Job {
    f: *const (dyn Fn(usize) + Sync + 'static),
    chunks: usize,
}

// SAFETY: the pointer is to a `Sync` closure, dereferenced only while `Pool::run` waits for its
// chunks (see `Pool::run`).
unsafe impl Send for Job {}

#[derive(Default)]
struct State {
    job: Option<Job>,
    /// Next chunk to hand out.
    next: usize,
    /// Chunks handed out or waiting, not yet finished.
    pending: usize,
    panicked: bool,
}

#[derive(Default)]
struct Shared {
    state: Mutex<State>,
    work: Condvar,
    done: Condvar,
}

fn lock(m: &Mutex<State>) -> MutexGuard<'_, State> {
    m.lock().unwrap_or_else(PoisonError::into_inner)
}

impl Shared {
    /// Takes the next chunk of the job in flight, if any is left.
    fn take(state: &mut State) -> Option<(Job, usize)> {
        let job = state.job?;
        (state.next < job.chunks).then(|| {
            state.next += 1;
            (job, state.next - 1)
        })
    }

    /// Runs chunk `c` of `job` and counts it done.
    fn run_chunk(&self, job: Job, c: usize) {
        // SAFETY: `Pool::run` keeps the closure borrowed until `pending` reaches 0, which
        // happens only after this call returns.
        let f = unsafe { &*job.f };
        let ok = catch_unwind(AssertUnwindSafe(|| f(c))).is_ok();
        let mut s = lock(&self.state);
        s.panicked |= !ok;
        s.pending -= 1;
        if s.pending == 0 {
            self.done.notify_all();
        }
    }
}

/// Threads that wait for [`Pool::run`]'s jobs.
pub(crate) struct Pool {
    shared: Arc<Shared>,
    workers: usize,
    /// One job at a time (callers on several threads queue here).
    one_at_a_time: Mutex<()>,
}

impl Pool {
    /// The process's pool: one worker fewer than [`super::gather::threads`] (the caller is one).
    pub(crate) fn global() -> &'static Pool {
        static POOL: OnceLock<Pool> = OnceLock::new();
        POOL.get_or_init(|| Pool::new(super::gather::threads().saturating_sub(1)))
    }

    fn new(workers: usize) -> Pool {
        let shared = Arc::new(Shared::default());
        let mut started = 0;
        for i in 0..workers {
            let shared = Arc::clone(&shared);
            let spawned = std::thread::Builder::new().name(format!("rouge-mesh-{i}")).spawn(move || {
                loop {
                    let mut s = lock(&shared.state);
                    let (job, c) = loop {
                        match Shared::take(&mut s) {
                            Some(t) => break t,
                            None => s = shared.work.wait(s).unwrap_or_else(PoisonError::into_inner),
                        }
                    };
                    drop(s);
                    shared.run_chunk(job, c);
                }
            });
            started += usize::from(spawned.is_ok());
        }
        Pool { shared, workers: started, one_at_a_time: Mutex::new(()) }
    }

    /// Threads a job runs on: the workers and the caller.
    pub(crate) fn threads(&self) -> usize {
        self.workers + 1
    }

    /// Calls `f(c)` for every `c` in `0..chunks`, on the workers and this thread, and returns
    /// when all are done.
    ///
    /// # Panics
    /// If `f` panicked on any chunk (after every chunk has finished). `f` must not call
    /// [`Pool::run`] itself (it would wait for itself).
    pub(crate) fn run(&self, chunks: usize, f: &(dyn Fn(usize) + Sync)) {
        if chunks == 0 {
            return;
        }
        let _one = self.one_at_a_time.lock().unwrap_or_else(PoisonError::into_inner);
        // SAFETY: only the lifetime is erased; this function does not return (nor unwind)
        // before `pending` is 0, that is before every dereference of the pointer has ended,
        // and it clears the job before returning.
        let f: *const (dyn Fn(usize) + Sync + 'static) = unsafe { std::mem::transmute(f) };
        {
            let mut s = lock(&self.shared.state);
            *s = State { job: Some(Job { f, chunks }), next: 0, pending: chunks, panicked: false };
        }
        self.shared.work.notify_all();
        loop {
            let taken = Shared::take(&mut lock(&self.shared.state));
            let Some((job, c)) = taken else { break };
            self.shared.run_chunk(job, c);
        }
        let mut s = lock(&self.shared.state);
        while s.pending > 0 {
            s = self.shared.done.wait(s).unwrap_or_else(PoisonError::into_inner);
        }
        s.job = None;
        let panicked = s.panicked;
        drop(s);
        assert!(!panicked, "a mesh worker panicked");
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::{AtomicUsize, Ordering};

    #[test]
    fn every_chunk_runs_once_on_several_threads_and_jobs_follow_each_other() {
        let pool = Pool::new(3);
        assert_eq!(pool.threads(), 4);
        for chunks in [1usize, 4, 57] {
            let hits: Vec<AtomicUsize> = (0..chunks).map(|_| AtomicUsize::new(0)).collect();
            pool.run(chunks, &|c| {
                hits[c].fetch_add(1, Ordering::Relaxed);
            });
            assert!(hits.iter().all(|h| h.load(Ordering::Relaxed) == 1), "{chunks} chunks");
        }
    }

    #[test]
    fn a_panicking_chunk_panics_the_caller_after_the_others_finish() {
        let pool = Pool::new(2);
        let finished = AtomicUsize::new(0);
        let result = catch_unwind(AssertUnwindSafe(|| {
            pool.run(8, &|c| {
                assert!(c != 3, "chunk 3 fails");
                finished.fetch_add(1, Ordering::Relaxed);
            })
        }));
        assert!(result.is_err());
        assert_eq!(finished.load(Ordering::Relaxed), 7);
        let again = AtomicUsize::new(0);
        pool.run(5, &|_| {
            again.fetch_add(1, Ordering::Relaxed);
        });
        assert_eq!(again.load(Ordering::Relaxed), 5, "the pool works after a panic");
    }
}
