//! Building the shared library: the system C compiler over the C back end's
//! output, in a temporary directory that is removed afterwards.
//!
//! The runtime (`stc_rt.c`) is the same for every program: it is compiled
//! once per content and compiler into the system's temporary directory and
//! reused (written under a unique name, then renamed, so concurrent builds
//! never see half a file).

use std::collections::hash_map::DefaultHasher;
use std::hash::{Hash, Hasher};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::atomic::{AtomicU64, Ordering};

use crate::Error;

/// The flags of every compilation: C99, optimised as the C differential
/// tests compile, position-independent for a shared library, and the
/// watchdog compiled in (the runtime's `--max-steps`).
const CFLAGS: &[&str] = &["-std=c99", "-O1", "-fPIC", "-DSTC_WATCHDOG"];

/// The C compiler to use, and flags of the user's added to [`CFLAGS`].
#[derive(Clone, Debug)]
pub struct Toolchain {
    pub cc: String,
    pub flags: Vec<String>,
}

impl Default for Toolchain {
    /// `$CC`, else `cc`; extra flags from `$STC_CFLAGS` (split at spaces:
    /// warnings, `-fsanitize=undefined`, `-O2`...).
    fn default() -> Self {
        Toolchain {
            cc: std::env::var("CC")
                .ok()
                .filter(|c| !c.trim().is_empty())
                .unwrap_or_else(|| "cc".into()),
            flags: std::env::var("STC_CFLAGS")
                .map(|f| f.split_whitespace().map(str::to_string).collect())
                .unwrap_or_default(),
        }
    }
}

impl Toolchain {
    /// Writes `files` into `dir` and builds `dir/program.so` from them.
    pub fn shared_library(&self, dir: &Path, files: &[(String, String)]) -> Result<PathBuf, Error> {
        for (name, text) in files {
            std::fs::write(dir.join(name), text)
                .map_err(|e| Error::Build(format!("cannot write {name}: {e}")))?;
        }
        let runtime = self.runtime_object(files)?;
        let out = dir.join("program.so");
        let mut cmd = Command::new(&self.cc);
        cmd.current_dir(dir)
            .args(CFLAGS)
            .args(&self.flags)
            .arg("-shared")
            .arg("-o")
            .arg(&out)
            .arg("program.c")
            .arg(&runtime)
            .arg("-lm");
        self.run(cmd, "the generated C")?;
        Ok(out)
    }

    /// `stc_rt.c` compiled, from the cache when it is there.
    fn runtime_object(&self, files: &[(String, String)]) -> Result<PathBuf, Error> {
        let mut h = DefaultHasher::new();
        self.cc.hash(&mut h);
        CFLAGS.hash(&mut h);
        self.flags.hash(&mut h);
        let mut sources: Vec<&(String, String)> = files
            .iter()
            .filter(|(n, _)| n.starts_with("stc_") && (n.ends_with(".h") || n == "stc_rt.c"))
            .collect();
        sources.sort();
        sources.hash(&mut h);
        let cache = std::env::temp_dir().join(format!("stc-c-runtime-{:016x}.o", h.finish()));
        if cache.is_file() {
            return Ok(cache);
        }
        let dir = TempDir::new()?;
        for (name, text) in &sources {
            std::fs::write(dir.path().join(name), text)
                .map_err(|e| Error::Build(format!("cannot write {name}: {e}")))?;
        }
        let obj = dir.path().join("stc_rt.o");
        let mut cmd = Command::new(&self.cc);
        cmd.current_dir(dir.path())
            .args(CFLAGS)
            .args(&self.flags)
            .arg("-c")
            .arg("-o")
            .arg(&obj)
            .arg("stc_rt.c");
        self.run(cmd, "the C runtime")?;
        let tmp = cache.with_extension(format!("o.{}", unique()));
        std::fs::copy(&obj, &tmp)
            .and_then(|_| std::fs::rename(&tmp, &cache))
            .map_err(|e| Error::Build(format!("cannot write {}: {e}", cache.display())))?;
        Ok(cache)
    }

    fn run(&self, mut cmd: Command, what: &str) -> Result<(), Error> {
        let out = cmd.output().map_err(|e| {
            Error::Build(format!(
                "cannot run the C compiler `{}` ({e}); install one (gcc or clang) or set CC",
                self.cc
            ))
        })?;
        if out.status.success() {
            return Ok(());
        }
        let msg = String::from_utf8_lossy(&out.stderr);
        let first: Vec<&str> = msg.lines().take(20).collect();
        Err(Error::Build(format!(
            "`{}` failed on {what} ({}):\n{}",
            self.cc,
            out.status,
            first.join("\n")
        )))
    }
}

/// A number no other build of this process or another one has used.
fn unique() -> String {
    static COUNT: AtomicU64 = AtomicU64::new(0);
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_nanos());
    format!(
        "{}-{}-{nanos}",
        std::process::id(),
        COUNT.fetch_add(1, Ordering::Relaxed)
    )
}

/// A directory of its own under the system's temporary directory, removed
/// when dropped.
pub(crate) struct TempDir(PathBuf);

impl TempDir {
    pub(crate) fn new() -> Result<TempDir, Error> {
        let path = std::env::temp_dir().join(format!("stc-c-{}", unique()));
        std::fs::create_dir(&path)
            .map_err(|e| Error::Build(format!("cannot create {}: {e}", path.display())))?;
        Ok(TempDir(path))
    }

    pub(crate) fn path(&self) -> &Path {
        &self.0
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}
