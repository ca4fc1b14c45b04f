//! Line–line corner geometry (Wu et al. 2016 eqs. 21–22; docs/corners.md).
//!
//! A corner is the apex `W0` of two pocket walls. Wall 1 arrives at the apex, wall 2 leaves it;
//! the pocket interior is on the left of both (counter-clockwise boundary). The interior corner
//! angle is `2α`; the unit bisector `b̂` points from the apex into the pocket.

use crate::error::{Error, Param, num};
use crate::geom::{Circle, P2, cross, p2, rot90};
use serde::{Deserialize, Serialize};

/// A normalised line `A x + B y + C = 0` (`A² + B² = 1`) with the side factor `F = ±1` such that
/// `A x + B y + C + F·d = 0` is the line moved a distance `d` into the pocket.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct LineEq {
    pub a: f64,
    pub b: f64,
    pub c: f64,
    pub f: f64,
}

impl LineEq {
    /// The line through `p` with direction `dir`, `F` chosen from an interior point `q`:
    /// `F = −sign(A·xq + B·yq + C)` (the sign rule of docs/corners.md).
    pub fn through(p: P2, dir: P2, interior: P2) -> Result<LineEq, Error> {
        let len = dir.norm();
        if !(len.is_finite() && len > 1e-12) {
            return Err(Error::geometry("edge length", len, "a finite length > 0 mm (degenerate edge)"));
        }
        let n = rot90(dir / len);
        let (a, b) = (n.x, n.y);
        let c = -(a * p.x + b * p.y);
        let side = a * interior.x + b * interior.y + c;
        if side.abs() < 1e-12 {
            return Err(Error::geometry("interior point", "on the edge", "strictly inside the pocket"));
        }
        Ok(LineEq { a, b, c, f: -side.signum() })
    }

    /// Signed value `A x + B y + C` (the distance from the line, positive on the normal side).
    pub fn value(&self, p: P2) -> f64 {
        self.a * p.x + self.b * p.y + self.c
    }

    /// Distance of `p` from the line moved `d` into the pocket: `|A x + B y + C + F d|` (eq. 25 form).
    pub fn distance_offset(&self, p: P2, d: f64) -> f64 {
        (self.value(p) + self.f * d).abs()
    }
}

/// Intersection of the two lines each moved `d` into the pocket, by Cramer's rule (eq. 22):
/// `xm = [(B1C2 − B2C1) + d(B1F2 − B2F1)]/T`, `ym = [(A2C1 − A1C2) + d(A2F1 − A1F2)]/T`,
/// `T = A1B2 − A2B1`. Sweeping `d` traces the bisector. Parallel lines (`T ≈ 0`) are an error.
pub fn bisector_point(l1: &LineEq, l2: &LineEq, d: f64) -> Result<P2, Error> {
    let t = l1.a * l2.b - l2.a * l1.b;
    if t.abs() < 1e-12 {
        return Err(Error::geometry("corner angle", "0° or 180° (parallel edges)", "strictly between 0° and 180°"));
    }
    let x = ((l1.b * l2.c - l2.b * l1.c) + d * (l1.b * l2.f - l2.b * l1.f)) / t;
    let y = ((l2.a * l1.c - l1.a * l2.c) + d * (l2.a * l1.f - l1.a * l2.f)) / t;
    Ok(p2(x, y))
}

/// A convex line–line pocket corner: apex, wall directions, half-angle.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Corner {
    /// Apex `W0` of the walls (mm).
    pub apex: P2,
    /// Unit direction of wall 1, travelling towards the apex.
    pub dir_in: P2,
    /// Unit direction of wall 2, travelling away from the apex.
    pub dir_out: P2,
    /// Half of the interior angle, α (rad), 0 < α < π/2.
    pub half_angle: f64,
    /// Unit bisector `b̂`, from the apex into the pocket.
    pub bisector: P2,
}

impl Corner {
    /// Corner from the apex and the two wall directions (pocket on the left of both, i.e. a
    /// left turn from `dir_in` to `dir_out`). Errors for degenerate, reflex or straight corners.
    pub fn new(apex: P2, dir_in: P2, dir_out: P2) -> Result<Corner, Error> {
        for (name, v) in [("apex", apex), ("dir_in", dir_in), ("dir_out", dir_out)] {
            if !(v.x.is_finite() && v.y.is_finite()) {
                return Err(Error::geometry(name, format!("({}, {})", num(v.x), num(v.y)), "finite coordinates"));
            }
        }
        let (li, lo) = (dir_in.norm(), dir_out.norm());
        if li < 1e-12 || lo < 1e-12 {
            return Err(Error::geometry("edge length", li.min(lo), "a length > 0 mm (degenerate edge)"));
        }
        let (u, v) = (dir_in / li, dir_out / lo);
        let turn = cross(u, v);
        // Interior angle between the walls at the apex: π − (turning angle).
        let interior = std::f64::consts::PI - turn.atan2(u.dot(&v));
        if !(turn > 1e-9 && interior > 1e-9) {
            return Err(Error::geometry(
                "corner angle",
                format!("{:.3}°", interior.to_degrees()),
                "a convex corner strictly between 0° and 180° (pocket on the left of both edges)",
            ));
        }
        let b = v - u;
        Ok(Corner { apex, dir_in: u, dir_out: v, half_angle: 0.5 * interior, bisector: b / b.norm() })
    }

