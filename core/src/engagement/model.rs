//! Analytic engagement angle: the straight cut and the two-circle model of Wu et al. (2016)
//! eqs. (2)–(6), in the form derived in docs/corners.md.
//!
//! Symbols: tool radius `r`; previous offset circle (O1, R1) — everything inside it is already
//! cut, everything outside is assumed to be material; current offset circle (O2, R2); the tool
//! centre runs on (O2, ρ = R2 − r). Angles in radians.

use crate::error::{Error, Param, num};
use crate::geom::{Circle, P2, bisect_edge, cross, golden_min, p2};
use serde::{Deserialize, Serialize};
use std::f64::consts::{PI, TAU};

/// Direction of travel on a circle: counter-clockwise (G3) or clockwise (G2), seen from +Z.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Turn {
    /// Counter-clockwise, G3.
    Ccw,
    /// Clockwise, G2.
    Cw,
}

/// Straight-cut engagement `a = arccos(1 − a_e/r)` (docs/corners.md) for a radial depth
/// `0 ≤ a_e ≤ 2r`. Errors name the step-over or the tool diameter and the allowed range.
pub fn straight_engagement(a_e: f64, r: f64) -> Result<f64, Error> {
    if !(r.is_finite() && r > 0.0) {
        return Err(Error::param(Param::ToolDiameter, 2.0 * r, "a finite number > 0 mm"));
    }
    if !(a_e.is_finite() && (0.0..=2.0 * r).contains(&a_e)) {
        return Err(Error::param(Param::StepOver, a_e, format!("from 0 to the tool diameter {} mm", num(2.0 * r))));
    }
    Ok((1.0 - a_e / r).clamp(-1.0, 1.0).acos())
}

/// Inverse of [`straight_engagement`]: radial depth `a_e = r(1 − cos a)`.
pub fn radial_depth_for_engagement(a: f64, r: f64) -> f64 {
    r * (1.0 - a.cos())
}

/// Engagement of one tool position on the current circle.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct EngagementAt {
    /// Engaged angle (rad), 0 when the tool is in air.
    pub angle: f64,
    /// True when the whole tool is in material (`d ≥ R1 + r`): reported as π, the slotting limit.
    pub slotting: bool,
}

/// Maximum of the engagement over one pass of the current circle.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct MaxEngagement {
    /// Maximum engaged angle (rad).
    pub angle: f64,
    /// Polar angle φ of the tool centre about O2 where it occurs (rad, in [0, 2π)).
    pub phi: f64,
    /// True when some position of the pass is fully in material.
    pub slotting: bool,
}

/// Two-circle engagement model (Wu et al. 2016 eqs. 2–6; docs/corners.md).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct TwoCircle {
    /// Previous offset circle (O1, R1): already cut.
    pub previous: Circle,
    /// Current offset circle (O2, R2).
    pub current: Circle,
    /// Tool radius r (mm).
    pub tool_radius: f64,
    /// Direction of travel on the current circle.
    pub turn: Turn,
}

/// Largest scan step of [`TwoCircle::max_engagement`] (1°).
const SCAN_STEP: f64 = PI / 180.0;
/// Fewest scan samples across the arc where the tool can be engaged.
const MIN_SCAN_SAMPLES: usize = 64;
/// Width in φ (rad) to which each maximum of the scan is refined.
const REFINE_TOL: f64 = 1e-12;
/// Bisection steps onto the edge of slotting (a step of 1° halved to below the last bit).
const EDGE_BISECTION: usize = 64;

