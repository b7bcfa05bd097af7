//! Programs too large for the memory model (E0901) through the command
//! line: every subcommand that compiles reports the same diagnostic and
//! exits 1 (spec/cli.md: the sources have errors), writes nothing, and
//! runs nothing; a failure of the bytecode compiler itself (a frame that
//! only the VM's temporaries make too large) is the same for `build` and
//! `run`.

use std::path::PathBuf;

/// The program whose layout used to wrap: `t.z` shared its address with
/// `t.y`, and `stc run` printed r = -26214 with exit 0.
const WRAPPED: &str = "\
TYPE S : STRUCT a : ARRAY[0..16000000] OF LREAL; END_STRUCT; END_TYPE
TYPE T : STRUCT x, y : ARRAY[0..40] OF S; z : INT; END_STRUCT; END_TYPE
PROGRAM Main VAR t : T; END_VAR VAR_OUTPUT r : INT; END_VAR
t.z := 5; t.y[0].a[0] := 1.1; r := t.z;
END_PROGRAM
";

/// Every declaration fits; only the VM's frame of `Outer`, which holds
/// `b` and the frame of its call of `Inner` (each 544 MB), does not.
const VM_FRAME: &str = "\
TYPE Big : ARRAY[0..8299] OF STRING[65535]; END_TYPE
FUNCTION Inner : INT
VAR_INPUT a : Big; END_VAR
Inner := LEN(a[0]);
END_FUNCTION
FUNCTION Outer : INT
VAR_INPUT b : Big; END_VAR
Outer := Inner(a := b);
END_FUNCTION
PROGRAM Main
VAR_OUTPUT r : INT; END_VAR
r := 1;
END_PROGRAM
";

fn scratch(name: &str, text: &str) -> (PathBuf, String) {
    let dir = std::env::temp_dir().join(format!("stc-too-large-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let src = dir.join("main.st");
    std::fs::write(&src, text).unwrap();
    (dir, src.to_string_lossy().into_owned())
}

#[test]
fn a_wrapped_layout_is_an_error_for_every_subcommand() {
    let (dir, src) = scratch("wrapped", WRAPPED);
    let bin = dir.join("out.stbc").to_string_lossy().into_owned();
    let cdir = dir.join("c").to_string_lossy().into_owned();
    let commands: Vec<Vec<&str>> = vec![
        vec!["stc", "check", &src],
        vec!["stc", "run", &src],
        vec!["stc", "run", "--format", "json", &src],
        vec!["stc", "build", "--emit", "vmasm", &src],
        vec!["stc", "build", "--emit", "bytecode", "-o", &bin, &src],
        vec!["stc", "build", "--emit", "c", "-o", &cdir, &src],
        vec!["stc", "build", "--emit", "ir", &src],
    ];
    for argv in commands {
        let out = stc::cli::run_args(&argv);
        assert_eq!(out.status, 1, "{argv:?}: {}", out.stderr);
        assert!(out.stdout.is_empty(), "{argv:?}: {}", out.stdout);
        assert_eq!(
            out.stderr.matches("error[E0901]").count(),
            2,
            "{argv:?}: {}",
            out.stderr
        );
        assert!(
            out.stderr
                .contains("main.st:2:17: error[E0901]: member `x` needs 5248000328 bytes"),
            "{argv:?}: {}",
            out.stderr
        );
    }
    assert!(!dir.join("out.stbc").exists() && !dir.join("c").exists());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_frame_the_vm_cannot_place_exits_1_from_build_and_run_alike() {
    let (dir, src) = scratch("vm-frame", VM_FRAME);
    // (The IR's layout fits: only the VM's frames, with their temporaries,
    // do not.)
    assert_eq!(stc::cli::run_args(&["stc", "check", &src]).status, 0);
    let build = stc::cli::run_args(&["stc", "build", "--emit", "vmasm", &src]);
    let run = stc::cli::run_args(&["stc", "run", &src]);
    for out in [&build, &run] {
        assert_eq!(out.status, 1, "{}", out.stderr);
        assert!(
            out.stderr
                .contains("main.st:6:10: error[E0901]: the frame of `Outer` with its temporaries"),
            "{}",
            out.stderr
        );
    }
    assert_eq!(build.stderr, run.stderr);
    assert!(build.stdout.is_empty() && run.stdout.is_empty());
    let _ = std::fs::remove_dir_all(&dir);
}
