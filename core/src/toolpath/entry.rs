//! How the tool gets down to depth (docs/pockets.md): a helix, a straight zig-zag ramp, or
//! straight down outside the stock beyond an open edge. Both the helix and the ramp start
//! [`HELIX_START_Z_MM`] above the stock top and descend at most at the ramp angle; what an entry
//! clears at depth (its *bore*) is the first move of the path at depth and part of the stock
//! the path is measured over (the `engagement` module's `measure`). Where an entry is placed is the
//! pocket planners' business (docs/pockets.md).

use crate::geom::mirror::mirror_point;
use crate::geom::{P2, Segment};
use serde::{Deserialize, Serialize};
use std::f64::consts::{PI, TAU};

/// Height above the stock top Z0 where the helix starts (mm).
pub const HELIX_START_Z_MM: f64 = 0.5;
/// How far the ramp's bore reaches beyond its ends for the evaluator (mm): the legs stood at
/// both ends, whose periphery the evaluator would count as material at exactly r (see
/// [`Entry::bore`]).
const RAMP_END_MM: f64 = 1e-3;

/// A helical entry: the tool centre on a circle, descending from [`HELIX_START_Z_MM`] to the
/// depth over whole turns in the loops' sense.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Helix {
    pub center: P2,
    pub radius: f64,
    /// Angle of the start (and end) point (rad).
    pub start_angle: f64,
    /// +1 counter-clockwise (climb), −1 clockwise.
    pub sense: f64,
    /// Ramp angle (rad): the descent per turn is 2π·r_h·tan(ramp) at most.
    pub ramp_rad: f64,
}

impl Helix {
    /// Whole turns needed to descend `drop` mm at the ramp angle.
    pub fn turns(&self, drop: f64) -> usize {
        let per_turn = TAU * self.radius * self.ramp_rad.tan();
        ((drop / per_turn) - 1e-9).ceil().max(1.0) as usize
    }

    /// The helix as a full circle in the plane (what it clears at depth).
    pub fn circle(&self) -> Segment {
        Segment::Arc {
            center: self.center,
            radius: self.radius,
            start_angle: self.start_angle,
            sweep: self.sense * TAU,
        }
    }

    /// Length of the 3D helix descending `drop` mm (mm).
    pub fn length(&self, drop: f64) -> f64 {
        let n = self.turns(drop) as f64;
        ((n * TAU * self.radius).powi(2) + drop * drop).sqrt()
    }
}

/// A straight zig-zag ramp: legs back and forth on the line between `end` and `start`, each
/// descending by the same amount at most at the ramp angle, the last one reaching the depth at
/// `start`; at depth the tool then runs once from `start` to `end` (the flat pass that removes
/// the last leg's wedge).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Ramp {
    pub start: P2,
    pub end: P2,
    /// Ramp angle (rad): a leg of length L descends L·tan(ramp) at most.
    pub ramp_rad: f64,
}

impl Ramp {
    /// Legs needed to descend `drop` mm at the ramp angle.
    pub fn legs(&self, drop: f64) -> usize {
        let per_leg = (self.end - self.start).norm() * self.ramp_rad.tan();
        ((drop / per_leg) - 1e-9).ceil().max(1.0) as usize
    }

    /// Where the first leg starts: legs alternate and the last ends at `start`, so the first
    /// starts at `end` for an odd number of legs and at `start` for an even one.
    pub fn first_point(&self, drop: f64) -> P2 {
        if self.legs(drop) % 2 == 1 { self.end } else { self.start }
    }

    /// Length of the 3D legs descending `drop` mm (mm).
    pub fn length(&self, drop: f64) -> f64 {
        let n = self.legs(drop) as f64;
        ((n * (self.end - self.start).norm()).powi(2) + drop * drop).sqrt()
    }
}

/// The way down of one connected part of a pocket.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Entry {
    Helix(Helix),
    Ramp(Ramp),
    /// Straight down at `at`, beyond an open edge of the pocket: the tool's disc there keeps
    /// at least r from the stock, so the descent cuts nothing (not a plunge).
    Outside {
        at: P2,
    },
    /// Straight down at `at` into stock the path has already cleared there, through its whole
    /// depth (a retract where a link finds no way at depth): the tool's disc meets no stock on
    /// the way down, so the descent cuts nothing (not a plunge).
    Down {
        at: P2,
    },
}

impl Entry {
    /// What the entry clears at depth, and its first move there: the helix's flat turn, or the
    /// ramp's flat pass.
    pub fn at_depth(&self) -> Segment {
        match self {
            Entry::Helix(h) => h.circle(),
            Entry::Ramp(r) => Segment::Line { start: r.start, end: r.end },
            Entry::Outside { at } | Entry::Down { at } => Segment::Line { start: *at, end: *at },
        }
    }

    /// What the entry cleared, as the evaluator's `before` path: the helix circle, or the ramp
    /// line lengthened by [`RAMP_END_MM`] at each end (the legs turned at both ends, so their
    /// end discs are cut; the evaluator counts a periphery point exactly r from every position
    /// as material); outside the stock the point of the descent (its disc is off the stock, it
    /// clears nothing).
    pub fn bore(&self) -> Segment {
        match self {
            Entry::Helix(h) => h.circle(),
            Entry::Ramp(r) => {
                let u = (r.end - r.start) / (r.end - r.start).norm();
                Segment::Line { start: r.start - u * RAMP_END_MM, end: r.end + u * RAMP_END_MM }
            }
            Entry::Outside { at } | Entry::Down { at } => Segment::Line { start: *at, end: *at },
        }
    }

    /// Where the entry is: the helix centre, the ramp's middle, the point outside the stock.
    pub fn center(&self) -> P2 {
        match self {
            Entry::Helix(h) => h.center,
            Entry::Ramp(r) => (r.start + r.end) * 0.5,
            Entry::Outside { at } | Entry::Down { at } => *at,
        }
    }

    /// Length of the descent from [`HELIX_START_Z_MM`] to `depth` below the stock top (mm);
    /// outside the stock straight down.
    pub fn descent_length(&self, depth: f64) -> f64 {
        let drop = HELIX_START_Z_MM + depth;
        match self {
            Entry::Helix(h) => h.length(drop),
            Entry::Ramp(r) => r.length(drop),
            Entry::Outside { .. } | Entry::Down { .. } => drop,
        }
    }

    /// The entry of the mirror image (x → −x): a helix turns the other way.
    pub fn mirrored(&self) -> Entry {
        match *self {
            Entry::Helix(h) => Entry::Helix(Helix {
                center: mirror_point(h.center),
                start_angle: PI - h.start_angle,
                sense: -h.sense,
                ..h
            }),
            Entry::Ramp(r) => Entry::Ramp(Ramp { start: mirror_point(r.start), end: mirror_point(r.end), ..r }),
            Entry::Outside { at } => Entry::Outside { at: mirror_point(at) },
            Entry::Down { at } => Entry::Down { at: mirror_point(at) },
        }
    }
}
