//! Work materials for the cutting-force model: the six coefficients of the linear edge-force
//! model (Altintas & Lee 1996), the built-in library
//! (`assets/materials/library.toml`, every value with its source), the checks a coefficient
//! set must pass, and their calibration from full-slot tests (derivation in
//! docs/process-model.md, "Cutting forces").
//!
//! Units: Ktc, Krc, Kac in N/mm² (force per chip area), Kte, Kre, Kae in N/mm (force per edge
//! length).

use crate::error::{Error, Param, num};
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// Name of the default material: the paper's P20, unhardened (docs/process-model.md, "The P20
/// default set").
pub const DEFAULT_MATERIAL: &str = "p20";

/// The usual range of Krc/Ktc (docs/process-model.md: public fitted sets with negative or odd
/// entries exist; a set outside this range is refused unless the user allows it).
pub const RADIAL_RATIO_RANGE: (f64, f64) = (0.2, 0.6);

/// The built-in library's text (also written out by the GUI and CLI for users to edit).
pub const LIBRARY_TOML: &str = include_str!("../../assets/materials/library.toml");

/// The six coefficients of the linear edge-force model (Altintas & Lee 1996):
/// dF_t = (Ktc·h + Kte)·dz, dF_r = (Krc·h + Kre)·dz, dF_a = (Kac·h + Kae)·dz.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Coefficients {
    /// Tangential cutting coefficient Ktc (N/mm²).
    pub ktc: f64,
    /// Radial cutting coefficient Krc (N/mm²).
    pub krc: f64,
    /// Axial cutting coefficient Kac (N/mm²).
    pub kac: f64,
    /// Tangential edge coefficient Kte (N/mm).
    pub kte: f64,
    /// Radial edge coefficient Kre (N/mm).
    pub kre: f64,
    /// Axial edge coefficient Kae (N/mm).
    pub kae: f64,
}

impl Coefficients {
    /// The coefficients with their parameter names, in the order Ktc, Krc, Kac, Kte, Kre, Kae.
    pub fn named(&self) -> [(Param, f64); 6] {
        [
            (Param::Ktc, self.ktc),
            (Param::Krc, self.krc),
            (Param::Kac, self.kac),
            (Param::Kte, self.kte),
            (Param::Kre, self.kre),
            (Param::Kae, self.kae),
        ]
    }

    /// Check a set: every value finite and ≥ 0 (≤ 10⁶), Ktc > 0, and — unless
    /// `allow_unusual_ratio` — Krc/Ktc within [`RADIAL_RATIO_RANGE`]. The error names the field.
    pub fn check(&self, allow_unusual_ratio: bool) -> Result<(), Error> {
        for (p, v) in self.named() {
            if !(v.is_finite() && (0.0..=1.0e6).contains(&v)) {
                return Err(Error::param(p, v, "a finite number from 0 to 1e6 (N/mm² or N/mm)"));
            }
        }
        if self.ktc <= 0.0 {
            return Err(Error::param(Param::Ktc, self.ktc, "greater than 0 N/mm²"));
        }
        let (lo, hi) = RADIAL_RATIO_RANGE;
        let ratio = self.krc / self.ktc;
        if !allow_unusual_ratio && !(lo..=hi).contains(&ratio) {
            return Err(Error::param(
                Param::Krc,
                self.krc,
                format!(
                    "from {}·Ktc to {}·Ktc = {} to {} N/mm² (now Krc/Ktc = {}; set \
                     allow-unusual-ratio = true to use it anyway)",
                    num(lo),
                    num(hi),
                    num(lo * self.ktc),
                    num(hi * self.ktc),
                    num(ratio)
                ),
            ));
        }
        Ok(())
    }
}

/// One material of a library.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub struct Material {
    /// Name used in job files and on the command line (`--material`).
    pub name: String,
    /// Label for people (GUI picker).
    pub label: String,
    /// Accept Krc/Ktc outside [`RADIAL_RATIO_RANGE`].
    #[serde(default)]
    pub allow_unusual_ratio: bool,
    #[serde(flatten)]
    pub coefficients: Coefficients,
}

