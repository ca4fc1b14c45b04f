//! The window at the common screen sizes (1366 × 768 and 1920 × 1080) with four pinned variants:
//! every text of every tab lies within the panel it is drawn in (nothing cut off at a panel's
//! edge), the plots' legends lie outside the data, and no two curves of one plot look alike.

use super::*;
use crate::app::panels::legend::record::{self, Drawn};
use egui_kittest::kittest::{By, NodeT};

/// The screen sizes the window is laid out for.
const SIZES: [(f32, f32); 2] = [(1366.0, 768.0), (1920.0, 1080.0)];

/// The window at `size` with the paper's set pinned, a fourth pin, and an edited job that is
/// none of them: five variants in every plot.
fn with_four_pins(size: (f32, f32)) -> Harness<'static, App> {
    let app = App::new(Job::default(), None, Box::new(FakeDialogs { open: None, save: None }));
    let mut h =
        Harness::builder().with_size(egui::vec2(size.0, size.1)).build_ui_state(|ui, app: &mut App| app.show(ui), app);
    h.run();
    h.get_by_label(Tab::Compare.spec().label).click();
    h.run();
    h.get_by_label("Pin the paper's set").click();
    h.run();
    h.state_mut().state.job.step = 0.6;
    h.run();
    wait_for_plans(&mut h);
    h.get_by_label("Pin current job").click();
    h.run();
    h.state_mut().state.job.step = 0.7;
    h.run();
    wait_for_plans(&mut h);
    assert_eq!(h.state().variants.len(), 4, "four pins");
    h
}

/// Step the window until the background work (plans, pocket) is done.
fn wait_for_plans(h: &mut Harness<'_, App>) {
    let t0 = Instant::now();
    while (h.state().pocket.pending() || h.state().planner.pending()) && t0.elapsed().as_secs() < 120 {
        std::thread::sleep(std::time::Duration::from_millis(20));
        h.step();
    }
    h.run();
}

/// The rectangle of node `n` in the window, if it has one.
fn rect_of<'t>(n: &impl NodeT<'t>) -> Option<egui::Rect> {
    let b = n.accesskit_node().bounding_box()?;
    Some(egui::Rect::from_min_max(egui::pos2(b.x0 as f32, b.y0 as f32), egui::pos2(b.x1 as f32, b.y1 as f32)))
}

/// The horizontal extent of the panel a text at `r` is drawn in: the parameters on the left,
/// the derived values on the right, the tab between them (the whole width without them, and for
/// the menu and status bars above and below the side panels).
fn panel_of(h: &Harness<'_, App>, r: egui::Rect, width: f32) -> (f32, f32) {
    let side = h.state().view.tab.spec().slot_panels;
    let rect = |name: &str| h.ctx.data(|d| d.get_temp::<egui::Rect>(crate::app::layout::panel_rect_id(name)));
    let (left, right) = if side { (rect("parameters"), rect("derived")) } else { (None, None) };
    let (Some(left), Some(right)) = (left, right) else { return (0.0, width) };
    if r.bottom() <= left.top() || r.top() >= left.bottom() {
        (0.0, width)
    } else if r.left() < left.right() {
        (0.0, left.right())
    } else if r.left() >= right.left() {
        (right.left(), width)
    } else {
        (left.right(), right.left())
    }
}

/// The texts of the window that reach past the left or right edge of the panel they are drawn
/// in (or of the window), with their extent and the panel's; and how many texts it checked.
fn cut_off(h: &Harness<'_, App>, width: f32) -> (Vec<String>, usize) {
    let (mut bad, mut checked) = (Vec::new(), 0);
    for n in h.query_all(By::new().predicate(|_| true)) {
        let node = n.accesskit_node();
        // the panels' resize handles sit on the panels' edges
        if node.role() == Role::Splitter {
            continue;
        }
        let Some(text) = node.label().or_else(|| node.value()) else { continue };
        let Some(r) = rect_of(&n) else { continue };
        if text.trim().is_empty() || !r.is_positive() {
            continue;
        }
        checked += 1;
        let (lo, hi) = panel_of(h, r, width);
        if r.left() < lo - 0.5 || r.right() > hi + 0.5 {
            bad.push(format!(
                "{:?} {text:?}: x {:.0}..{:.0} in a panel {lo:.0}..{hi:.0}",
                node.role(),
                r.left(),
                r.right()
            ));
        }
    }
    (bad, checked)
}

