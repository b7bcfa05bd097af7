//! `stc test` on fixtures (tests/unit) and on a new project.

mod common;

#[test]
fn failing_passing_and_faulting_tests_are_reported_with_file_and_line() {
    let file = common::data_dir().join("unit/failing.st");
    let f = file.to_str().unwrap();
    let junit = std::env::temp_dir().join(format!("stc-junit-{}.xml", std::process::id()));
    let o = stc::cli::run_args(&["stc", "test", f, "--junit", junit.to_str().unwrap()]);
    assert_eq!(o.status, 1, "{o:?}");
    assert_eq!(o.stderr, "", "{o:?}");
    let out = &o.stdout;
    assert!(out.starts_with("running 5 tests\n"), "{out}");
    assert!(
        out.contains("test TEST_passes ... ok (1 cycle, 3 checks, at T#0s)\n"),
        "{out}"
    );
    assert!(out.contains(&format!(
        "test TEST_fails ... FAILED (1 cycle, 2 checks, at T#0s)\n    {f}:16: sum: expected 3, actual 2\n    {f}:17: text: expected 'x', actual 'y'\n"
    )), "{out}");
    assert!(out.contains("test TEST_faults ... FAILED"), "{out}");
    assert!(out.contains("division by zero"), "{out}");
    assert!(out.contains(&format!(
        "test TEST_fails_in_cycle_3 ... FAILED (3 cycles, 3 checks, at T#20ms)\n    {f}:33: n stays below 3: expected TRUE, actual FALSE\n"
    )), "{out}");
    assert!(
        out.contains("test TEST_done_early ... ok (4 cycles, 4 checks, at T#30ms)"),
        "{out}"
    );
    assert!(
        out.ends_with("test result: FAILED. 2 passed, 3 failed\n"),
        "{out}"
    );
    let xml = std::fs::read_to_string(&junit).unwrap();
    assert!(xml.contains("tests=\"5\" failures=\"3\""), "{xml}");
    assert!(xml.contains("<testcase name=\"TEST_passes\""), "{xml}");
    let _ = std::fs::remove_file(&junit);

    let o = stc::cli::run_args(&["stc", "test", f, "--filter", "PASSES"]);
    assert_eq!(o.status, 0, "{o:?}");
    assert!(o.stdout.starts_with("running 1 test\n"), "{}", o.stdout);
}

#[test]
fn a_new_project_tests_pass_with_virtual_time() {
    let dir = std::env::temp_dir().join(format!("stc-test-cmd-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let d = dir.to_str().unwrap();
    assert_eq!(stc::cli::run_args(&["stc", "init", d]).status, 0);
    let m = dir.join("stc.toml");
    let o = stc::cli::run_args(&["stc", "test", "--manifest-path", m.to_str().unwrap()]);
    assert_eq!(o.status, 0, "{o:?}");
    assert!(
        o.stdout.contains("test TEST_Increment ... ok"),
        "{}",
        o.stdout
    );
    assert!(
        o.stdout
            .contains("test TEST_Timer_after_50ms ... ok (6 cycles, 7 checks, at T#50ms)"),
        "{}",
        o.stdout
    );
    let o = stc::cli::run_args(&[
        "stc",
        "fmt",
        "--check",
        "--manifest-path",
        m.to_str().unwrap(),
    ]);
    assert_eq!((o.status, o.stdout.as_str()), (0, ""), "{o:?}");
    let _ = std::fs::remove_dir_all(&dir);
}
