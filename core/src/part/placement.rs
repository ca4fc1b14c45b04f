//! An operation's place on the part (docs/jobs.md, "Placement"): the keys `origin = [x, y]`
//! (mm, default [0, 0]) and `rotation` (degrees, counter-clockwise, default 0) of an
//! `[[operation]]` table put the operation's own coordinates in the part's: a point of the
//! operation is rotated about its own origin, then moved to `origin` ([`Placement`]).

use crate::error::{Error, num};
use crate::geom::p2;
use crate::nc::Placement;

/// Largest distance of an operation's origin from the part's along X or Y (mm): a part of
/// 10 m, and far below the largest coordinate the NC writer writes (10 km).
pub const MAX_ORIGIN_MM: f64 = 10_000.0;

/// Largest rotation either way (degrees): one turn.
pub const MAX_ROTATION_DEG: f64 = 360.0;

/// The placement keys `origin` and `rotation` taken out of the operation's table `t`; the
/// identity where they are absent. Errors name the key and its allowed range.
pub fn take_placement(t: &mut toml::Table) -> Result<Placement, Error> {
    let origin = match t.remove("origin") {
        None => p2(0.0, 0.0),
        Some(v) => {
            let xy = v.as_array().filter(|a| a.len() == 2).map(|a| a.iter().map(number).collect::<Vec<_>>());
            match xy.as_deref() {
                Some(&[Some(x), Some(y)]) if in_range(x, MAX_ORIGIN_MM) && in_range(y, MAX_ORIGIN_MM) => p2(x, y),
                _ => {
                    return Err(Error::File(format!(
                        "origin = {v}: must be [x, y], two finite numbers from {} to {} mm",
                        num(-MAX_ORIGIN_MM),
                        num(MAX_ORIGIN_MM)
                    )));
                }
            }
        }
    };
    let rotation_deg = match t.remove("rotation") {
        None => 0.0,
        Some(v) => match number(&v) {
            Some(r) if in_range(r, MAX_ROTATION_DEG) => r,
            _ => {
                return Err(Error::File(format!(
                    "rotation = {v}: must be a finite angle from {} to {} degrees",
                    num(-MAX_ROTATION_DEG),
                    num(MAX_ROTATION_DEG)
                )));
            }
        },
    };
    Ok(Placement { origin, rotation_rad: rotation_deg.to_radians() })
}

/// A TOML number (integer or float) as f64.
fn number(v: &toml::Value) -> Option<f64> {
    match v {
        toml::Value::Float(f) => Some(*f),
        toml::Value::Integer(i) => Some(*i as f64),
        _ => None,
    }
}

/// Finite and within ±`max` (NaN is not).
fn in_range(v: f64, max: f64) -> bool {
    v.is_finite() && v.abs() <= max
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
mod tests {
    use super::*;

    fn table(text: &str) -> toml::Table {
        toml::from_str(text).expect("toml")
    }

    #[test]
    fn origin_and_rotation_place_the_operation_and_default_to_none() {
        let mut t = table("origin = [10, -2.5]\nrotation = 90.0\ndepth = 3.0\n");
        let p = take_placement(&mut t).expect("placement");
        assert_eq!(p.origin, p2(10.0, -2.5));
        // (1, 0) turned a quarter counter-clockwise is (0, 1), then moved by the origin
        let q = p.apply(p2(1.0, 0.0));
        assert!((q - p2(10.0, -1.5)).norm() < 1e-12, "{q:?}");
        assert!(!t.contains_key("origin") && !t.contains_key("rotation") && t.contains_key("depth"));
        let mut t = table("depth = 3.0\n");
        assert!(take_placement(&mut t).expect("placement").is_identity());
    }

    #[test]
    fn bad_origins_and_rotations_are_refused_by_key() {
        for (text, key) in [
            ("origin = [nan, 0.0]", "origin = "),
            ("origin = [0.0, inf]", "origin = "),
            ("origin = [1.0]", "origin = "),
            ("origin = [1.0, 2.0, 3.0]", "origin = "),
            ("origin = \"1, 2\"", "origin = "),
            ("origin = [20000.0, 0.0]", "origin = "),
            ("rotation = nan", "rotation = "),
            ("rotation = -inf", "rotation = "),
            ("rotation = 400.0", "rotation = "),
            ("rotation = \"90\"", "rotation = "),
        ] {
            let e = take_placement(&mut table(text)).expect_err(text).to_string();
            assert!(e.starts_with(key) && e.contains("must be"), "{text}: {e}");
        }
    }
}
