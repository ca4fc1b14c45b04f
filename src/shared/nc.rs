//! The NC options of an export, built in one place for every export of both front ends
//! (`export`, `corner --export`, `pocket --export`, the window's slot, corner and pocket
//! exports): an export's choices in, the core's [`NcOptions`] and [`CutSetup`] out; every
//! option no front end offers keeps the core's default (safe height, tool number).

use trochoplan_core::feed::VariableFeed;
use trochoplan_core::nc::{CutSetup, Dialect, NcOptions};

/// What a user chooses for an NC program (the fields of [`NcOptions`] a front end offers).
#[derive(Clone, Debug, PartialEq)]
pub struct NcChoices {
    pub dialect: Dialect,
    /// Largest distance of the written path from the planned one, before rounding (mm).
    pub tolerance_mm: f64,
    /// Curves as G1 chords instead of G2/G3 arcs.
    pub linear_segments: bool,
    /// Coolant on (M8) during the cut.
    pub coolant: bool,
    /// Header comment text.
    pub title: String,
    /// Loop form (slot programs).
    pub compact: bool,
    /// Feed of the moves that cut nothing (mm/min); `None`: the cutting feed.
    pub return_feed_mm_per_min: Option<f64>,
    /// Per-block feed for a target chip thickness (slot programs).
    pub variable_feed: Option<VariableFeed>,
}

impl NcChoices {
    /// The choices every export offers; the others as the core's defaults (no title, expanded
    /// program, cutting feed everywhere).
    pub fn new(dialect: Dialect, tolerance_mm: f64, linear_segments: bool, coolant: bool) -> NcChoices {
        let d = NcOptions::default();
        NcChoices {
            dialect,
            tolerance_mm,
            linear_segments,
            coolant,
            title: d.title,
            compact: d.compact,
            return_feed_mm_per_min: d.return_feed_mm_per_min,
            variable_feed: d.variable_feed,
        }
    }

    /// The core's options of these choices (validated by the core when a program is written).
    pub fn options(&self) -> NcOptions {
        NcOptions {
            dialect: self.dialect,
            tolerance_mm: self.tolerance_mm,
            linear_segments: self.linear_segments,
            coolant: self.coolant,
            title: self.title.clone(),
            compact: self.compact,
            return_feed_mm_per_min: self.return_feed_mm_per_min,
            variable_feed: self.variable_feed.clone(),
            ..NcOptions::default()
        }
    }
}

/// What a corner or pocket program needs beyond its plan: depth below Z0 (mm) and spindle
/// speed (rpm), validated by the core when the program is written.
pub fn cut_setup(depth_mm: f64, spindle_rpm: f64) -> CutSetup {
    CutSetup { depth_mm, spindle_rpm }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn choices_set_what_they_name_and_keep_the_cores_other_defaults() {
        let mut c = NcChoices::new(Dialect::Fanuc, 0.02, true, true);
        c.title = "t".into();
        c.return_feed_mm_per_min = Some(900.0);
        let o = c.options();
        let d = NcOptions::default();
        assert_eq!((o.dialect, o.tolerance_mm, o.linear_segments, o.coolant), (Dialect::Fanuc, 0.02, true, true));
        assert_eq!((o.title.as_str(), o.return_feed_mm_per_min), ("t", Some(900.0)));
        assert_eq!((o.safe_z_mm, o.tool_number, o.compact), (d.safe_z_mm, d.tool_number, d.compact));
        // the choices every export offers alone: the core's defaults for the rest
        let short = NcChoices::new(Dialect::Fanuc, 0.02, true, true).options();
        assert_eq!(short, NcOptions { title: String::new(), return_feed_mm_per_min: None, ..o });
    }
}
