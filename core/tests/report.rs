//! The report's top-level numbers agree with its own rows, for every pocket strategy on the
//! 60 × 40 rectangle and the 60 × 60 L with 25 mm arms, and for every corner method: the links
//! are the `link` rows, the length at depth is the sum of all rows, the peak is the largest
//! row's, the time is every move at its paced feed plus the descents at the feed. Read from the
//! serialised JSON (what `trochoplan pocket` and `trochoplan corner` print), so the keys are
//! checked, not only the fields.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use serde_json::Value;
use trochoplan_core::corner::{CornerMethod, CornerRequest, evaluate};
use trochoplan_core::geom::{Polygon, p2};
use trochoplan_core::pocket::{self, PocketRequest, PocketStrategy};
use trochoplan_core::report;

/// Rounding of sums of the same segment lengths taken in another order (mm, degrees).
const TOL: f64 = 1e-9;

fn num(v: &Value, key: &str) -> f64 {
    v[key].as_f64().unwrap_or_else(|| panic!("{key} in {v}"))
}

/// Total length of the `by_kind` rows of `kind` (all rows with `None`).
fn rows_length(v: &Value, kind: Option<&str>) -> f64 {
    let rows = v["by_kind"].as_array().expect("by_kind");
    rows.iter().filter(|r| kind.is_none_or(|k| r["kind"] == k)).map(|r| num(r, "length_mm")).sum()
}

/// Length of a JSON segment (line or arc; mm).
fn segment_length(s: &Value) -> f64 {
    let pt = |k: &str| (s[k][0].as_f64().expect("x"), s[k][1].as_f64().expect("y"));
    match s["kind"].as_str() {
        Some("line") => {
            let ((x0, y0), (x1, y1)) = (pt("start"), pt("end"));
            (x1 - x0).hypot(y1 - y0)
        }
        Some("arc") => (num(s, "radius") * num(s, "sweep")).abs(),
        other => panic!("segment kind {other:?}"),
    }
}

fn rows_peak(v: &Value) -> f64 {
    v["by_kind"].as_array().expect("by_kind").iter().map(|r| num(r, "max_engagement_deg")).fold(0.0, f64::max)
}

fn close(label: &str, key: &str, got: f64, want: f64) {
    assert!((got - want).abs() <= TOL * want.abs().max(1.0), "{label}: {key} = {got}, its rows give {want}");
}