/// A material library: `[[material]]` entries of a TOML file.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Library {
    #[serde(rename = "material")]
    pub materials: Vec<Material>,
}

/// Largest material library read (bytes): the built-in one is 4.4 kB for 6 materials with
/// their sources, so 1 MiB holds over 1000 such entries (10 000 without comments). Reading
/// takes memory about 40 times the text (a library of 100 000 bare entries, 9.9 MB, took
/// 381 MB), so this keeps a library within about 40 MB and a fraction of a second.
pub const MAX_LIBRARY_BYTES: usize = 1 << 20;
/// Most materials in one library (a bare entry is about 100 bytes: the byte limit allows
/// about as many).
pub const MAX_MATERIALS: usize = 10_000;
/// Most names an unknown-material error lists.
const LISTED_NAMES: usize = 40;

impl Library {
    /// Read and check a library (at most [`MAX_LIBRARY_BYTES`] and [`MAX_MATERIALS`] entries,
    /// every entry's coefficients pass [`Coefficients::check`], names are unique and not
    /// empty); `what` names the file in errors.
    pub fn from_toml(text: &str, what: &str) -> Result<Library, Error> {
        if text.len() > MAX_LIBRARY_BYTES {
            return Err(Error::param(
                Param::Materials,
                format!("{what}: {} bytes", text.len()),
                format!("a library of at most {MAX_LIBRARY_BYTES} bytes"),
            ));
        }
        let lib: Library = toml::from_str(text).map_err(|e| Error::File(format!("{what}: {e}")))?;
        if lib.materials.len() > MAX_MATERIALS {
            return Err(Error::param(
                Param::Materials,
                format!("{what}: {} materials", lib.materials.len()),
                format!("a library of at most {MAX_MATERIALS} materials"),
            ));
        }
        let mut seen = std::collections::HashSet::with_capacity(lib.materials.len());
        for (i, m) in lib.materials.iter().enumerate() {
            if m.name.trim().is_empty() || !seen.insert(m.name.as_str()) {
                return Err(Error::File(format!("{what}: material {}: empty or repeated name {:?}", i + 1, m.name)));
            }
            m.coefficients.check(m.allow_unusual_ratio).map_err(|e| Error::File(format!("{what}: {}: {e}", m.name)))?;
        }
        if lib.materials.is_empty() {
            return Err(Error::File(format!("{what}: no [[material]] entries")));
        }
        Ok(lib)
    }

    /// The built-in library (`assets/materials/library.toml`; tested to load).
    pub fn builtin() -> &'static Library {
        static LIB: std::sync::OnceLock<Library> = std::sync::OnceLock::new();
        LIB.get_or_init(|| {
            Library::from_toml(LIBRARY_TOML, "built-in material library").unwrap_or(Library { materials: Vec::new() })
        })
    }

    /// The material called `name`, or an error listing the names.
    pub fn get(&self, name: &str) -> Result<&Material, Error> {
        self.materials.iter().find(|m| m.name == name).ok_or_else(|| {
            let names: Vec<&str> = self.materials.iter().take(LISTED_NAMES).map(|m| m.name.as_str()).collect();
            let more = self.materials.len().saturating_sub(LISTED_NAMES);
            let more = if more > 0 { format!(" and {more} more") } else { String::new() };
            Error::param(Param::Material, name, format!("one of {}{more}", names.join(", ")))
        })
    }
}

/// One full-slot test for calibration: feed per tooth and the mean forces over a revolution
/// in the frame of Altintas & Lee 1996 (feed along +x, φ clockwise from +y).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct SlotTest {
    pub f_z_mm: f64,
    pub fx_n: f64,
    pub fy_n: f64,
    pub fz_n: f64,
}

/// Coefficients fitted from slot tests, with what the fit leaves.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Calibration {
    pub coefficients: Coefficients,
    /// Per test: measured minus fitted mean (Fx, Fy, Fz) (N).
    pub residuals_n: Vec<[f64; 3]>,
    /// Root-mean-square residual of Fx, Fy, Fz (N).
    pub rms_residual_n: [f64; 3],
}

