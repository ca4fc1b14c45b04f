//! A tool path as data: the ordered moves of the tool centre, each an exact segment in the
//! plane with its height at both ends, its kind and its feed, together with the entries that
//! take the tool down to depth and the moves reached by a retract. Every pocket strategy and
//! the corner planner return one ([`Toolpath`]); the NC writer writes one (`nc`'s
//! `program_for_path`), the back-plot reads a program into one (`nc`'s `read_toolpath`), and
//! `engagement::measure` measures one (modules after this one: docs/architecture.md).
//!
//! Conventions: mm, mm/min; the plane seen from +Z; heights relative to the stock top (z = 0,
//! depth negative).

pub mod entry;

pub use entry::{Entry, HELIX_START_Z_MM, Helix, Ramp};

use crate::geom::Segment;
use serde::{Deserialize, Serialize};

/// What a move does (the evaluator's samples are reported per kind; JSON names kebab-case).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum MoveKind {
    /// The flat turn at depth after the helix (inside its bore), or the flat pass after a
    /// zig-zag ramp (on its line).
    Entry,
    /// The concentric circles clearing the largest circle.
    Spiral,
    /// A trochoid circle on the axis.
    Circle,
    /// A tangent link between circles, or from a circle's centre out to its exit point.
    Link,
    /// Along the axis where the tool-centre circle would be smaller than r_min (a neck).
    Straight,
    /// Along the axis into the tool corner point of a convex corner, where no corner-point
    /// arcs are cut (the tip's end is not between two wall features, or the last circle does
    /// not touch both).
    Tip,
    /// Back along the axis through cleared material.
    Return,
    /// A ring of adaptive clearing (docs/adaptive-clearing.md).
    Ring,
    /// A thinning pass into a convex corner (docs/adaptive-clearing.md).
    Corner,
    /// The finishing contour (docs/adaptive-clearing.md).
    Finish,
    /// Arcs into a convex corner point, within the corner tolerance, with their approach
    /// along the wall and their way out: after the finishing pass of adaptive clearing
    /// (docs/adaptive-clearing.md), or after the last circle of a medial-axis tip (docs/pockets.md).
    CornerPoint,
    /// A feed move whose purpose the program does not say (read back from NC text).
    Cut,
    /// A rapid move (G0) read back from NC text; planners do not make them.
    Rapid,
}

impl MoveKind {
    /// The kind's name as the JSON writes it (kebab-case).
    pub fn name(self) -> &'static str {
        match self {
            MoveKind::Entry => "entry",
            MoveKind::Spiral => "spiral",
            MoveKind::Circle => "circle",
            MoveKind::Link => "link",
            MoveKind::Straight => "straight",
            MoveKind::Tip => "tip",
            MoveKind::Return => "return",
            MoveKind::Ring => "ring",
            MoveKind::Corner => "corner",
            MoveKind::Finish => "finish",
            MoveKind::CornerPoint => "corner-point",
            MoveKind::Cut => "cut",
            MoveKind::Rapid => "rapid",
        }
    }
}

/// One move of the tool centre.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Move {
    /// The move in the plane (line, arc, trochoid piece).
    pub segment: Segment,
    /// Height of the tool tip at its start and end (mm; equal for a move in the plane, different
    /// for a helix or a ramp leg).
    pub z_start_mm: f64,
    pub z_end_mm: f64,
    pub kind: MoveKind,
    /// Feed (mm/min); `None` where the planner leaves it to the program's options.
    pub feed_mm_per_min: Option<f64>,
}

/// The moves of a tool path in machining order, its entries and its retracts.
///
/// `moves` are the moves at depth (the pocket planners' moves are all at one depth,
/// `z_start_mm = z_end_mm`); each entry's descent is described by its [`Entry`], the first entry
/// reaching `moves[0]`. `retract_before` lists the moves reached by retract, rapid and a new
/// entry or a feed down into material the path has cleared.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Toolpath {
    pub moves: Vec<Move>,
    pub entries: Vec<Entry>,
    pub retract_before: Vec<usize>,
}

impl Toolpath {
    /// A tool path at depth `z_mm` from planned segments and their kinds (zipped: the shorter
    /// list decides), every feed left to the program's options.
    pub fn at_depth(
        segments: &[Segment],
        kinds: &[MoveKind],
        z_mm: f64,
        entries: Vec<Entry>,
        retract_before: Vec<usize>,
    ) -> Toolpath {
        let moves = segments
            .iter()
            .zip(kinds)
            .map(|(&segment, &kind)| Move { segment, z_start_mm: z_mm, z_end_mm: z_mm, kind, feed_mm_per_min: None })
            .collect();
        Toolpath { moves, entries, retract_before }
    }

    /// The segments in the plane, in order.
    pub fn segments(&self) -> Vec<Segment> {
        self.moves.iter().map(|m| m.segment).collect()
    }

    /// What each move does, in order.
    pub fn kinds(&self) -> Vec<MoveKind> {
        self.moves.iter().map(|m| m.kind).collect()
    }

    /// Length in the plane of every move (mm).
    pub fn length_mm(&self) -> f64 {
        self.moves.iter().map(|m| m.segment.length()).sum()
    }

    /// Length in the plane of the moves of the given kinds (mm).
    pub fn length_of(&self, kinds: &[MoveKind]) -> f64 {
        self.moves.iter().filter(|m| kinds.contains(&m.kind)).map(|m| m.segment.length()).sum()
    }

    /// The bores of the entries that clear material at depth (helices and ramps; a descent
    /// outside the stock or into cleared stock clears nothing): what the path is measured after.
    pub fn bores(&self) -> Vec<Segment> {
        self.entries
            .iter()
            .filter(|e| !matches!(e, Entry::Outside { .. } | Entry::Down { .. }))
            .map(Entry::bore)
            .collect()
    }

    /// Length of the entries' descents from [`HELIX_START_Z_MM`] to `depth_mm` below the top (mm).
    pub fn entry_length_mm(&self, depth_mm: f64) -> f64 {
        self.entries.iter().map(|e| e.descent_length(depth_mm)).sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every kind's name is its JSON name (serde's kebab-case), so the window and the JSON agree.
    #[test]
    fn kind_names_are_the_json_names() {
        use MoveKind::*;
        for k in [Entry, Spiral, Circle, Link, Straight, Tip, Return, Ring, Corner, Finish, CornerPoint, Cut, Rapid] {
            assert_eq!(serde_json::to_string(&k).unwrap(), format!("\"{}\"", k.name()));
        }
    }
}
