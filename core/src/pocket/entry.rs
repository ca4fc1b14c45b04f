//! How the tool gets down to depth in every pocket method (docs/pockets.md): a helix about a
//! point of large clearance, or — where not even the smallest helix fits — a straight zig-zag
//! ramp along the longest line through the region of tool centres around that point. Both start
//! [`HELIX_START_Z_MM`] above the stock top and descend at most at the ramp angle; neither
//! plunges. Where a pocket is open on a side (adaptive clearing's `--open-edges`), the tool
//! goes straight down *outside* the stock instead, beyond the open edge, where its whole disc
//! is off the material ([`Entry::Outside`]). What an entry clears at depth (its *bore*: the
//! helix circle, or the ramp line) is the first move of the path at depth and the `before`
//! path of the evaluator, so the tool never cuts from solid material straight down.

use super::adaptive::AdaptiveOptions;
use super::rings::link_is_inside;
use crate::error::{Error, Param, num};
use crate::geom::medial::Walls;
use crate::geom::{P2, Polygon, p2};
use crate::toolpath::entry::{Entry, HELIX_START_Z_MM, Helix, Ramp};
use std::f64::consts::PI;

/// Directions tried for the ramp line (every 1°).
const RAMP_DIRECTIONS: usize = 180;
/// Ramp lines at least this share of the longest compete on their mean clearance.
const RAMP_LENGTH_SHARE: f64 = 0.95;
/// Points along a ramp line where its clearance is sampled.
const RAMP_CLEARANCE_SAMPLES: usize = 16;
/// Bisection steps for the ramp line's ends.
const RAMP_BISECTION: usize = 40;

/// The helix radius r_h (mm) for a tool-centre region whose largest inscribed circle has
/// radius `inscribed` (mm): the option, else 0.375·D reduced down to 0.25·D (a bore of 50 % of
/// D) where the region is narrower; r_h ≤ 0.98 × `inscribed` keeps the bore inside. Error
/// (naming `--helix-radius`, one limit only) when that leaves less than the option, or, without
/// the option, less than 0.25·D: then no helix fits, and the error says so and names the slot
/// ([`crate::pocket::slot`]), which ramps into such a pocket.
pub(crate) fn helix_radius(options: &AdaptiveOptions, r: f64, inscribed: f64) -> Result<f64, Error> {
    let wanted = options.helix_radius_mm.unwrap_or(0.75 * r);
    let least = if options.helix_radius_mm.is_some() { wanted } else { 0.5 * r };
    // The helix circle must keep its bore inside the region: r_h ≤ inscribed radius.
    let fits = 0.98 * inscribed;
    let r_h = wanted.min(fits);
    if r_h >= least {
        return Ok(r_h);
    }
    let slot = "--method slot (what adaptive clearing, the default, picks for such a pocket) ramps into it instead";
    let why = if options.helix_radius_mm.is_some() {
        format!(
            "at most {} mm for this pocket (0.98 × the inscribed radius {} mm of its tool-centre region){}",
            num(fits),
            num(inscribed),
            if fits < 0.5 * r { format!("; {slot}") } else { String::new() }
        )
    } else {
        format!(
            "a pocket with room for a helix: none of at least 0.25 × D = {} mm fits this one (0.98 × the \
             inscribed radius {} mm of its tool-centre region is {} mm); {slot}",
            num(0.5 * r),
            num(inscribed),
            num(fits)
        )
    };
    Err(Error::param(Param::HelixRadius, wanted, why))
}

/// The entry of a part whose tool centres may reach `inscribed` mm around `center`: a helix
/// about it ([`helix_radius`], starting at `start_angle`, counter-clockwise), else — when no
/// helix radius was asked for and not even 0.25·D fits — a zig-zag ramp on the longest line
/// through `center` along which the tool centre keeps r from every wall of `polygon`
/// ([`ramp_line`]). Error naming `--helix-radius` when that line is shorter than D too.
pub fn entry_at(
    polygon: &Polygon,
    r: f64,
    options: &AdaptiveOptions,
    center: P2,
    inscribed: f64,
    start_angle: f64,
) -> Result<Entry, Error> {
    let ramp_rad = options.ramp_deg.to_radians();
    match helix_radius(options, r, inscribed) {
        Ok(radius) => Ok(Entry::Helix(Helix { center, radius, start_angle, sense: 1.0, ramp_rad })),
        Err(e) if options.helix_radius_mm.is_some() => Err(e),
        Err(_) => {
            let (start, end, longest) = ramp_line(polygon, r, center);
            if (end - start).norm() < 2.0 * r {
                return Err(Error::param(
                    Param::HelixRadius,
                    0.5 * r,
                    format!(
                        "a pocket with room for a helix of 0.25 × D or a straight ramp of at least D = {} mm \
                         (the longest line for the tool centre here is {} mm)",
                        num(2.0 * r),
                        num(longest)
                    ),
                ));
            }
            Ok(Entry::Ramp(Ramp { start, end, ramp_rad }))
        }
    }
}

