//! The regime map drawn from curves alone: regions filled and labelled with
//! their motions, the curves over them, codimension-two points marked.

use std::path::Path;

use crate::study::curves::{CurveSet, Regions};

/// Draw the regime map of `set` cut into `regions` to `path` (SVG or PNG by extension).
pub fn plot_regimes(
    set: &CurveSet,
    regions: &Regions,
    title: &str,
    path: &Path,
) -> Result<(), String> {
    let _ = (set, regions, title, path);
    Err("not built yet".into())
}
