//! NC programs of a planned pocket corner ([`CornerPlan`]) and of a whole pocket
//! ([`PocketPlan`]: rings or the medial axis): the header description of each and the [`PathJob`] written by
//! the shared program frame [`program_for_path`] (same header, set-up, approach, retract and end
//! as a slot program). Used by `trochoplan corner/pocket --export` and by the GUI's Corner tab,
//! so both write the same text.
//!
//! Frames: a corner has its apex at X0 Y0 and its bisector along +X; a pocket keeps the
//! coordinates of its polygon; the stock top is Z0 in both.

use super::{NcOptions, NcProgram, PathJob, PathLevel, program_for_path, program_for_path_levels};
use crate::corner::{CornerPlan, CornerSettings};
use crate::error::{Error, Param};
use crate::pocket::{AdaptivePlan, LinkKind, PerforativePlan, PocketPath, PocketPlan, RingPlan};
use crate::toolpath::Entry;

/// What a corner or pocket plan does not carry: the cutting depth and the spindle speed.
/// Checked by [`PathJob::validate`] (errors name `depth` and `rpm`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CutSetup {
    /// Cutting depth below the stock top Z0 (mm).
    pub depth_mm: f64,
    pub spindle_rpm: f64,
}

impl Default for CutSetup {
    /// The CLI's defaults: 6 mm deep (the slot job's a_p), 2000 rpm (Wagih et al. Table 1).
    fn default() -> Self {
        CutSetup { depth_mm: 6.0, spindle_rpm: 2000.0 }
    }
}

/// The program of the corner `plan`, planned with `settings` for the symmetric corner of
/// `angle_deg` (the interior angle as the user gave it, written into the header).
pub fn corner_program(
    plan: &CornerPlan,
    settings: &CornerSettings,
    angle_deg: f64,
    cut: CutSetup,
    opts: &NcOptions,
) -> Result<NcProgram, Error> {
    if !(angle_deg.is_finite() && angle_deg > 0.0 && angle_deg < 180.0) {
        return Err(Error::param(Param::Angle, angle_deg, "a finite number between 0 and 180 degrees"));
    }
    let s = settings;
    let a_str = s.straight_engagement()?;
    let job = PathJob {
        toolpath: &plan.toolpath,
        depth_mm: cut.depth_mm,
        feed_mm_per_min: s.feed_mm_per_min,
        spindle_rpm: cut.spindle_rpm,
        tool_diameter_mm: 2.0 * s.tool_radius,
        default_title: "TrochoPlan corner",
        description: vec![
            format!(
                "corner {} deg, method {}, {} circles, path {:.3} mm",
                angle_deg,
                plan.method.name(),
                plan.circles.len(),
                plan.path_length_mm
            ),
            format!("apex X0 Y0, bisector along +X, walls {:.3} mm", s.edge_length),
            format!("depth {:.3} mm below the stock top Z0", cut.depth_mm),
            format!(
                "tool T{} D {:.3} mm, {:.0} rpm, feed {:.1} mm/min",
                opts.frame.tool_number,
                2.0 * s.tool_radius,
                cut.spindle_rpm,
                s.feed_mm_per_min
            ),
            format!(
                "a_e {:.4} mm, engagement straight {:.2} deg, target {:.2} deg",
                s.step_over,
                a_str.to_degrees(),
                s.target.to_degrees()
            ),
        ],
    };
    program_for_path(&job, opts)
}

/// The program of the whole pocket `plan`, any strategy ([`PocketPlan::toolpath`]).
pub fn pocket_program(plan: &PocketPlan, cut: CutSetup, opts: &NcOptions) -> Result<NcProgram, Error> {
    pocket_path_program(plan.path(), pocket_summary(plan), cut, &[], opts)
}

