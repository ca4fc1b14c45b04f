//! NC dialects as data: what differs between controllers is written down here, once; the
//! emitter ([`super::writer`]) reads it (docs/architecture.md).

use crate::error::{Error, Param};
use crate::frame::Units;
use serde::{Deserialize, Serialize};
use std::f64::consts::{PI, TAU};

/// Target controller family. Serialised by its CLI name; the GUI's older spellings (the
/// variant names) still load.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Dialect {
    /// LinuxCNC RS274NGC (named parameters, O-word loops).
    #[default]
    #[serde(rename = "linuxcnc", alias = "LinuxCnc")]
    LinuxCnc,
    /// Fanuc-style ISO: `%`, program number, I/J incremental, decimal points always written.
    #[serde(rename = "fanuc", alias = "Fanuc")]
    Fanuc,
    /// GRBL 1.1: no O-words, no tool change, at most a half circle per arc block.
    #[serde(rename = "grbl", alias = "Grbl")]
    Grbl,
    /// Siemens Sinumerik 840D: `;` comments, G71 metric, R-parameters, labels and GOTOB.
    #[serde(rename = "sinumerik", alias = "Sinumerik")]
    Sinumerik,
}

/// How comments are written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CommentStyle {
    /// `(text)`: LinuxCNC, Fanuc, GRBL.
    Parens,
    /// `; text`: Sinumerik.
    Semicolon,
}

/// How the tool is called.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ToolCall {
    /// `T1 M6` then `G43 H1` (tool length offset).
    ChangeAndLengthOffset,
    /// `T1 D1` then `M6` (Sinumerik: D activates the tool offset).
    SinumerikTD,
    /// No tool words (GRBL has no tool changer support); the tool is named in a comment.
    CommentOnly,
}

/// Compact (looped) program form a dialect supports.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LoopStyle {
    /// LinuxCNC `o100 while [...]` … `o100 endwhile` with named parameters (docs/nc-export.md).
    OWord,
    /// Sinumerik R-parameters, a label and `IF … GOTOB` (Grechishnikov et al. 2017).
    RParameter,
}

/// Everything the emitter needs to know about a dialect.
#[derive(Clone, Copy, Debug)]
pub struct DialectSpec {
    /// CLI name.
    pub name: &'static str,
    /// Name for people (GUI).
    pub label: &'static str,
    /// What marks the dialect's programs (GUI tooltip).
    pub about: &'static str,
    /// File extension of its programs, without the dot.
    pub extension: &'static str,
    /// Decimals of coordinates (mm); the quantum is 10^-decimals.
    pub decimals: u32,
    pub comment: CommentStyle,
    /// Lines before the header comment (tape start).
    pub program_start: &'static [&'static str],
    /// Whether the program number `O…` follows the tape start (Fanuc).
    pub program_number: bool,
    /// Whether a program name is written as the `%_N_NAME_MPF` header (Sinumerik), when given.
    pub program_name_header: bool,
    /// The modal set-up block: plane, units, absolute, feed per minute, cancels (metric; see
    /// [`DialectSpec::setup_words`]).
    pub setup: &'static str,
    /// The metric word of `setup` and the word that replaces it in an inch program.
    pub unit_words: (&'static str, &'static str),
    /// Largest tool number T.
    pub max_tool_number: u32,
    /// Largest length offset number (H; D on Sinumerik).
    pub max_length_offset: u32,
    /// Path-blending word followed by the tolerance (LinuxCNC `G64 P…`: blend corners but stay
    /// within the tolerance of the programmed path), if the dialect takes one.
    pub blend_tolerance_word: Option<&'static str>,
    pub tool_call: ToolCall,
    /// Largest sweep of one arc block (rad).
    pub max_arc_sweep: f64,
    /// Largest start/end radius difference we allow in an arc block (mm), at or below what the
    /// controller checks: LinuxCNC 2.9's rs274 accepted 0.02 mm and rejected 0.04 mm (probed
    /// by hand, 5 mm radius); GRBL rejects > 0.005 mm and > 0.1 %; Fanuc parameter 3410 and
    /// Sinumerik MD 21000 CIRCLE_ERROR_CONST are machine settings, typically ~0.01 mm. The
    /// emitter keeps it ≤ q·√2 (writer docs), so this is a guard, not a target.
    pub arc_radius_tolerance_mm: f64,
    /// Lines after the last motion (program end).
    pub program_end: &'static [&'static str],
    /// The compact form, if the dialect has one.
    pub loop_style: Option<LoopStyle>,
    /// Whether G0 moves the tool on a straight line (coordinated), so that a rapid at depth
    /// through cleared stock follows the planned line. Where it may not (Fanuc's non-linear
    /// positioning unless parameter 1401#1 LRP is set; Sinumerik's G0 outside linear
    /// interpolation, machine data G0_LINEAR_MODE / RTLIOF), such moves are written as G1 at
    /// their feed.
    pub straight_rapid: bool,
}

