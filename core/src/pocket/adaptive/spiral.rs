//! Steps 1–3 of adaptive clearing (docs/adaptive-clearing.md): the helix about k0, the spiral of
//! G1 half-turns out of its bore into the stadium of a thin core, and the rings grown along the
//! core, each a concave-cut step outside the last.

use super::MAX_PASSES;
use super::loops::{Builder, closest_on, start_near};
use super::options::{AdaptiveOptions, concave_step};
use crate::geom::offset::{BoolOp, Region, largest};
use crate::geom::{P2, Polygon, Segment, cross, p2};
use crate::toolpath::{Helix, MoveKind};
use std::f64::consts::PI;

/// Candidates q₂ = r_h + (j/N)(q_f − r_h), j < N, for the radius where the spiral's ends start
/// along the axis (the shortest spiral wins).
pub(super) const SPIRAL_CANDIDATES: usize = 16;

/// Helix about k0, the spiral out of its bore into the stadium (ring 0) and the rings along the
/// core `core` = C ⊖ T (module docs, steps 1–3); the helix, the end ring 0 left to the corner
/// passes (its centre, the other end's, the gap; only where `may_trim`: no arm rings follow)
/// and the number of rings.
#[allow(clippy::too_many_arguments)]
pub(super) fn spiral_and_rings(
    b: &mut Builder,
    region: &Region,
    core: &Region,
    (inscribed, k0): (f64, P2),
    polygon: &Polygon,
    (r, t, r_h, phi): (f64, f64, f64, f64),
    (options, may_trim): (&AdaptiveOptions, bool),
) -> (Helix, Option<(P2, P2, f64)>, usize) {
    // Wall point nearest k0: every ring passes within (inscribed − T) of it.
    let walls = region.segments();
    let foot = walls
        .iter()
        .map(|s| closest_on(s, k0).0)
        .min_by(|a, c| (a - k0).norm().total_cmp(&(c - k0).norm()))
        .unwrap_or(k0);
    let n_foot = if (foot - k0).norm() > 1e-9 { (foot - k0).normalize() } else { p2(1.0, 0.0) };
    // The first ring is the circle about k0 that (nearly) touches the nearest wall, at q0:
    // (K ∩ D(k0, s0)) ⊕ T with s0 = 0.995·R_in − T; every later ring contains it, so passes
    // within 0.005·R_in of q0, where consecutive rings are joined.
    let s0 = (0.995 * inscribed - t).max(0.0);
    let spiral_end = s0 + t;
    // Where the centres of the spiral's end half-turns may travel: along the axis of a thin
    // core C ⊖ q_f (q_f = spiral_end), so the spiral ends as the stadium of that axis.
    let axis = stadium_axis(region, spiral_end, k0, concave_step(spiral_end, r, phi)).filter(|&(u, _, _, w)| {
        // the stadium's side must meet a wall at k0, where the rings are joined (below)
        let m = crate::geom::rot90(u);
        let side = k0 + (if m.dot(&n_foot) >= 0.0 { m } else { -m }) * (spiral_end + w);
        walls.iter().map(|sg| (closest_on(sg, side).0 - side).norm()).fold(f64::INFINITY, f64::min)
            <= 0.005 * inscribed + 1e-9
    });
    let (u, s_plus, s_minus, w) = axis.unwrap_or((crate::geom::rot90(n_foot), 0.0, 0.0, 0.0));
    let spiral_end = spiral_end + w;
    let n = if axis.is_some() {
        let m = crate::geom::rot90(u);
        if m.dot(&n_foot) >= 0.0 { m } else { -m }
    } else {
        n_foot
    };
    // Spiral radii at half turns, r_h → q_f. The ends' centres start along the axis once the
    // radius passes q₂ and reach the axis' ends at q_f: a revolution then moves each end's
    // centre by κ·Δq (κ = s_ext/(q_f − q₂)), so the tip of an end steps Δq(1 + κ), held to
    // the concave-cut step of the radius. q₂ is the candidate with the shortest spiral.
    let s_ext = s_plus.max(s_minus);
    let radii = |q2: f64| {
        let kappa = s_ext / (spiral_end - q2).max(1e-9);
        let mut q = vec![r_h];
        while let Some(&last) = q.last() {
            if last >= spiral_end - 1e-9 || q.len() > MAX_PASSES {
                break;
            }
            let next = if last < q2 - 1e-9 {
                (last + 0.5 * concave_step(last, r, phi)).min(q2)
            } else {
                last + 0.5 * concave_step(last, r, phi) / (1.0 + kappa)
            };
            q.push(next.min(spiral_end));
        }
        q
    };
    let lambda_of = |q2: f64, qi: f64| ((qi - q2) / (spiral_end - q2).max(1e-9)).clamp(0.0, 1.0);
    let spiral_length = |q2: f64, q: &[f64]| -> f64 {
        q.windows(2).map(|w| 0.5 * PI * (w[0] + w[1]) + 2.0 * s_ext * lambda_of(q2, w[0])).sum()
    };
    let (q2, q) = (0..SPIRAL_CANDIDATES)
        .map(|j| r_h + (j as f64 / SPIRAL_CANDIDATES as f64) * (spiral_end - r_h))
        .map(|q2| (q2, radii(q2)))
        .min_by(|a, c| spiral_length(a.0, &a.1).total_cmp(&spiral_length(c.0, &c.1)))
        .unwrap_or((r_h, vec![r_h]));
    let halves = q.len() - 1;
    // The last half-turn ends on the side n (toward the nearest wall): e_last = −n.
    let e_of = |i: usize| if (halves - 1 - i).is_multiple_of(2) { -n } else { n };
    let theta0 = if halves > 0 { e_of(0).y.atan2(e_of(0).x) } else { n.y.atan2(n.x) };
    let helix =
        Helix { center: k0, radius: r_h, start_angle: theta0, sense: 1.0, ramp_rad: options.ramp_deg.to_radians() };
    b.push(helix.circle(), MoveKind::Entry);
    let mut last_half = None;
    for i in 0..halves {
        let e = e_of(i);
        // Centre of this end half-turn on the axis: its middle direction rot90(e) is ±u.
        let lambda = lambda_of(q2, q[i]);
        let ext = if crate::geom::rot90(e).dot(&u) > 0.0 { s_plus } else { -s_minus };
        let a = k0 + u * (lambda * ext);
        let start = a + e * q[i];
        b.line(start, MoveKind::Spiral);
        let seg = Segment::Arc {
            center: a + e * (0.5 * (q[i] - q[i + 1])),
            radius: 0.5 * (q[i] + q[i + 1]),
            start_angle: e.y.atan2(e.x),
            sweep: PI,
        };
        last_half = Some(seg);
        b.push(seg, MoveKind::Spiral);
    }
    // Ring 0 closes the spiral: the stadium of radius q_f about the axis (the circle about k0
    // where the core has no axis).
    let m = crate::geom::rot90(u);
    let (a_plus, a_minus) = (k0 + u * s_plus, k0 - u * s_minus);
    let ang = |v: P2| v.y.atan2(v.x);
    let stadium = [
        Segment::Line { start: a_minus - m * spiral_end, end: a_plus - m * spiral_end },
        Segment::Arc { center: a_plus, radius: spiral_end, start_angle: ang(-m), sweep: PI },
        Segment::Line { start: a_plus + m * spiral_end, end: a_minus + m * spiral_end },
        Segment::Arc { center: a_minus, radius: spiral_end, start_angle: ang(m), sweep: PI },
    ];
    let q0 = b.at();
    let mut ring0 = start_near(&stadium, q0);
    let cut = Region::with_bulges(&[
        (a_minus - m * spiral_end, 0.0),
        (a_plus - m * spiral_end, 1.0),
        (a_plus + m * spiral_end, 0.0),
        (a_minus + m * spiral_end, 1.0),
    ]);
    let rings_cut = core_rings(core, k0, (s0, t), (r, phi), &cut, q0);
    // Where no ring follows the stadium, ring 0 stops before the end half-circle the spiral
    // ended on: that half-turn left a crescent from Δ = q_f − q_{n−1} at its start to 0 at its
    // end, which the corner passes at that end take with their first arc (started Δ/k further
    // out on the bisector, below), instead of a half-circle mostly in air and the link back.
    let mut trimmed = None;
    if may_trim && axis.is_some() && rings_cut.is_empty() && halves >= 2 {
        // (the spiral's end may lie a short line before the stadium's half-circle ends)
        while ring0.last().is_some_and(|sg| matches!(sg, Segment::Line { .. }) && sg.length() < 0.1 * r) {
            ring0.pop();
        }
        if let (Some(&Segment::Arc { center, radius, .. }), Some(&Segment::Arc { center: c_h, radius: r_half, .. })) =
            (ring0.last(), last_half.as_ref())
        {
            ring0.pop();
            let other = if (center - a_plus).norm() < (center - a_minus).norm() { a_minus } else { a_plus };
            // the gap between this half-circle and the spiral's last half-turn, at most
            trimmed = Some((center, other, radius - r_half + (center - c_h).norm()));
        }
    }
    for seg in ring0 {
        b.push(seg, MoveKind::Ring);
    }
    let rings = 1 + rings_cut.len();
    crate::pocket::runs::cut_rings(
        b,
        polygon,
        (r, concave_step(t, r, phi), phi, options.finish_stock_mm),
        &stadium,
        rings_cut,
    );
    (helix, trimmed, rings)
}

