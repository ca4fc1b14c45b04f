//! What the window keeps between sessions: the user's [`Inputs`] (one undo history covers them
//! all), the selected [`Tab`] and the job file, stored together as one [`State`].

use super::panels::corner::CornerInputs;
use super::panels::corner_nc::CornerNcSettings;
use super::panels::export::ExportSettings;
use super::panels::sweep::SweepSettings;
use serde::{Deserialize, Serialize};
use std::path::PathBuf;
use trochoplan_core::Job;

/// Which view fills the centre of the window (the tab list is `tabs::TABS`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum Tab {
    #[default]
    Plots,
    Compare,
    Sweep,
    /// The "Export NC" panel.
    Export,
    /// One pocket corner and its corner trochoids (issue #5).
    Corner,
}

/// A pinned variant as persisted.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PinnedJob {
    pub label: String,
    pub job: Job,
}

/// Everything the user chose except the tab and the file name: undo and redo restore it whole.
#[derive(Clone, Debug, PartialEq)]
pub struct Inputs {
    pub job: Job,
    /// Show the explanation text under every plot.
    pub teach: bool,
    /// Cycles drawn in the path view.
    pub cycles_shown: usize,
    /// The chip view zooms onto the middle of the chip instead of showing all of it.
    pub chip_close_up: bool,
    /// Overlay pinned variants in the Plots tab too.
    pub overlay_pins: bool,
    /// The pinned variants of the Compare tab (at most `compare::MAX_VARIANTS`, all valid).
    pub pinned: Vec<PinnedJob>,
    pub sweep: SweepSettings,
    /// NC export options.
    pub export: ExportSettings,
    /// Inputs of the Corner tab.
    pub corner: CornerInputs,
    /// NC export options of the Corner tab.
    pub corner_nc: CornerNcSettings,
}

impl Default for Inputs {
    fn default() -> Self {
        Inputs {
            job: Job::default(),
            teach: false,
            cycles_shown: 5,
            chip_close_up: true,
            overlay_pins: true,
            pinned: Vec::new(),
            sweep: SweepSettings::default(),
            export: ExportSettings::default(),
            corner: CornerInputs::default(),
            corner_nc: CornerNcSettings::default(),
        }
    }
}

/// Everything persisted between sessions (eframe storage key `trochoplan-state`): the
/// [`Inputs`], the tab and the file, as one flat record — the shape earlier versions stored, so
/// their saved state still loads; fields missing from it take their defaults.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct State {
    pub job: Job,
    pub tab: Tab,
    pub teach: bool,
    pub cycles_shown: usize,
    pub chip_close_up: bool,
    pub overlay_pins: bool,
    pub pinned: Vec<PinnedJob>,
    pub sweep: SweepSettings,
    pub export: ExportSettings,
    pub corner: CornerInputs,
    pub corner_nc: CornerNcSettings,
    /// The job file last opened or saved.
    pub file: Option<PathBuf>,
}

impl Default for State {
    fn default() -> Self {
        State::new(Inputs::default(), Tab::default(), None)
    }
}

impl State {
    /// The record of `inputs`, `tab` and `file`.
    pub fn new(inputs: Inputs, tab: Tab, file: Option<PathBuf>) -> State {
        let Inputs { job, teach, cycles_shown, chip_close_up, overlay_pins, pinned, sweep, export, corner, corner_nc } =
            inputs;
        State {
            job,
            tab,
            teach,
            cycles_shown,
            chip_close_up,
            overlay_pins,
            pinned,
            sweep,
            export,
            corner,
            corner_nc,
            file,
        }
    }

    /// The inputs, tab and file of the record.
    pub fn split(self) -> (Inputs, Tab, Option<PathBuf>) {
        let State { job, tab, teach, cycles_shown, chip_close_up, overlay_pins, pinned, sweep, export, corner, corner_nc, file } =
            self;
        let inputs = Inputs { job, teach, cycles_shown, chip_close_up, overlay_pins, pinned, sweep, export, corner, corner_nc };
        (inputs, tab, file)
    }
}
