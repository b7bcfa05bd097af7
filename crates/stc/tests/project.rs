//! Projects: `stc init` and the commands run inside a project without file
//! arguments (stc.toml).

use std::path::PathBuf;
use std::process::Command;

fn temp_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("stc-project-test-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

fn stc_in(dir: &PathBuf, args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_stc"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("stc runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn init_makes_a_project_that_checks_runs_and_is_formatted() {
    let dir = temp_dir("init");
    let d = dir.to_str().unwrap();
    let o = stc::cli::run_args(&["stc", "init", d, "--name", "demo"]);
    assert_eq!(o.status, 0, "{o:?}");
    assert!(dir.join("stc.toml").is_file());
    // A second init does not overwrite.
    let o = stc::cli::run_args(&["stc", "init", d]);
    assert_eq!(o.status, 2, "{o:?}");

    let (status, out, err) = stc_in(&dir, &["check"]);
    assert_eq!((status, out.as_str(), err.as_str()), (0, "", ""));
    let (status, out, err) = stc_in(&dir, &["run", "--format", "json"]);
    assert_eq!(status, 0, "{err}");
    // [run] cycles = 10, program = "Main".
    assert_eq!(
        out.trim(),
        r#"{"cycle":10,"time":"T#90ms","values":{"Main.count":10}}"#
    );
    // The command line wins over the manifest.
    let (status, out, _) = stc_in(&dir, &["run", "--cycles", "3"]);
    assert_eq!(status, 0);
    assert!(out.contains("Main.count = 3"), "{out}");
    let (status, out, err) = stc_in(&dir, &["fmt", "--check"]);
    assert_eq!((status, out.as_str(), err.as_str()), (0, "", ""));
    // From a subfolder, the manifest above is found.
    let (status, _, err) = stc_in(&dir.join("src"), &["check"]);
    assert_eq!(status, 0, "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn manifest_settings_apply_and_errors_name_the_line() {
    let dir = temp_dir("settings");
    std::fs::create_dir_all(dir.join("src")).unwrap();
    std::fs::write(
        dir.join("src/a.st"),
        "PROGRAM P\n    VAR\n        x : INT;\n    END_VAR\n    x := x / 0;\nEND_PROGRAM\n",
    )
    .unwrap();
    let manifest = dir.join("stc.toml");
    let m = manifest.to_str().unwrap();
    // Division by a constant zero is an error, not a warning: check it is
    // reported with the project's files.
    std::fs::write(&manifest, "[project]\nsources = [\"src/*.st\"]\n").unwrap();
    let o = stc::cli::run_args(&["stc", "check", "--manifest-path", m]);
    assert_eq!(o.status, 1, "{o:?}");
    assert!(o.stderr.contains("a.st:5:"), "{}", o.stderr);

    std::fs::write(
        &manifest,
        "[project]\nsources = [\"src/*.st\"]\nedtion = \"iec2\"\n",
    )
    .unwrap();
    let o = stc::cli::run_args(&["stc", "check", "--manifest-path", m]);
    assert_eq!(o.status, 2, "{o:?}");
    assert!(
        o.stderr.contains("stc.toml:3: unknown field `edtion`"),
        "{}",
        o.stderr
    );

    std::fs::write(&manifest, "[project]\nsources = [\"nothing/*.st\"]\n").unwrap();
    let o = stc::cli::run_args(&["stc", "check", "--manifest-path", m]);
    assert_eq!(o.status, 2, "{o:?}");
    assert!(o.stderr.contains("no source file matches"), "{}", o.stderr);

    let empty = temp_dir("no-manifest");
    std::fs::create_dir_all(&empty).unwrap();
    let (status, _, err) = stc_in(&empty, &["check"]);
    assert_eq!(status, 2);
    assert!(err.contains("no stc.toml"), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
    let _ = std::fs::remove_dir_all(&empty);
}

#[test]
fn warning_levels_from_the_manifest() {
    let dir = temp_dir("levels");
    std::fs::create_dir_all(&dir).unwrap();
    // W0104-style warnings: find one the analyser gives for this program.
    std::fs::write(
        dir.join("a.st"),
        "PROGRAM P\n    VAR\n        x : INT;\n    END_VAR\n    x := 32767 + 1;\nEND_PROGRAM\n",
    )
    .unwrap();
    let manifest = dir.join("stc.toml");
    let m = manifest.to_str().unwrap();
    std::fs::write(&manifest, "").unwrap();
    let o = stc::cli::run_args(&["stc", "check", "--manifest-path", m]);
    let code = o
        .stderr
        .split("warning[")
        .nth(1)
        .and_then(|s| s.get(..5))
        .map(str::to_string);
    let Some(code) = code else {
        panic!("expected a warning: {o:?}");
    };
    assert_eq!(o.status, 0, "{o:?}");
    std::fs::write(&manifest, format!("[diagnostics]\ndeny = [\"{code}\"]\n")).unwrap();
    let o = stc::cli::run_args(&["stc", "check", "--manifest-path", m]);
    assert_eq!(o.status, 1, "{o:?}");
    assert!(o.stderr.contains(&format!("error[{code}]")), "{}", o.stderr);
    std::fs::write(&manifest, format!("[diagnostics]\nallow = [\"{code}\"]\n")).unwrap();
    let o = stc::cli::run_args(&["stc", "check", "--manifest-path", m]);
    assert_eq!((o.status, o.stderr.as_str()), (0, ""), "{o:?}");
    std::fs::write(&manifest, "[diagnostics]\nwarnings = \"deny\"\n").unwrap();
    let o = stc::cli::run_args(&["stc", "check", "--manifest-path", m]);
    assert_eq!(o.status, 1, "{o:?}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn lint_levels_from_the_manifest_and_the_command_line() {
    let dir = temp_dir("lints");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("a.st"),
        "PROGRAM P\n    VAR_INPUT\n        mode : INT;\n    END_VAR\n    VAR_OUTPUT\n        x : INT;\n    END_VAR\n    CASE mode OF\n        0: x := 0;\n    END_CASE;\nEND_PROGRAM\n",
    )
    .unwrap();
    let manifest = dir.join("stc.toml");
    let m = manifest.to_str().unwrap();
    std::fs::write(&manifest, "").unwrap();
    // CASE without ELSE is off by default.
    let o = stc::cli::run_args(&["stc", "check", "--manifest-path", m]);
    assert_eq!((o.status, o.stderr.as_str()), (0, ""), "{o:?}");
    std::fs::write(&manifest, "[lints]\ncase-without-else = \"warn\"\n").unwrap();
    let o = stc::cli::run_args(&["stc", "check", "--manifest-path", m]);
    assert_eq!(o.status, 0, "{o:?}");
    assert!(o.stderr.contains("warning[L0006]"), "{}", o.stderr);
    std::fs::write(&manifest, "[lints]\nL0006 = \"deny\"\n").unwrap();
    let o = stc::cli::run_args(&["stc", "check", "--manifest-path", m]);
    assert_eq!(o.status, 1, "{o:?}");
    assert!(o.stderr.contains("error[L0006]"), "{}", o.stderr);
    // The command line wins.
    let o = stc::cli::run_args(&["stc", "check", "--manifest-path", m, "-A", "L0006"]);
    assert_eq!((o.status, o.stderr.as_str()), (0, ""), "{o:?}");
    // A bad key or level names the line (exit 2).
    std::fs::write(
        &manifest,
        "[project]\nname = \"p\"\n\n[lints]\ncase-without = \"warn\"\n",
    )
    .unwrap();
    let o = stc::cli::run_args(&["stc", "check", "--manifest-path", m]);
    assert_eq!(o.status, 2, "{o:?}");
    assert!(
        o.stderr.contains("stc.toml:5: unknown lint `case-without`"),
        "{}",
        o.stderr
    );
    let _ = std::fs::remove_dir_all(&dir);
}