impl TwoCircle {
    /// Checks that the radii are finite and positive and that the tool fits in the current
    /// circle (`R2 ≥ r`).
    pub fn validate(&self) -> Result<(), Error> {
        let r = self.tool_radius;
        if !(r.is_finite() && r > 0.0) {
            return Err(Error::param(Param::ToolDiameter, 2.0 * r, "a finite number > 0 mm"));
        }
        let (c1, c2) = (self.previous, self.current);
        if !(c1.radius.is_finite() && c1.radius > 0.0) {
            return Err(Error::geometry("R1", c1.radius, "a finite number > 0 mm"));
        }
        if !(c2.radius.is_finite() && c2.radius >= r) {
            return Err(Error::geometry("R2", c2.radius, format!("a finite number ≥ the tool radius {} mm", num(r))));
        }
        for (name, p) in [("O1", c1.center), ("O2", c2.center)] {
            if !(p.x.is_finite() && p.y.is_finite()) {
                return Err(Error::geometry(name, format!("({}, {})", num(p.x), num(p.y)), "finite coordinates"));
            }
        }
        Ok(())
    }

    /// Tool centre `C(φ) = O2 + ρ(cos φ, sin φ)` (paper eq. 5).
    pub fn tool_center(&self, phi: f64) -> P2 {
        let rho = self.current.radius - self.tool_radius;
        self.current.center + p2(phi.cos(), phi.sin()) * rho
    }

    /// Engagement at tool-centre polar angle φ about O2 (docs/corners.md):
    /// `δ = arccos((d² + r² − R1²)/(2dr))` (eqs. 3, 6), `β` = angle from C→E1 to C→O1 turning
    /// with the travel, `a = max(0, β − δ)` (eq. 4), with the guards of docs/corners.md.
    pub fn engagement_at(&self, phi: f64) -> EngagementAt {
        let r = self.tool_radius;
        let (o1, r1) = (self.previous.center, self.previous.radius);
        let u = p2(phi.cos(), phi.sin());
        let c = self.tool_center(phi);
        let e1 = c + u * r;
        let air = EngagementAt { angle: 0.0, slotting: false };
        if (e1 - o1).norm() <= r1 {
            return air; // the wall point is already cut
        }
        let d = (c - o1).norm();
        if d + r <= r1 {
            return air; // the tool is wholly inside the previous circle
        }
        if d >= r1 + r {
            return EngagementAt { angle: PI, slotting: true };
        }
        let delta = ((d * d + r * r - r1 * r1) / (2.0 * d * r)).clamp(-1.0, 1.0).acos();
        let w = (o1 - c) / d;
        let gamma0 = u.dot(&w).clamp(-1.0, 1.0).acos();
        let x = cross(u, w);
        let beta = match self.turn {
            Turn::Ccw if x >= 0.0 => gamma0,
            Turn::Cw if x <= 0.0 => gamma0,
            _ => TAU - gamma0,
        };
        EngagementAt { angle: (beta - delta).max(0.0), slotting: false }
    }

    /// The arc of φ where the wall point `E1 = O2 + R2·(cos φ, sin φ)` lies outside the
    /// previous circle, as (start, width): the only tool positions that can be engaged
    /// ([`TwoCircle::engagement_at`] is 0 wherever E1 is already cut). With `v = O2 − O1`,
    /// `|v + R2·u|² > R1²` ⟺ `v·u > (R1² − |v|² − R2²)/(2R2)`, an arc centred on the direction of v.
    /// None when there is no such position.
    fn engaged_arc(&self) -> Option<(f64, f64)> {
        let v = self.current.center - self.previous.center;
        let dist = v.norm();
        let (r1, r2) = (self.previous.radius, self.current.radius);
        let rhs = (r1 * r1 - dist * dist - r2 * r2) / (2.0 * r2);
        let theta = if dist > 0.0 { v.y.atan2(v.x) } else { 0.0 };
        if rhs < -dist {
            Some((theta, TAU))
        } else if rhs >= dist {
            None
        } else {
            let half = (rhs / dist).clamp(-1.0, 1.0).acos();
            Some((theta - half, 2.0 * half))
        }
    }

