//! A caching C compiler driver for the differential test.
//!
//! Every C tree of the differential test holds its own copy of the same
//! runtime and simulation harness, and `make sim` compiles all of it with
//! one `cc ... -o sim *.c` command: about half a second a program, nearly
//! all of it the unchanged runtime. `stc-progen cc ARGS...` (given to make
//! as `CC`) compiles each file of such a command on its own, reusing the
//! object of a file whose preprocessed text and flags it has compiled
//! before (keyed by a hash of both, so a runtime that includes
//! program-specific headers is never reused wrongly), then links. The tree,
//! its Makefile and `make sim` stay the contract; only the compiler
//! driver changes, and any other command (`-c`, `-E`, no `-o`) goes to the
//! real compiler untouched. A text is cached the second time it is met, so
//! each program's own file does not fill the cache.
//!
//! The cache directory is `STC_PROGEN_CC_CACHE`; the real compiler
//! `STC_PROGEN_REAL_CC` (default `cc`).

use std::path::{Path, PathBuf};
use std::process::Command;

/// The environment variable naming the cache directory.
pub const CACHE_VAR: &str = "STC_PROGEN_CC_CACHE";
/// The environment variable naming the real compiler.
pub const REAL_CC_VAR: &str = "STC_PROGEN_REAL_CC";

/// Runs the compiler command `args` (without the program name), caching
/// objects as described in the module documentation; returns the exit
/// status. The compiler's messages go to this process's stderr.
pub fn run(args: &[String]) -> i32 {
    let real = std::env::var(REAL_CC_VAR).unwrap_or_else(|_| "cc".into());
    let cache = std::env::var_os(CACHE_VAR).map(PathBuf::from);
    let plan = cache.and_then(|c| Plan::of(args).map(|p| (c, p)));
    let Some((cache, plan)) = plan else {
        return status(Command::new(&real).args(args));
    };
    match plan.build(&real, &cache) {
        Some(code) => code,
        // Anything unexpected: let the real compiler say what it says.
        None => status(Command::new(&real).args(args)),
    }
}

fn status(cmd: &mut Command) -> i32 {
    match cmd.status() {
        Ok(s) => s.code().unwrap_or(1),
        Err(e) => {
            eprintln!("stc-progen cc: cannot run the compiler: {e}");
            127
        }
    }
}

/// A compile-and-link command split into its parts.
struct Plan {
    sources: Vec<String>,
    output: String,
    /// Flags for compiling (`-std`, `-O`, `-D`, `-I`, `-W`...).
    flags: Vec<String>,
    /// Flags for linking (`-l...`, `-pthread`, and the compile flags).
    link: Vec<String>,
}

impl Plan {
    /// The plan of a `cc FLAGS -o OUT a.c b.c -lLIB` command, or `None`
    /// for anything else.
    fn of(args: &[String]) -> Option<Plan> {
        let mut p = Plan {
            sources: Vec::new(),
            output: String::new(),
            flags: Vec::new(),
            link: Vec::new(),
        };
        let mut it = args.iter();
        while let Some(a) = it.next() {
            match a.as_str() {
                "-c" | "-E" | "-S" | "-M" | "-MM" | "-" => return None,
                "-o" => p.output = it.next()?.clone(),
                s if s.ends_with(".c") && !s.starts_with('-') => p.sources.push(s.to_string()),
                s if s.starts_with("-l") || s.starts_with("-L") || s == "-pthread" => {
                    p.link.push(s.to_string());
                    if s == "-pthread" {
                        p.flags.push(s.to_string());
                    }
                }
                s if s.starts_with('-') => {
                    // A flag with a separate value would be misread.
                    if matches!(s, "-I" | "-D" | "-U" | "-include" | "-x" | "-MF" | "-MT") {
                        return None;
                    }
                    p.flags.push(s.to_string());
                }
                _ => return None,
            }
        }
        if p.output.is_empty() || p.sources.is_empty() {
            return None;
        }
        Some(p)
    }

    /// Compiles each source through the cache and links; `None` when the
    /// cache cannot be used (then the caller runs the command as given).
    fn build(&self, real: &str, cache: &Path) -> Option<i32> {
        std::fs::create_dir_all(cache).ok()?;
        let mut objects = Vec::new();
        for src in &self.sources {
            let pre = Command::new(real)
                .args(&self.flags)
                .arg("-E")
                .arg(src)
                .output()
                .ok()?;
            if !pre.status.success() {
                return None;
            }
            let mut key_text = pre.stdout;
            key_text.extend_from_slice(self.flags.join("\u{1}").as_bytes());
            let key = format!(
                "{:016x}{:016x}{:08x}",
                fnv1a(&key_text, 0xcbf2_9ce4_8422_2325),
                fnv1a(&key_text, 0x8422_2325_cbf2_9ce4),
                key_text.len() as u32
            );
            let obj = cache.join(format!("{key}.o"));
            let seen = cache.join(format!("{key}.seen"));
            if obj.exists() {
                objects.push(obj);
                continue;
            }
            // A text seen once before is cached; one seen for the first
            // time (the program's own file, mostly) is compiled here only,
            // so that files met once do not fill the cache.
            let cached = seen.exists();
            let target = if cached {
                // Compile next to the cache entry, then rename: workers
                // compiling the same file at once both succeed.
                cache.join(format!("{key}.{}.tmp.o", std::process::id()))
            } else {
                let _ = std::fs::write(&seen, b"");
                PathBuf::from(format!("{}.{}.o", self.output, objects.len()))
            };
            let code = status(
                Command::new(real)
                    .args(&self.flags)
                    .arg("-c")
                    .arg(src)
                    .arg("-o")
                    .arg(&target),
            );
            if code != 0 {
                let _ = std::fs::remove_file(&target);
                return Some(code);
            }
            if cached {
                std::fs::rename(&target, &obj).ok()?;
                objects.push(obj);
            } else {
                objects.push(target);
            }
        }
        Some(status(
            Command::new(real)
                .args(&self.flags)
                .arg("-o")
                .arg(&self.output)
                .args(&objects)
                .args(&self.link),
        ))
    }
}

/// FNV-1a, 64 bits, from the given basis.
fn fnv1a(bytes: &[u8], basis: u64) -> u64 {
    let mut h = basis;
    for &b in bytes {
        h ^= u64::from(b);
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
    h
}

#[cfg(test)]
mod tests {
    use super::*;

    fn strings(a: &[&str]) -> Vec<String> {
        a.iter().map(|s| s.to_string()).collect()
    }

    #[test]
    fn plans_only_compile_and_link_commands() {
        let p = Plan::of(&strings(&[
            "-std=c99",
            "-O0",
            "-DSTC_WATCHDOG",
            "-o",
            "sim",
            "program.c",
            "stc_rt.c",
            "-lm",
        ]))
        .unwrap();
        assert_eq!(p.sources, ["program.c", "stc_rt.c"]);
        assert_eq!(p.output, "sim");
        assert_eq!(p.flags, ["-std=c99", "-O0", "-DSTC_WATCHDOG"]);
        assert_eq!(p.link, ["-lm"]);
        assert!(Plan::of(&strings(&["-c", "a.c", "-o", "a.o"])).is_none());
        assert!(Plan::of(&strings(&["a.c"])).is_none());
        assert!(Plan::of(&strings(&["-I", "x", "-o", "s", "a.c"])).is_none());
        assert!(Plan::of(&strings(&["-o", "s", "a.o"])).is_none());
    }
}