#[test]
fn pocket_keys_agree_with_their_rows() {
    let rect = vec![p2(0.0, 0.0), p2(60.0, 0.0), p2(60.0, 40.0), p2(0.0, 40.0)];
    let l_shape = vec![p2(0.0, 0.0), p2(60.0, 0.0), p2(60.0, 25.0), p2(25.0, 25.0), p2(25.0, 60.0), p2(0.0, 60.0)];
    for (name, pts) in [("rectangle", rect), ("L", l_shape)] {
        for strategy in PocketStrategy::ALL {
            let label = format!("{name} {}", strategy.name());
            // the slot takes narrow pockets only: the 120 × 16 one for it
            let narrow = vec![p2(0.0, 0.0), p2(120.0, 0.0), p2(120.0, 16.0), p2(0.0, 16.0)];
            let pts = if strategy == PocketStrategy::Slot { narrow } else { pts.clone() };
            let req =
                PocketRequest { polygon: Polygon::new(pts).expect("polygon"), strategy, ..PocketRequest::default() };
            let plan = pocket::plan(&req).expect("plan");
            let rep = report::pocket(&req, &plan).expect("report");
            let v = serde_json::to_value(&rep).expect("json");
            assert_eq!(v["method"], strategy.name(), "{label}");
            let at_depth = num(&v, "length_at_depth_mm");
            close(&label, "link_length_mm", num(&v, "link_length_mm"), rows_length(&v, Some("link")));
            close(&label, "length_at_depth_mm", at_depth, rows_length(&v, None));
            close(&label, "max_engagement_deg", num(&v, "max_engagement_deg"), rows_peak(&v));
            assert!(num(&v, "p95_engagement_deg") <= num(&v, "max_engagement_deg"), "{label}");
            assert!(num(&v, "air_length_mm") <= at_depth, "{label}");
            let entry = match strategy {
                PocketStrategy::Adaptive => num(&v, "helix_length_mm"),
                _ => num(&v, "entry_length_mm"),
            };
            // every move at its paced feed (the `pace` block, one feed per segment), the descents
            // at the programmed feed
            let feeds = v["pace"]["feeds_mm_per_min"].as_array().expect("pace feeds");
            let moves = v["segments"].as_array().expect("segments");
            assert_eq!(feeds.len(), moves.len(), "{label}");
            let paced: f64 =
                moves.iter().zip(feeds).map(|(s, f)| segment_length(s) / f.as_f64().expect("feed") * 60.0).sum();
            let feed = num(&v, "feed_mm_per_min");
            close(&label, "time_s", num(&v, "time_s"), paced + entry / feed * 60.0);
            let segments = moves.len();
            assert_eq!(v["kinds"].as_array().map(Vec::len), Some(segments), "{label}");
            match strategy {
                PocketStrategy::Rings(_) => {
                    let rings = v["rings"].as_array().expect("rings");
                    assert_eq!(v["ring_count"].as_u64(), Some(rings.len() as u64), "{label}");
                    let ring_sum = rings.iter().map(|g| num(g, "length_mm")).sum::<f64>();
                    close(&label, "path_length_mm", num(&v, "path_length_mm"), ring_sum);
                }
                PocketStrategy::MedialAxis => {
                    close(&label, "path_length_mm", num(&v, "path_length_mm"), at_depth);
                    assert_eq!(v["by_kind"], v["by_move"], "{label}");
                    let circles = v["circles"].as_array().expect("circles").len();
                    assert_eq!(v["circle_count"].as_u64(), Some(circles as u64), "{label}");
                }
                PocketStrategy::Adaptive => {
                    let parts = num(&v, "parts") as usize;
                    assert_eq!(v["entries"].as_array().map(Vec::len), Some(parts), "{label}");
                }
                PocketStrategy::Slot => {
                    assert_eq!(v["ramps"].as_array().map(Vec::len), Some(1), "{label}");
                    assert!(num(&v, "ramp_full_width_depth_mm") <= num(&v, "ramp_pass_limit_mm") + 1e-9, "{label}");
                }
            }
            // the accessors the window reads are the same numbers
            assert_eq!(rep.length_at_depth_mm(), at_depth, "{label}");
            assert_eq!(rep.link_length_mm(), num(&v, "link_length_mm"), "{label}");
            assert_eq!(rep.time_s(), num(&v, "time_s"), "{label}");
            assert_eq!(rep.max_engagement_deg(), num(&v, "max_engagement_deg"), "{label}");
            assert_eq!(rep.entry_length_mm(), entry, "{label}");
        }
    }
}

#[test]
fn corner_keys_agree_with_their_rows() {
    for method in CornerMethod::ALL {
        let label = method.name();
        let req = CornerRequest { method, ..CornerRequest::DEFAULT };
        let rep = report::corner(&evaluate(&req).expect("corner")).expect("report");
        let v = serde_json::to_value(&rep).expect("json");
        let at_depth = num(&v, "length_at_depth_mm");
        close(label, "link_length_mm", num(&v, "link_length_mm"), rows_length(&v, Some("link")));
        close(label, "length_at_depth_mm", at_depth, rows_length(&v, None));
        close(label, "path_length_mm", num(&v, "path_length_mm"), at_depth);
        close(label, "max_engagement_deg", num(&v, "max_engagement_deg"), rows_peak(&v));
        assert!(num(&v, "air_length_mm") <= at_depth, "{label}");
        let tip =
            v["by_kind"].as_array().expect("rows").iter().filter(|r| r["kind"] == "corner-point" || r["kind"] == "tip");
        let tip_peak = tip.map(|r| num(r, "max_engagement_deg")).fold(0.0, f64::max);
        close(label, "corner_point.max_engagement_deg", num(&v["corner_point"], "max_engagement_deg"), tip_peak);
    }
}