/// Mean forces of a full slot (φ from 0 to π) by the closed form of the edge-force model
/// (derived in docs/process-model.md):
/// F̄x = −N·a_p·Krc·f_z/4 − N·a_p·Kre/π, F̄y = N·a_p·Ktc·f_z/4 + N·a_p·Kte/π,
/// F̄z = N·a_p·Kac·f_z/π + N·a_p·Kae/2.
pub fn slot_mean_forces(k: &Coefficients, teeth: u32, depth_mm: f64, f_z_mm: f64) -> [f64; 3] {
    let na = f64::from(teeth) * depth_mm;
    [
        -na * k.krc * f_z_mm / 4.0 - na * k.kre / PI,
        na * k.ktc * f_z_mm / 4.0 + na * k.kte / PI,
        na * k.kac * f_z_mm / PI + na * k.kae / 2.0,
    ]
}

/// The six coefficients from full-slot tests (docs/process-model.md): each mean force is linear in
/// f_z; the least-squares slope and intercept of F̄y give Ktc = 4·slope/(N·a_p) and
/// Kte = π·intercept/(N·a_p), of F̄x Krc = −4·slope/(N·a_p) and Kre = −π·intercept/(N·a_p), of F̄z
/// Kac = π·slope/(N·a_p) and Kae = 2·intercept/(N·a_p).
///
/// Needs at least two different feeds (`slot-forces`); the result is not checked against the
/// usual ratios (the caller shows it with its residuals).
pub fn calibrate_slot(tests: &[SlotTest], teeth: u32, depth_mm: f64) -> Result<Calibration, Error> {
    for t in tests {
        for v in [t.f_z_mm, t.fx_n, t.fy_n, t.fz_n] {
            if !v.is_finite() {
                return Err(Error::param(Param::SlotForces, v, "finite numbers"));
            }
        }
        if t.f_z_mm <= 0.0 {
            return Err(Error::param(Param::SlotForces, t.f_z_mm, "f_z > 0 mm in every row"));
        }
    }
    let n = tests.len() as f64;
    let mean_f = tests.iter().map(|t| t.f_z_mm).sum::<f64>() / n.max(1.0);
    let sxx: f64 = tests.iter().map(|t| (t.f_z_mm - mean_f).powi(2)).sum();
    // Two feeds at least, and not all (numerically) the same: else the slope is undetermined.
    if tests.len() < 2 || sxx <= (1e-9 * mean_f).powi(2) * n {
        return Err(Error::param(
            Param::SlotForces,
            format!("{} test(s) at {} different feed(s)", tests.len(), distinct_feeds(tests)),
            "at least two tests at different feeds per tooth f_z (the mean forces are fitted as lines in f_z)",
        ));
    }
    let line = |get: fn(&SlotTest) -> f64| {
        let mean_y = tests.iter().map(get).sum::<f64>() / n;
        let slope = tests.iter().map(|t| (t.f_z_mm - mean_f) * (get(t) - mean_y)).sum::<f64>() / sxx;
        (slope, mean_y - slope * mean_f)
    };
    let ((sx, ix), (sy, iy), (sz, iz)) = (line(|t| t.fx_n), line(|t| t.fy_n), line(|t| t.fz_n));
    let na = f64::from(teeth) * depth_mm;
    let coefficients = Coefficients {
        ktc: 4.0 * sy / na,
        krc: -4.0 * sx / na,
        kac: PI * sz / na,
        kte: PI * iy / na,
        kre: -PI * ix / na,
        kae: 2.0 * iz / na,
    };
    let residuals_n: Vec<[f64; 3]> = tests
        .iter()
        .map(|t| {
            let f = slot_mean_forces(&coefficients, teeth, depth_mm, t.f_z_mm);
            [t.fx_n - f[0], t.fy_n - f[1], t.fz_n - f[2]]
        })
        .collect();
    let rms = |i: usize| (residuals_n.iter().map(|r| r[i] * r[i]).sum::<f64>() / n).sqrt();
    Ok(Calibration { coefficients, rms_residual_n: [rms(0), rms(1), rms(2)], residuals_n })
}