    /// Maximum engagement over one full pass of the current circle. Scanned only over the arc
    /// where the tool can be engaged ([`TwoCircle::engaged_arc`]), in steps of at most 1° and
    /// at least 64 samples across the arc (its middle, the position farthest from O1 and so the
    /// first to slot, is a sample); every local maximum of the scan (each end of a plateau) is
    /// then refined by golden section within a step either side of it. Where the scan passes
    /// into slotting, the engagement jumps to π from `β − δ` with δ → 0 (as the square root of
    /// the distance to the edge), which may lie above π: the last position before the edge is
    /// found by bisection to the last bit and taken too.
    pub fn max_engagement(&self) -> MaxEngagement {
        self.peak_up_to(f64::INFINITY)
    }

    /// Whether the peak engagement ([`TwoCircle::max_engagement`]) exceeds `limit` (rad): the
    /// same scan and refinement, stopped at the first position that reads above it, so the same
    /// answer as `max_engagement().angle > limit`, sooner where it is yes.
    pub fn exceeds(&self, limit: f64) -> bool {
        self.peak_up_to(limit).angle > limit
    }

    /// [`TwoCircle::max_engagement`], returning at the first position that reads above `limit`.
    fn peak_up_to(&self, limit: f64) -> MaxEngagement {
        let Some((start, width)) = self.engaged_arc() else {
            return MaxEngagement { angle: 0.0, phi: 0.0, slotting: false };
        };
        let full = width >= TAU;
        // φ in [0, 2π), as reported
        let at = |phi: f64| self.engagement_at(phi.rem_euclid(TAU));
        // a closed circle: n samples, the neighbours wrap; an arc: n + 1 samples, both ends on
        // its ends (where the engagement is 0)
        let mut n = ((width / SCAN_STEP).ceil() as usize).max(MIN_SCAN_SAMPLES);
        n += n % 2;
        let h = width / n as f64;
        let count = if full { n } else { n + 1 };
        let mut samples: Vec<EngagementAt> = Vec::with_capacity(count);
        for k in 0..count {
            let e = at(start + k as f64 * h);
            if e.angle > limit {
                let phi = (start + k as f64 * h).rem_euclid(TAU);
                return MaxEngagement { angle: e.angle, phi, slotting: e.slotting };
            }
            samples.push(e);
        }
        let air = EngagementAt { angle: 0.0, slotting: false };
        let sample = |k: isize| -> EngagementAt {
            if full {
                samples[k.rem_euclid(count as isize) as usize]
            } else {
                usize::try_from(k).ok().and_then(|k| samples.get(k).copied()).unwrap_or(air)
            }
        };
        let mut best = (start, 0.0);
        let take = |best: &mut (f64, f64), phi: f64, a: f64| {
            if a > best.1 {
                *best = (phi, a);
            }
        };
        for (k, e) in samples.iter().enumerate() {
            if best.1 > limit {
                break;
            }
            let phi0 = start + k as f64 * h;
            take(&mut best, phi0, e.angle);
            let (left, right) = (sample(k as isize - 1), sample(k as isize + 1));
            if e.angle > 0.0
                && e.angle >= left.angle
                && e.angle >= right.angle
                && !(e.angle == left.angle && e.angle == right.angle)
            {
                let (phi, neg) = golden_min(phi0 - h, phi0 + h, REFINE_TOL, |p| -at(p).angle);
                take(&mut best, phi, -neg);
            }
            if !e.slotting {
                for (side, next) in [(-h, left), (h, right)] {
                    if next.slotting {
                        let edge = bisect_edge(phi0, phi0 + side, EDGE_BISECTION, |p| !at(p).slotting);
                        take(&mut best, edge, at(edge).angle);
                    }
                }
            }
        }
        let slotting = samples.iter().any(|e| e.slotting);
        MaxEngagement { angle: best.1, phi: best.0.rem_euclid(TAU), slotting }
    }

