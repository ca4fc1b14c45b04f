//! The NC options of an export, built in one place for every export of both front ends
//! (`export`, `corner --export`, `pocket --export`, the window's slot, corner and pocket
//! exports): an export's choices in, the core's [`NcOptions`] and [`CutSetup`] out; every
//! field of [`NcOptions`] is one of these choices.

use trochoplan_core::feed::VariableFeed;
use trochoplan_core::frame::ProgramFrame;
use trochoplan_core::nc::{CutSetup, Dialect, NcOptions};

/// What a user chooses for an NC program (the fields of [`NcOptions`] a front end offers).
#[derive(Clone, Debug, PartialEq)]
pub struct NcChoices {
    pub dialect: Dialect,
    /// Largest distance of the written path from the planned one, before rounding (mm).
    pub tolerance_mm: f64,
    /// Curves as G1 chords instead of G2/G3 arcs.
    pub linear_segments: bool,
    /// Tool, offsets, heights, units, coolant, spindle direction, program number or name.
    pub frame: ProgramFrame,
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
    pub fn new(dialect: Dialect, tolerance_mm: f64, linear_segments: bool, frame: ProgramFrame) -> NcChoices {
        let d = NcOptions::default();
        NcChoices {
            dialect,
            tolerance_mm,
            linear_segments,
            frame,
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
            frame: self.frame.clone(),
            title: self.title.clone(),
            compact: self.compact,
            return_feed_mm_per_min: self.return_feed_mm_per_min,
            variable_feed: self.variable_feed.clone(),
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
        let frame = ProgramFrame { tool_number: 7, ..ProgramFrame::default() };
        let mut c = NcChoices::new(Dialect::Fanuc, 0.02, true, frame.clone());
        c.title = "t".into();
        c.return_feed_mm_per_min = Some(900.0);
        let o = c.options();
        let d = NcOptions::default();
        assert_eq!((o.dialect, o.tolerance_mm, o.linear_segments), (Dialect::Fanuc, 0.02, true));
        assert_eq!(o.frame, frame);
        assert_eq!((o.title.as_str(), o.return_feed_mm_per_min), ("t", Some(900.0)));
        assert_eq!(o.compact, d.compact);
        // the choices every export offers alone: the core's defaults for the rest
        let short = NcChoices::new(Dialect::Fanuc, 0.02, true, frame).options();
        assert_eq!(short, NcOptions { title: String::new(), return_feed_mm_per_min: None, ..o });
    }
}
