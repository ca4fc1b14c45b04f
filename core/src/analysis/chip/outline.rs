//! The outline of one tooth's chip for drawing: the engaged arc of the tool circle and the
//! chip's inner boundary (the previous tooth's circle or the swept edge).

use super::engagement::engagement;
use super::swept::{EarlySweep, Frame, Swept};
use super::thickness::radial_thickness;
use crate::analysis::edge::PreviousEdge;
use crate::geom::P2;
use crate::path::{Cycle, CyclePos};

/// Outline of the chip cut by the tooth at arc length `s` (mm from the cycle start, steady
/// state, cycle origin at (0, 0)): the engaged arc of the tool circle, then back along the
/// inner boundary of the chip (the previous tooth's circle or the swept edge), as a closed
/// polygon with `n` points per engaged interval and side. Empty when the tooth cuts nothing.
/// For drawing the chip (teaching view); the numbers come from [`super::tooth_series`].
pub fn chip_outline(cycle: &Cycle, edge: &PreviousEdge, r: f64, f_z: f64, s: f64, n: usize) -> Vec<P2> {
    let len = cycle.length();
    let start = CyclePos { seg: 0, t: 0.0 };
    let Some(pos) = cycle.advance(start, s.clamp(0.0, len)) else { return Vec::new() };
    let f = Frame::at(cycle, pos, P2::zeros());
    let prev = if s >= f_z {
        cycle.advance(start, s - f_z).map(|p| Frame::at(cycle, p, P2::zeros()).c)
    } else {
        cycle.advance(start, len + s - f_z).map(|p| Frame::at(cycle, p, P2::new(0.0, -cycle.step)).c)
    };
    let early = EarlySweep::new(cycle, P2::zeros(), r, 0.25);
    let swept = Swept::before(edge, &early, s, len);
    let e = engagement(&swept, &f, r);
    // The chip's inner boundary: the material as the previous tooth left it (for the first
    // tooth of the cycle, the material before a tooth of the previous cycle).
    let inner = if s >= f_z { swept } else { Swept::before_previous_cycle_tooth(edge, &early, len + s - f_z, cycle) };
    let centre_swept = inner.margin(f.c) <= 0.0;
    let n = n.max(2);
    let mut out = Vec::new();
    for &(a, b) in &e.intervals {
        let phis: Vec<f64> = (0..=n).map(|i| a + (b - a) * i as f64 / n as f64).collect();
        out.extend(phis.iter().map(|&p| f.c + f.dir(p) * r));
        out.extend(
            phis.iter().rev().map(|&p| f.c + f.dir(p) * (r - radial_thickness(&inner, &f, prev, r, centre_swept, p))),
        );
    }
    out
}