const LINUXCNC: DialectSpec = DialectSpec {
    name: "linuxcnc",
    label: "LinuxCNC",
    about: "RS274NGC: G64 P blending at the tolerance, O-word while loop available.",
    extension: "ngc",
    decimals: 4,
    comment: CommentStyle::Parens,
    program_start: &[],
    program_number: false,
    program_name_header: false,
    // G91.1: arc centres I/J incremental from the arc start (LinuxCNC default, stated anyway)
    setup: "G17 G21 G40 G49 G80 G90 G91.1 G94",
    unit_words: ("G21", "G20"),
    max_tool_number: 99_999,
    max_length_offset: 99_999,
    blend_tolerance_word: Some("G64 P"),
    tool_call: ToolCall::ChangeAndLengthOffset,
    max_arc_sweep: TAU,
    arc_radius_tolerance_mm: 0.01,
    program_end: &["M30"],
    loop_style: Some(LoopStyle::OWord),
    straight_rapid: true,
};

const FANUC: DialectSpec = DialectSpec {
    name: "fanuc",
    label: "Fanuc-style ISO",
    about: "Fanuc-style ISO: % tape marks, program number (O1000 unless set), 3 decimals.",
    extension: "nc",
    decimals: 3,
    comment: CommentStyle::Parens,
    program_start: &["%"],
    program_number: true,
    program_name_header: false,
    setup: "G17 G21 G40 G49 G80 G90 G94",
    unit_words: ("G21", "G20"),
    max_tool_number: 9_999,
    max_length_offset: 999,
    blend_tolerance_word: None,
    tool_call: ToolCall::ChangeAndLengthOffset,
    max_arc_sweep: TAU,
    arc_radius_tolerance_mm: 0.005,
    program_end: &["M30", "%"],
    loop_style: None,
    straight_rapid: false,
};

const GRBL: DialectSpec = DialectSpec {
    name: "grbl",
    label: "GRBL",
    about: "GRBL 1.1: no tool change or loops; arcs split into half circles at most.",
    extension: "gcode",
    decimals: 3,
    comment: CommentStyle::Parens,
    program_start: &[],
    program_number: false,
    program_name_header: false,
    setup: "G17 G21 G40 G90 G94",
    unit_words: ("G21", "G20"),
    max_tool_number: 99_999,
    max_length_offset: 99_999,
    blend_tolerance_word: None,
    tool_call: ToolCall::CommentOnly,
    max_arc_sweep: PI,
    arc_radius_tolerance_mm: 0.005,
    program_end: &["M30"],
    loop_style: None,
    straight_rapid: true,
};

const SINUMERIK: DialectSpec = DialectSpec {
    name: "sinumerik",
    label: "Sinumerik 840D",
    about: "Siemens Sinumerik 840D: ; comments, G71, R-parameter loop available.",
    extension: "mpf",
    decimals: 3,
    comment: CommentStyle::Semicolon,
    program_start: &[],
    program_number: false,
    program_name_header: true,
    // G71: metric in Siemens mode (G21 is the ISO-dialect word)
    setup: "G17 G40 G71 G90 G94",
    unit_words: ("G71", "G700"),
    max_tool_number: 32_000,
    max_length_offset: 9,
    blend_tolerance_word: None,
    tool_call: ToolCall::SinumerikTD,
    max_arc_sweep: TAU,
    arc_radius_tolerance_mm: 0.01,
    program_end: &["M30"],
    loop_style: Some(LoopStyle::RParameter),
    straight_rapid: false,
};

impl DialectSpec {
    /// The set-up block for `units`: the metric word replaced by the inch word in an inch
    /// program.
    pub fn setup_words(&self, units: Units) -> String {
        match units {
            Units::Mm => self.setup.to_string(),
            Units::Inch => self
                .setup
                .split(' ')
                .map(|w| if w == self.unit_words.0 { self.unit_words.1 } else { w })
                .collect::<Vec<_>>()
                .join(" "),
        }
    }
}

impl Dialect {
    /// All dialects, in CLI order.
    pub const ALL: [Dialect; 4] = [Dialect::LinuxCnc, Dialect::Fanuc, Dialect::Grbl, Dialect::Sinumerik];

    /// The dialect's data.
    pub fn spec(self) -> &'static DialectSpec {
        match self {
            Dialect::LinuxCnc => &LINUXCNC,
            Dialect::Fanuc => &FANUC,
            Dialect::Grbl => &GRBL,
            Dialect::Sinumerik => &SINUMERIK,
        }
    }

    /// CLI name.
    pub fn name(self) -> &'static str {
        self.spec().name
    }

    /// Name for people (GUI radio buttons).
    pub fn label(self) -> &'static str {
        self.spec().label
    }

    /// What marks the dialect's programs (GUI tooltip).
    pub fn about(self) -> &'static str {
        self.spec().about
    }

    /// File extension of its programs, without the dot.
    pub fn extension(self) -> &'static str {
        self.spec().extension
    }

    /// Parse a CLI name.
    pub fn from_name(s: &str) -> Result<Dialect, Error> {
        Dialect::ALL
            .into_iter()
            .find(|d| d.name() == s)
            .ok_or_else(|| Error::param(Param::Dialect, s, "one of linuxcnc, fanuc, grbl, sinumerik"))
    }
}

