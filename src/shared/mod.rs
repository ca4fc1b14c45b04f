//! What both front ends use: the command line (`cli.rs` and its command files) and the window
//! (`app/`, `panels/`, `worker.rs`) take files, NC options and outlines from here, never from
//! each other's files (checked by `src/layout_tests.rs`).
//!
//! - [`files`]: atomic writes, bounded regular-file reads, input/output distinctness.
//! - [`nc`]: the core's NC options and cut setup built from an export's choices, in one place
//!   for the slot, corner and pocket exports of both front ends.
//! - [`outline`]: a pocket outline file (DXF, SVG or point list) read through the core.

pub mod files;
pub mod nc;
pub mod outline;
