//! The widget labels of every panel, in one place: each is also the widget's accessible name,
//! which is how the GUI tests (`gui_tests/`, egui_kittest) find it. A constant is named after
//! its text.

// Parameter panel (the slot job): each field's label is the core's `Param::label`.

// Export NC panel (the slot's program).
pub const NC_TOLERANCE: &str = "NC tolerance";
pub const LINEAR_SEGMENTS: &str = "Linear segments (G1 chords only)";
pub const COMPACT_LOOP: &str = "Compact loop";
pub const FASTER_RETURN_FEED: &str = "Faster return feed";
pub const RETURN_FEED: &str = "Return feed";
pub const SAVE_NC_PROGRAM: &str = "Save NC program…";

// Corner tab: one corner.
pub const CORNER_ANGLE: &str = "Corner angle (°)";
pub const CORNER_TOOL_DIAMETER: &str = "Corner tool diameter D (mm)";
pub const RING_STEP_OVER: &str = "Ring step-over a_e (mm)";
pub const STRAIGHT_ENGAGEMENT: &str = "Engagement on the straight walls (°)";
pub const ALLOWED_CORNER_EXCESS: &str = "Allowed corner excess (share)";

// Pocket tab.
pub const POCKET_VERTICES: &str = "Pocket vertices (x,y per line)";
/// The pocket's open edges (adaptive clearing).
pub const POCKET_OPEN_EDGES: &str = "Open edges";
pub const POCKET_OPEN_OUTLINE: &str = "Open outline…";

// Program tab.
pub const OPEN_PROGRAM_A: &str = "Open program A…";
pub const OPEN_PROGRAM_B: &str = "Open program B…";
pub const OPEN_STOCK: &str = "Open stock outline…";
pub const OPEN_PART: &str = "Open part outline…";
pub const VERIFY: &str = "Verify";
pub const CANCEL_VERIFY: &str = "Cancel verification";
pub const POSITION: &str = "Position in the program";

// Corner tab: the acceptance table.
pub const CANCEL_TABLE: &str = "Cancel table";
pub const RESTART_TABLE: &str = "Restart table";

// Program panel (the frame of every program; Export tab).
pub const TOOL_NUMBER: &str = "Tool number";
pub const OWN_LENGTH_OFFSET: &str = "Own length offset";
pub const LENGTH_OFFSET: &str = "Length offset";
pub const WORK_OFFSET: &str = "Work offset";
pub const CLEARANCE: &str = "Clearance height";
pub const OWN_RETRACT: &str = "Own retract height";
pub const RETRACT: &str = "Retract height";
pub const UNITS: &str = "Units";
pub const PROGRAM_COOLANT: &str = "Coolant";
pub const SPINDLE_DIRECTION: &str = "Spindle direction";
pub const PROGRAM_NUMBER: &str = "Program number";
pub const PROGRAM_NAME: &str = "Program name";

// The path field (no system file dialog).
pub const PATH_FIELD: &str = "File path";
pub const PATH_OPEN: &str = "Open file";
pub const PATH_SAVE: &str = "Save file";
pub const PATH_CANCEL: &str = "Cancel";

// Corner and Pocket tabs: the NC export.
pub const NC_EXPORT: &str = "NC export";
pub const CORNER_NC_TOLERANCE: &str = "Corner NC tolerance";
pub const G1_CHORDS_ONLY: &str = "G1 chords only";
pub const DEPTH_BELOW_Z0: &str = "Depth below Z0";
pub const SPINDLE: &str = "Spindle";
pub const SAVE_PROGRAM_AS: &str = "Save program as…";
