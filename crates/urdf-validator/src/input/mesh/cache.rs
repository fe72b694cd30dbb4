//! The per-run mesh cache: each file loaded once and shared, backed by the disk cache.

use std::collections::HashMap;
use std::fmt;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, PoisonError};

use super::{load_mesh_with, summary_of, DiskCache, MeshData, MeshError, MeshOptions, MeshSummary};

/// Thread-safe cache keyed by path: each file read and parsed once per run, shared across
/// robots/poses. Clones share the same entries. With a [`DiskCache`], meshes loaded in earlier runs are
/// read from it, and meshes loaded now are kept in it.
#[derive(Default, Clone)]
pub struct MeshCache {
    entries: Arc<Mutex<CacheEntries>>,
    /// Summaries read from the disk cache (meshes not loaded), so each entry header is read once.
    summaries: Arc<Mutex<HashMap<PathBuf, MeshSummary>>>,
    options: MeshOptions,
    disk: Option<DiskCache>,
}

type CacheEntries = HashMap<PathBuf, Arc<Result<MeshData, MeshError>>>;

impl fmt::Debug for MeshCache {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let entries = self.lock().len();
        f.debug_struct("MeshCache")
            .field("entries", &entries)
            .field("options", &self.options)
            .field("disk", &self.disk)
            .finish()
    }
}

impl MeshCache {
    /// An empty cache loading with the default [`MeshOptions`].
    pub fn new() -> Self {
        Self::default()
    }

    /// An empty cache loading with `options`.
    pub fn with_options(options: MeshOptions) -> Self {
        Self {
            entries: Arc::default(),
            summaries: Arc::default(),
            options,
            disk: None,
        }
    }

    /// The options meshes are loaded with.
    pub fn options(&self) -> MeshOptions {
        self.options
    }

    /// This cache, also reading and keeping meshes in `disk` (across runs).
    pub fn with_disk_cache(self, disk: DiskCache) -> Self {
        Self {
            disk: Some(disk),
            ..self
        }
    }

    /// The mesh at `path` (or why it could not be loaded), read on first use. The lock is not held
    /// while a file is parsed; if two threads race on the same new path both parse it, and both get
    /// the entry stored first.
    pub fn get(&self, path: &Path) -> Arc<Result<MeshData, MeshError>> {
        if let Some(entry) = self.lock().get(path) {
            return Arc::clone(entry);
        }
        let loaded = Arc::new(self.load(path));
        Arc::clone(self.lock().entry(path.to_path_buf()).or_insert(loaded))
    }

    /// The mesh at `path` without its points (or why it could not be loaded): from this cache when it
    /// holds the mesh, else from the disk cache's entry header alone (read once), else loaded whole (and
    /// kept).
    pub fn summary(&self, path: &Path) -> Result<MeshSummary, MeshError> {
        if let Some(entry) = self.lock().get(path) {
            return summary_of(entry);
        }
        let summaries = || {
            self.summaries
                .lock()
                .unwrap_or_else(PoisonError::into_inner)
        };
        if let Some(summary) = summaries().get(path) {
            return Ok(*summary);
        }
        if let Some(summary) = self
            .disk
            .as_ref()
            .and_then(|disk| disk.read_summary(path, &self.options))
        {
            summaries().insert(path.to_path_buf(), summary);
            return Ok(summary);
        }
        summary_of(&self.get(path))
    }

    /// The mesh at `path` from the disk cache, else from its file (then kept in the disk cache).
    fn load(&self, path: &Path) -> Result<MeshData, MeshError> {
        let Some(disk) = &self.disk else {
            return load_mesh_with(path, &self.options);
        };
        if let Some(mesh) = disk.read(path, &self.options) {
            return Ok(mesh);
        }
        let loaded = load_mesh_with(path, &self.options);
        if let Ok(mesh) = &loaded {
            disk.write(path, &self.options, mesh);
        }
        loaded
    }

    /// Number of paths loaded (or failed) so far.
    pub fn len(&self) -> usize {
        self.lock().len()
    }

    /// Whether nothing has been loaded yet.
    pub fn is_empty(&self) -> bool {
        self.lock().is_empty()
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, CacheEntries> {
        // A panic elsewhere while holding the lock cannot leave the map half-updated.
        self.entries.lock().unwrap_or_else(PoisonError::into_inner)
    }
}