/// The plots' titles shown cut short: narrower than their text on one line, yet one line high.
fn cut_titles(h: &Harness<'_, App>) -> Vec<String> {
    let font = egui::TextStyle::Body.resolve(&h.ctx.global_style());
    let row = h.ctx.fonts_mut(|f| f.row_height(&font));
    let mut bad = Vec::new();
    for n in h.query_all(By::new().predicate(|_| true)) {
        let node = n.accesskit_node();
        let Some(text) = node.label().or_else(|| node.value()) else { continue };
        let Some(r) = rect_of(&n) else { continue };
        if !crate::app::panels::plots::titles::ALL.contains(&text.as_str()) {
            continue;
        }
        let natural = h.ctx.fonts_mut(|f| f.layout_no_wrap(text.clone(), font.clone(), egui::Color32::BLACK).size().x);
        if natural > r.width() + 1.0 && r.height() < 1.5 * row {
            bad.push(format!("{text:?}: {:.0} px of {natural:.0} shown on one line", r.width()));
        }
    }
    bad
}

/// Every tab of the window, each shown once its background work is done.
fn every_tab(h: &mut Harness<'_, App>, mut check: impl FnMut(&mut Harness<'_, App>, &str)) {
    for spec in &crate::app::tabs::TABS {
        h.get_by_label(spec.label).click();
        h.run();
        wait_for_plans(h);
        check(h, spec.label);
    }
}

#[test]
fn every_tab_fits_a_1366_by_768_and_a_1920_by_1080_window() {
    let mut bad = Vec::new();
    for size in SIZES {
        let mut h = with_four_pins(size);
        // the check sees the side panels (the menu bar's entries above them are not cut off)
        assert!(h.ctx.data(|d| d.get_temp::<egui::Rect>(crate::app::layout::panel_rect_id("derived"))).is_some());
        every_tab(&mut h, |h, tab| {
            let (texts, checked) = cut_off(h, size.0);
            assert!(checked > 20, "{tab}: {checked} texts seen");
            let titles = cut_titles(h);
            bad.extend(texts.into_iter().chain(titles).map(|b| format!("{size:?} {tab}: {b}")));
        });
    }
    bad.dedup();
    assert!(bad.is_empty(), "{} texts cut off:\n{}", bad.len(), bad.join("\n"));
}

/// The plots of the slot's tabs (the chip view has no legend and one variant).
const PLOTS: [&str; 6] = ["path_view", "h_plot", "engagement_plot", "wall_plot", "force_plot", "imprint_plot"];

/// Curves of one plot that look alike (same colour, line style and fill) though they show
/// different things or variants, and curves of one thing drawn in different looks.
fn look_alikes(drawn: &[Drawn]) -> Vec<String> {
    let mut bad = Vec::new();
    for (i, a) in drawn.iter().enumerate() {
        for b in &drawn[i + 1..] {
            let same = (a.layer, &a.what) == (b.layer, &b.what);
            let look = |d: &Drawn| (d.look.color, d.look.style, d.look.fill);
            if same != (look(a) == look(b)) {
                bad.push(format!("{a:?} and {b:?}"));
            }
        }
    }
    bad
}

#[test]
fn the_look_alike_check_finds_a_force_component_in_a_variants_colour() {
    use crate::app::panels::legend::Look;
    use crate::app::panels::palette;
    let drawn = |layer, what: &str, color| Drawn { layer, what: what.into(), look: Look::solid(color, 1.0) };
    let fine = [drawn(None, "Fx", palette::FORCE_X), drawn(Some(1), "F_R", palette::VARIANTS[1])];
    assert!(look_alikes(&fine).is_empty());
    // the colours before: Fy drawn in the first pin's orange
    let clash = [drawn(None, "Fy", palette::VARIANTS[1]), drawn(Some(1), "F_R", palette::VARIANTS[1])];
    assert_eq!(look_alikes(&clash).len(), 1);
}

/// Least height of a plot's data area (px): room for a few grid lines.
const MIN_PLOT_HEIGHT: f32 = 60.0;

#[test]
fn no_two_curves_of_a_plot_look_alike_and_the_legends_lie_outside_the_data() {
    for size in SIZES {
        plots_at(size);
    }
}

/// The plots of the slot's tabs in a window of `size`: no two curves alike, the legend above
/// the data, the data inside the window and high enough to read.
fn plots_at(size: (f32, f32)) {
    let mut h = with_four_pins(size);
    let window = egui::Rect::from_min_size(egui::Pos2::ZERO, egui::vec2(size.0, size.1));
    let mut bad = Vec::new();
    let mut seen = Vec::new();
    for tab in [Tab::Plots, Tab::Compare, Tab::Forces] {
        h.get_by_label(tab.spec().label).click();
        h.run();
        wait_for_plans(&mut h);
        for id in PLOTS {
            // the plots drawn this frame (a plot of another tab keeps its last record)
            let Some(plot) = record::get(&h.ctx, id) else { continue };
            record::forget(&h.ctx, id);
            seen.push(id);
            bad.extend(look_alikes(&plot.drawn).into_iter().map(|b| format!("{tab:?} {id}: {b}")));
            let variants: std::collections::BTreeSet<usize> = plot.drawn.iter().filter_map(|d| d.layer).collect();
            assert_eq!(variants.len(), 5, "{size:?} {tab:?} {id}: the edited job and four pins drawn");
            assert!(plot.legend.is_positive(), "{tab:?} {id}: a legend");
            let data = plot.data;
            assert!(window.contains_rect(data), "{size:?} {tab:?} {id}: the data {data:?} in the window");
            assert!(data.height() >= MIN_PLOT_HEIGHT, "{size:?} {tab:?} {id}: {data:?} high enough");
            assert!(
                plot.legend.bottom() <= plot.data.top(),
                "{tab:?} {id}: legend {:?} above the data {:?}",
                plot.legend,
                plot.data
            );
        }
    }
    seen.sort_unstable();
    seen.dedup();
    assert_eq!(seen.len(), PLOTS.len(), "every plot drawn: {seen:?}");
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}