    /// Closed form of the peak engagement (derived in docs/corners.md):
    /// `cos a_max = (k² − ρ² − r²)/(2ρr)` with `k = R1 − |O1O2|`, valid only when the peak is
    /// where the tool periphery passes through M (the first case of Wu et al. §2.4.1). A test
    /// oracle and fast path, not a replacement for [`TwoCircle::max_engagement`].
    pub fn closed_form_max(&self) -> f64 {
        let r = self.tool_radius;
        let rho = self.current.radius - r;
        let k = self.previous.radius - (self.current.center - self.previous.center).norm();
        ((k * k - rho * rho - r * r) / (2.0 * rho * r)).clamp(-1.0, 1.0).acos()
    }
}

#[cfg(test)]
#[path = "../../tests/rng_common/mod.rs"]
mod rng_common;

#[cfg(test)]
mod tests {
    use super::*;

    const TOL_DEG: f64 = 1e-3;

    fn deg(x: f64) -> f64 {
        x.to_degrees()
    }

    fn close(name: &str, got: f64, want: f64, tol: f64) {
        assert!((got - want).abs() <= tol, "{name}: got {got}, want {want} (tol {tol})");
    }

    #[test]
    fn straight_cut_matches_widia_table() {
        // The straight cut's a_e/D table of docs/corners.md: ae/D → engagement (deg), D = 10.
        let r = 5.0;
        for (ae_d, want) in [(0.05, 25.842), (0.10, 36.870), (0.20, 53.130), (0.30, 66.422), (0.50, 90.0), (1.0, 180.0)]
        {
            let a = straight_engagement(ae_d * 2.0 * r, r).unwrap();
            close(&format!("ae/D = {ae_d}"), deg(a), want, TOL_DEG);
        }
        // Inverse: a = 46°, D = 10 → ae = 1.5267 mm.
        close("ae(46°)", radial_depth_for_engagement(46f64.to_radians(), r), 1.5267, 1e-4);
    }

    #[test]
    fn straight_cut_rejects_bad_depth_naming_it() {
        for ae in [-0.1, 10.1, f64::NAN] {
            let e = straight_engagement(ae, 5.0).unwrap_err();
            assert_eq!(e.subject(), Some("step-over"), "{e}");
        }
        assert_eq!(straight_engagement(1.0, 0.0).unwrap_err().subject(), Some("tool-diameter"));
    }

    fn equal_radii() -> TwoCircle {
        TwoCircle {
            previous: Circle::new(p2(0.0, 0.0), 10.0),
            current: Circle::new(p2(1.0, 0.0), 10.0),
            tool_radius: 5.0,
            turn: Turn::Ccw,
        }
    }

    #[test]
    fn two_circle_equal_radii_spec_values() {
        // Worked example of docs/corners.md (CCW, O1 = (0,0), R1 = R2 = 10, r = 5, O2 = (1,0)).
        let m = equal_radii();
        m.validate().unwrap();
        for (phi, want) in [(0.0, 49.458), (-30.0, 51.621), (30.0, 41.877), (60.0, 28.842)] {
            let a = m.engagement_at(f64::to_radians(phi)).angle;
            close(&format!("a({phi}°)"), deg(a), want, TOL_DEG);
        }
        let mx = m.max_engagement();
        close("a_max", deg(mx.angle), 51.684, TOL_DEG);
        // At the peak |C − M| = r, cos φ = 0.9 (φ = −25.84°).
        close("phi at a_max", deg(mx.phi) - 360.0, -(0.9f64.acos().to_degrees()), 1e-3);
        close("closed form", m.closed_form_max().cos(), 31.0 / 50.0, 1e-12);
        close("scan vs closed form", deg(mx.angle), deg(m.closed_form_max()), TOL_DEG);
        assert!(!mx.slotting);
    }