    /// The symmetric corner of interior angle `angle` (rad) with apex at the origin, bisector
    /// along +x: wall 1 comes in from the upper right, wall 2 leaves to the lower right.
    pub fn symmetric(angle: f64) -> Result<Corner, Error> {
        if !(angle.is_finite() && angle > 0.0 && angle < std::f64::consts::PI) {
            return Err(Error::param(
                Param::Angle,
                format!("{}°", num(angle.to_degrees())),
                "strictly between 0° and 180°",
            ));
        }
        let h = 0.5 * angle;
        Corner::new(p2(0.0, 0.0), -p2(h.cos(), h.sin()), p2(h.cos(), -h.sin()))
    }

    /// Wall 1 and wall 2 as normalised lines with `F` pointing into the pocket.
    pub fn wall_lines(&self) -> Result<(LineEq, LineEq), Error> {
        let q = self.apex + self.bisector;
        Ok((LineEq::through(self.apex, self.dir_in, q)?, LineEq::through(self.apex, self.dir_out, q)?))
    }

    /// Point on the bisector at distance `t` from the apex.
    pub fn on_bisector(&self, t: f64) -> P2 {
        self.apex + self.bisector * t
    }

    /// Circle centred at `W0 + t b̂` tangent to both walls: radius `R(t) = t sin α` (docs/corners.md).
    pub fn wall_tangent_circle(&self, t: f64) -> Circle {
        Circle::new(self.on_bisector(t), t * self.half_angle.sin())
    }

    /// Bisector parameter of the wall-tangent circle of radius `radius`: `t = R / sin α`.
    pub fn t_for_radius(&self, radius: f64) -> f64 {
        radius / self.half_angle.sin()
    }

    /// Foot of `p` on wall 1 (the line through the apex along `dir_in`).
    pub fn foot_on_wall_in(&self, p: P2) -> P2 {
        self.apex + self.dir_in * (p - self.apex).dot(&self.dir_in)
    }

    /// Foot of `p` on wall 2.
    pub fn foot_on_wall_out(&self, p: P2) -> P2 {
        self.apex + self.dir_out * (p - self.apex).dot(&self.dir_out)
    }

    /// Left (inward) unit normal of wall 1.
    pub fn normal_in(&self) -> P2 {
        rot90(self.dir_in)
    }

    /// Left (inward) unit normal of wall 2.
    pub fn normal_out(&self) -> P2 {
        rot90(self.dir_out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bisector_worked_example() {
        // Hand-computed: edge 1 y = 0 (0, 1, 0, −1); edge 2 through the origin at 60°,
        // (sin 60°, −cos 60°, 0, −1); T = −0.866025; d = 1 → M = (1.732051, 1).
        let s60 = 60f64.to_radians().sin();
        let c60 = 60f64.to_radians().cos();
        let l1 = LineEq { a: 0.0, b: 1.0, c: 0.0, f: -1.0 };
        let l2 = LineEq { a: s60, b: -c60, c: 0.0, f: -1.0 };
        let m = bisector_point(&l1, &l2, 1.0).unwrap();
        assert!((m.x - 1.732051).abs() < 1e-6 && (m.y - 1.0).abs() < 1e-6, "{m:?}");
        // On the 30° bisector at distance d / sin 30° = 2 from the apex.
        assert!((m.norm() - 2.0).abs() < 1e-12);
    }

    #[test]
    fn derived_lines_reproduce_spec_coefficients_up_to_sign() {
        // The same corner built by Corner::new: pocket between y = 0 and the 60° edge, walked
        // with the pocket on the left: in along the 60° edge, out along y = 0. The inward
        // offsets must meet on the bisector at d / sin α for any d.
        let c = Corner::new(p2(0.0, 0.0), -p2(0.5, 3f64.sqrt() / 2.0), p2(1.0, 0.0)).unwrap();
        assert!((c.half_angle.to_degrees() - 30.0).abs() < 1e-12);
        let (l1, l2) = c.wall_lines().unwrap();
        for d in [0.5, 1.0, 3.0] {
            let m = bisector_point(&l1, &l2, d).unwrap();
            let want = c.on_bisector(d / c.half_angle.sin());
            assert!((m - want).norm() < 1e-12, "d = {d}: {m:?} vs {want:?}");
            // Moved line passes through M: A x + B y + C + F d = 0.
            assert!(l1.distance_offset(m, d) < 1e-12 && l2.distance_offset(m, d) < 1e-12);
        }
    }

    #[test]
    fn wall_tangent_circle_touches_both_walls() {
        for deg in [30.0f64, 90.0, 150.0] {
            let c = Corner::symmetric(deg.to_radians()).unwrap();
            let (l1, l2) = c.wall_lines().unwrap();
            let circ = c.wall_tangent_circle(7.0);
            assert!((l1.value(circ.center).abs() - circ.radius).abs() < 1e-12);
            assert!((l2.value(circ.center).abs() - circ.radius).abs() < 1e-12);
        }
    }

    #[test]
    fn bad_corners_are_named_errors() {
        assert_eq!(Corner::symmetric(0.0).unwrap_err().subject(), Some("angle"));
        assert_eq!(Corner::symmetric(f64::NAN).unwrap_err().subject(), Some("angle"));
        assert_eq!(Corner::symmetric(std::f64::consts::PI).unwrap_err().subject(), Some("angle"));
        assert_eq!(Corner::new(p2(0.0, 0.0), p2(0.0, 0.0), p2(1.0, 0.0)).unwrap_err().subject(), Some("edge length"));
        // A right turn is a reflex (outside) corner for a CCW pocket.
        assert_eq!(Corner::new(p2(0.0, 0.0), p2(1.0, 0.0), p2(0.0, -1.0)).unwrap_err().subject(), Some("corner angle"));
    }
}
