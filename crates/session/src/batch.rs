//! One job per input file, on threads of their own outside rayon's pool.
//!
//! A file's validation may wait for its watchdog (`--timeout`: the job runs on a thread of its own and the
//! caller waits for its answer or the deadline), and its stages hand their heavy work (meshes, sampling) to
//! the pool. Were the files themselves pool tasks, a batch with as many files as the pool has workers would
//! leave every worker waiting for work queued behind itself: a directory, a pre-commit run or a
//! `validate_many` call hung until the timeout. So each file's job runs on a plain thread, as many at once
//! as the pool has workers, and only the stages' inner work goes to the pool: no worker ever waits on
//! anything but pool work.

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;
use std::sync::PoisonError;

/// `job` applied to every item, the items shared among as many threads as rayon's pool has workers
/// (`--jobs`, `RAYON_NUM_THREADS`); the calling thread is one of them. One result per item, in order.
/// Called from outside the pool (as the command, the Python package and the MCP server do), none of the
/// threads is a pool worker, so a job may wait on anything, including work of the pool.
pub fn map_files<T, R, F>(items: &[T], job: F) -> Vec<R>
where
    T: Sync,
    R: Send,
    F: Fn(&T) -> R + Sync,
{
    // Asking rayon for its size starts its pool: a single file needs no second thread (its stages start
    // the pool themselves when they have parallel work).
    let threads = if items.len() > 1 {
        rayon::current_num_threads()
    } else {
        1
    };
    map_on_threads(items, threads, job)
}

/// [`map_files`] on `threads` threads (at most one per item).
fn map_on_threads<T, R, F>(items: &[T], threads: usize, job: F) -> Vec<R>
where
    T: Sync,
    R: Send,
    F: Fn(&T) -> R + Sync,
{
    let threads = threads.clamp(1, items.len().max(1));
    if threads == 1 {
        return items.iter().map(job).collect();
    }
    let next = AtomicUsize::new(0);
    let results: Vec<Mutex<Option<R>>> = items.iter().map(|_| Mutex::new(None)).collect();
    let work = || loop {
        let index = next.fetch_add(1, Ordering::Relaxed);
        let Some(item) = items.get(index) else {
            break;
        };
        let result = job(item);
        *results[index]
            .lock()
            .unwrap_or_else(PoisonError::into_inner) = Some(result);
    };
    std::thread::scope(|scope| {
        for index in 1..threads {
            // A thread that cannot be started leaves its share to the others (this one at least).
            let _ = std::thread::Builder::new()
                .name(format!("files {index}"))
                .spawn_scoped(scope, work);
        }
        work();
    });
    results
        .into_iter()
        .filter_map(|slot| slot.into_inner().unwrap_or_else(PoisonError::into_inner))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use rayon::prelude::*;
    use std::sync::{mpsc, Arc};
    use std::time::Duration;

    #[test]
    fn results_come_in_item_order() {
        let items: Vec<u32> = (0..100).collect();
        let squares = map_files(&items, |n| n * n);
        assert_eq!(squares, items.iter().map(|n| n * n).collect::<Vec<_>>());
        assert!(map_files(&[] as &[u32], |n| *n).is_empty());
    }

    /// Each job waits, outside the pool, for work it hands to the pool: as many jobs as the pool has
    /// workers, and more. Run as pool tasks (`par_iter`), every worker would wait for work queued behind
    /// itself and no answer would come.
    #[test]
    fn jobs_that_wait_for_pool_work_finish_with_as_many_files_as_workers() {
        for workers in [1, 2] {
            let pool = Arc::new(
                rayon::ThreadPoolBuilder::new()
                    .num_threads(workers)
                    .build()
                    .unwrap(),
            );
            let items: Vec<u64> = (0..6).collect();
            // As the watchdog does: the job on a thread of its own, its answer awaited.
            let sums = map_on_threads(&items, workers, |&n| {
                let (done, answer) = mpsc::channel();
                let pool = Arc::clone(&pool);
                std::thread::spawn(move || {
                    let sum: u64 =
                        pool.install(|| (0..1000u64).into_par_iter().map(|i| i * n).sum());
                    let _ = done.send(sum);
                });
                answer.recv_timeout(Duration::from_secs(20))
            });
            for (n, sum) in items.iter().zip(sums) {
                assert_eq!(sum, Ok(499_500 * n), "{workers} worker(s)");
            }
        }
    }
}
