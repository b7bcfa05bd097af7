//! IR snapshots: each program of `tests/ir` lowered and dumped as
//! `stc build --emit ir` prints it.

mod common;

#[test]
fn ir_dumps_match_their_snapshots() {
    let dir = common::data_dir().join("ir");
    let mut snapshots = Vec::new();
    common::run_all(&dir, |case| {
        let name = case.file_name().unwrap().to_string_lossy().to_string();
        let out = stc::cli::run_args(&["stc", "build", "--emit", "ir", case.to_str().unwrap()]);
        if out.status != 0 {
            return Err(out.stderr);
        }
        snapshots.push((name, out.stdout));
        Ok(())
    });
    insta::with_settings!({snapshot_path => "../../../tests/ir/snapshots", prepend_module_to_snapshot => false}, {
        for (name, text) in snapshots {
            insta::assert_snapshot!(name, text);
        }
    });
}
