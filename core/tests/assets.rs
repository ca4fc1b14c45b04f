//! Every example job in assets/ parses and plans.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

#[test]
fn example_jobs_plan() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets");
    let mut n = 0;
    for entry in std::fs::read_dir(&dir).expect("assets folder") {
        let path = entry.expect("entry").path();
        if path.extension().is_some_and(|e| e == "toml") {
            let text = std::fs::read_to_string(&path).expect("readable");
            let job = trochoplan_core::Job::from_toml(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            trochoplan_core::plan(&job).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            n += 1;
        }
    }
    assert!(n >= 4, "{n} example jobs");
    // The paper's Table 1 file is exactly the built-in default job.
    let text = std::fs::read_to_string(dir.join("paper-table1.toml")).expect("readable");
    assert_eq!(trochoplan_core::Job::from_toml(&text).expect("parses"), trochoplan_core::Job::default());
}
