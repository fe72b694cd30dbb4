//! Results of the expensive analyses kept from one run to the next on the same document (the language
//! server validates a document again after every edit), each under a fingerprint of everything it reads.
//!
//! A run whose fingerprint matches a kept one takes the kept result instead of computing it: an effort or
//! mass edit leaves the workspace sampling's inputs (kinematics, geometry, the pose, the options) as they
//! were, so the sampling is not done again. A fingerprint hashes values, never source positions, so an
//! edit elsewhere in the file (a comment, a line inserted above) matches too.

use std::any::Any;
use std::collections::VecDeque;
use std::hash::{DefaultHasher, Hash, Hasher};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex, PoisonError};

use nalgebra::{Isometry3, Vector3};

/// The results kept across runs on one document. Clones share them; a run without one computes
/// everything.
#[derive(Clone, Default)]
pub struct Memo {
    shared: Arc<Shared>,
}

#[derive(Default)]
struct Shared {
    /// The most recent results, newest last, at most [`Memo::KEPT`].
    kept: Mutex<VecDeque<(u64, Arc<dyn Any + Send + Sync>)>>,
    /// Results taken from `kept` since the memo was made.
    reused: AtomicUsize,
    /// Results computed (and kept) since the memo was made.
    computed: AtomicUsize,
}

impl std::fmt::Debug for Memo {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Memo")
            .field("reused", &self.reused())
            .field("computed", &self.computed())
            .finish()
    }
}

impl Memo {
    /// Results kept at most: the latest runs' sampled arms (a robot has a few), not a growing history.
    const KEPT: usize = 16;

    /// The result kept under `key`, if there is one of type `T`.
    pub(crate) fn take<T: Clone + 'static>(&self, key: u64) -> Option<T> {
        let kept = self
            .shared
            .kept
            .lock()
            .unwrap_or_else(PoisonError::into_inner);
        let value = kept
            .iter()
            .rev()
            .find(|(k, _)| *k == key)
            .and_then(|(_, value)| value.downcast_ref::<T>())
            .cloned();
        if value.is_some() {
            self.shared.reused.fetch_add(1, Ordering::Relaxed);
        }
        value
    }

    /// Keep `value`, a whole result (never one a cancelled run left partial), under `key`; the oldest
    /// result goes when [`Memo::KEPT`] are kept.
    pub(crate) fn keep<T: Send + Sync + 'static>(&self, key: u64, value: T) {
        self.shared.computed.fetch_add(1, Ordering::Relaxed);
        let mut kept = self
            .shared
            .kept
            .lock()
            .unwrap_or_else(PoisonError::into_inner);
        kept.retain(|(k, _)| *k != key);
        if kept.len() == Self::KEPT {
            kept.pop_front();
        }
        kept.push_back((key, Arc::new(value)));
    }

    /// How many results were taken from the memo instead of computed.
    pub fn reused(&self) -> usize {
        self.shared.reused.load(Ordering::Relaxed)
    }

    /// How many results were computed and kept.
    pub fn computed(&self) -> usize {
        self.shared.computed.load(Ordering::Relaxed)
    }
}

/// A hash of the values one analysis reads: floats by their bits (so `-0.0` and `0.0` differ, and a
/// NaN matches itself), in the order they are fed.
pub(crate) struct Fingerprint(DefaultHasher);

impl Fingerprint {
    /// An empty fingerprint for the analysis named `what` (results of two analyses never match).
    pub fn new(what: &str) -> Self {
        let mut hasher = DefaultHasher::new();
        what.hash(&mut hasher);
        Fingerprint(hasher)
    }

    /// Feed a value that hashes itself.
    pub fn value(&mut self, value: impl Hash) -> &mut Self {
        value.hash(&mut self.0);
        self
    }

    /// Feed a float.
    pub fn float(&mut self, value: f64) -> &mut Self {
        self.0.write_u64(value.to_bits());
        self
    }

    /// Feed floats, with their count.
    pub fn floats(&mut self, values: &[f64]) -> &mut Self {
        self.0.write_usize(values.len());
        for &value in values {
            self.float(value);
        }
        self
    }

    /// Feed a vector.
    pub fn vector(&mut self, v: &Vector3<f64>) -> &mut Self {
        self.floats(v.as_slice())
    }

    /// Feed a placement (translation and unit quaternion).
    pub fn placement(&mut self, p: &Isometry3<f64>) -> &mut Self {
        self.vector(&p.translation.vector);
        self.floats(p.rotation.coords.as_slice())
    }

    /// Feed an optional float.
    pub fn optional(&mut self, value: Option<f64>) -> &mut Self {
        match value {
            Some(v) => self.value(1u8).float(v),
            None => self.value(0u8),
        }
    }

    /// The hash.
    pub fn finish(&self) -> u64 {
        self.0.finish()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_kept_result_is_taken_until_the_newer_ones_push_it_out() {
        let memo = Memo::default();
        assert_eq!(memo.take::<u64>(1), None);
        memo.keep(1, 10u64);
        assert_eq!(memo.take::<u64>(1), Some(10));
        memo.keep(1, 11u64);
        assert_eq!(
            memo.take::<u64>(1),
            Some(11),
            "kept again: the newer result"
        );
        for key in 2..(Memo::KEPT as u64 + 2) {
            memo.keep(key, key);
        }
        assert_eq!(memo.take::<u64>(1), None, "the oldest went");
        assert_eq!(
            memo.take::<u64>(Memo::KEPT as u64 + 1),
            Some(Memo::KEPT as u64 + 1)
        );
        assert_eq!((memo.reused(), memo.computed()), (3, Memo::KEPT + 2));
    }

    #[test]
    fn a_result_of_another_type_under_the_same_key_is_not_taken() {
        let memo = Memo::default();
        memo.keep(5, 1u32);
        assert_eq!(memo.take::<&str>(5), None);
        assert_eq!(memo.take::<u32>(5), Some(1));
    }

    #[test]
    fn fingerprints_tell_floats_and_analyses_apart() {
        let print = |what: &str, v: f64| Fingerprint::new(what).float(v).finish();
        assert_eq!(print("a", 1.0), print("a", 1.0));
        assert_ne!(print("a", 1.0), print("a", 1.0 + f64::EPSILON));
        assert_ne!(print("a", 0.0), print("a", -0.0));
        assert_eq!(print("a", f64::NAN), print("a", f64::NAN));
        assert_ne!(print("a", 1.0), print("b", 1.0));
        let optional = |v: Option<f64>| Fingerprint::new("o").optional(v).finish();
        assert_ne!(optional(None), optional(Some(0.0)));
    }
}
