//! The file side of the real-time controller (`stc run --realtime`):
//! the retain file (`--retain`, `--retain-interval`, `--cold`). The
//! runtime makes and checks the image (`stc_runtime::retain`); this module
//! reads it at a warm start and writes it crash-safely between cycles.
//!
//! A save writes the whole image to `FILE.tmp` beside the file, flushes it
//! to the disk (`fsync`), renames it over `FILE` (atomic on POSIX file
//! systems) and flushes the directory, so after a crash at any moment
//! `FILE` is either the previous complete image or the new one.

use std::fs::{self, File};
use std::io::Write;
use std::path::{Path, PathBuf};

use stc_runtime::retain::{cycles_between_saves, Retained};
use stc_runtime::{Between, Simulation};

/// The retain file of a run.
pub struct RetainFile {
    path: PathBuf,
    tmp: PathBuf,
    retained: Retained,
    /// Save after every `every`-th cycle.
    every: u64,
    /// Reported once: a failing disk must not flood stderr every cycle.
    failed: bool,
    warn: Box<dyn FnMut(String)>,
}

impl RetainFile {
    /// Sets the retain file up for `sim`; unless `cold`, restores the
    /// retained variables from `path` if it holds a valid image of this
    /// program (a missing file is a cold start; an invalid one is reported
    /// through `warn` and ignored).
    pub fn open(
        sim: &mut Simulation,
        path: &Path,
        interval_ns: Option<i64>,
        cold: bool,
        mut warn: Box<dyn FnMut(String)>,
    ) -> RetainFile {
        let retained = sim.retained();
        let mut tmp = path.as_os_str().to_owned();
        tmp.push(".tmp");
        if !cold {
            match fs::read(path) {
                Ok(bytes) => match sim.warm_start(retained.clone(), bytes) {
                    Ok(cycle) => warn(format!(
                        "note: warm start: {} retained variable(s) restored from {} (saved after cycle {cycle})",
                        retained.regions.len(),
                        path.display()
                    )),
                    Err(e) => warn(format!(
                        "warning: {}: {e}; not loaded (cold start)",
                        path.display()
                    )),
                },
                Err(e) if e.kind() == std::io::ErrorKind::NotFound => {}
                Err(e) => warn(format!(
                    "warning: cannot read {}: {e}; cold start",
                    path.display()
                )),
            }
        }
        RetainFile {
            path: path.to_path_buf(),
            tmp: PathBuf::from(tmp),
            retained,
            every: cycles_between_saves(interval_ns, sim.plan().tick_ns),
            failed: false,
            warn,
        }
    }

    /// Saves the image after the last completed cycle.
    fn save(&mut self, sim: &Simulation) {
        let Some(image) = sim.save_retained(&self.retained) else {
            return;
        };
        if let Err(e) = write_atomically(&self.path, &self.tmp, &image) {
            if !self.failed {
                (self.warn)(format!(
                    "warning: cannot save the retained variables to {}: {e}",
                    self.path.display()
                ));
                self.failed = true;
            }
        }
    }
}

impl Between for RetainFile {
    fn after_cycle(&mut self, sim: &mut Simulation, k: u64) {
        if k.is_multiple_of(self.every) {
            self.save(sim);
        }
    }

    fn at_end(&mut self, sim: &mut Simulation) {
        if !sim.completed().is_multiple_of(self.every) {
            self.save(sim);
        }
    }
}

/// Writes `bytes` to `tmp`, flushes it to the disk and renames it to
/// `path`, then flushes the directory (Unix) so the rename survives a
/// power loss.
pub fn write_atomically(path: &Path, tmp: &Path, bytes: &[u8]) -> std::io::Result<()> {
    {
        let mut f = File::create(tmp)?;
        f.write_all(bytes)?;
        f.sync_all()?;
    }
    fs::rename(tmp, path)?;
    #[cfg(unix)]
    {
        let dir = match path.parent() {
            Some(d) if !d.as_os_str().is_empty() => d,
            _ => Path::new("."),
        };
        File::open(dir)?.sync_all()?;
    }
    Ok(())
}

/// Several things to do between cycles: before a cycle in order, after
/// one in the reverse order, so what is pushed last is nearest to the
/// program on both sides (the inputs are read, then the forces written;
/// after the cycle the forces are written again before the outputs and the
/// retained variables are taken).
pub struct All(pub Vec<Box<dyn Between>>);

impl Between for All {
    fn before_cycle(&mut self, sim: &mut Simulation, k: u64) {
        for b in &mut self.0 {
            b.before_cycle(sim, k);
        }
    }
    fn after_cycle(&mut self, sim: &mut Simulation, k: u64) {
        for b in self.0.iter_mut().rev() {
            b.after_cycle(sim, k);
        }
    }
    fn at_end(&mut self, sim: &mut Simulation) {
        for b in self.0.iter_mut().rev() {
            b.at_end(sim);
        }
    }
    fn faulted(&mut self, sim: &mut Simulation, k: u64, fault: &stc_vm::VmFault) {
        for b in self.0.iter_mut().rev() {
            b.faulted(sim, k, fault);
        }
    }
}