    #[test]
    fn two_circle_unequal_radii_spec_values() {
        // Worked example of docs/corners.md: O1 = (0,0), R1 = 8, O2 = (1.5,0), R2 = 10, r = 5.
        let m = TwoCircle {
            previous: Circle::new(p2(0.0, 0.0), 8.0),
            current: Circle::new(p2(1.5, 0.0), 10.0),
            tool_radius: 5.0,
            turn: Turn::Ccw,
        };
        close("a(0)", deg(m.engagement_at(0.0).angle), 92.866, TOL_DEG);
        let mx = m.max_engagement();
        close("a_max", deg(mx.angle), 98.917, TOL_DEG);
        close("phi at a_max", deg(mx.phi) - 360.0, -49.5, 0.1);
        close("closed form cos", m.closed_form_max().cos(), -0.155, 1e-12);
    }

    #[test]
    fn clockwise_is_the_mirror_image() {
        // Mirroring the equal-radii case in y turns CCW into CW and φ into −φ.
        let ccw = equal_radii();
        let cw = TwoCircle { turn: Turn::Cw, ..ccw };
        for phi in [-60.0f64, -30.0, 0.0, 30.0, 60.0, 120.0] {
            let a = ccw.engagement_at(phi.to_radians()).angle;
            let b = cw.engagement_at((-phi).to_radians()).angle;
            close(&format!("mirror at {phi}°"), b, a, 1e-12);
        }
        close("mirror max", cw.max_engagement().angle, ccw.max_engagement().angle, 1e-9);
    }

    #[test]
    fn guards_air_and_slotting() {
        // Same circle twice: nothing left to cut.
        let same = TwoCircle { current: Circle::new(p2(0.0, 0.0), 10.0), ..equal_radii() };
        assert_eq!(same.max_engagement().angle, 0.0);
        // Current circle far away from the previous one: full slot, flagged.
        let far = TwoCircle { current: Circle::new(p2(40.0, 0.0), 10.0), ..equal_radii() };
        let mx = far.max_engagement();
        assert!(mx.slotting);
        close("slotting limit", mx.angle, PI, 1e-12);
    }

    /// The reference the scan is checked against: every 0.1° over the whole circle, then golden
    /// section within 0.1° either side of the best sample. Returns the peak, whether a sample
    /// slots, and the model's rounding noise there: the spread of the engagement over 41
    /// positions within 2e-8 rad of the peak, where a smooth peak changes by less than 1e-15
    /// rad (near-concentric circles put the arccosines' arguments so near ±1 that their last
    /// bits spread the engagement by up to some 1e-9 rad); 0 where one of them slots or reads
    /// air (a peak at a jump of the engagement).
    fn fine_scan(m: &TwoCircle) -> (f64, bool, f64) {
        let step = 0.1f64.to_radians();
        let n = (TAU / step).round() as usize;
        let (mut best, mut slotting) = ((0.0, -1.0), false);
        for i in 0..n {
            let e = m.engagement_at(i as f64 * step);
            slotting |= e.slotting;
            if e.angle > best.1 {
                best = (i as f64 * step, e.angle);
            }
        }
        let (phi, neg) = golden_min(best.0 - step, best.0 + step, 1e-10, |p| -m.engagement_at(p).angle);
        let at = if -neg > best.1 { phi } else { best.0 };
        let near: Vec<EngagementAt> = (-20..=20).map(|i| m.engagement_at(at + i as f64 * 1e-9)).collect();
        let noise = if near.iter().any(|e| e.slotting || e.angle == 0.0) {
            0.0 // a jump to slotting or from air, no noise
        } else {
            let hi = near.iter().fold(f64::NEG_INFINITY, |a, e| a.max(e.angle));
            hi - near.iter().fold(f64::INFINITY, |a, e| a.min(e.angle))
        };
        (best.1.max(-neg), slotting, noise)
    }

