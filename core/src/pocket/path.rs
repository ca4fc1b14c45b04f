//! What every pocket plan has, whatever its strategy: the pocket, the settings, the tool path
//! ([`Toolpath`]: moves at depth, entries, retracts) and its [`Measurement`], with the lengths
//! and the time derived from them.

use super::PocketSettings;
use crate::engagement::{EvaluatorOptions, Measurement, Stock, measure};
use crate::error::Error;
use crate::geom::mirror::mirror_point;
use crate::geom::{Polygon, Segment};
use crate::toolpath::{MoveKind, Toolpath};
use serde::{Deserialize, Serialize};

/// A pocket's tool path and its measurement.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PocketPath {
    /// The validated pocket (counter-clockwise).
    pub polygon: Polygon,
    /// Its islands (material that stays; none: a plain pocket).
    #[serde(default)]
    pub islands: Vec<Polygon>,
    pub settings: PocketSettings,
    /// Every move at depth in machining order, the entries of the parts, the retracts.
    pub toolpath: Toolpath,
    /// The evaluator over `polygon` with the entries' bores as cut ([`measure`]).
    pub measurement: Measurement,
    /// Length of the link moves at depth (mm): the moves of kind [`MoveKind::Link`] (returns,
    /// air and rapids have their own kinds).
    pub link_length_mm: f64,
    /// Length of the entries' descents from above the stock top (mm).
    pub entry_length_mm: f64,
    /// Time at the feed: the descents and every move at depth, each at its own feed (s).
    pub time_s: f64,
    /// The rapids through cleared stock and the feed of every move ([`super::pace`]); `None`
    /// before pacing (every move at the programmed feed).
    #[serde(default)]
    pub pace: Option<super::pace::Pace>,
    /// Cuts made before this path (a larger tool's sweep before rest machining): stock already
    /// cleared, for every measure of the path (its levels too). Empty: the whole pocket is stock.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub precut: Vec<Segment>,
}

impl PocketPath {
    /// Measure `toolpath` over `polygon` (positions `settings.spacing` apart), its entries
    /// descending to `depth_mm` below the stock top.
    pub fn measured(
        polygon: &Polygon,
        settings: PocketSettings,
        toolpath: Toolpath,
        depth_mm: f64,
    ) -> Result<PocketPath, Error> {
        PocketPath::measured_with_islands(polygon, &[], settings, toolpath, depth_mm)
    }

    /// [`Self::measured`] over the pocket `polygon` with its `islands` (the evaluator's stock
    /// is the pocket less the islands).
    pub fn measured_with_islands(
        polygon: &Polygon,
        islands: &[Polygon],
        settings: PocketSettings,
        toolpath: Toolpath,
        depth_mm: f64,
    ) -> Result<PocketPath, Error> {
        PocketPath::measured_over(Stock { polygon, precut: &[], islands }, settings, toolpath, depth_mm)
    }

    /// [`Self::measured_with_islands`] over `stock` with its earlier cuts (`precut`, e.g. a
    /// larger tool's sweep before rest machining) as cut.
    pub fn measured_over(
        stock: Stock<'_>,
        settings: PocketSettings,
        toolpath: Toolpath,
        depth_mm: f64,
    ) -> Result<PocketPath, Error> {
        let (polygon, islands, precut) = (stock.polygon, stock.islands, stock.precut.to_vec());
        let opts = EvaluatorOptions::new(settings.tool_radius, settings.spacing);
        let measurement = measure(&toolpath, stock, &opts)?;
        let link_length_mm = toolpath.length_of(&[MoveKind::Link]);
        let entry_length_mm = toolpath.entry_length_mm(depth_mm);
        let time_s = (measurement.length_at_depth_mm + entry_length_mm) / settings.feed_mm_per_min * 60.0;
        Ok(PocketPath {
            polygon: polygon.clone(),
            islands: islands.to_vec(),
            settings,
            toolpath,
            measurement,
            link_length_mm,
            entry_length_mm,
            time_s,
            pace: None,
            precut,
        })
    }

    /// The moves' segments in machining order.
    pub fn segments(&self) -> Vec<Segment> {
        self.toolpath.segments()
    }

    /// What each move does, in machining order.
    pub fn kinds(&self) -> Vec<MoveKind> {
        self.toolpath.kinds()
    }

    /// The segments in machining order and the indices of those reached by a retract.
    pub fn tool_path(&self) -> (Vec<Segment>, Vec<usize>) {
        (self.toolpath.segments(), self.toolpath.retract_before.clone())
    }

    /// Maximum measured engagement of one kind of move (0 if absent).
    pub fn max_of(&self, kind: MoveKind) -> f64 {
        self.measurement.max_of(kind)
    }

    /// The same path mirrored in x for the pocket `polygon` (the original of a mirrored plan):
    /// moves, entries, earlier cuts, the profile's positions and the maxima's places.
    pub fn mirrored(mut self, polygon: &Polygon) -> PocketPath {
        self.polygon = polygon.clone();
        self.islands = self.islands.iter().filter_map(|i| crate::geom::mirror::mirrored_polygon(i).ok()).collect();
        for m in &mut self.toolpath.moves {
            m.segment = m.segment.mirrored_x();
        }
        for e in &mut self.toolpath.entries {
            *e = e.mirrored();
        }
        for s in &mut self.precut {
            *s = s.mirrored_x();
        }
        for smp in &mut self.measurement.profile.samples {
            smp.x_mm = -smp.x_mm;
        }
        for m in &mut self.measurement.maxima {
            m.at = mirror_point(m.at);
        }
        self
    }
}