fn distinct_feeds(tests: &[SlotTest]) -> usize {
    let mut f: Vec<f64> = tests.iter().map(|t| t.f_z_mm).collect();
    f.sort_by(f64::total_cmp);
    f.dedup();
    f.len()
}

/// Most slot tests in one calibration file: a calibration takes a handful of feeds (the
/// usual series is 4–10), each test a few bytes of input but a residual object in the report;
/// 2 million rows (a 66 MB file) take 14 s and 3.3 GB, 1000 take milliseconds.
pub const MAX_SLOT_TESTS: usize = 1000;

/// Reads slot tests (at most [`MAX_SLOT_TESTS`]) from CSV: a header naming the columns `f_z`,
/// `fx`, `fy`, `fz` (any order, any case, units after an underscore allowed:
/// `f_z_mm,fx_n,fy_n,fz_n`), then one test per line; `#` comments and blank lines skipped.
/// Errors name the line.
pub fn parse_slot_forces(text: &str, what: &str) -> Result<Vec<SlotTest>, Error> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut columns: Option<[usize; 4]> = None;
    let mut tests = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let fields: Vec<&str> = line.split([',', ';', '\t']).map(str::trim).collect();
        let bad = |why: String| Error::File(format!("{what} line {}: {why}, got {line:?}", i + 1));
        let Some(cols) = columns else {
            let find = |names: &[&str]| {
                fields.iter().position(|f| {
                    let f = f.to_ascii_lowercase();
                    names.iter().any(|n| f == *n || f.strip_prefix(n).is_some_and(|u| u.starts_with('_')))
                })
            };
            match (find(&["f_z", "feed_per_tooth"]), find(&["fx"]), find(&["fy"]), find(&["fz"])) {
                (Some(a), Some(b), Some(c), Some(d)) if a != d => columns = Some([a, b, c, d]),
                _ => return Err(bad("expected a header with the columns f_z, fx, fy, fz".into())),
            }
            continue;
        };
        let mut v = [0.0; 4];
        for (k, &c) in cols.iter().enumerate() {
            let field = fields.get(c).ok_or_else(|| bad(format!("expected {} fields", fields.len().max(c + 1))))?;
            v[k] = field
                .parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
                .ok_or_else(|| bad(format!("field {} is not a finite number", c + 1)))?;
        }
        if tests.len() == MAX_SLOT_TESTS {
            return Err(Error::param(
                Param::SlotForces,
                format!("{what}: more than {MAX_SLOT_TESTS} tests"),
                format!("a file of at most {MAX_SLOT_TESTS} tests (one per line)"),
            ));
        }
        tests.push(SlotTest { f_z_mm: v[0], fx_n: v[1], fy_n: v[2], fz_n: v[3] });
    }
    Ok(tests)
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
mod tests {
    use super::*;

    /// The built-in library loads, holds its five materials, and its p20 entry is
    /// the default set of docs/process-model.md ("The P20 default set").
    #[test]
    fn builtin_library_loads_with_the_documented_default() {
        let lib = Library::from_toml(LIBRARY_TOML, "library").expect("loads");
        let names: Vec<&str> = lib.materials.iter().map(|m| m.name.as_str()).collect();
        assert_eq!(names, ["p20", "p20-prehardened", "aisi-1045", "al-6061-t6", "ti-6al-4v"]);
        let p20 = lib.get(DEFAULT_MATERIAL).expect("p20").coefficients;
        // docs/process-model.md, "The P20 default set"
        assert_eq!(p20, Coefficients { ktc: 2400.0, krc: 960.0, kac: 360.0, kte: 35.0, kre: 35.0, kae: 5.0 });
        assert_eq!(Library::builtin(), &lib);
        let err = lib.get("unobtainium").expect_err("unknown");
        assert_eq!(err.parameter(), Some(Param::Material));
        assert!(err.to_string().contains("p20, p20-prehardened"), "{err}");
    }

