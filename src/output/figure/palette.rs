//! The colours of the figures' categories (domains, structures, sets of
//! motions): nine distinct hues, their light companions, two dark ones,
//! then hues spread by the golden angle, so any number of categories gets a
//! colour. No grey: greys mark what is not a category (no motion, not
//! computed, reference lines).

use plotters::style::RGBColor;

const PALETTE: [RGBColor; 20] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
    RGBColor(174, 199, 232),
    RGBColor(255, 187, 120),
    RGBColor(152, 223, 138),
    RGBColor(255, 152, 150),
    RGBColor(197, 176, 213),
    RGBColor(196, 156, 148),
    RGBColor(247, 182, 210),
    RGBColor(219, 219, 141),
    RGBColor(158, 218, 229),
    RGBColor(57, 59, 121),
    RGBColor(132, 60, 57),
];

/// The colour of the category ranked `rank` (0 first).
pub fn category(rank: usize) -> RGBColor {
    if let Some(&c) = PALETTE.get(rank) {
        return c;
    }
    // Beyond the palette: spread hues by the golden angle (HSL, s = l = 0.55).
    let h = (rank as f64 * 137.508) % 360.0;
    let (s, l) = (0.55, 0.55);
    let c = (1.0 - (2.0f64 * l - 1.0).abs()) * s;
    let x = c * (1.0 - ((h / 60.0) % 2.0 - 1.0).abs());
    let (r, g, b) = match (h / 60.0) as u32 {
        0 => (c, x, 0.0),
        1 => (x, c, 0.0),
        2 => (0.0, c, x),
        3 => (0.0, x, c),
        4 => (x, 0.0, c),
        _ => (c, 0.0, x),
    };
    let m = l - c / 2.0;
    let u = |v: f64| ((v + m) * 255.0).round() as u8;
    RGBColor(u(r), u(g), u(b))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn neighbouring_categories_differ() {
        for k in 0..200 {
            assert_ne!(category(k), category(k + 1), "ranks {k} and {}", k + 1);
        }
    }
}