/// Words that make a comment *active* when it begins with them (after spaces, any case):
/// LinuxCNC executes `(MSG,…)`, `(DEBUG,…)`, `(PRINT,…)`, `(LOG…)`, `(ABORT,…)`,
/// `(PROBEOPEN …)`/`(PROBECLOSE)` and, with its Python plug-in, `(PY,…)`; GRBL 1.1 shows
/// `(MSG,…)`. Matched as prefixes of the comment's first word (`LOG` covers `LOGOPEN`,
/// `LOGAPPEND`, `LOGCLOSE`; `PROBE` both probe words), so no spelling slips through.
const ACTIVE_COMMENT_WORDS: [&str; 7] = ["MSG", "DEBUG", "PRINT", "LOG", "ABORT", "PROBE", "PY"];

/// Text made safe for a comment of any dialect: one line, printable ASCII, no comment
/// delimiters, never an active comment. `(`/`)` become `[`/`]` (LinuxCNC rejects a nested "("
/// and a ")" would end the comment early), `;` becomes `,`, `%` (Fanuc/LinuxCNC tape mark)
/// becomes `_`, control characters and newlines become spaces, other characters `?`; text
/// whose first word begins with one of [`ACTIVE_COMMENT_WORDS`] gets a leading `- `
/// (LinuxCNC executes such comments: `ABORT,stop` would abort the program, `LOGOPEN,/path`
/// would open a file on the controller);
/// at most 70 characters.
pub fn sanitize_comment(text: &str) -> String {
    let mapped: String = text
        .chars()
        .map(|c| match c {
            '(' => '[',
            ')' => ']',
            ';' => ',',
            '%' => '_',
            c if c.is_ascii_control() => ' ',
            c if c.is_ascii() => c,
            _ => '?',
        })
        .collect();
    let words: Vec<&str> = mapped.split_whitespace().collect();
    let mut line = words.join(" ");
    let first_word: String =
        line.chars().take_while(char::is_ascii_alphabetic).collect::<String>().to_ascii_uppercase();
    if ACTIVE_COMMENT_WORDS.iter().any(|w| first_word.starts_with(w)) {
        line.insert_str(0, "- ");
    }
    line.chars().take(70).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sanitized_comments_cannot_break_out() {
        let evil = "a (nested) comment;\nG0 X0 ) % é\t(";
        let s = sanitize_comment(evil);
        assert_eq!(s, "a [nested] comment, G0 X0 ] _ ? [");
        assert!(!s.contains(['(', ')', ';', '\n', '\r', '%']));
        assert!(sanitize_comment(&"x".repeat(500)).len() <= 70);
    }

    #[test]
    fn no_text_forms_an_active_comment() {
        // LinuxCNC executes these when a comment begins with them (any case,
        // leading spaces); each must come out as a plain comment that still shows the text.
        for evil in [
            "ABORT,stop",
            "  abort,stop",
            "MSG,hello",
            "msg ,hello",
            "DEBUG,#<x>",
            "Print,1",
            "LOG,x",
            "LOGOPEN,/tmp/x",
            "logappend,/tmp/x",
            "LOGCLOSE",
            "PROBEOPEN /tmp/p",
            "probeclose",
            "PY,import os",
            "\tMsG,tab first",
            "(ABORT,stop)",
        ] {
            let s = sanitize_comment(evil);
            let word: String = s.trim_start().chars().take_while(char::is_ascii_alphabetic).collect();
            assert!(word.is_empty(), "{evil:?} -> {s:?} still begins with a word");
            assert!(
                s.to_ascii_uppercase().contains(&evil.trim().trim_start_matches('(').to_ascii_uppercase()[..4]),
                "{s}"
            );
        }
        // ordinary titles are unchanged
        assert_eq!(sanitize_comment("TrochoPlan slot"), "TrochoPlan slot");
        assert_eq!(sanitize_comment("Message to the operator"), "Message to the operator");
    }

    #[test]
    fn dialect_names_round_trip_and_errors_name_the_parameter() {
        for d in Dialect::ALL {
            assert_eq!(Dialect::from_name(d.name()), Ok(d));
        }
        let err = Dialect::from_name("heidenhain").expect_err("unknown");
        assert_eq!(err.parameter(), Some(Param::Dialect));
    }

    #[test]
    fn dialects_serialise_by_name_and_old_gui_spellings_load() {
        for (d, old) in Dialect::ALL.into_iter().zip(["\"LinuxCnc\"", "\"Fanuc\"", "\"Grbl\"", "\"Sinumerik\""]) {
            assert_eq!(serde_json::to_string(&d).expect("json"), format!("\"{}\"", d.name()));
            assert_eq!(serde_json::from_str::<Dialect>(old).expect("old spelling"), d);
            assert_eq!(serde_json::from_str::<Dialect>(&format!("\"{}\"", d.name())).expect("name"), d);
        }
        assert_eq!(Dialect::Sinumerik.extension(), "mpf");
    }
}
