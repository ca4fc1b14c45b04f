//! Panels of the planner window: one function per panel. Panels edit the state they are given
//! or return a [`Command`]; commands run after all panels have drawn (see `app/commands.rs`).

pub mod compare;
pub mod corner;
pub mod corner_nc;
pub mod corner_table;
pub mod export;
pub mod graphics;
pub mod label;
pub mod legend;
pub mod metrics;
pub mod number;
pub mod operations;
pub mod operations_list;
pub mod operations_load;
pub mod optimise;
pub mod palette;
pub mod params;
pub mod path_field;
pub mod plane;
pub mod plots;
pub mod pocket;
pub mod pocket_inputs;
pub mod pocket_numbers;
pub mod pocket_plot;
pub mod program;
pub mod program_frame;
pub mod program_plots;
pub mod program_view;
pub mod sweep;
pub mod teach;

pub use super::Command;
