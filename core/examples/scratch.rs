fn main() {
    let t = std::time::Instant::now();
    for _ in 0..50 { let _ = trochoplan_core::plan(&trochoplan_core::Job::default()); }
    println!("plan {:?}", t.elapsed() / 50);
}