/// The longest straight line through `center` along which the tool centre keeps r from every
/// edge of `polygon` ([`link_is_inside`]): every 1° of direction, each end found by bisection
/// (the segment from `center` stays inside up to one length and not beyond, the region being
/// closed). Of the lines at least 95 % as long as the longest (and at least D when the
/// longest is), the one with the largest mean clearance from the walls (sampled at 16
/// points) — in a slot its middle line, not its diagonal, so the passes after it cut even
/// bands on both sides. Returns its ends and the longest length; a point (both ends at
/// `center`) where the centre itself does not fit.
pub fn ramp_line(polygon: &Polygon, r: f64, center: P2) -> (P2, P2, f64) {
    if !link_is_inside(polygon, center, center, r) {
        return (center, center, 0.0);
    }
    let v = polygon.vertices();
    let reach = v.iter().map(|q| (q - center).norm()).fold(0.0, f64::max);
    let extent = |u: P2| {
        let (mut good, mut bad) = (0.0, reach);
        for _ in 0..RAMP_BISECTION {
            let mid = 0.5 * (good + bad);
            if link_is_inside(polygon, center, center + u * mid, r) {
                good = mid;
            } else {
                bad = mid;
            }
        }
        good
    };
    let lines: Vec<(P2, P2)> = (0..RAMP_DIRECTIONS)
        .map(|k| {
            let a = PI * k as f64 / RAMP_DIRECTIONS as f64;
            let u = p2(a.cos(), a.sin());
            (center - u * extent(-u), center + u * extent(u))
        })
        .collect();
    let longest = lines.iter().map(|(a, b)| (b - a).norm()).fold(0.0, f64::max);
    let walls = Walls::new(polygon);
    let mean_clearance = |(a, b): &(P2, P2)| {
        let n = RAMP_CLEARANCE_SAMPLES;
        (0..=n).map(|k| walls.clearance(a + (b - a) * (k as f64 / n as f64))).sum::<f64>() / (n + 1) as f64
    };
    let least = longest.min((RAMP_LENGTH_SHARE * longest).max(2.0 * r));
    let (a, b) = lines
        .into_iter()
        .filter(|(a, b)| (b - a).norm() >= least)
        .max_by(|x, y| mean_clearance(x).total_cmp(&mean_clearance(y)))
        .unwrap_or((center, center));
    (a, b, longest)
}

/// Most helix turns (or zig-zag legs) of one descent: beyond, the program grows without a
/// purpose (a helix of 1e-9 mm radius would turn 10¹⁰ times).
pub const MAX_DESCENT_TURNS: f64 = 2000.0;