/// The two header lines that summarise the plan of the whole pocket `plan`, any strategy.
pub(super) fn pocket_summary(plan: &PocketPlan) -> [String; 2] {
    match plan {
        PocketPlan::Rings(p) => ring_summary(p),
        PocketPlan::MedialAxis(p) => perforative_summary(p),
        PocketPlan::Adaptive(p) => adaptive_summary(p),
        PocketPlan::Slot(p) => {
            let ramp_deg = match p.path.toolpath.entries.first() {
                Some(Entry::Ramp(r)) => r.ramp_rad.to_degrees(),
                _ => p.options.ramp_deg,
            };
            [
                format!(
                    "{}, slot {}, ramp {:.2} deg, passes {:.2} mm",
                    outline_words(&p.path),
                    p.options.direction.name(),
                    ramp_deg,
                    p.ramp_pass_depth_mm
                ),
                format!(
                    "at depth {:.1} mm, {} loops, peak {:.2} deg, target {:.2} deg",
                    p.path.measurement.length_at_depth_mm,
                    p.loops,
                    p.path.measurement.max_engagement_rad.to_degrees(),
                    p.target_rad.to_degrees()
                ),
            ]
        }
    }
}

/// The summary of an adaptively cleared pocket (its program: per part a helical entry from
/// above the stock top, no plunge, then its moves at depth; a retract and rapid between parts).
/// The outline in a program's header: "pocket of 4 vertices", and its islands if it has any
/// ("pocket of 4 vertices and 2 islands").
fn outline_words(path: &PocketPath) -> String {
    let vertices = path.polygon.vertices().len();
    match path.islands.len() {
        0 => format!("pocket of {vertices} vertices"),
        1 => format!("pocket of {vertices} vertices and 1 island"),
        n => format!("pocket of {vertices} vertices and {n} islands"),
    }
}

fn adaptive_summary(plan: &AdaptivePlan) -> [String; 2] {
    let way_in = match plan.parts[0].entry {
        Entry::Helix(h) => format!("helix R {:.3} mm {:.1} deg", h.radius, plan.options.ramp_deg),
        Entry::Ramp(_) => format!("zig-zag ramp {:.1} deg", plan.options.ramp_deg),
        Entry::Outside { .. } => format!("from outside the stock (open edges {:?})", plan.open_edges),
        Entry::Down { .. } => "straight down into cleared stock".to_owned(),
    };
    [
        format!(
            "{}, adaptive {}, {} part(s), {}",
            outline_words(&plan.path),
            plan.options.direction.name(),
            plan.parts.len(),
            way_in
        ),
        format!(
            "at depth {:.1} mm, links {:.1} mm, peak {:.2} deg, target {:.2} deg",
            plan.path.measurement.length_at_depth_mm,
            plan.path.link_length_mm,
            plan.path.measurement.max_engagement_rad.to_degrees(),
            plan.target_rad.to_degrees()
        ),
    ]
}

/// The summary of a pocket cleared by rings (its program: its tool path, [`RingPlan::path`],
/// retracting before the links that a straight move cannot take).
fn ring_summary(plan: &RingPlan) -> [String; 2] {
    let feed_links = plan.links.iter().filter(|l| l.kind == LinkKind::Feed).count();
    [
        format!(
            "{}, method {}, {} rings, {} corner trochoids",
            outline_words(&plan.path),
            plan.method.name(),
            plan.rings.len(),
            plan.trochoid_corners
        ),
        format!(
            "rings {:.3} mm, {} feed links {:.3} mm, {} retract links",
            plan.path_length_mm,
            feed_links,
            plan.path.link_length_mm,
            plan.links.len() - feed_links
        ),
    ]
}

/// The program of a pocket cleared by perforative trochoids along its medial axis: its path
/// in machining order, a retract, rapid and plunge at the start of every part but the first.
pub fn perforative_program(plan: &PerforativePlan, cut: CutSetup, opts: &NcOptions) -> Result<NcProgram, Error> {
    pocket_path_program(&plan.path, perforative_summary(plan), cut, &[], opts)
}

/// The summary of a pocket cleared along its medial axis.
fn perforative_summary(plan: &PerforativePlan) -> [String; 2] {
    [
        format!(
            "{}, method medial-axis, {} circles, {} part(s)",
            outline_words(&plan.path),
            plan.circles.len(),
            plan.parts
        ),
        format!(
            "path {:.3} mm, body engagement {:.2} deg (target {:.2} deg)",
            plan.path.measurement.length_at_depth_mm,
            plan.body_max_rad.to_degrees(),
            plan.target_rad.to_degrees()
        ),
    ]
}

