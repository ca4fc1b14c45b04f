//! Stored states of versions before the Pocket tab: they kept the pocket's inputs in the Corner
//! tab's record (`corner.polygon_text`, `corner.pocket_step_over_mm`, `corner.pocket_adaptive`,
//! `corner.pocket_open_edges`, with `corner.mode: Pocket` when the pocket was shown). Such a
//! record loads as it is (the fields the current [`Inputs`] do not know are ignored, the mode
//! `Pocket` reads as `Corner`), and [`move_pocket`] then moves its pocket to the Pocket tab.

use super::panels::corner::CornerInputs;
use super::panels::pocket::PocketInputs;
use super::{Inputs, Tab, View};
use serde::{Deserialize, Deserializer};
use trochoplan_core::corner::CornerMethod;
use trochoplan_core::pocket::PocketStrategy;

/// The record under `INPUTS_KEY` as far as the move needs it.
#[derive(Deserialize, Default)]
#[serde(default)]
pub struct EarlierRecord {
    corner: EarlierCorner,
    /// The record has the Pocket tab's own inputs: there is nothing to move.
    #[serde(deserialize_with = "present")]
    pocket: bool,
}

/// The Corner tab's record of versions before the Pocket tab.
#[derive(Deserialize)]
#[serde(default)]
struct EarlierCorner {
    mode: EarlierMode,
    method: CornerMethod,
    tool_diameter_mm: f64,
    polygon_text: String,
    pocket_step_over_mm: f64,
    pocket_adaptive: bool,
    pocket_open_edges: String,
}

impl Default for EarlierCorner {
    /// What those versions took for a missing field: the defaults of the two tabs now.
    fn default() -> Self {
        let (c, p) = (CornerInputs::default(), PocketInputs::default());
        EarlierCorner {
            mode: EarlierMode::Corner,
            method: c.method,
            tool_diameter_mm: c.tool_diameter_mm,
            polygon_text: p.polygon_text,
            pocket_step_over_mm: p.step_over_mm,
            pocket_adaptive: p.strategy == PocketStrategy::Adaptive,
            pocket_open_edges: p.open_edges,
        }
    }
}

/// The Corner tab's modes of versions before the Pocket tab.
#[derive(Deserialize, Default, PartialEq, Eq)]
enum EarlierMode {
    #[default]
    Corner,
    Table,
    Pocket,
}

/// True for any value that is there (the field is missing: `false`, its default).
fn present<'de, D: Deserializer<'de>>(d: D) -> Result<bool, D::Error> {
    serde::de::IgnoredAny::deserialize(d).map(|_| true)
}

/// Move the pocket of an `earlier` record into the Pocket tab's inputs (with the Corner tab's
/// NC export settings, which it was exported with) and show the Pocket tab if the pocket mode
/// was shown. A record that already has the Pocket tab's inputs is left as it is.
pub fn move_pocket(earlier: EarlierRecord, inputs: &mut Inputs, view: &mut View) {
    if earlier.pocket {
        return;
    }
    let c = earlier.corner;
    inputs.pocket = PocketInputs {
        polygon_text: c.polygon_text,
        step_over_mm: c.pocket_step_over_mm,
        strategy: if c.pocket_adaptive { PocketStrategy::Adaptive } else { PocketStrategy::from_method(c.method) },
        open_edges: c.pocket_open_edges,
        ..PocketInputs::default()
    };
    inputs.pocket_nc = inputs.corner_nc.clone();
    if c.mode == EarlierMode::Pocket && view.tab == Tab::Corner {
        view.tab = Tab::Pocket;
    }
}
