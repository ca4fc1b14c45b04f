//! The colours of the plots, defined once. One palette for the variants (the edited job and the
//! pinned ones: their curves and their headings in the Compare table), one for the quantities a
//! plan draws beside its main curve (the force components), and the marks shared by every plot
//! (current tooth, chip, limits, walls). No colour is in two of them, so two curves of one plot
//! never share a colour unless their line styles tell them apart.

use eframe::egui::Color32;

/// Colours of the variants: the edited job first, the pinned ones (up to four) after. A
/// categorical palette of well separated hues (blue, orange, green, purple, brown).
pub const VARIANTS: [Color32; 5] = [
    Color32::from_rgb(31, 119, 180),
    Color32::from_rgb(240, 128, 14),
    Color32::from_rgb(44, 160, 44),
    Color32::from_rgb(148, 103, 189),
    Color32::from_rgb(140, 86, 75),
];

/// Force component along x (cyan).
pub const FORCE_X: Color32 = Color32::from_rgb(23, 190, 207);
/// Force component along y (pink).
pub const FORCE_Y: Color32 = Color32::from_rgb(227, 119, 194);
/// Force component along z (olive).
pub const FORCE_Z: Color32 = Color32::from_rgb(170, 170, 30);
/// The quantity colours, in the order of [`FORCE_X`], [`FORCE_Y`], [`FORCE_Z`].
pub const QUANTITIES: [Color32; 3] = [FORCE_X, FORCE_Y, FORCE_Z];

/// The current tooth: its cursor, its chip and the path it took this cycle (red).
pub const CURSOR: Color32 = Color32::from_rgb(214, 39, 40);
/// A recommended limit drawn as a line (dark red, dashed where it is drawn).
pub const LIMIT: Color32 = Color32::from_rgb(120, 20, 40);
/// The slot walls and the stock face (grey).
pub const WALL: Color32 = Color32::from_rgb(128, 128, 128);
/// The tool while it cuts nothing, and the tool edge in the chip view (dark grey).
pub const TOOL: Color32 = Color32::from_rgb(64, 64, 64);
/// The bar of t_hmax in the h plot (black).
pub const TIME_TO_PEAK: Color32 = Color32::from_rgb(0, 0, 0);
/// The cooling intervals in the h plot (light blue fill).
pub const COOLING_FILL: Color32 = Color32::from_rgba_unmultiplied_const(40, 120, 200, 45);

#[cfg(test)]
mod tests {
    use super::*;

    /// Every opaque colour a curve is drawn in.
    fn all() -> impl Iterator<Item = Color32> {
        VARIANTS.into_iter().chain(QUANTITIES).chain([CURSOR, LIMIT, WALL, TOOL, TIME_TO_PEAK])
    }

    /// Euclidean distance of two colours in RGB (0–441).
    fn distance(a: Color32, b: Color32) -> f32 {
        let d = |x: u8, y: u8| f32::from(x) - f32::from(y);
        (d(a.r(), b.r()).powi(2) + d(a.g(), b.g()).powi(2) + d(a.b(), b.b()).powi(2)).sqrt()
    }

    #[test]
    fn the_colours_are_pairwise_far_apart() {
        let colours: Vec<Color32> = all().collect();
        assert_eq!(colours.len(), 13);
        for (i, a) in colours.iter().enumerate() {
            for b in &colours[i + 1..] {
                // 60 of 441: two colours any closer look alike in a thin line
                assert!(distance(*a, *b) > 60.0, "{a:?} and {b:?} are too close: {}", distance(*a, *b));
            }
        }
    }
}
