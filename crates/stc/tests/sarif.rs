//! `--message-format sarif`: the document is SARIF 2.1.0.
//!
//! The OASIS schema is not vendored (its licence terms are not those of this
//! repository); instead this test checks what the schema requires of every
//! object stc writes: the top-level `version` and `runs`, a run's
//! `tool.driver.name`, a result's `message.text`, the enumerations of
//! `level` and `columnKind`, `ruleIndex` pointing at the rule with the same
//! id, regions with 1-based lines and columns (end after start), artifact
//! locations with a URI reference, related locations with unique ids, and
//! no property the schema does not define on these objects.

use serde_json::Value;

fn keys_within(v: &Value, allowed: &[&str], what: &str) {
    let obj = v
        .as_object()
        .unwrap_or_else(|| panic!("{what} is not an object: {v}"));
    for k in obj.keys() {
        assert!(
            allowed.contains(&k.as_str()),
            "{what} has unknown property `{k}`"
        );
    }
}

fn check_location(l: &Value) {
    keys_within(l, &["id", "physicalLocation", "message"], "location");
    if let Some(m) = l.get("message") {
        assert!(m["text"].is_string());
    }
    let p = &l["physicalLocation"];
    keys_within(p, &["artifactLocation", "region"], "physicalLocation");
    let uri = p["artifactLocation"]["uri"].as_str().expect("uri");
    assert!(
        !uri.is_empty() && !uri.contains(' ') && !uri.contains('\\'),
        "{uri}"
    );
    let r = &p["region"];
    keys_within(
        r,
        &["startLine", "startColumn", "endLine", "endColumn"],
        "region",
    );
    let n = |k: &str| r[k].as_u64().unwrap_or_else(|| panic!("region.{k}"));
    assert!(n("startLine") >= 1 && n("startColumn") >= 1);
    assert!(n("endLine") >= n("startLine"));
    if n("endLine") == n("startLine") {
        assert!(n("endColumn") > n("startColumn"), "{r}");
    }
}

fn check_sarif(doc: &Value) {
    keys_within(doc, &["$schema", "version", "runs"], "sarifLog");
    assert_eq!(doc["version"], "2.1.0");
    let runs = doc["runs"].as_array().expect("runs");
    assert_eq!(runs.len(), 1);
    let run = &runs[0];
    keys_within(run, &["tool", "results", "columnKind"], "run");
    assert_eq!(run["columnKind"], "unicodeCodePoints");
    let driver = &run["tool"]["driver"];
    keys_within(driver, &["name", "version", "rules"], "toolComponent");
    assert_eq!(driver["name"], "stc");
    let rules = driver["rules"].as_array().expect("rules");
    for r in rules {
        keys_within(
            r,
            &[
                "id",
                "name",
                "shortDescription",
                "fullDescription",
                "defaultConfiguration",
            ],
            "reportingDescriptor",
        );
        assert!(r["id"].is_string() && r["shortDescription"]["text"].is_string());
        assert!(["error", "warning", "note", "none"]
            .contains(&r["defaultConfiguration"]["level"].as_str().unwrap()));
    }
    for res in run["results"].as_array().expect("results") {
        keys_within(
            res,
            &[
                "ruleId",
                "ruleIndex",
                "level",
                "message",
                "locations",
                "relatedLocations",
            ],
            "result",
        );
        assert!(res["message"]["text"]
            .as_str()
            .is_some_and(|t| !t.is_empty()));
        assert!(["error", "warning", "note", "none"].contains(&res["level"].as_str().unwrap()));
        let i = res["ruleIndex"].as_u64().unwrap() as usize;
        assert_eq!(rules[i]["id"], res["ruleId"]);
        for l in res["locations"].as_array().expect("locations") {
            check_location(l);
        }
        if let Some(rel) = res.get("relatedLocations") {
            let mut ids = Vec::new();
            for l in rel.as_array().unwrap() {
                check_location(l);
                let id = l["id"].as_u64().expect("related location id");
                assert!(!ids.contains(&id));
                ids.push(id);
            }
        }
    }
}

#[test]
fn check_writes_a_valid_sarif_document() {
    let dir = std::env::temp_dir().join(format!("stc-sarif-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let f = dir.join("bad file.st");
    std::fs::write(
        &f,
        "PROGRAM P\n    VAR\n        x : INT;\n        unused : INT;\n    END_VAR\n    IF x > 0 THEN\n        x := TRUE;\n    END_WHILE;\nEND_PROGRAM\n",
    )
    .unwrap();
    let o = stc::cli::run_args(&[
        "stc",
        "check",
        "--message-format",
        "sarif",
        f.to_str().unwrap(),
    ]);
    assert_eq!(o.status, 1, "{o:?}");
    let doc: Value = serde_json::from_str(&o.stderr).expect("one JSON document");
    check_sarif(&doc);
    let results = doc["runs"][0]["results"].as_array().unwrap();
    assert!(!results.is_empty());
    assert!(results.iter().any(|r| r["level"] == "warning"), "{doc}");
    let first = results
        .iter()
        .find(|r| r["level"] == "error")
        .expect("an error");
    let loc = &first["locations"][0]["physicalLocation"];
    assert!(loc["artifactLocation"]["uri"]
        .as_str()
        .unwrap()
        .ends_with("bad%20file.st"));
    assert!(
        results.iter().any(|r| r.get("relatedLocations").is_some()),
        "{doc}"
    );

    // A clean project is a document with no results.
    std::fs::write(&f, "PROGRAM P\nEND_PROGRAM\n").unwrap();
    let o = stc::cli::run_args(&[
        "stc",
        "check",
        "--message-format",
        "sarif",
        f.to_str().unwrap(),
    ]);
    assert_eq!(o.status, 0, "{o:?}");
    let doc: Value = serde_json::from_str(&o.stderr).unwrap();
    check_sarif(&doc);
    assert_eq!(doc["runs"][0]["results"].as_array().unwrap().len(), 0);
    let _ = std::fs::remove_dir_all(&dir);
}
