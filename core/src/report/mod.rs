//! One report of a planned corner, pocket or measured path: what `trochoplan corner`,
//! `trochoplan pocket` and `trochoplan engagement` print as JSON (the serde serialisation of
//! these types) and what the window's Corner and Pocket tabs show. Built from the plan by
//! [`pocket()`], [`corner()`] and [`engagement()`]; degrees here, as the JSON has them (radians
//! in the plans). The rows the three share (per kind of move, corner points, entries) are
//! defined here.

pub mod corner;
pub mod engagement;
pub mod pocket;
pub mod slot;

pub use corner::{CircleRow, CornerSummary, CornerTipRow, corner};
pub use engagement::{EngagementReport, SampleRow, engagement};
pub use pocket::{
    AdaptiveReport, AxisCircleRow, CornerPassesRow, LinkRow, MedialAxisReport, PocketReport, RingRow, RingsReport,
    pocket,
};
pub use slot::SlotReport;

use crate::engagement::KindMax;
use crate::geom::P2;
use crate::pocket::CornerPoint;
use crate::toolpath::{Entry, HELIX_START_Z_MM, Helix, MoveKind};
use serde::Serialize;

/// A point as `[x, y]` (mm).
pub(crate) fn xy(p: P2) -> [f64; 2] {
    [p.x, p.y]
}

/// Chip thickness per tooth feed at an engagement φ (rad): h_max/f_z = sin φ up to 90°, 1 beyond
/// (the chip is thickest where the edge is normal to the feed).
pub fn hmax_per_fz(phi: f64) -> f64 {
    phi.min(0.5 * std::f64::consts::PI).sin()
}

/// The largest engagement of one kind of move, where, and the length of those moves.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct KindRow {
    pub kind: MoveKind,
    pub max_engagement_deg: f64,
    pub at: [f64; 2],
    pub length_mm: f64,
}

impl KindRow {
    /// The row of one measured kind.
    pub fn of(m: &KindMax) -> KindRow {
        KindRow { kind: m.kind, max_engagement_deg: m.max_rad.to_degrees(), at: xy(m.at), length_mm: m.length_mm }
    }
}

/// A convex corner point reached by corner-point arcs (within the corner tolerance).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CornerPointRow {
    pub vertex: [f64; 2],
    pub angle_deg: f64,
    /// Arcs after the finishing arc, the last of radius δ (the corner tolerance).
    pub arcs: usize,
    pub last_radius_mm: f64,
    /// Material left on the bisector, δ(1/sin(α/2) − 1).
    pub residual_mm: f64,
    /// Largest radial depth of an arc, on the bisector (mm).
    pub max_radial_depth_mm: f64,
    /// Peak over the arcs, their approach along the wall and their way out, and where.
    pub max_engagement_deg: f64,
    pub at: [f64; 2],
    /// Chip thickness per tooth feed at the peak, h_max/f_z = sin(peak) (1 at 90° and above).
    pub hmax_per_fz: f64,
}

impl CornerPointRow {
    /// The row of one corner point of a plan.
    pub fn of(c: &CornerPoint) -> CornerPointRow {
        CornerPointRow {
            vertex: xy(c.vertex),
            angle_deg: c.angle_rad.to_degrees(),
            arcs: c.arcs,
            last_radius_mm: c.last_radius_mm,
            residual_mm: c.residual_mm,
            max_radial_depth_mm: c.max_radial_depth_mm,
            max_engagement_deg: c.max_engagement_rad.to_degrees(),
            at: xy(c.at),
            hmax_per_fz: hmax_per_fz(c.max_engagement_rad),
        }
    }
}

/// A helix entry.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct HelixRow {
    pub center: [f64; 2],
    pub radius_mm: f64,
    pub ramp_deg: f64,
    /// Whole turns from 0.5 mm above the stock top to the depth.
    pub turns: usize,
}

impl HelixRow {
    /// The row of a helix descending to `depth_mm` below the stock top.
    pub fn of(h: &Helix, depth_mm: f64) -> HelixRow {
        HelixRow {
            center: xy(h.center),
            radius_mm: h.radius,
            ramp_deg: h.ramp_rad.to_degrees(),
            turns: h.turns(HELIX_START_Z_MM + depth_mm),
        }
    }
}

/// A zig-zag ramp where no helix fits: legs between `end` and `start`, the last reaching the
/// depth at `start`, then the flat pass to `end`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RampRow {
    pub start: [f64; 2],
    pub end: [f64; 2],
    pub ramp_deg: f64,
    /// Legs from 0.5 mm above the stock top to the depth.
    pub legs: usize,
}

/// One entry: its kind and where (a helix's centre, a ramp's middle, the point outside).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct EntryRow {
    pub kind: &'static str,
    pub at: [f64; 2],
}

impl EntryRow {
    /// The row of one entry.
    pub fn of(e: &Entry) -> EntryRow {
        let kind = match e {
            Entry::Helix(_) => "helix",
            Entry::Ramp(_) => "ramp",
            Entry::Outside { .. } => "outside",
            Entry::Down { .. } => "down",
        };
        EntryRow { kind, at: xy(e.center()) }
    }
}

/// The helices and the ramps of `entries`, descending to `depth_mm` below the stock top.
pub fn entry_rows(entries: &[Entry], depth_mm: f64) -> (Vec<HelixRow>, Vec<RampRow>) {
    let drop = HELIX_START_Z_MM + depth_mm;
    let helices = entries
        .iter()
        .filter_map(|e| match e {
            Entry::Helix(h) => Some(HelixRow::of(h, depth_mm)),
            Entry::Ramp(_) | Entry::Outside { .. } | Entry::Down { .. } => None,
        })
        .collect();
    let ramps = entries
        .iter()
        .filter_map(|e| match e {
            Entry::Ramp(r) => Some(RampRow {
                start: xy(r.start),
                end: xy(r.end),
                ramp_deg: r.ramp_rad.to_degrees(),
                legs: r.legs(drop),
            }),
            Entry::Helix(_) | Entry::Outside { .. } | Entry::Down { .. } => None,
        })
        .collect();
    (helices, ramps)
}