/// The descent's work is bounded: with the smallest helix the pocket may get (the option, else
/// 0.25·D) and the ramp angle, descending from [`HELIX_START_Z_MM`] to the depth takes at most
/// [`MAX_DESCENT_TURNS`] turns (a zig-zag ramp, at least D long, takes fewer legs than a helix
/// of 0.25·D takes turns: a leg descends D·tan θ, a turn π·D/2·tan θ). Error naming
/// `--helix-radius` (when given) or `--ramp-angle`, and the least value.
pub(crate) fn validate_descent(options: &AdaptiveOptions, r: f64) -> Result<(), Error> {
    let drop = HELIX_START_Z_MM + options.depth_mm;
    let tan = options.ramp_deg.to_radians().tan();
    let r_h = options.helix_radius_mm.unwrap_or(0.5 * r).min(0.5 * r);
    let turns = drop / (std::f64::consts::TAU * r_h * tan);
    if turns <= MAX_DESCENT_TURNS {
        return Ok(());
    }
    let least_radius = drop / (std::f64::consts::TAU * tan * MAX_DESCENT_TURNS);
    if let Some(h) = options.helix_radius_mm
        && least_radius <= 0.5 * r
    {
        return Err(Error::param(
            Param::HelixRadius,
            h,
            format!(
                "at least {} mm at a {}° ramp and {} mm depth (at most {MAX_DESCENT_TURNS} turns down)",
                num(least_radius),
                num(options.ramp_deg),
                num(options.depth_mm)
            ),
        ));
    }
    let least_deg = (drop / (std::f64::consts::TAU * r_h * MAX_DESCENT_TURNS)).atan().to_degrees();
    Err(Error::param(
        Param::RampAngle,
        options.ramp_deg,
        format!(
            "at least {}° for a helix of {} mm radius and {} mm depth (at most {MAX_DESCENT_TURNS} turns down)",
            num(least_deg),
            num(r_h),
            num(options.depth_mm)
        ),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rect(w: f64, h: f64) -> Polygon {
        Polygon::new(vec![p2(0.0, 0.0), p2(w, 0.0), p2(w, h), p2(0.0, h)]).expect("rect")
    }

    #[test]
    fn a_narrow_pocket_gets_a_ramp_along_its_length() {
        // 60 × 14, D = 10: the tool centres lie in the 50 × 4 rectangle [5, 55] × [5, 9]; its
        // inscribed radius 2 is below 0.98⁻¹ × 0.25·D, so no helix. The lines through its
        // centre (30, 7) from 0° to 4° run end wall to end wall (tan 4° · 50 = 3.5 ≤ 4), the
        // longest 50/cos 4° = 50.12 mm; all are within 95 % of it, and the middle line y = 7
        // (0°, 50 mm) keeps the most clearance.
        let opts = AdaptiveOptions::default();
        let e = entry_at(&rect(60.0, 14.0), 5.0, &opts, p2(30.0, 7.0), 2.0, 0.0).expect("ramp");
        let Entry::Ramp(ramp) = e else { panic!("ramp expected, got {e:?}") };
        let len = (ramp.end - ramp.start).norm();
        assert!((ramp.start.y - 7.0).abs() < 1e-9 && (ramp.end.y - 7.0).abs() < 1e-9, "{ramp:?}");
        assert!((len - 50.0).abs() < 1e-6, "{ramp:?}");
        // 6.5 mm at 5° on 50 mm legs: 6.5 / (50 tan 5°) = 1.49 → 2 legs, the first from `start`
        assert_eq!(ramp.legs(6.5), 2);
        assert_eq!(ramp.first_point(6.5), ramp.start);
        let want = ((2.0 * len).powi(2) + 6.5f64.powi(2)).sqrt();
        assert!((ramp.length(6.5) - want).abs() < 1e-6);
    }

    #[test]
    fn too_narrow_for_a_ramp_of_one_diameter_names_the_helix_radius() {
        // 14 × 14, D = 10: the centres lie in a 4 × 4 square, its longest line the diagonal
        // 4√2 = 5.66 mm < D.
        let opts = AdaptiveOptions::default();
        let e = entry_at(&rect(14.0, 14.0), 5.0, &opts, p2(7.0, 7.0), 2.0, 0.0).expect_err("too small");
        assert_eq!(e.subject(), Some("helix-radius"), "{e}");
        assert!(e.to_string().contains("5.6568542"), "{e}");
        // an explicit helix radius that does not fit is an error, not a ramp
        let asked = AdaptiveOptions { helix_radius_mm: Some(3.0), ..opts };
        let e = entry_at(&rect(60.0, 14.0), 5.0, &asked, p2(30.0, 7.0), 2.0, 0.0).expect_err("asked");
        assert_eq!(e.subject(), Some("helix-radius"), "{e}");
    }

    #[test]
    fn helix_radius_errors_state_one_limit() {
        // inscribed 1.8 mm (a 14 mm wide pocket, D = 10, s_f = 0.2): 0.98 × 1.8 = 1.764 mm, below
        // 0.25·D = 2.5 mm, so no helix fits; the message gives that one limit and the slot,
        // no lower bound above it.
        let opts = AdaptiveOptions::default();
        let e = helix_radius(&opts, 5.0, 1.8).expect_err("no helix fits");
        let text = e.to_string();
        assert_eq!(e.subject(), Some("helix-radius"), "{e}");
        assert!(text.contains("none of at least 0.25 × D = 2.5 mm fits") && text.contains("1.764"), "{e}");
        assert!(text.contains("--method slot") && !text.contains("at most"), "{e}");
        let asked = AdaptiveOptions { helix_radius_mm: Some(3.75), ..opts };
        let e = helix_radius(&asked, 5.0, 1.8).expect_err("too large");
        let text = e.to_string();
        assert!(text.contains("at most 1.764") && text.contains("--method slot"), "{e}");
        assert!(!text.contains("below") && !text.contains("least"), "{e}");
        // an asked radius that fits is taken, however small
        assert_eq!(helix_radius(&AdaptiveOptions { helix_radius_mm: Some(1.5), ..opts }, 5.0, 1.8).ok(), Some(1.5));
        // room for a smaller helix than asked: one upper limit, no slot
        let e = helix_radius(&asked, 5.0, 3.0).expect_err("too large");
        assert!(e.to_string().contains("at most 2.94") && !e.to_string().contains("slot"), "{e}");
    }

    #[test]
    fn wide_pockets_get_the_default_helix() {
        let opts = AdaptiveOptions::default();
        let e = entry_at(&rect(60.0, 40.0), 5.0, &opts, p2(30.0, 20.0), 15.0, 0.0).expect("helix");
        assert!(matches!(e, Entry::Helix(h) if (h.radius - 3.75).abs() < 1e-12), "{e:?}");
        let m = e.mirrored().mirrored();
        assert_eq!(m, e);
    }
}