    /// Negative, non-finite and unusual sets are refused by field; the ratio check can be
    /// switched off (the Ti-6Al-4V entry does so).
    #[test]
    fn checks_name_the_field() {
        let ok = Coefficients { ktc: 2400.0, krc: 960.0, kac: 360.0, kte: 35.0, kre: 35.0, kae: 5.0 };
        assert!(ok.check(false).is_ok());
        for (bad, p) in [
            (Coefficients { kac: -518.0, ..ok }, Param::Kac),
            (Coefficients { kte: f64::NAN, ..ok }, Param::Kte),
            (Coefficients { kre: f64::INFINITY, ..ok }, Param::Kre),
            (Coefficients { ktc: 0.0, ..ok }, Param::Ktc),
            (Coefficients { krc: 100.0, ..ok }, Param::Krc),
            (Coefficients { krc: 2000.0, ..ok }, Param::Krc),
        ] {
            let e = bad.check(false).expect_err("refused");
            assert_eq!(e.parameter(), Some(p), "{e}");
            assert!(e.to_string().contains(p.cli_name()), "{e}");
        }
        assert!(Coefficients { krc: 100.0, ..ok }.check(true).is_ok());
        assert!(Coefficients { kac: -1.0, ..ok }.check(true).is_err(), "signs are always checked");
        let text = LIBRARY_TOML.replace("allow-unusual-ratio = true\n", "");
        let e = Library::from_toml(&text, "edited").expect_err("Ti ratio 0.19 refused without the switch");
        assert!(e.to_string().contains("ti-6al-4v") && e.to_string().contains("krc"), "{e}");
    }

    /// Calibration inverts the closed form: slot tests generated from a known set by
    /// [`slot_mean_forces`] give that set back with zero residuals; noise shows in the residuals.
    #[test]
    fn calibration_recovers_the_set_that_made_the_tests() {
        let k = Coefficients { ktc: 2400.0, krc: 960.0, kac: 360.0, kte: 35.0, kre: 35.0, kae: 5.0 };
        let tests: Vec<SlotTest> = [0.05, 0.075, 0.1, 0.125]
            .iter()
            .map(|&f| {
                let [fx, fy, fz] = slot_mean_forces(&k, 4, 6.0, f);
                SlotTest { f_z_mm: f, fx_n: fx, fy_n: fy, fz_n: fz }
            })
            .collect();
        // The worked example of docs/process-model.md ("Checks"): the slot at f_z = 0.075 has
        // means (−699.38, 1347.38, 266.26) N.
        let m = slot_mean_forces(&k, 4, 6.0, 0.075);
        for (got, want) in m.iter().zip([-699.38, 1347.38, 266.26]) {
            assert!((got - want).abs() < 0.01, "{got} vs {want}");
        }
        let c = calibrate_slot(&tests, 4, 6.0).expect("fit");
        for ((p, got), (_, want)) in c.coefficients.named().iter().zip(k.named()) {
            assert!((got - want).abs() < 1e-9 * want.max(1.0), "{p:?}: {got} vs {want}");
        }
        assert!(c.rms_residual_n.iter().all(|r| *r < 1e-9));
        let mut noisy = tests.clone();
        noisy[1].fy_n += 10.0;
        let c = calibrate_slot(&noisy, 4, 6.0).expect("fit");
        assert!(c.rms_residual_n[1] > 1.0 && c.rms_residual_n[0] < 1e-9);
    }

    #[test]
    fn calibration_needs_two_feeds() {
        let t = SlotTest { f_z_mm: 0.1, fx_n: -900.0, fy_n: 1700.0, fz_n: 300.0 };
        for tests in [vec![], vec![t], vec![t, t, t]] {
            let e = calibrate_slot(&tests, 4, 6.0).expect_err("underdetermined");
            assert_eq!(e.parameter(), Some(Param::SlotForces), "{e}");
        }
        let e = calibrate_slot(&[t, SlotTest { fy_n: f64::NAN, ..t }], 4, 6.0).expect_err("NaN");
        assert_eq!(e.parameter(), Some(Param::SlotForces));
    }