/// Step 3: the rings (K ∩ D(k0, s)) ⊕ T of the core K = `core`, s growing from s0 by the
/// concave-cut step of radius T, each restarted at the wall point q0 where the spiral ended; a
/// ring that adds to the stadium `cut` less area than a strip of 2 % of the step along its whole
/// length (it lies inside the stadium but for slivers) is not cut.
pub(super) fn core_rings(
    core: &Region,
    k0: P2,
    (s0, t): (f64, f64),
    (r, phi): (f64, f64),
    cut: &Region,
    q0: P2,
) -> Vec<Vec<Segment>> {
    let step = concave_step(t, r, phi);
    let reach = core.vertices().iter().map(|&v| (v - k0).norm()).fold(0.0, f64::max);
    let mut s = (s0 + step).min(reach);
    let (mut rings_cut, mut prev): (Vec<Vec<Segment>>, Option<Region>) = (Vec::new(), None);
    while s > s0 + 1e-9 && rings_cut.len() < MAX_PASSES {
        let grown = crate::pocket::growth::grown(core, k0, s, reach, prev.as_ref(), step);
        let filled = grown.as_ref().is_none_or(|g| crate::pocket::growth::fills(g, core));
        if let Some(o) = grown.as_ref().and_then(|g| largest(g.offset(-t))) {
            let outside: f64 = o.boolean(cut, BoolOp::Not).iter().map(|p| p.area().abs()).sum();
            if outside >= 0.02 * step * o.path_length() {
                rings_cut.push(start_near(&o.segments(), q0));
            }
        }
        let stalled = prev.as_ref().zip(grown.as_ref()).is_some_and(|(p, g)| g.area() <= p.area() * (1.0 + 1e-9));
        if s >= reach && (filled || stalled) {
            break;
        }
        (s, prev) = ((s + step).min(reach), grown.or(prev));
    }
    rings_cut
}

