//! # trochoplan-core
//!
//! The computing core of TrochoPlan: trochoidal slot tool paths as exact segments, and their
//! analysis — path length, cycle time, MRR, local maximum chip thickness h per tooth, engagement
//! angle, cooling time and wall waviness — after Wagih et al., "Analysis and development of
//! elliptical tool path in trochoidal milling", CIRP JMST 47 (2023) ("the paper").
//!
//! Conventions: millimetres, seconds, mm/min, rpm; radians inside (degrees only in reports).
//! The slot runs along +y from the stock face y = 0, centred on x = 0; the −x wall is the
//! "left" wall. XY plane seen from +z, counter-clockwise positive.
//!
//! Modules:
//! - [`job`]: the job and its validation ([`Job::validate`] → [`ValidJob`]).
//! - [`geom`]: points, exact segments (line, arc, eq. (1) trochoid piece), circles, simple
//!   polygons, numerics, the medial axis, offsets and booleans of loops.
//! - [`path`]: the four slot path types as one repeated cycle.
//! - [`analysis`]: edge of previous cycles, per-tooth h and engagement, waviness, step limit,
//!   cutting forces (linear edge-force model with helix) and bottom imprints.
//! - [`material`]: force coefficients, the material library, slot-test calibration.
//! - [`feed`]: variable feed: per-block feed for a target chip thickness, in bands.
//! - [`machine`]: machine limits, presets and the feed planner (real cycle time).
//! - [`optimize`]: the job of highest real MRR within the user's limits; Pareto front.
//! - [`nc`]: NC programs (LinuxCNC, Fanuc-style ISO, GRBL, Sinumerik), biarc output.
//! - [`toolpath`]: a tool path as data: moves (segment, heights, kind, feed), entries, retracts.
//! - [`engagement`]: the two-circle model, the independent evaluator, and [`engagement::measure`]
//!   of a tool path (per-kind maxima, 95th percentile, air).
//! - [`corner`]: pocket corners: corner trochoids, corner-point arcs, acceptance rows;
//!   [`corner::evaluate`] — corner request in, plans, profiles and acceptance row out.
//! - [`outline`]: pocket outlines from point lists, DXF and SVG files: loops in mm, nested
//!   into pockets with islands; [`outline::read`].
//! - [`pocket`]: polygonal pockets by rings or along the medial axis; [`pocket::plan`].
//! - [`plan`]: [`plan()`] — job in, [`Plan`] out; used by the GUI and the CLI.
//! - [`slot_levels`]: a slot in levels, open or closed: each level's tool path, analysis and
//!   measured moves.
//! - [`quantity`]: every metric and per-tooth series column as data (key, label, unit, source).
//! - [`sweep`]: the swept parameters and their rules (which path, which values).
//! - [`part`]: a part made by several operations (slots, pockets, corners) with a tool table:
//!   planned in order, reported, written as one program with tool changes.
//! - [`verify`]: any NC program read, timed and measured move by move: engagement, axial
//!   depth, chip at the reached feed, force, torque, power, and its problems.
//! - [`warnings`]: the limits a planned slot is checked against (engagement, minimum chip,
//!   spindle power and torque), each with its source, and the plan's warnings in words.
//! - [`error`]: the [`Error`] type and the [`Param`] names of every user parameter.

pub mod analysis;
pub mod corner;
pub mod engagement;
pub mod error;
pub mod feed;
pub mod frame;
pub mod geom;
pub mod job;
pub mod machine;
pub mod material;
pub mod nc;
pub mod optimize;
pub mod outline;
pub mod part;
pub mod path;
pub mod plan;
pub mod pocket;
pub mod quantity;
pub mod report;
pub mod slot_levels;
pub mod sweep;
pub mod toolpath;
pub mod verify;
pub mod warnings;

pub use error::{Error, Param};
pub use job::{Job, PathKind, ValidJob};
pub use plan::{Metrics, Plan, plan};
