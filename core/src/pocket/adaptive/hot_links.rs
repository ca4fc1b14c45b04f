//! Links that cut: in a pocket with islands, a link between two runs may have to go round an
//! island through stock not yet cleared (the router knows the walls and the islands, not the
//! stock). The measured plan says where: a link whose measured engagement is above the limit
//! (the target + 1°) is replaced by a retract, the tool going down again on the end of the
//! link — the start of the run it led to, on the ring before it (cleared), or, where the link
//! ended on a slant onto a ring that grew all round, at the start of that slant, which lies on
//! the ring before. Repeated on the new plan (the stock the removed link cut is then cut by the
//! runs after it) at most [`MAX_ROUNDS`] times.

use super::loops::Builder;
use super::plan::AdaptivePart;
use crate::engagement::move_peaks;
use crate::pocket::path::PocketPath;
use crate::toolpath::MoveKind;

/// Most times the links above the limit are replaced on one plan.
pub(super) const MAX_ROUNDS: usize = 4;

/// The moves of `b` and the parts `parts` with every link group of `path` (its moves, measured)
/// that reads above `limit` (rad) replaced by a retract (module docs); `None` where none does.
pub(super) fn without_hot_links(
    path: &PocketPath,
    b: &Builder,
    parts: &[AdaptivePart],
    limit: f64,
) -> Option<(Builder, Vec<AdaptivePart>)> {
    let segments = path.segments();
    if segments.len() != b.segments.len() {
        return None;
    }
    let peak = move_peaks(&path.measurement.profile, &segments);
    // the link groups (maximal runs of link moves) and which moves to drop
    let mut drop = vec![false; segments.len()];
    let mut retract_at = Vec::new();
    let mut i = 0;
    while i < segments.len() {
        if b.kinds[i] != MoveKind::Link {
            i += 1;
            continue;
        }
        let start = i;
        while i < segments.len() && b.kinds[i] == MoveKind::Link {
            i += 1;
        }
        if !peak[start..i].iter().any(|&p| p > limit) {
            continue;
        }
        // keep the last move where it does not cut above the limit and is a slant onto a run
        // (its start on the ring before); else go down at the run itself
        let keep_last = i - start > 1 && peak[i - 1] <= limit;
        let end = if keep_last { i - 1 } else { i };
        drop[start..end].iter_mut().for_each(|d| *d = true);
        retract_at.push(end);
    }
    if retract_at.is_empty() {
        return None;
    }
    // old index → new index of the first kept move at or after it
    let mut new_index = vec![0; segments.len() + 1];
    let mut kept = 0;
    for k in 0..segments.len() {
        new_index[k] = kept;
        if !drop[k] {
            kept += 1;
        }
    }
    new_index[segments.len()] = kept;
    let mut nb = Builder::default();
    for k in (0..segments.len()).filter(|&k| !drop[k]) {
        nb.segments.push(b.segments[k]);
        nb.kinds.push(b.kinds[k]);
    }
    nb.retracts = b.retracts.iter().chain(&retract_at).map(|&k| new_index[k]).filter(|&k| k < kept).collect();
    nb.retracts.sort_unstable();
    nb.retracts.dedup();
    Some((nb, renumbered(parts, &new_index)))
}

/// `parts` with their first and end moves renumbered by `new_index` (old move index → new,
/// one past the last included) after moves were dropped or replaced.
pub(super) fn renumbered(parts: &[AdaptivePart], new_index: &[usize]) -> Vec<AdaptivePart> {
    parts
        .iter()
        .map(|p| AdaptivePart {
            first_segment: new_index[p.first_segment],
            end_segment: new_index[p.end_segment],
            ..p.clone()
        })
        .collect()
}
