//! What the window keeps between sessions ([`State`]): the user's [`Inputs`] (one undo history
//! covers them all) and the [`View`] (the selected tab and the job file).

use super::earlier::{EarlierRecord, move_pocket};
use super::panels::corner::CornerInputs;
use super::panels::corner_nc::CornerNcSettings;
use super::panels::export::ExportSettings;
use super::panels::optimise::OptimiseSettings;
use super::panels::pocket::PocketInputs;
use super::panels::program::ProgramSettings;
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
    /// Cutting forces and bottom imprints.
    Forces,
    /// The "Export NC" panel.
    Export,
    /// One pocket corner and its corner trochoids.
    Corner,
    /// A whole pocket.
    Pocket,
    /// Feed over the cycle on the machine, and the optimiser.
    Optimise,
    /// Verify an NC program.
    Program,
    /// The operations of a part job file.
    Operations,
}

/// A pinned variant as persisted.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PinnedJob {
    pub label: String,
    pub job: Job,
}

/// Everything the user chose except the tab and the file name: undo and redo restore it whole.
///
/// Stored under [`INPUTS_KEY`], the key and flat record of earlier versions (which also held
/// the view's fields: they are ignored here); fields missing from a stored record take their
/// defaults.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default)]
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
    /// Inputs of the Pocket tab.
    pub pocket: PocketInputs,
    /// NC export options of the Pocket tab.
    pub pocket_nc: CornerNcSettings,
    /// Limits of the optimiser.
    pub optimise: OptimiseSettings,
    /// Stock, tool, material and machine of the Program tab.
    pub program: ProgramSettings,
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
            pocket: PocketInputs::default(),
            pocket_nc: CornerNcSettings::default(),
            optimise: OptimiseSettings::default(),
            program: ProgramSettings::default(),
        }
    }
}

/// What the window shows, persisted but not undone: stored under [`VIEW_KEY`], or read from the
/// record under [`INPUTS_KEY`] where earlier versions kept it.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct View {
    pub tab: Tab,
    /// The job file last opened or saved.
    pub file: Option<PathBuf>,
    /// Jobs, outlines and part job files last opened or saved, newest first (the File menu's
    /// recent files).
    pub recent: Vec<PathBuf>,
    /// Those of [`View::recent`] that were opened as part job files (a part is a `.toml` file
    /// like a job).
    pub recent_parts: Vec<PathBuf>,
    /// The part job file open in the Operations tab, opened again at the next start.
    pub part: Option<PathBuf>,
}

/// eframe storage key of [`Inputs`].
pub const INPUTS_KEY: &str = "trochoplan-state";
/// eframe storage key of [`View`].
pub const VIEW_KEY: &str = "trochoplan-view";

/// Everything persisted between sessions.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct State {
    pub inputs: Inputs,
    pub view: View,
}

impl State {
    /// The state stored in `storage`, if there is one.
    pub fn load(storage: &dyn eframe::Storage) -> Option<State> {
        let mut inputs = eframe::get_value::<Inputs>(storage, INPUTS_KEY)?;
        let mut view = eframe::get_value::<View>(storage, VIEW_KEY)
            .or_else(|| eframe::get_value::<View>(storage, INPUTS_KEY))
            .unwrap_or_default();
        // a record from before the Pocket tab: its pocket moves there
        if let Some(earlier) = eframe::get_value::<EarlierRecord>(storage, INPUTS_KEY) {
            move_pocket(earlier, &mut inputs, &mut view);
        }
        Some(State { inputs, view })
    }

    /// This state editing `job`.
    pub fn with_job(self, job: Job) -> State {
        State { inputs: Inputs { job, ..self.inputs }, view: self.view }
    }

    /// Store `inputs` and `view` in `storage`.
    pub fn save(inputs: &Inputs, view: &View, storage: &mut dyn eframe::Storage) {
        eframe::set_value(storage, INPUTS_KEY, inputs);
        eframe::set_value(storage, VIEW_KEY, view);
    }
}
