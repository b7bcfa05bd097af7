//! `stc.toml`, the project manifest, and `stc init`, which writes one.
//!
//! A subcommand given no source files looks for `stc.toml` in the current
//! folder and its parents (or takes `--manifest-path`), as cargo does, and
//! takes from it the sources (globs relative to the manifest's folder), the
//! edition, the levels of warnings and the run settings. Options on the
//! command line win over the manifest. Unknown keys and bad values are
//! errors naming the file and the key's line (exit status 2).
//!
//! ```toml
//! [project]
//! name = "plant"
//! sources = ["src/**/*.st"]     # default: every .st file below the folder
//! edition = "iec3"              # or "iec2"
//!
//! [diagnostics]
//! warnings = "warn"             # or "deny": warnings fail the build (-W error)
//! allow = ["W0104"]             # warnings not reported
//! deny = ["W0401"]              # warnings reported as errors
//!
//! [lints]                       # each lint's level: allow, warn or deny
//! case-without-else = "warn"    # by name (docs/diagnostics.md) ...
//! L0001 = "deny"                # ... or by code
//!
//! [run]
//! program = "Main"              # or config = "Plant"
//! tick = "10ms"
//! cycles = 100
//!
//! [test]
//! sources = ["tests/**/*.st"]   # added to the sources by `stc test` only
//! ```

use std::path::{Path, PathBuf};

use serde::Deserialize;
use stc_diagnostics::{Code, CodeSeverity};

