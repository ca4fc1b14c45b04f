//! The corner strategies (Wu et al. 2016 §4.2) and how the front ends name them: the CLI's
//! value and its help line, the GUI's button label and tooltip. Every front end reads them
//! from here.

use serde::{Deserialize, Serialize};

/// Corner strategy. Serialised by its CLI name; the GUI's older spellings ("Variable",
/// "MedialAxis", …) are read too, so saved window state still loads.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum CornerMethod {
    /// The plain contour-parallel ring: straight into the tool corner point and out.
    #[serde(alias = "Plain")]
    Plain,
    /// Variable circles on the bisector (Wu et al. 2016 §4.2.1, eqs. 23–24).
    #[serde(alias = "Variable")]
    Variable,
    /// Isometric circles along U offset by rh (Wu et al. 2016 §4.2.2, eq. 25).
    #[serde(alias = "Isometric")]
    Isometric,
    /// Perforative circles along the medial axis of the pocket (Wu et al. §4.2; §3.5).
    #[serde(alias = "MedialAxis")]
    MedialAxis,
}

impl CornerMethod {
    /// Every method, in the order the front ends list them.
    pub const ALL: [CornerMethod; 4] =
        [CornerMethod::Plain, CornerMethod::Variable, CornerMethod::Isometric, CornerMethod::MedialAxis];

    /// CLI / JSON name.
    pub fn name(self) -> &'static str {
        match self {
            CornerMethod::Plain => "plain",
            CornerMethod::Variable => "variable",
            CornerMethod::Isometric => "isometric",
            CornerMethod::MedialAxis => "medial-axis",
        }
    }

    /// The method of a CLI / JSON name.
    pub fn from_name(name: &str) -> Option<CornerMethod> {
        CornerMethod::ALL.into_iter().find(|m| m.name() == name)
    }

    /// One line for `trochoplan corner --help`.
    pub fn help(self) -> &'static str {
        match self {
            CornerMethod::Plain => "The plain contour-parallel ring (no corner trochoids), for comparison",
            CornerMethod::Variable => "Variable circles on the bisector (Wu et al. 2016 eqs. 23–24)",
            CornerMethod::Isometric => "Isometric circles (Wu et al. 2016, section 4.2.2, eq. 25)",
            CornerMethod::MedialAxis => {
                "Perforative circles along the medial axis of the pocket (Voronoi, boostvoronoi)"
            }
        }
    }

    /// Button label in the GUI.
    pub fn label(self) -> &'static str {
        match self {
            CornerMethod::Plain => "plain ring",
            CornerMethod::Variable => "variable circles",
            CornerMethod::Isometric => "isometric circles",
            CornerMethod::MedialAxis => "medial axis",
        }
    }

    /// Tooltip of the GUI's button.
    pub fn tooltip(self) -> &'static str {
        match self {
            CornerMethod::Plain => "The contour-parallel ring turning at the corner, no trochoids (for comparison).",
            CornerMethod::Variable => {
                "Circles tangent to both offset walls, centres on the bisector (eqs. 21–22); each next circle \
                 found by bisection between the limit points M and N until its engagement lies in \
                 (a*, a* + ε] (eqs. 23–24)."
            }
            CornerMethod::Isometric => {
                "Circles of one radius rh (default: the tool radius), centre spacing from the engagement \
                 limit; needs rh above the threshold rh1 (eq. 25)."
            }
            CornerMethod::MedialAxis => {
                "Perforative circles along the medial axis of the corner's remaining material \
                 (segment Voronoi diagram; Wu et al. 2016, section 4.2)."
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_and_old_gui_spellings_load() {
        for m in CornerMethod::ALL {
            assert_eq!(CornerMethod::from_name(m.name()), Some(m));
            let json = serde_json::to_string(&m).expect("json");
            assert_eq!(json, format!("\"{}\"", m.name()));
            assert_eq!(serde_json::from_str::<CornerMethod>(&json).expect("back"), m);
        }
        for (old, m) in [
            ("\"Plain\"", CornerMethod::Plain),
            ("\"Variable\"", CornerMethod::Variable),
            ("\"Isometric\"", CornerMethod::Isometric),
            ("\"MedialAxis\"", CornerMethod::MedialAxis),
        ] {
            assert_eq!(serde_json::from_str::<CornerMethod>(old).expect("old spelling"), m);
        }
        assert_eq!(CornerMethod::from_name("bogus"), None);
    }
}