/// A pocket's program in polygon coordinates: two summary lines of the plan, then the frame
/// and the tool lines shared by every pocket method; the path at `levels`
/// ([`program_for_path_levels`], a line on them in the header), at `cut.depth_mm` when there
/// are none.
pub(super) fn pocket_path_program(
    path: &PocketPath,
    summary: [String; 2],
    cut: CutSetup,
    levels: &[PathLevel],
    opts: &NcOptions,
) -> Result<NcProgram, Error> {
    let [first, second] = summary;
    let s = &path.settings;
    let job = PathJob {
        toolpath: &path.toolpath,
        depth_mm: cut.depth_mm,
        feed_mm_per_min: s.feed_mm_per_min,
        spindle_rpm: cut.spindle_rpm,
        tool_diameter_mm: 2.0 * s.tool_radius,
        default_title: "TrochoPlan pocket",
        description: vec![
            first,
            second,
            format!("polygon file coordinates, depth {:.3} mm below the stock top Z0", cut.depth_mm),
            format!(
                "tool T{} D {:.3} mm, {:.0} rpm, feed {:.1} mm/min, a_e {:.4} mm",
                opts.frame.tool_number,
                2.0 * s.tool_radius,
                cut.spindle_rpm,
                s.feed_mm_per_min,
                s.step_over
            ),
        ],
    };
    if levels.is_empty() {
        return program_for_path(&job, opts);
    }
    let axial = levels.iter().map(|l| l.top_mm + l.depth_mm).fold(0.0, f64::max);
    // a floor pass: a last level thinner than the others
    let last = levels.last().map_or(axial, |l| l.top_mm + l.depth_mm);
    let levels_text = if levels.len() > 1 && last < axial - 1e-9 {
        format!("{} levels of {axial:.3} mm and a floor pass of {last:.3} mm", levels.len() - 1)
    } else {
        format!("{} levels of {axial:.3} mm", levels.len())
    };
    let mut job = job;
    job.description
        .push(format!("{levels_text}, each entered {:.1} mm above the floor above", crate::toolpath::HELIX_START_Z_MM));
    program_for_path_levels(&job, levels, opts)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::corner::{Corner, CornerMethod, CornerScenario, plan_corner};
    use crate::engagement::parse_points;
    use crate::geom::{P2, Polygon};
    use crate::nc::{Dialect, backplot};
    use crate::pocket::{PocketRequest, plan_rings};

    fn corner_plan(angle_deg: f64) -> (CornerPlan, CornerSettings) {
        let s = CornerSettings::new(5.0, 2.0).expect("settings");
        let sc = CornerScenario::new(Corner::symmetric(angle_deg.to_radians()).expect("corner"), s).expect("scenario");
        (plan_corner(&sc, CornerMethod::Variable).expect("plan"), s)
    }

    fn polyline_length(pts: &[P2]) -> f64 {
        pts.windows(2).map(|w| (w[1] - w[0]).norm()).sum()
    }

    /// Relative length agreement of a back-plot with its plan: the rs274 tests' 0.1 %.
    const LENGTH_REL: f64 = 1e-3;

    #[test]
    fn corner_program_retraces_the_plan_and_describes_it() {
        let (plan, s) = corner_plan(120.0);
        let cut = CutSetup { depth_mm: 3.0, spindle_rpm: 3000.0 };
        let prog = corner_program(&plan, &s, 120.0, cut, &NcOptions::default()).expect("program");
        let t = &prog.text;
        assert!(t.starts_with("(TrochoPlan corner)\n(corner 120 deg, method variable, "), "{t}");
        assert!(t.contains("\nG1 Z-3.0000 F600.0\n") && t.contains("\nS3000 M3\n"), "{t}");
        // the program's own motion, read back from its text, from the path start to its end
        let pts = backplot(t, Dialect::LinuxCnc, 1e-3).expect("back-plot");
        let (first, last) = (pts.first().expect("points"), pts.last().expect("points"));
        let (start, end) =
            (plan.toolpath.segments()[0].start(), plan.toolpath.segments()[plan.toolpath.segments().len() - 1].end());
        assert!((*first - start).norm() < 1e-4 && (*last - end).norm() < 1e-4, "{first:?} {last:?}");
        let len = polyline_length(&pts);
        assert!(
            (len - plan.path_length_mm).abs() < LENGTH_REL * plan.path_length_mm,
            "{len} vs {}",
            plan.path_length_mm
        );
        // chords instead of arcs: the same motion, more blocks, no arcs
        let chords = NcOptions { linear_segments: true, ..NcOptions::default() };
        let p2 = corner_program(&plan, &s, 120.0, cut, &chords).expect("chords");
        assert!(p2.blocks > prog.blocks && !p2.text.contains("\nG3") && prog.text.contains("\nG3"));
    }

    #[test]
    fn bad_corner_and_pocket_inputs_name_the_parameter() {
        let (plan, s) = corner_plan(90.0);
        let o = NcOptions::default();
        for (cut, angle, opts, name) in [
            (CutSetup { depth_mm: -1.0, ..CutSetup::default() }, 90.0, o.clone(), "depth"),
            (CutSetup { spindle_rpm: f64::NAN, ..CutSetup::default() }, 90.0, o.clone(), "rpm"),
            (CutSetup::default(), f64::NAN, o.clone(), "angle"),
            (CutSetup::default(), 180.0, o.clone(), "angle"),
            (CutSetup::default(), 90.0, NcOptions { compact: true, ..o.clone() }, "compact"),
            (CutSetup::default(), 90.0, NcOptions { tolerance_mm: 2.0, ..o.clone() }, "tolerance"),
        ] {
            let e = corner_program(&plan, &s, angle, cut, &opts).expect_err("invalid");
            assert_eq!(e.subject(), Some(name), "{e}");
        }
        let pocket = rectangle_pocket();
        let e = pocket_program(&pocket, CutSetup { depth_mm: 0.0, ..CutSetup::default() }, &o).expect_err("depth");
        assert_eq!(e.subject(), Some("depth"), "{e}");
    }

    /// 60 × 40 mm rectangle, D = 10, a_e = 4: the papers' plain rings ([`plan_rings`], the
    /// layout without entry or core) at offsets d = 5, 9, 13, 17 (d < 20) with perimeters
    /// 200 − 8d = 160, 128, 96, 64 (448 mm), joined by three feed links of a_e = 4 mm (12 mm).
    fn rectangle_pocket() -> PocketPlan {
        let polygon = Polygon::new(parse_points("0,0\n60,0\n60,40\n0,40\n", "rect").expect("points")).expect("poly");
        let req = PocketRequest { polygon, step_over_mm: 4.0, spacing_mm: 1.0, ..PocketRequest::default() };
        let settings = req.settings().expect("settings");
        PocketPlan::Rings(plan_rings(&req.polygon, settings, CornerMethod::Plain).expect("pocket"))
    }

    #[test]
    fn pocket_program_writes_rings_and_links() {
        let plan = rectangle_pocket();
        let prog =
            pocket_program(&plan, CutSetup::default(), &NcOptions { dialect: Dialect::Fanuc, ..NcOptions::default() })
                .expect("program");
        let t = &prog.text;
        assert!(t.contains("(pocket of 4 vertices, method plain, 4 rings, 0 corner trochoids)"), "{t}");
        assert!(t.contains("(rings 448.000 mm, 3 feed links 12.000 mm, 0 retract links)"), "{t}");
        let pts = backplot(t, Dialect::Fanuc, 1e-3).expect("back-plot");
        let PocketPlan::Rings(rings) = &plan else { panic!("rings expected") };
        let want = rings.path_length_mm + rings.path.link_length_mm;
        let len = polyline_length(&pts);
        assert!((len - want).abs() < LENGTH_REL * want, "{len} vs {want}");
    }
}