pub const FILE_NAME: &str = "stc.toml";

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Raw {
    project: Option<RawProject>,
    diagnostics: Option<RawDiagnostics>,
    run: Option<RawRun>,
    test: Option<RawTest>,
    /// Lint levels by lint name or code: `case-without-else = "warn"`.
    lints: Option<std::collections::BTreeMap<toml::Spanned<String>, toml::Spanned<String>>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawProject {
    name: Option<String>,
    sources: Option<Vec<toml::Spanned<String>>>,
    edition: Option<Edition>,
}

#[derive(Deserialize, Clone, Copy, PartialEq, Eq, Debug, Default)]
#[serde(rename_all = "lowercase")]
pub enum Edition {
    Iec2,
    #[default]
    Iec3,
}

#[derive(Deserialize, Clone, Copy, PartialEq, Eq, Debug, Default)]
#[serde(rename_all = "lowercase")]
pub enum WarningLevel {
    #[default]
    Warn,
    Deny,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawDiagnostics {
    warnings: Option<WarningLevel>,
    #[serde(default)]
    allow: Vec<toml::Spanned<String>>,
    #[serde(default)]
    deny: Vec<toml::Spanned<String>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawRun {
    config: Option<String>,
    program: Option<String>,
    tick: Option<toml::Spanned<String>>,
    cycles: Option<u64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawTest {
    sources: Option<Vec<toml::Spanned<String>>>,
}

/// A read and checked manifest.
#[derive(Debug, Clone)]
pub struct Manifest {
    /// The folder holding `stc.toml`: globs are relative to it.
    pub root: PathBuf,
    pub name: Option<String>,
    pub sources: Vec<String>,
    pub test_sources: Vec<String>,
    pub edition: Edition,
    pub warnings: WarningLevel,
    pub allow: Vec<Code>,
    pub deny: Vec<Code>,
    /// The lints' levels: each lint's default, then `[lints]`.
    pub lints: stc_lint::Levels,
    pub run: RunSettings,
}

#[derive(Debug, Clone, Default)]
pub struct RunSettings {
    pub config: Option<String>,
    pub program: Option<String>,
    pub tick: Option<String>,
    pub cycles: Option<u64>,
}

/// A problem with the manifest, already phrased `file:line: message`.
#[derive(Debug)]
pub struct ManifestError(pub String);

impl std::fmt::Display for ManifestError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

fn line_of(text: &str, offset: usize) -> usize {
    text.get(..offset)
        .map_or(1, |t| t.bytes().filter(|&b| b == b'\n').count() + 1)
}

/// The manifest in `dir` or the nearest parent folder that has one.
pub fn find(dir: &Path) -> Option<PathBuf> {
    dir.ancestors()
        .map(|d| d.join(FILE_NAME))
        .find(|p| p.is_file())
}

/// Reads and checks a manifest file.
pub fn load(path: &Path) -> Result<Manifest, ManifestError> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| ManifestError(format!("cannot read {}: {e}", path.display())))?;
    let root = path
        .parent()
        .map(|p| {
            if p.as_os_str().is_empty() {
                PathBuf::from(".")
            } else {
                p.to_path_buf()
            }
        })
        .unwrap_or_else(|| PathBuf::from("."));
    parse(&text, &path.display().to_string(), root)
}

/// Parses manifest text; `name` is how errors call the file.
pub fn parse(text: &str, name: &str, root: PathBuf) -> Result<Manifest, ManifestError> {
    let at = |offset: usize, msg: &str| {
        ManifestError(format!("{name}:{}: {msg}", line_of(text, offset)))
    };
    let raw: Raw = toml::from_str(text).map_err(|e| {
        let msg = e.message().trim().to_string();
        match e.span() {
            Some(span) => at(span.start, &msg),
            None => ManifestError(format!("{name}: {msg}")),
        }
    })?;
    let globs = |list: Option<Vec<toml::Spanned<String>>>, default: &[&str]| {
        let list = match list {
            Some(l) => l,
            None => return Ok(default.iter().map(|s| s.to_string()).collect()),
        };
        let mut out = Vec::new();
        for g in list {
            if let Err(e) = globset::Glob::new(g.get_ref()) {
                return Err(at(
                    g.span().start,
                    &format!("bad glob `{}`: {e}", g.get_ref()),
                ));
            }
            out.push(g.into_inner());
        }
        Ok(out)
    };
    let project = raw.project.unwrap_or(RawProject {
        name: None,
        sources: None,
        edition: None,
    });
    let sources = globs(project.sources, &["**/*.st", "**/*.il"])?;
    let test_sources = globs(raw.test.and_then(|t| t.sources), &[])?;
    let codes = |list: Vec<toml::Spanned<String>>| {
        let mut out = Vec::new();
        for c in list {
            match Code::parse(c.get_ref()) {
                Some(code) if code.severity() == CodeSeverity::Warning => out.push(code),
                Some(_) => {
                    return Err(at(
                        c.span().start,
                        &format!(
                            "{} is an error, not a warning: its level cannot be changed",
                            c.get_ref()
                        ),
                    ))
                }
                None => {
                    return Err(at(
                        c.span().start,
                        &format!(
                            "unknown diagnostic code `{}` (see `stc explain`)",
                            c.get_ref()
                        ),
                    ))
                }
            }
        }
        Ok(out)
    };
    let (warnings, allow, deny) = match raw.diagnostics {
        Some(d) => (
            d.warnings.unwrap_or_default(),
            codes(d.allow)?,
            codes(d.deny)?,
        ),
        None => (WarningLevel::Warn, Vec::new(), Vec::new()),
    };
    let mut lints = stc_lint::Levels::default();
    for (key, value) in raw.lints.unwrap_or_default() {
        let Some(lint) = stc_lint::find(key.get_ref()) else {
            return Err(at(
                key.span().start,
                &format!(
                    "unknown lint `{}` (the lints: {})",
                    key.get_ref(),
                    stc_lint::LINTS
                        .iter()
                        .map(|l| l.name)
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            ));
        };
        let Some(level) = stc_lint::Level::parse(value.get_ref()) else {
            return Err(at(
                value.span().start,
                &format!(
                    "bad level `{}` for lint `{}`: allow, warn or deny",
                    value.get_ref(),
                    key.get_ref()
                ),
            ));
        };
        lints.set(lint.code, level);
    }
    let run = match raw.run {
        Some(r) => {
            if r.config.is_some() && r.program.is_some() {
                return Err(ManifestError(format!(
                    "{name}: [run] has both `config` and `program`; give one"
                )));
            }
            let tick = match r.tick {
                Some(t) => {
                    if let Err(e) = stc_runtime::parse_tick(t.get_ref()) {
                        return Err(at(t.span().start, &format!("bad `tick`: {e}")));
                    }
                    Some(t.into_inner())
                }
                None => None,
            };
            RunSettings {
                config: r.config,
                program: r.program,
                tick,
                cycles: r.cycles,
            }
        }
        None => RunSettings::default(),
    };
    Ok(Manifest {
        root,
        name: project.name,
        sources,
        test_sources,
        edition: project.edition.unwrap_or_default(),
        warnings,
        allow,
        deny,
        lints,
        run,
    })
}

impl Manifest {
    /// The project's source files (sorted), and with `tests` its test files
    /// too.
    pub fn files(&self, tests: bool) -> Result<Vec<PathBuf>, ManifestError> {
        let mut patterns = self.sources.clone();
        if tests {
            patterns.extend(self.test_sources.iter().cloned());
        }
        let mut b = globset::GlobSetBuilder::new();
        for p in &patterns {
            let g = globset::GlobBuilder::new(p)
                .literal_separator(true)
                .build()
                .map_err(|e| ManifestError(format!("bad glob `{p}`: {e}")))?;
            b.add(g);
        }
        let set = b
            .build()
            .map_err(|e| ManifestError(format!("bad globs: {e}")))?;
        let mut out = Vec::new();
        let walk = walkdir::WalkDir::new(&self.root)
            .sort_by_file_name()
            .into_iter()
            .filter_entry(|e| {
                e.depth() == 0
                    || !e
                        .file_name()
                        .to_str()
                        .is_some_and(|n| n.starts_with('.') || n == "target")
            });
        for e in walk {
            let e = e.map_err(|e| ManifestError(format!("cannot read the project: {e}")))?;
            if !e.file_type().is_file() {
                continue;
            }
            let rel = e.path().strip_prefix(&self.root).unwrap_or(e.path());
            if set.is_match(rel) {
                out.push(e.path().to_path_buf());
            }
        }
        out.sort();
        if out.is_empty() {
            return Err(ManifestError(format!(
                "{}: no source file matches {}",
                self.root.join(FILE_NAME).display(),
                patterns
                    .iter()
                    .map(|p| format!("`{p}`"))
                    .collect::<Vec<_>>()
                    .join(", ")
            )));
        }
        Ok(out)
    }
}

const MAIN_ST: &str = "\
(* The program the project runs: `stc run` runs it (stc.toml, [run]). *)
PROGRAM Main
    VAR_INPUT
        start : BOOL := TRUE;
    END_VAR
    VAR_OUTPUT
        count : INT;
    END_VAR
    IF start THEN
        count := Increment(count);
    END_IF;
END_PROGRAM

(* Adds one, and stops at the largest INT. *)
FUNCTION Increment : INT
    VAR_INPUT
        n : INT;
    END_VAR
    IF n < 32767 THEN
        Increment := n + 1;
    ELSE
        Increment := n;
    END_IF;
END_FUNCTION
";

const TEST_ST: &str = "\
(* Tests are PROGRAMs whose names start with TEST_: `stc test` runs each one
   alone, for one cycle or as many as TEST_CYCLES asks for. *)
PROGRAM TEST_Increment
    ASSERT_EQ_INT(2, Increment(1), 'one more');
    ASSERT_EQ_INT(32767, Increment(32767), 'stops at the largest INT');
END_PROGRAM

(* Virtual time: cycle k runs at (k - 1) * tick (stc.toml: 10ms). *)
PROGRAM TEST_Timer_after_50ms
    VAR
        t : TON;
        cycle : INT;
    END_VAR
    TEST_CYCLES(6);
    cycle := cycle + 1;
    t(IN := TRUE, PT := T#50ms);
    IF cycle < 6 THEN
        ASSERT_FALSE(t.Q, 'not yet');
    ELSE
        ASSERT_TRUE(t.Q, 'done at T#50ms');
        ASSERT_EQ_TIME(T#50ms, t.ET, 'elapsed');
    END_IF;
END_PROGRAM
";

/// `stc init DIR`: a new project with a manifest, a first program and a
/// test. Refuses to overwrite an existing manifest.
pub fn init(dir: &Path, name: Option<&str>) -> Result<String, ManifestError> {
    let manifest = dir.join(FILE_NAME);
    if manifest.exists() {
        return Err(ManifestError(format!(
            "{} already exists; not overwritten",
            manifest.display()
        )));
    }
    let name = name
        .map(str::to_string)
        .or_else(|| {
            std::fs::canonicalize(dir)
                .ok()
                .and_then(|d| d.file_name().map(|n| n.to_string_lossy().into_owned()))
        })
        .unwrap_or_else(|| "project".into());
    let text = format!(
        "[project]\nname = {name:?}\nsources = [\"src/**/*.st\"]\nedition = \"iec3\"\n\n\
         [diagnostics]\nwarnings = \"warn\"\n\n\
         [run]\nprogram = \"Main\"\ntick = \"10ms\"\ncycles = 10\n\n\
         [test]\nsources = [\"tests/**/*.st\"]\n"
    );
    let io = |e: std::io::Error| {
        ManifestError(format!(
            "cannot create the project in {}: {e}",
            dir.display()
        ))
    };
    std::fs::create_dir_all(dir.join("src")).map_err(io)?;
    std::fs::create_dir_all(dir.join("tests")).map_err(io)?;
    for (path, contents) in [
        (dir.join("src/main.st"), MAIN_ST),
        (dir.join("tests/test_main.st"), TEST_ST),
    ] {
        if !path.exists() {
            std::fs::write(&path, contents).map_err(io)?;
        }
    }
    std::fs::write(&manifest, text).map_err(io)?;
    Ok(format!(
        "created project `{name}` in {} (stc.toml, src/main.st, tests/test_main.st)\n",
        dir.display()
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn err(text: &str) -> String {
        parse(text, "stc.toml", PathBuf::from(".")).unwrap_err().0
    }

    #[test]
    fn a_full_manifest_reads() {
        let m = parse(
            "[project]\nname = \"p\"\nsources = [\"src/*.st\"]\nedition = \"iec2\"\n\
             [diagnostics]\nwarnings = \"deny\"\nallow = [\"W0104\"]\n\
             [run]\nconfig = \"Plant\"\ntick = \"T#20ms\"\ncycles = 5\n[test]\nsources = [\"t/*.st\"]\n",
            "stc.toml",
            PathBuf::from("."),
        )
        .unwrap();
        assert_eq!(m.edition, Edition::Iec2);
        assert_eq!(m.warnings, WarningLevel::Deny);
        assert_eq!(m.allow, vec![Code::W0104]);
        assert_eq!(m.run.config.as_deref(), Some("Plant"));
        assert_eq!(m.run.cycles, Some(5));
        assert_eq!(m.test_sources, vec!["t/*.st".to_string()]);
        assert_eq!(m.lints, stc_lint::Levels::default());
    }

    #[test]
    fn lint_levels_by_name_or_code() {
        let m = parse(
            "[lints]\ncase-without-else = \"warn\"\nL0002 = \"allow\"\nreal_equality = \"deny\"\n",
            "stc.toml",
            PathBuf::from("."),
        )
        .unwrap();
        use stc_lint::Level;
        assert_eq!(m.lints.get(Code::L0006), Level::Warn);
        assert_eq!(m.lints.get(Code::L0002), Level::Allow);
        assert_eq!(m.lints.get(Code::L0007), Level::Deny);
        assert_eq!(m.lints.get(Code::L0001), Level::Allow);
        assert_eq!(m.lints.get(Code::L0003), Level::Warn);
    }

    #[test]
    fn unknown_keys_and_bad_values_name_the_line() {
        let e = err("[project]\nname = \"p\"\nsourcs = [\"a\"]\n");
        assert!(e.starts_with("stc.toml:3: unknown field `sourcs`"), "{e}");
        let e = err("[project]\nedition = \"iec4\"\n");
        assert!(e.starts_with("stc.toml:2: unknown variant `iec4`"), "{e}");
        let e = err("\n[run]\ntick = \"fast\"\n");
        assert!(e.starts_with("stc.toml:3: bad `tick`"), "{e}");
        let e = err("[diagnostics]\nallow = [\"W9999\"]\n");
        assert!(
            e.starts_with("stc.toml:2: unknown diagnostic code `W9999`"),
            "{e}"
        );
        let e = err("[diagnostics]\n\ndeny = [\"E0301\"]\n");
        assert!(e.starts_with("stc.toml:3: E0301 is an error"), "{e}");
        let e = err("[lints]\nx = \"warn\"\n");
        assert!(e.starts_with("stc.toml:2: unknown lint `x`"), "{e}");
        let e = err("[lints]\n\ncase-without-else = \"loud\"\n");
        assert!(e.starts_with("stc.toml:3: bad level `loud`"), "{e}");
        let e = err("[lints]\nmagic-number = 1\n");
        assert!(e.starts_with("stc.toml:2:"), "{e}");
        let e = err("[run]\ncycles = -1\n");
        assert!(e.starts_with("stc.toml:2:"), "{e}");
    }
}