    #[test]
    fn scan_is_at_least_the_fine_scan_on_random_circle_pairs() {
        // Circle pairs of every kind: a random current circle about a random previous one; the
        // current circle just poking out of the previous one (a sliver of engagement narrower
        // than 1°); loops of a slot (the current circle a small step ahead, radii alike); and
        // pairs far enough apart that part of the pass slots (a plateau at π). The scan must
        // find at least the fine scan's peak, at a position whose engagement it is, and flag
        // slotting wherever the fine scan saw it; `exceeds` must agree with it.
        let mut rng = super::rng_common::Rng(0x5EED_2C1C);
        let (mut better, mut slots, mut slivers, mut worst_noise) = (0usize, 0usize, 0usize, 0.0f64);
        let mut worst_short = 0.0f64;
        for case in 0..3000 {
            let r = rng.f(0.5, 6.0);
            let r1 = rng.f(r, 5.0 * r);
            let kind = case % 4;
            let (r2, dist) = match kind {
                0 => {
                    let r2 = rng.f(r, 5.0 * r);
                    (r2, rng.f(0.0, r1 + r2 + r))
                }
                1 => {
                    let r2 = rng.f(r, r1);
                    (r2, r1 - r2 + r1 * rng.f(1e-7, 1e-3))
                }
                2 => {
                    let r2 = r1 * rng.f(0.8, 1.2).max(r / r1);
                    (r2, rng.f(0.0, 0.5 * r))
                }
                _ => {
                    let r2 = rng.f(r, 5.0 * r);
                    (r2, r1 + r - (r2 - r) + rng.f(-0.5, 2.0) * r)
                }
            };
            let dir = rng.f(0.0, TAU);
            let o1 = p2(rng.f(-50.0, 50.0), rng.f(-50.0, 50.0));
            let m = TwoCircle {
                previous: Circle::new(o1, r1),
                current: Circle::new(o1 + p2(dir.cos(), dir.sin()) * dist.max(0.0), r2),
                tool_radius: r,
                turn: if rng.n(2) == 0 { Turn::Ccw } else { Turn::Cw },
            };
            let got = m.max_engagement();
            let (want, want_slot, noise) = fine_scan(&m);
            // at least the fine scan's peak, to within the model's own rounding there
            assert!(
                got.angle >= want - noise - 1e-12,
                "case {case}: {m:?}: {} < fine scan {want} (noise {noise:e})",
                got.angle
            );
            worst_noise = worst_noise.max(noise);
            worst_short = worst_short.max(want - got.angle);
            assert_eq!(m.engagement_at(got.phi).angle, got.angle, "case {case}: engagement at the peak's φ");
            assert!(!want_slot || got.slotting, "case {case}: {m:?}: slotting missed");
            // the early-stopping test gives the same answer as the peak, at and about it
            for limit in [got.angle - 1e-9, got.angle, got.angle + 1e-9, rng.f(0.0, PI)] {
                assert_eq!(m.exceeds(limit), got.angle > limit, "case {case}: {m:?}: limit {limit}");
            }
            better += usize::from(got.angle > want + 1e-9);
            slots += usize::from(got.slotting);
            slivers += usize::from(kind == 1 && got.angle > 0.0 && got.angle < 0.2);
        }
        // the kinds are all there: slotting passes and slivers of engagement
        assert!(slots > 300 && slivers > 300, "slotting {slots}, slivers {slivers}");
        eprintln!(
            "scan above the fine scan in {better} of 3000 pairs; {slots} slotting, {slivers} slivers; rounding noise up to {worst_noise:e} rad, \
             below the fine scan by up to {worst_short:e} rad"
        );
    }

    #[test]
    fn validate_names_the_bad_radius() {
        let bad = TwoCircle { current: Circle::new(p2(1.0, 0.0), 4.0), ..equal_radii() };
        assert_eq!(bad.validate().unwrap_err().subject(), Some("R2"));
        let nan = TwoCircle { previous: Circle::new(p2(0.0, 0.0), f64::NAN), ..equal_radii() };
        assert_eq!(nan.validate().unwrap_err().subject(), Some("R1"));
    }
}
