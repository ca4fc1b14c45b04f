use trochoplan_core::*;
fn main() {
    for i in 0..8 {
        let r_e = 0.5 + 0.1 * i as f64;
        let job = Job { path: PathKind::Elliptical, aspect_ratio: r_e, ..Job::default() };
        let m = plan(&job).unwrap().metrics;
        println!("r_e {:.1} h {:.4} tcyc {:.3} thmax {:.3} tcool {:.3} mrr {:.0} eng {:.2} Wl {:.5} Wr {:.5}",
            r_e, m.h_max_mm, m.t_cycle_s, m.t_hmax_s, m.t_cooling_s, m.mrr_mm3_per_min, m.engagement_max_deg, m.waviness_left_mm, m.waviness_right_mm);
    }
    for kind in [PathKind::Circular, PathKind::CircularType, PathKind::LinearElliptical] {
        let job = Job { path: kind, aspect_ratio: 0.8, linear_distance: 0.75, ..Job::default() };
        let m = plan(&job).unwrap().metrics;
        println!("{:?} h {:.4} tcyc {:.3} thmax {:.3} tcool {:.3} mrr {:.0} eng {:.2} Wl {:.5} Wr {:.5}",
            kind, m.h_max_mm, m.t_cycle_s, m.t_hmax_s, m.t_cooling_s, m.mrr_mm3_per_min, m.engagement_max_deg, m.waviness_left_mm, m.waviness_right_mm);
    }
}