/// The axis of a thin core: the core C ⊖ q (one loop) whose vertices lie within `width` of a
/// line through `k0`, as the unit direction u and the extents s₊, s₋ ≥ 0 of its vertices along
/// u either side of k0 (u along the core's longest edge), and the widening w of the
/// stadium's radius q (below). `None` where the core is
/// not that thin (an L, a square) or its extents are below a tenth of `width`.
pub(super) fn stadium_axis(region: &Region, q: f64, k0: P2, width: f64) -> Option<(P2, f64, f64, f64)> {
    let ks = region.offset(q);
    let [k] = ks.as_slice() else { return None };
    let vs: Vec<P2> = k.vertices();
    let (mut u, mut far) = (p2(1.0, 0.0), 0.0);
    for (i, a) in vs.iter().enumerate() {
        let c = vs[(i + 1) % vs.len()];
        if (c - a).norm() > far {
            (u, far) = ((c - a) / (c - a).norm(), (c - a).norm());
        }
    }
    if far < 0.2 * width {
        return None;
    }
    let off = |v: &P2| cross(u, v - k0);
    if vs.iter().any(|v| off(v).abs() > 0.5 * width) {
        return None;
    }
    let along = |v: &P2| u.dot(&(v - k0));
    let s_plus = vs.iter().map(along).fold(0.0, f64::max);
    let s_minus = vs.iter().map(|v| -along(v)).fold(0.0, f64::max);
    // Widened by the core's half-width w (the stadium then reaches the walls the core's offset
    // reaches) and shortened by w, where its axis keeps q + w from every wall.
    let w = vs.iter().map(|v| off(v).abs()).fold(0.0, f64::max);
    let walls = region.segments();
    let clear = |p: P2| walls.iter().map(|sg| (closest_on(sg, p).0 - p).norm()).fold(f64::INFINITY, f64::min);
    let (sp, sm) = ((s_plus - w).max(0.0), (s_minus - w).max(0.0));
    if [k0 + u * sp, k0 - u * sm, k0].iter().all(|&p| clear(p) >= q + w - 1e-9) {
        Some((u, sp, sm, w))
    } else {
        Some((u, s_plus, s_minus, 0.0))
    }
}