    #[test]
    fn slot_force_csv_reads_named_columns_and_reports_bad_lines() {
        let text = "# tests\nf_z_mm,fx_n,fy_n,fz_n\n0.05,-600,1100,200\n\n0.1;-800;1500;280\n";
        let t = parse_slot_forces(text, "f.csv").expect("parses");
        assert_eq!(t.len(), 2);
        assert_eq!(t[1], SlotTest { f_z_mm: 0.1, fx_n: -800.0, fy_n: 1500.0, fz_n: 280.0 });
        let t = parse_slot_forces("fy,fz,fx,f_z\n1,2,3,0.05\n", "f.csv").expect("any order");
        assert_eq!(t[0], SlotTest { f_z_mm: 0.05, fx_n: 3.0, fy_n: 1.0, fz_n: 2.0 });
        for bad in
            ["0.05,1,2,3\n", "f_z,fx,fy,fz\n0.05,1,2\n", "f_z,fx,fy,fz\n0.05,1,x,3\n", "f_z,fx,fy,fz\n0.05,1,inf,3\n"]
        {
            let e = parse_slot_forces(bad, "f.csv").expect_err(bad);
            assert!(e.to_string().contains("f.csv line"), "{e}");
        }
    }

    #[test]
    fn libraries_and_slot_files_are_bounded_before_the_work() {
        let entry = |i: usize| {
            format!(
                "[[material]]\nname = \"m{i}\"\nlabel = \"\"\nktc = 1e3\nkrc = 4e2\nkac = 1e2\nkte = 1e1\nkre = 1e1\nkae = 1e0\n"
            )
        };
        // one byte over the limit, whatever it holds
        let big = format!("{}#{}", entry(0), "x".repeat(MAX_LIBRARY_BYTES - entry(0).len()));
        assert_eq!(big.len(), MAX_LIBRARY_BYTES + 1);
        let e = Library::from_toml(&big, "big.toml").expect_err("too big");
        assert_eq!(e.parameter(), Some(Param::Materials), "{e}");
        // one entry over the count (entries of 13 + 16 + 11 + 6·10 = 100 bytes at most: 10 001 of
        // them fit in 1 MiB)
        let many: String = (0..=MAX_MATERIALS).map(entry).collect();
        assert!(many.len() <= MAX_LIBRARY_BYTES, "{}", many.len());
        let e = Library::from_toml(&many, "many.toml").expect_err("too many");
        assert_eq!(e.parameter(), Some(Param::Materials), "{e}");
        // at the count: loads, repeated names still found (a set, not pairs)
        let lib =
            Library::from_toml(&many[..many.rfind("[[material]]").expect("entry")], "ok.toml").expect("at the limit");
        assert_eq!(lib.materials.len(), MAX_MATERIALS);
        let e = lib.get("none").expect_err("unknown");
        assert!(e.to_string().contains(&format!("and {} more", MAX_MATERIALS - LISTED_NAMES)), "{e}");
        let twice = format!("{}{}", entry(7), entry(7));
        assert!(Library::from_toml(&twice, "twice.toml").expect_err("repeated").to_string().contains("repeated"));
        // slot tests: the limit passes, one more is named
        let rows = |n: usize| -> String {
            let body: String = (0..n).map(|i| format!("{},1,2,3\n", 0.01 + 1e-6 * i as f64)).collect();
            format!("f_z,fx,fy,fz\n{body}")
        };
        assert_eq!(parse_slot_forces(&rows(MAX_SLOT_TESTS), "s.csv").expect("at the limit").len(), MAX_SLOT_TESTS);
        let e = parse_slot_forces(&rows(MAX_SLOT_TESTS + 1), "s.csv").expect_err("one more");
        assert_eq!(e.parameter(), Some(Param::SlotForces), "{e}");
    }
}
