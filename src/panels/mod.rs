//! Panels of the planner window: one function per panel. Panels edit the state they are given
//! or return a [`Command`]; commands run after all panels have drawn (see `app.rs`).

pub mod compare;
pub mod corner;
pub mod corner_nc;
pub mod corner_table;
pub mod export;
pub mod graphics;
pub mod metrics;
pub mod params;
pub mod plots;
pub mod sweep;
pub mod teach;

/// Something a panel asks for that touches files, dialogs, the undo history, pins or threads.
#[must_use]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Command {
    Open,
    Save,
    SaveAs,
    ResetJob,
    Undo,
    Redo,
    Pin,
    PinPaperSet,
    Unpin(usize),
    ClearPins,
    LoadPinned(usize),
    StartSweep,
    CancelSweep,
    /// Ask for a file and write the previewed NC program.
    ExportNc,
    /// Stop the Corner tab's acceptance table.
    CancelCornerTable,
    /// Compute the acceptance table again.
    RestartCornerTable,
    /// Ask for a file and write the Corner tab's previewed NC program.
    ExportCornerNc,
}