/// The lines (1-based) of `source` that hand a plot's legend to egui_plot (`.legend(…)` on a
/// plot), which draws it inside the plot, over the curves.
fn inside_legends(source: &str) -> Vec<usize> {
    source.lines().enumerate().filter(|(_, l)| l.contains(".legend(")).map(|(n, _)| n + 1).collect()
}

#[test]
fn the_inside_legend_check_finds_egui_plots_legend_and_not_the_row_above() {
    let plot = "Plot::new(\"p\")\n    .height(200.0)\n    .legend(Legend::default())\n    .show(ui, |p| {});";
    assert_eq!(inside_legends(plot), [3]);
    assert!(inside_legends("let h = legend::show_above(ui, &entries, 1);\nlegend::show(ui, &e, 2);").is_empty());
}

/// Every plot of the window draws its legend in a row above the data ([`legend::show`]): no
/// panel's source gives a plot egui_plot's legend, which lies inside the plot over the curves.
///
/// [`legend::show`]: crate::app::panels::legend::show
#[test]
fn no_plot_draws_its_legend_inside_the_data() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("src/panels");
    let mut read = Vec::new();
    let mut found = Vec::new();
    for entry in std::fs::read_dir(&dir).expect("the panels' sources") {
        let path = entry.expect("a directory entry").path();
        // the tests (this file names what it looks for) are a folder of their own
        if path.extension().is_none_or(|e| e != "rs") {
            continue;
        }
        let source = std::fs::read_to_string(&path).expect("a panel's source");
        let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
        found.extend(inside_legends(&source).into_iter().map(|n| format!("{name}:{n}")));
        read.push(name);
    }
    // the check reads the panels that draw plots
    for plotting in ["plots.rs", "corner.rs", "optimise.rs", "sweep.rs", "program_plots.rs", "export.rs"] {
        assert!(read.iter().any(|n| n == plotting), "{plotting} read from {}", dir.display());
    }
    assert!(found.is_empty(), "egui_plot's legend inside the plot at {}", found.join(", "));
}

/// The variants of each plot of the Plots tab drawn this frame: plot id and the variants
/// (layers) of its curves.
fn variants_drawn(h: &mut Harness<'_, App>) -> Vec<(&'static str, std::collections::BTreeSet<usize>)> {
    for id in PLOTS {
        record::forget(&h.ctx, id);
    }
    h.run();
    PLOTS
        .iter()
        .filter_map(|&id| Some((id, record::get(&h.ctx, id)?.drawn.iter().filter_map(|d| d.layer).collect())))
        .collect()
}

/// A click on a variant's entry in a legend hides that variant's curves in that plot only (the
/// entry stays, to be clicked again), and a second click shows them again.
#[test]
fn a_click_on_a_legend_entry_hides_its_curves_and_another_shows_them() {
    let mut h = with_four_pins(SIZES[0]);
    h.get_by_label(Tab::Plots.spec().label).click();
    h.run();
    wait_for_plans(&mut h);
    let all: std::collections::BTreeSet<usize> = (0..5).collect();
    let before = variants_drawn(&mut h);
    assert!(before.len() >= 3 && before.iter().all(|(_, v)| *v == all), "{before:?}");
    let entries = || By::new().role(Role::Button).label("current");
    let n = h.query_all(entries()).count();
    assert_eq!(n, before.len(), "one entry for the edited job in each plot's legend");
    h.query_all(entries()).nth(1).expect("the second plot's entry").click();
    let after = variants_drawn(&mut h);
    let without: std::collections::BTreeSet<usize> = (1..5).collect();
    let changed: Vec<_> = after.iter().filter(|(_, v)| *v != all).collect();
    assert_eq!(changed.len(), 1, "one plot: {after:?}");
    assert_eq!(changed[0].1, without, "the edited job's curves hidden, the pins' kept");
    assert_eq!(h.query_all(entries()).count(), n, "the entry stays in the legend");
    h.query_all(entries()).nth(1).expect("the entry again").click();
    let again = variants_drawn(&mut h);
    assert!(again.iter().all(|(_, v)| *v == all), "shown again: {again:?}");
}
