use trochoplan_core::*;
fn main() {
    let job = Job { path: PathKind::LinearElliptical, slot_width: 15.853471236390334, tool_diameter: 10.931536777662792, teeth: 1, feed: 200.0, rpm: 1000.0, step: 2.752883202992419, aspect_ratio: 0.5, linear_distance: 4.970772461538742, slot_length: 200.0, ..Job::default() };
    let p = plan(&job).unwrap();
    let w = &p.right_wall;
    println!("W {:e} extreme {}", w.waviness_mm, w.extreme_x_mm);
    for (y, x) in &w.samples { if (x - w.extreme_x_mm).abs() > 1e-9 { println!("y {y} x {x} dev {:e}", x - w.extreme_x_mm); } }
}
